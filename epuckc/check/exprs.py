"""Expressions: variables, readings, operators and functions, each checked
for its kind (units) and bounded by an interval (static range analysis).

Every value is an int in its kind's natural unit (mm, steps/s, deg, ms; a
reading is a plain count) with the arithmetic of stdlib/arith.py: exact
inside an expression while it fits 32 bits, saturated to 16 bits where it
is stored (`_store`: a variable, an argument). The kinds combine as quantities do: a count times a
quantity is that quantity, a quantity divided by a count too, and two
quantities of one kind divide into a count; adding or comparing two
different kinds is an error that names both. A number written without a
unit takes the kind of what it is combined with (`heading > 90`).

Variables and their intervals are variables.py's.
"""
from __future__ import annotations

from typing import Optional

from ..diagnostics import Fix
from ..stdlib import arith, imath
from ..stdlib.table import READING_ARRAYS, STANDARD_READINGS
from . import devices
from ..stdlib.units import (ANGLE, DISTANCE, DURATION, INT, INT16_MAX, INT16_MIN, SPEED,
                            UNITS, describe_kind, quantity, round_nearest)
from ..syntax import ast
from . import arrays, bits, convert, decided as deciders, functions
from .messages import _code, _kind_word, _shown, did_you_mean
from .program import BOOL, Expr

EXAMPLE_UNIT = {DISTANCE: "mm", SPEED: "steps/s", ANGLE: "deg", DURATION: "ms"}
COMPARISONS = ("<", "<=", ">", ">=", "==", "!=")


_EXACT = dict(arith.BINARY, neg=arith.neg, abs=arith.absolute, clamp=arith.clamp, sat=arith.sat,
              **arith.BITS, **{"~": arith.bit_not}, **imath.FUNCTIONS)


def _interval(e: Expr) -> str:
    return _interval_of(e.lo, e.hi)


def _interval_of(lo: int, hi: int) -> str:
    return str(lo) if lo == hi else f"{lo}..{hi}"


