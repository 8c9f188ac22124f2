"""Expressions as C: each checked Expr becomes one C expression over the
program's variables (`epk_v_NAME`) and the runtime's readings and
operations (runtime_c/rt_lang.c), so that the values are the same on every
target and no operation is undefined.

Inside an expression a value is exact while it fits 32 bits (stdlib/
arith.py). Each operation is printed in the cheapest C that gives that
value, decided from the checker's intervals: plain `int` arithmetic where
the exact result fits 16 bits (an int on every target), `long` where it
fits 32 (`(long)a * b`), and the runtime's saturating call where it may
not, or where C would be undefined (`/` or `%` by a divisor that can be 0
or -1 of the smallest value). A stored value that can leave 16 bits is
saturated by `rt_sat16`; C arithmetic computed in long whose value fits
16 bits is converted to int with a cast.
"""
from __future__ import annotations


from ..check.program import Expr
from ..stdlib import arith
from ..stdlib.table import READING_ARRAYS, STANDARD_READINGS

VAR_PREFIX = "epk_v_"

_CALLS = {"+": "rt_add", "-": "rt_sub", "*": "rt_mul", "/": "rt_div", "%": "rt_mod",
          "neg": "rt_neg", "abs": "rt_abs", "min": "rt_min", "max": "rt_max",
          "clamp": "rt_clamp", "random": "rt_random", "sat": "rt_sat16",
          "atan2": "rt_atan2", "hypot": "rt_hypot", "sqrt": "rt_sqrt", "sin": "rt_sin",
          "cos": "rt_cos", "<<": "rt_shl", ">>": "rt_shr"}
_C_OPS = {"<": "<", "<=": "<=", ">": ">", ">=": ">=", "==": "==", "!=": "!=",
          "and": "&&", "or": "||", "+": "+", "-": "-", "*": "*", "/": "/", "%": "%"}
# functions whose result is an int whatever their arguments
_INT_RESULT = {"random", "sat", "atan2", "sin", "cos", "argmin", "argmax", "<<", ">>"}


CONST_PREFIX = "epk_c_"


def var_name(name: str) -> str:
    """The C of a variable, or of an array variable's element `a[3]`."""
    return VAR_PREFIX + name


def base_name(name: str) -> str:
    """The variable of an element: `a` of `a[3]`."""
    return name.split("[", 1)[0]


def c_int(value: int) -> str:
    """An int literal that is an int on a 16-bit target too, or a long."""
    if value == arith.INT16_MIN:
        return "RT_INT_MIN"
    if arith.fits16(value, value):
        return str(value)
    return "RT_LONG_MIN" if value == arith.INT32_MIN else f"{value}L"


def c_expr(e: Expr, top: bool = True, readings: dict = None, consts=(),
           index_name: str = None) -> str:
    """The C text of `e`; `top`: no parentheses around its operation;
    `readings`: C names that hold readings already read (name -> C);
    `consts`: the names of the constant arrays; `index_name`: the C of the
    index of the element an assignment assigns."""
    text, is_long, level = _Printer(readings, index_name, consts).c(e, top)
    if is_long and e.op in _MUL + _ADD + ("neg",) and arith.fits16(e.lo, e.hi):
        # C arithmetic in long whose value is an int's: converted in the
        # open, where an int is wanted (gcc's -Woverflow takes the implicit
        # conversion of arithmetic it folds to a constant, `v + (-200L + -v)`,
        # for one that overflows; found by issue 42's campaign, seed 42172)
        return f"(int)({text})"
    return text if top or level == 0 else f"({text})"


_MUL, _ADD = ("*", "/", "%"), ("+", "-")
_BITS = ("&", "|", "^", "~", "<<", ">>")


