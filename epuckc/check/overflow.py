"""Overflow [W020]: an operation whose exact result can leave the 16-bit
range, where the runtime saturates it (stdlib/arith.py) and the program
goes on with a wrong value and no word.

Every expression the program computes (a value assigned, an argument, a
condition) is walked once, bottom up, after the checker built it. Each
operation's exact (unsaturated) interval is computed from its operands'
intervals, which are the values the runtime really gives them (saturated
where an operand saturates); where it leaves -32768..32767, the operation
is reported at its own span with that interval and its operands'. An
operation above one that is reported is not reported again: it is the same
root cause. A motor speed whose top operation saturates is W013's (the
runtime clamps the speed anyway); operations inside it are this module's.

The intervals are those of check/exprs.py (readings' ranges, constants,
each variable's interval over every assignment): no warning where they
prove the operation inside the range. The odometry's `x` and `y` are
16-bit values whose interval is all of 16 bits, which says nothing of
where the robot is: a value that leaves its range only for a robot more
than ODOMETRY_REACH_MM from where it started (`d = WX[wp] - x`, a goal's
distance) is not reported.

A warning's fix never changes what the program computes: it writes the
saturation the runtime does where the value is stored (`min(n + 1,
32767)`, `clamp(e, -32768, 32767)`), which says that it is meant;
tests/check/test_overflow_fixes.py applies every fix and checks again.
"""
from __future__ import annotations

from typing import Optional

from ..stdlib import arith, imath
from ..stdlib.arith import INT16_MAX, INT16_MIN, INT32_MAX, INT32_MIN
from ..stdlib.units import ANGLE, DISTANCE, DURATION, SPEED
from ..diagnostics import Fix
from ..syntax import ast
from . import conditions
from .messages import _shown, _target
from .program import Expr

_UNIT = {DISTANCE: " mm", SPEED: " steps/s", ANGLE: " deg", DURATION: " ms"}
ODOMETRY = ("x", "y")
ODOMETRY_REACH_MM = 16383       # 16 m from the start: farther than any arena
_FUNCTIONS = ("abs", "min", "max", "clamp", "random")


def op_of(e: Expr) -> str:
    """The operation of an Expr; a folded constant (op "num") that was an
    operation keeps its operands, and its node says which one it was."""
    if e.op != "num" or not e.args:
        return e.op
    if e.name == "sat":                 # a constant saturated where it is stored
        return "sat"
    node = e.node
    if isinstance(node, ast.BinOp):
        return node.op
    if isinstance(node, ast.Assign):
        return "+" if node.op == "+=" else "-"
    if isinstance(node, ast.FuncCall):
        return node.name.name
    return "neg"                        # UnaryOp `-`, or a ConstRef written `-x`


def exact(op: str, args) -> Optional[tuple]:
    """The interval of `op` over its operands' intervals, unsaturated: the
    mathematical result; None for the operations that cannot overflow."""
    if op not in ("+", "-", "*", "neg", "abs", "/"):
        return None                     # `%`, min, max, clamp, random, comparisons
    return arith.exact(op, *[(a.lo, a.hi) for a in args])


def _outside(interval, bits: int = 32) -> bool:
    return not (arith.fits32 if bits == 32 else arith.fits16)(*interval)


def _range(lo: int, hi: int, kind: str) -> str:
    unit = _UNIT.get(kind, "")
    return f"{lo}{unit}" if lo == hi else f"{lo}..{hi}{unit}"