class Exprs:
    """The checker's expressions and variables (a part of Checker)."""

    # -- source text, for messages --

    @staticmethod
    def _text(node) -> str:
        """A node as the formatter writes it, for messages (from the tree,
        not the file: the language server checks statements on their own)."""
        return _shown(node)

    # -- expressions --

    def _is_dynamic(self, value) -> bool:
        """Whether an argument is computed while the program runs (an
        operator, a variable or a reading), rather than a fixed value."""
        cls = value.__class__
        if cls is ast.ConstRef:
            name = value.name.name
            return name not in self.consts and (name in self.vars or name in STANDARD_READINGS)
        return cls is not ast.Number

    def _literal(self, node, allow_vars=True) -> Optional[Expr]:
        """A number with its unit, or a constant, as an Expr."""
        if isinstance(node, ast.ConstRef):
            name = node.name.name
            if name in self.consts:
                number, negated, problem = self._const_chain(name)
                if problem is not None or number is None:
                    self._const_value(node, INT, name)      # reports the problem
                    return None
                # a problem of the definition is said once, at its first use
                with self.diags.capture() as inner:
                    value = self._literal(number)
                for d in inner:
                    if d not in self._const_diagnostics:
                        self._const_diagnostics.add(d)
                        self.diags.items.append(d)
                if value is None:
                    return None
                v = -value.value if negated else value.value
                if not INT16_MIN <= v <= INT16_MAX:     # `const B = -A` with A = -32768
                    self.diags.error("E034", node.span,
                                     f"{_code(name)} is {v}, which does not fit a 16-bit int "
                                     f"({INT16_MIN}..{INT16_MAX})",
                                     help="expressions compute in 16-bit ints, as the e-puck "
                                          "does")
                    return None
                if node.negative:
                    v = arith.neg(v)    # the runtime's `-`: -(-32768) saturates to 32767
                if v != value.value:
                    value = Expr("num", value.kind, v, v, value=v, node=node, bare=value.bare)
                return Expr("num", value.kind, value.lo, value.hi, value=value.value, node=node,
                            bare=value.bare)
            if not allow_vars:
                self.diags.error("E052", node.span,
                                 f"a variable's initial value is a number or a constant, "
                                 f"not {_code(name)}",
                                 help="give it a number here, and its value in an action "
                                      "(`on immediate do ...`)")
                return None
            return self._name(node)
        if not abs(node.value) < 1e12:
            self.diags.error("E034", node.span, f"`{self._text(node)}` is far too large",
                             help=f"values are 16-bit ints: {INT16_MIN}..{INT16_MAX}")
            return None
        if node.unit is None:
            if node.value != int(node.value):
                self._whole(node, node.value)
                return None
            v = int(node.value)
            kind, bare = INT, True
        else:
            found = UNITS.get(node.unit)
            if found is None:
                self._value(node, INT, "value")         # reports the unknown unit
                return None
            kind, bare = found[0], False
            q = quantity(node.value, node.unit, kind)
            v = round_nearest(q.steps(self.geo) if kind == SPEED
                              else q.mm(self.geo) if kind == DISTANCE else q.value)
        if not INT16_MIN <= v <= INT16_MAX:
            self.diags.error("E034", node.span,
                             f"`{self._text(node)}` is {v} {EXAMPLE_UNIT.get(kind, '')}".rstrip()
                             + f", which does not fit a 16-bit int ({INT16_MIN}..{INT16_MAX})",
                             help="expressions compute in 16-bit ints, as the e-puck does")
            return None
        return Expr("num", kind, v, v, value=v, node=node, bare=bare)

    def _name(self, node: ast.ConstRef) -> Optional[Expr]:
        name = node.name.name
        info = self.vars.get(name)
        if (info is not None and info.size) or name in self.const_arrays \
                or name in READING_ARRAYS:
            arrays.bare_use(self, node.name, node)
            return None
        if info is not None:
            self.vars_used.add(name)
            e = Expr("var", info.kind, info.lo, info.hi, name=name, node=node.name)
        else:
            reading = STANDARD_READINGS.get(name)
            if reading is None:
                self.diags.error("E013", node.name.span, f"unknown name {_code(name)}",
                                 help=did_you_mean(node.name, list(self.vars) + list(self.consts)
                                                   + list(STANDARD_READINGS)) or
                                 f"declare it (`var {name} = 0` or `const {name} = 1`), or read "
                                 f"the robot: `ir0`..`ir7`, `x`, `heading`, ...")
                return None
            if not devices.require(self, reading.device, name, node.name.span):
                return None
            e = Expr("read", reading.kind, reading.lo, reading.hi, name=name, node=node.name)
        if node.negative:
            return self._unary("neg", e, node)
        return e

    def _expr(self, node) -> Optional[Expr]:
        """The checked Expr of an expression node, or None after reporting."""
        cls = node.__class__
        if cls is ast.Number or cls is ast.ConstRef:
            return self._literal(node)
        if cls is ast.Paren:
            return self._expr(node.expr)
        if cls is ast.UnaryOp:
            operand = self._expr(node.operand)
            if operand is None:
                return None
            return self._unary({"not": "not", "~": "~"}.get(node.op, "neg"), operand, node)
        if cls is ast.BinOp:
            if convert.is_fraction(node.left) or convert.is_fraction(node.right):
                return convert.fraction_beside(self, node)
            left, right = self._expr(node.left), self._expr(node.right)
            if left is None or right is None:
                return None
            return self._binary(node.op, left, right, node)
        if cls is ast.FuncCall:         # (directly: each level of nesting costs stack)
            return functions.call(self, node)
        if cls is ast.Index:
            return arrays.element(self, node)
        if cls is ast.Slice:
            arrays.bare_slice(self, node)
            return None
        self.diags.error("E024", node.span, "a condition such as `ir0 > 300` cannot go here",
                         help="conditions go after `when` or `if`")
        return None

    def _unary(self, op: str, e: Expr, node) -> Optional[Expr]:
        if op == "not":
            if not self._is_bool(e, "`not`"):
                return None
            return self._fold(Expr("not", BOOL, 0, 1, (e,), node=node))
        if op == "~":
            return bits.operation(self, "~", (e,), node)
        if not self._is_number(e, "`-`"):
            return None
        lo, hi = arith.interval(op, (e.lo, e.hi))
        return self._fold(Expr(op, e.kind, lo, hi, (e,), node=node, bare=e.bare))

    def _is_bool(self, e: Expr, where: str) -> bool:
        if e.kind == BOOL:
            return True
        self.diags.error("E050", e.node.span,
                         f"{where} takes a condition, but `{self._text(e.node)}` is "
                         f"{_kind_word(e.kind)}",
                         help=f"compare it: `{self._text(e.node)} > 0`")
        return False

    def _is_number(self, e: Expr, where: str) -> bool:
        if e.kind != BOOL:
            return True
        self.diags.error("E050", e.node.span,
                         f"{where} takes a number, but `{self._text(e.node)}` is a condition",
                         help="conditions go after `when` or `if`, and are joined with "
                              "`and`, `or`, `not`")
        return False

    @staticmethod
    def _adapt(e: Expr, kind: str) -> Expr:
        """A bare number where `kind` is wanted is of that kind."""
        if e.bare and e.kind == INT and kind not in (INT, BOOL):
            return Expr(e.op, kind, e.lo, e.hi, e.args, e.value, e.name, e.node, False)
        return e

    def _same_kind(self, a: Expr, b: Expr, node, what: str) -> Optional[tuple]:
        a, b = self._adapt(a, b.kind), self._adapt(b, a.kind)
        if a.kind != b.kind:
            self._kind_clash(node, a.kind, b.kind, what, left=a, right=b)
            return None
        return a, b

    def _one_kind(self, values: list, node, what: str) -> Optional[list]:
        """Values that must be of one kind (a function's arguments, an
        array's elements): adapted to it (bare numbers take it; none but
        bare ones: plain numbers), or None after E048 naming two that differ."""
        kinds = {v.kind for v in values if not v.bare}
        if len(kinds) > 1:
            first = next(v for v in values if not v.bare)
            other = next(v for v in values if not v.bare and v.kind != first.kind)
            self._kind_clash(node, first.kind, other.kind, what, left=first, right=other)
            return None
        kind = kinds.pop() if kinds else INT
        return [self._adapt(v, kind) for v in values]

    def _kind_clash(self, node, want: str, got: str, what: str, left=None, right=None,
                    notes=None):
        if left is not None:
            message = (f"{what} `{self._text(left.node)}`, {_kind_word(left.kind)}, and "
                       f"`{self._text(right.node)}`, {_kind_word(right.kind)}")
        else:
            message = f"{what}, but `{self._text(node.value if hasattr(node, 'value') else node)}` " \
                      f"is {_kind_word(got)}"
        if INT in (want, got) and BOOL not in (want, got):
            quantity_kind = want if got == INT else got
            unit = EXAMPLE_UNIT.get(quantity_kind, "")
            help = (f"a plain number times a quantity is that quantity: multiply by "
                    f"`1 {unit}`, or give the number a unit (`300 {unit}`)")
        elif left is None:          # a value stored where another kind is wanted
            help = convert.conversion(getattr(node, "value", node), got, want)
        else:
            help = convert.mixed(getattr(node, "op", "+"), left.node, right.node, left.kind,
                                 right.kind)
        self.diags.error("E048", node.span, message, notes=notes or [],
                         help=help or "both sides must be of one kind: convert one of them, "
                                      "or compare like with like")

    def _binary(self, op: str, a: Expr, b: Expr, node) -> Optional[Expr]:
        if op in ("and", "or"):
            if not (self._is_bool(a, f"`{op}`") and self._is_bool(b, f"`{op}`")):
                return None
            return self._fold(Expr(op, BOOL, 0, 1, (a, b), node=node))
        if op in arith.BITWISE:
            return bits.operation(self, op, (a, b), node)
        where = f"`{op}`"
        if not (self._is_number(a, where) and self._is_number(b, where)):
            return None
        if op in COMPARISONS:
            pair = self._same_kind(a, b, node, "cannot compare")
            if pair is None:
                return None
            decided = self._fold(Expr(op, BOOL, 0, 1, pair, node=node))
            if decided.constant:
                self._decided_comparison(decided, op, *pair)
            return decided
        if op in ("+", "-"):
            pair = self._same_kind(a, b, node, "cannot add" if op == "+" else "cannot subtract")
            if pair is None:
                return None
            a, b = pair
            kind = a.kind
        elif op == "*":
            if a.kind != INT and b.kind != INT:
                self._kind_clash(node, a.kind, b.kind, "cannot multiply", left=a, right=b)
                return None
            kind = b.kind if a.kind == INT else a.kind
        else:       # `/` and `%`
            if a.kind == INT and b.kind != INT:
                self._kind_clash(node, a.kind, b.kind,
                                 f"cannot divide a plain number by a quantity:", left=a, right=b)
                return None
            if a.kind != INT and b.kind != INT and a.kind != b.kind:
                self._kind_clash(node, a.kind, b.kind, "cannot divide", left=a, right=b)
                return None
            kind = INT if op == "/" and b.kind == a.kind else a.kind
            if not self._divisor(b, op):
                return None
        lo, hi = arith.interval(op, (a.lo, a.hi), (b.lo, b.hi))
        return self._fold(Expr(op, kind, lo, hi, (a, b), node=node, bare=a.bare and b.bare))

    def _decided_comparison(self, e: Expr, op: str, a: Expr, b: Expr):
        """W016: a comparison that is always true or always false, folded
        (the C never compares a value with itself)."""
        text, truth = self._text(e.node), "true" if e.value else "false"
        if a.constant and b.constant:
            return      # two fixed values: written so on purpose (`when 1 == 1`)
        unit = EXAMPLE_UNIT.get(a.kind if a.kind != INT else b.kind, "")
        unit = " " + unit if unit else ""
        decision = deciders.decide(op, a, b)
        difference, differing = decision.difference, decision.bits
        if difference == (0, 0):
            why = "it compares a value with itself"
        elif difference is not None and difference[0] == difference[1]:
            d = difference[0]
            why = (f"`{self._text(a.node)}` is always {abs(d)}{unit} "
                   f"{'more' if d > 0 else 'less'} than `{self._text(b.node)}`")
        elif difference is not None:
            why = (f"`{self._text(a.node)}` minus `{self._text(b.node)}` is always "
                   f"{_interval_of(*difference)}{unit}")
        elif differing:
            many = differing & (differing - 1)
            why = (f"`{self._text(a.node)}` and `{self._text(b.node)}` always differ in "
                   f"{'the bits' if many else 'the bit'} 0x{differing:04X}")
        else:
            why = " and ".join(f"`{self._text(side.node)}` is {_interval(side)}"
                               for side in (a, b) if not side.constant)
        self.diags.warning("W016", e.node.span, f"`{text}` is always {truth}: {why}",
                           help="compare with a value that can fall on either side, or drop "
                                "the comparison")

    def _divisor(self, b: Expr, op: str) -> bool:
        if b.lo == b.hi == 0:
            self.diags.error("E049", b.node.span,
                             f"`{op}` by `{self._text(b.node)}`, which is always 0",
                             help="divide by something else; at run time it would give 0")
            return False
        if b.lo <= 0 <= b.hi:
            text = self._text(b.node)
            self.diags.warning("W014", b.node.span,
                               f"`{text}` can be 0 ({b.lo}..{b.hi}): `{op}` by 0 gives 0",
                               help=f"if 0 is not what you want then, divide by "
                                    f"`max({text}, 1)`")
        return True

    def _store(self, e: Expr) -> Expr:
        """`e` where it is stored (a variable, an array element, an
        argument): saturated to 16 bits, which overflow.py warns of where
        `e`'s interval leaves them."""
        if e.kind == BOOL or arith.fits16(e.lo, e.hi):
            return e
        lo, hi = arith.interval("sat", (e.lo, e.hi))
        return self._fold(Expr("sat", e.kind, lo, hi, (e,), node=e.node, bare=e.bare))

    @staticmethod
    def _fold(e: Expr) -> Expr:
        """An operation on constants is a constant (random excepted); so is
        a comparison that decided.py decides (by the sides' intervals, the
        interval of their difference, or their bits)."""
        args = e.args
        if e.op in COMPARISONS:
            a, b = args
            decision = deciders.decide(e.op, a, b)
            if decision is None:
                return e
            decided = decision.value
            return Expr("num", BOOL, decided, decided, value=decided, node=e.node)
        if e.op in ("and", "or", "not"):
            values = [a.value for a in args if a.op == "num"]
            if e.op == "not" and values:
                v = int(not values[0])
            elif e.op == "and" and (0 in values or len(values) == 2):
                v = int(all(values) and len(values) == 2)
            elif e.op == "or" and (1 in values or len(values) == 2):
                v = int(any(values))
            else:
                return e
            return Expr("num", BOOL, v, v, value=v, node=e.node)
        if not args or not all(a.op == "num" for a in args) or e.op == "random":
            return e
        # the exact value, as the runtime computes it (an interval, as of
        # `%`, may be wider than the one value of constant operands); its
        # operands stay: overflow.py looks for an operation that saturated
        v = _EXACT[e.op](*(a.value for a in args))
        return Expr("num", e.kind, v, v, args, value=v, node=e.node, bare=e.bare,
                    name="sat" if e.op == "sat" else None)

    # -- uses of expressions --

    def _condition(self, node) -> Optional[Expr]:
        """The condition of `when` or `if`."""
        e = self._expr(node)
        if e is None or not self._is_bool(e, "a rule's condition"):
            return None
        self._overflow(e)
        return e

    def _dynamic_arg(self, value, p, call_name: str) -> Optional[Expr]:
        """An argument computed while the program runs, for parameter `p`."""
        e = self._expr(value)
        if e is None or not self._is_number(e, _code(p.name)):
            return None
        e = self._adapt(e, p.kind)
        if e.kind != p.kind:
            self.diags.error("E019", value.span,
                             f"{_code(p.name)} expects {describe_kind(p.kind)}, but "
                             f"`{self._text(value)}` is {_kind_word(e.kind)}",
                             help=convert.conversion(value, e.kind, p.kind)
                             or self._kind_help(p.kind, p.name))
            return None
        exact = e
        e = self._store(e)
        self._overflow(e, top=p.kind != SPEED)      # a speed's own range is W013's
        if p.kind == SPEED:
            e, stored = exact, e
            top = self.geo.max_speed
            if e.hi > top or e.lo < -top:
                v = e.hi if e.hi > top else e.lo
                where = "above max_speed" if v > 0 else "below -max_speed"
                self.diags.warning(
                    "W013", value.span,
                    f"{p.name} can reach {v} steps/s{_how(e, v == e.hi)}: {where} "
                    f"{'-' if v < 0 else ''}{top:.0f}; the runtime clamps it",
                    help=Fix(value.span, f"clamp({self._text(value)}, -{top:.0f}, {top:.0f})",
                             f"clamp it to -{top:.0f}..{top:.0f}: `clamp(..., -{top:.0f}, "
                             f"{top:.0f})`"))
            e = stored
        return e


def _how(e: Expr, high: bool) -> str:
    """` (300 + 4095)`: the operands that give an extreme of `e`."""
    if len(e.args) != 2 or e.op not in ("+", "-", "*", "/"):
        return ""
    a, b = e.args
    if e.op == "+":
        x, y = (a.hi, b.hi) if high else (a.lo, b.lo)
    elif e.op == "-":
        x, y = (a.hi, b.lo) if high else (a.lo, b.hi)
    else:
        pairs = [(x, y) for x in (a.lo, a.hi) for y in (b.lo, b.hi)
                 if e.op == "*" or y != 0]
        f = arith.BINARY[e.op]
        target = e.hi if high else e.lo
        found = [pr for pr in pairs if f(*pr) == target]
        if not found:
            return ""
        x, y = found[0]
    return f" ({x} {e.op} {y})" if y >= 0 else f" ({x} {e.op} ({y}))"