class _Printer:
    """Prints an Expr; each part gives (text, is_long, level): level 0 an
    operand that needs no parentheses, 1 a product, 2 a sum, 3 a bitwise
    operation (C's
    precedence: a part is parenthesised where its parent binds tighter)."""

    def __init__(self, readings, index_name=None, consts=()):
        self.readings = readings or {}
        self.index_name = index_name    # the C of the element an assignment assigns
        self.consts = consts            # the names of the constant arrays

    def c(self, e: Expr, top: bool, wide: bool = False) -> tuple:
        """`wide`: the part is computed in long (its leftmost operand made
        one: `8L * rt_ir(0)`), as its parent's result needs."""
        op = e.op
        if op == "num":
            if wide and arith.fits16(e.value, e.value):
                return f"{e.value}L", True, 0       # (-32768L too: a long's minus)
            return c_int(e.value), not arith.fits16(e.value, e.value), 0
        if wide:
            if op in _MUL + _ADD + ("neg",) and self._plain(e):
                return self._infix(e, wide=True)
            text, is_long, level = self.c(e, True)
            if is_long:
                return text, True, level
            return f"(long){text if level == 0 else f'({text})'}", True, 0
        if op == "var":
            return var_name(e.name), False, 0
        if op == "read":
            return self.readings.get(e.name) or STANDARD_READINGS[e.name].c, False, 0
        if op == "not":
            return f"!{self.c(e.args[0], False)[0]}", False, 0
        if op == "cur":         # `a[i] += e`: the element being assigned
            return f"{var_name(e.name)}[{self.index_name}]", False, 0
        if op == "index":
            return self._element(e), False, 0
        if op in _BITS:
            return self._bits(e, top)
        if op in ("argmin", "argmax"):      # over ints where every element fits one
            items = ", ".join(self.c(a, True)[0] for a in e.args)
            if all(arith.fits16(a.lo, a.hi) for a in e.args):
                return f"rt_{op}_int((const int[]){{{items}}}, {len(e.args)})", False, 0
            return f"rt_{op}((const long[]){{{items}}}, {len(e.args)})", False, 0
        if op in _MUL + _ADD + ("neg",) and self._plain(e):
            return self._infix(e, False)
        if op in _C_OPS and op not in _MUL + _ADD:      # comparisons, and, or
            a, b = (self.c(x, False)[0] for x in e.args)
            text = f"{a} {_C_OPS[op]} {b}"
            return (text if top else f"({text})"), False, 0
        args = ", ".join(self.c(a, True)[0] for a in e.args)
        return f"{_CALLS[op]}({args})", op not in _INT_RESULT, 0

    def _element(self, e: Expr) -> str:
        """`a[i]`: the index as it is where the checker proved it inside
        the array, else clamped to it by the runtime."""
        (i,) = e.args
        size = e.value
        index = self.c(i, True)[0]
        if not (0 <= i.lo and i.hi < size):
            index = f"rt_index({index}, {size})"
        if e.name in READING_ARRAYS:
            return f"{READING_ARRAYS[e.name][1]}({index})"
        prefix = CONST_PREFIX if e.name in self.consts else VAR_PREFIX
        return f"{prefix}{e.name}[{index}]"

    def _bits(self, e: Expr, top: bool) -> tuple:
        """The bitwise operators on operands of 16 bits (the checker
        saturated any that could leave them): C's own `&`, `|`, `^`, `~`
        (two's complement ints give the same bits on every target), and
        `<<`, `>>` where C's gives the language's value (a count 0..15, a
        value >= 0 whose shifted bits stay below the sign), else the
        runtime's rt_shl, rt_shr (defined for every value and count). C
        binds these below a comparison: the operation is parenthesised
        unless it is the whole expression (level 3: any parent that
        takes it as it is parenthesises it)."""
        op, args = e.op, e.args
        if op in ("<<", ">>"):
            a, n = args
            # (a count of 16 or more is undefined in C where int is 16 bits,
            # whatever the value: `0 << 16` too)
            plain = a.lo >= 0 and 0 <= n.lo and n.hi <= 15 and (
                op == ">>" or arith.fits16(a.hi << n.hi, a.hi << n.hi))
            if not plain:       # (each operand printed once: a chain is linear)
                return f"{_CALLS[op]}({self.c(a, True)[0]}, {self.c(n, True)[0]})", False, 0
        parts = []
        for a in args:
            text, is_long, level = self.c(a, False)
            parts.append(f"({text})" if level else text)
        if op == "~":
            return f"~{parts[0]}", False, 0
        text = f"{parts[0]} {op} {parts[1]}"
        return (text, False, 3) if top else (f"({text})", False, 0)

    @staticmethod
    def _plain(e: Expr) -> bool:
        """Whether C's own operator gives the exact value: the result fits
        32 bits, and no division by 0 (or of the smallest value by -1)."""
        op, args = e.op, e.args
        ranges = [(a.lo, a.hi) for a in args]
        if op in ("/", "%"):
            b = ranges[1]
            if b[0] <= 0 <= b[1]:
                return False
            if op == "%":       # C's `%` of its type's smallest value by -1 is undefined:
                # -32768 % -1 where int is 16 bits (its operands may be ints)
                return not (b[0] <= -1 <= b[1]) or ranges[0][0] > arith.INT16_MIN
        exact = arith.exact(op, *ranges)
        return exact is not None and arith.fits32(*exact)

    def _infix(self, e: Expr, wide: bool) -> tuple:
        op = e.op
        exact = arith.exact(op, *[(a.lo, a.hi) for a in e.args]) if op != "%" else (e.lo, e.hi)
        level = 2 if op in _ADD else 1
        # int operands whose result needs long: the first one is widened
        # (so is one that a parent widens)
        wide = wide or not arith.fits16(*exact)
        parts = []
        for i, a in enumerate(e.args):
            text, is_long, inner = self.c(a, False, wide=wide and i == 0)
            # a right operand of the parent's level keeps its parentheses:
            # C groups from the left, and each part has its own C type
            if inner > level or (inner == level and i == 1) or (op == "neg" and inner):
                text = f"({text})"
            parts.append((text, is_long, a))
        wide = any(is_long for _, is_long, _ in parts)
        if op == "neg":
            operand = parts[0][0]
            return f"-({operand})" if operand.startswith("-") else f"-{operand}", wide, 0
        return f"{parts[0][0]} {_C_OPS[op]} {parts[1][0]}", wide, level