class Overflow:
    """The checker's overflow warnings (a part of Checker)."""

    def _guarded_body(self, body: ast.ActionBody, guard: Optional[Expr]) -> list:
        """A rule's steps (names.py's `_body`), its first step checked with
        the intervals its guard leaves its variables: the guard is evaluated
        just before the step runs, in the same poll, so `if n < 3 do n += 1`
        gives `n` 1..3. A variable is back to its whole interval after the
        first call that may assign it (itself, a named action, or an `if`
        that may)."""
        bounds = conditions.narrowed(conditions.formula(guard),
                                     {n: (v.lo, v.hi) for n, v in self.vars.items()}) \
            if guard is not None and body.steps else {}
        bounds = {n: b for n, b in bounds.items() if n in self.vars}
        if not bounds:
            return self._body(body)
        steps = [self._calls_narrowed(body.steps[0].calls, bounds)]    # (branches.py)
        for step in body.steps[1:]:
            steps.append([r for r in map(self._call, step.calls) if r is not None])
        return steps

    def _overflow(self, e: Optional[Expr], top: bool = True) -> None:
        """Reports each operation of `e` that can saturate, once per root
        cause; `top`: whether `e`'s own operation is looked at too."""
        if e is None:
            return
        saturating = set()              # ids of the Exprs at or above a report
        stack = [(e, False)]
        while stack:                    # post-order, without recursion
            node, done = stack.pop()
            if not done:
                stack.append((node, True))
                stack.extend((a, False) for a in node.args)
                continue
            if any(id(a) in saturating for a in node.args):
                saturating.add(id(node))
                continue
            if node is e and not top:
                continue
            op = op_of(node)
            if op == "sat":             # a value stored: saturated to 16 bits
                inner = node.args[0]
                if _outside((inner.lo, inner.hi), 16) and not _odometry_only(inner, 16):
                    saturating.add(id(node))
                    self._report_overflow(inner, op_of(inner), (inner.lo, inner.hi), 16)
                continue
            if op in ("<<", ">>"):      # a shift whose bits can leave the 16
                a, n = node.args
                lost = arith.shift_loses((a.lo, a.hi), (n.lo, n.hi) if op == "<<"
                                         else (-n.hi, -n.lo))
                if lost is not None:
                    saturating.add(id(node))
                    self._report_shift(node, a, n, lost)
                continue
            interval = exact(op, node.args) if node.args else None
            if interval is not None and _outside(interval) and not _odometry_only(node, 32):
                saturating.add(id(node))
                self._report_overflow(node, op, interval, 32)

    def _report_shift(self, e: Expr, a: Expr, n: Expr, lost: tuple) -> None:
        """W020 at a shift to the left that can lose bits: `a << n` is
        a * 2**n only while that fits 16 bits (stdlib/arith.py)."""
        text, operand, count = _text_of(e), _parens(a), _parens(n)
        lo, hi, most = lost
        if e.op == ">>" or op_of(e) == ">>":
            count = f"(-{count})"
        fits = [k for k in range(16) if arith.fits16(a.lo << k, a.hi << k)]
        if n.constant or not fits or e.op == ">>" or op_of(e) == ">>":
            fix = (f"if dropping them is meant, keep only the bits that stay: `({operand} & "
                   f"0x{(1 << (15 - most)) - 1:X}) << {most}` keeps the result positive"
                   if most < 15 else f"a shift by {most} keeps no bit but the lowest, in the "
                                     f"sign")
        else:
            fix = f"bound the count: `{operand} << clamp({_text_of(n)}, 0, {max(fits)})` fits"
        self.diags.warning(
            "W020", e.node.span,
            f"`{text}` can lose bits: {operand} * 2^{count} can be {_range(lo, hi, e.kind)}, "
            f"more than the 16 bits of a value hold ({INT16_MIN}..{INT16_MAX}); the bits "
            f"shifted past the 16th are dropped"
            + (f" (`{operand}` is {_range(a.lo, a.hi, a.kind)})" if not a.constant else ""),
            help=fix + "; else shift a smaller value, or multiply (`*` is exact up to 32 bits "
                       "inside an expression)")

    def _report_overflow(self, e: Expr, op: str, interval: tuple, bits: int) -> None:
        """W020 at `e`: its value can leave the 16 bits of where it is
        stored (bits 16), or an operation the 32 bits of an expression's
        values (bits 32)."""
        text = _text_of(e)
        lo, hi = interval
        low, high = (INT16_MIN, INT16_MAX) if bits == 16 else (INT32_MIN, INT32_MAX)
        if hi > high and lo < low:
            where = f"it saturates at {low} and {high}"
        else:
            where = f"it saturates at {high if hi > high else low}"
        if bits == 16:
            what = f"outside the 16-bit range of a stored value ({low}..{high})"
            where += " where it is stored"
        else:
            what = f"outside the 32-bit range of a value inside an expression ({low}..{high})"
        # the operands' intervals; for a stored value, those of its
        # variables and readings only (a long sum's parts say little)
        shown = [a for a in e.args if not isinstance(a.node, ast.Number)
                 and (bits == 32 or a.op in ("var", "read"))]
        operands = "" if isinstance(e.node, ast.Assign) or op == "sat" else \
            ", ".join(f"`{_text_of(a)}` is {_range(a.lo, a.hi, a.kind)}" for a in shown)
        leaves = all(a.op in ("var", "read", "num") for a in e.args)
        witness = _witness(e, op, hi if hi > high else lo) if lo != hi and (
            bits == 32 or leaves) else ""
        self.diags.warning(
            "W020", e.node.span,
            f"`{text}` can be {_range(lo, hi, e.kind)}, {what}{witness}: {where}"
            + (f" ({operands})" if operands else ""),
            help=_fix(e, op, interval, bits))


_FOLDED = ("+", "-", "*", "/", "%", "neg", "abs", "min", "max", "clamp", "sat")


def _odometry_only(e: Expr, bits: int) -> bool:
    """Whether `e` (its exact value: an operation's, or a value to store)
    fits `bits` once `x` and `y` are within ODOMETRY_REACH_MM of the start:
    then only a robot farther away makes it leave them. Each operation's
    interval is computed again from its operands' (a loop, not recursion);
    one the arithmetic cannot compute again keeps its own."""
    reach = {}
    stack = [(e, False)]
    found = False
    while stack:
        node, done = stack.pop()
        if id(node) in reach:
            continue
        if not done:
            stack.append((node, True))
            stack.extend((a, False) for a in node.args if id(a) not in reach)
            continue
        args = [reach[id(a)] for a in node.args]
        op = op_of(node)
        if node.op == "read" and node.name in ODOMETRY:
            found = True
            reach[id(node)] = (max(node.lo, -ODOMETRY_REACH_MM), min(node.hi, ODOMETRY_REACH_MM))
        elif node is e:             # the exact value, as the report's
            reach[id(node)] = (exact(op, [_Span(*a) for a in args]) if args else None) \
                or (node.lo, node.hi)
        elif not args or all(a == (x.lo, x.hi) for a, x in zip(args, node.args)):
            reach[id(node)] = (node.lo, node.hi)
        elif op in _FOLDED:
            reach[id(node)] = arith.interval(op, *args)
        elif op in imath.FUNCTIONS:
            reach[id(node)] = imath.interval(op, *args)
        else:
            reach[id(node)] = (node.lo, node.hi)
    return found and not _outside(reach[id(e)], bits)


class _Span:
    """An operand's interval, for exact()."""
    def __init__(self, lo: int, hi: int):
        self.lo, self.hi = lo, hi


def _witness(e: Expr, op: str, extreme: int) -> str:
    """`, e.g. 16 * 4095 = 65520`: operand values that give the extreme."""
    if len(e.args) != 2 or op not in ("+", "-", "*", "/"):
        return ""
    a, b = e.args
    for x in (a.lo, a.hi):
        for y in (b.lo, b.hi, -1, 1):
            if not b.lo <= y <= b.hi or (op == "/" and y == 0):
                continue
            got = exact(op, (_Point(x), _Point(y)))
            if got[0] == extreme:
                shown = f"({y})" if y < 0 else str(y)
                return f", e.g. {x} {op} {shown} = {extreme}"
    return ""


class _Point:
    """An operand of one value, for exact()."""
    def __init__(self, v: int):
        self.lo = self.hi = v


def _text_of(e: Expr) -> str:
    node = e.node
    return _shown(node)


def _parens(e: Expr) -> str:
    """An operand's text, parenthesised unless it is one token or call."""
    text = _text_of(e)
    return text if isinstance(e.node, (ast.Number, ast.ConstRef, ast.Ident, ast.Paren,
                                       ast.FuncCall, ast.Index)) else f"({text})"


def _saturated(text: str, lo: int, hi: int) -> str:
    """`text` bounded as the runtime's saturation where it is stored bounds
    it: the same value, said (`min(n + 1, 32767)`)."""
    if lo < INT16_MIN and hi > INT16_MAX:
        return f"clamp({text}, {INT16_MIN}, {INT16_MAX})"
    return f"min({text}, {INT16_MAX})" if hi > INT16_MAX else f"max({text}, {INT16_MIN})"


def _fix(e: Expr, op: str, interval: tuple, bits: int):
    """The fix, which never changes a value: a variable that keeps growing
    is bounded where it is given its value, and any other value to store
    is bounded where it is stored, each at what the runtime saturates it to
    (a fix that divided would change what the value means). An operation
    that leaves 32 bits inside an expression has no such fix: the help says
    what to change."""
    lo, hi = interval
    if bits == 32:
        worst = max(hi, -lo)
        return (f"the exact value ({worst} at most) needs more than 32 bits, where the runtime "
                f"saturates it: keep the operands smaller (a reading divided before it is "
                f"multiplied), or bound them with `clamp(..., lo, hi)`")
    if isinstance(e.node, ast.Assign):          # `n += v`
        name, value = _target(e.node), _shown(e.node.value)
        sign = "+" if e.node.op == "+=" else "-"
        bounded = f"{name} = {_saturated(f'{name} {sign} {value}', lo, hi)}"
        growing = arith.fits16(*exact("+", e.args[1:] * 2) or (0, 0))
        why = (f"`{name}` keeps growing: say where it stops, `{bounded}` (where it saturates "
               f"now), or reset it" if growing else
               f"the sum can leave 16 bits: say that it saturates, `{bounded}`")
        return Fix(e.node.span, bounded, why)
    bounded = _saturated(_text_of(e), lo, hi)
    return Fix(e.node.span, bounded,
               f"say that saturating is meant: `{bounded}` stores the same value; or keep "
               f"the value in range where it is computed (a guard, a smaller operand)")