ODOMETRY = frozenset({"x", "y", "heading"})


def changes_with_time(e: Expr) -> bool:
    """Whether an expression's value can change while only time passes:
    the odometry follows the wheels, `random` is new at each evaluation
    (everything else it can read is an input or a variable)."""
    todo = [e]
    while todo:
        x = todo.pop()
        if x.op == "random" or (x.op == "read" and x.name in ODOMETRY):
            return True
        todo.extend(x.args)
    return False


def variables_of(e: Expr) -> set:
    """The names of the variables an expression's C reads (after folding:
    a variable inside a comparison that the checker decided is not read)."""
    found, todo = set(), [e]
    while todo:
        x = todo.pop()
        if x.op in ("var", "cur", "index"):
            found.add(base_name(x.name))
        todo.extend(x.args)
    return found


def indexed_arrays(e: Expr) -> set:
    """The arrays an expression indexes with a computed index."""
    found, todo = set(), [e]
    while todo:
        x = todo.pop()
        if x.op == "index":
            found.add(x.name)
        todo.extend(x.args)
    return found


def readings_of(e: Expr) -> set:
    """The names of the readings an expression reads."""
    found = {e.name} if e.op == "read" else set()
    for a in e.args:
        found |= readings_of(a)
    return found


def proximity_read(e: Expr) -> set:
    """The proximity sensors (0..7) an expression reads."""
    found = set()
    if e.op == "read" and e.name.startswith("ir") and e.name[2:].isdigit():
        found.add(int(e.name[2:]))
    for a in e.args:
        found |= proximity_read(a)
    return found
