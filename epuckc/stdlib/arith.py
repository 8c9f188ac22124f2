"""The language's arithmetic, exactly as the runtime computes it
(runtime_c/rt_lang.c). Inside an expression every value is exact while it
fits 32 bits, and an operation whose result would not saturates at
-2147483648..2147483647 (`sat32`); a value is saturated to 16 bits,
-32768..32767, only where it is stored: in a variable, an array element or
an argument (`sat`, the runtime's rt_sat16). Division truncates towards
zero, and division or `%` by zero gives 0. The checker folds constants and
bounds intervals with these functions; a property test runs them against
the C runtime (tests/runtime/test_language.py).
"""
from __future__ import annotations

INT16_MIN, INT16_MAX = -32768, 32767
INT32_MIN, INT32_MAX = -2**31, 2**31 - 1


def sat(v: int) -> int:
    """A value as it is stored: saturated to 16 bits."""
    return INT16_MIN if v < INT16_MIN else INT16_MAX if v > INT16_MAX else v


def sat32(v: int) -> int:
    """An intermediate value: saturated to 32 bits."""
    return INT32_MIN if v < INT32_MIN else INT32_MAX if v > INT32_MAX else v


def fits16(lo: int, hi: int) -> bool:
    return INT16_MIN <= lo and hi <= INT16_MAX


def fits32(lo: int, hi: int) -> bool:
    return INT32_MIN <= lo and hi <= INT32_MAX


def add(a: int, b: int) -> int:
    return sat32(a + b)


def sub(a: int, b: int) -> int:
    return sat32(a - b)


def mul(a: int, b: int) -> int:
    return sat32(a * b)


def _truncated(a: int, b: int) -> int:
    q = abs(a) // abs(b)
    return q if (a < 0) == (b < 0) else -q


def div(a: int, b: int) -> int:
    return 0 if b == 0 else sat32(_truncated(a, b))


def mod(a: int, b: int) -> int:
    if b == 0:
        return 0
    r = abs(a) % abs(b)
    return sat32(-r if a < 0 else r)


def neg(a: int) -> int:
    return sat32(-a)


def absolute(a: int) -> int:
    return sat32(abs(a))


def clamp(x: int, lo: int, hi: int) -> int:
    """`clamp(x, lo, hi)`: lo when x < lo, else hi when x > hi (so hi wins
    when lo > hi)."""
    return hi if max(x, lo) > hi else max(x, lo)


BINARY = {"+": add, "-": sub, "*": mul, "/": div, "%": mod,
          "min": min, "max": max}
COMPARE = {"<": lambda a, b: a < b, "<=": lambda a, b: a <= b, ">": lambda a, b: a > b,
           ">=": lambda a, b: a >= b, "==": lambda a, b: a == b, "!=": lambda a, b: a != b}


# ---- intervals: [lo, hi] that hold every value an operation can give ----------

def interval(op: str, a: tuple, b: tuple = None, c: tuple = None) -> tuple:
    """The interval of `op` over operand intervals a, b (and c for clamp)."""
    if op in ("+", "-", "*"):
        f = BINARY[op]
        corners = [f(x, y) for x in a for y in b]
        return min(corners), max(corners)
    if op == "min":
        return min(a[0], b[0]), min(a[1], b[1])
    if op == "max":
        return max(a[0], b[0]), max(a[1], b[1])
    if op == "neg":
        return neg(a[1]), neg(a[0])
    if op == "abs":
        if a[0] >= 0:
            return a
        if a[1] <= 0:
            return absolute(a[1]), absolute(a[0])
        return 0, max(absolute(a[0]), a[1])
    if op == "clamp":
        # min(max(x, lo), hi) grows with each of its arguments
        return clamp(a[0], b[0], c[0]), clamp(a[1], b[1], c[1])
    if op == "sat":
        return sat(a[0]), sat(a[1])
    if op == "/":
        divisors = [d for d in (b[0], b[1], -1, 1) if b[0] <= d <= b[1] and d != 0]
        values = [div(x, d) for x in a for d in divisors]
        if b[0] <= 0 <= b[1]:
            values.append(0)
        return min(values), max(values)
    if op == "%":
        biggest = max(abs(b[0]), abs(b[1]))
        if biggest == 0:
            return 0, 0
        lo = max(a[0], -(biggest - 1)) if a[0] < 0 else 0
        hi = min(a[1], biggest - 1) if a[1] > 0 else 0
        return lo, hi
    raise ValueError(op)


def exact(op: str, a: tuple, b: tuple = None) -> tuple | None:
    """The mathematical interval of `op` over operand intervals (no
    saturation): where it leaves 32 bits the runtime saturates; None for the
    operations whose result lies within their operands' (`%`, min, ...)."""
    if op in ("+", "-", "*"):
        (a0, a1), (b0, b1) = a, b
        if op == "+":
            return a0 + b0, a1 + b1
        if op == "-":
            return a0 - b1, a1 - b0
        corners = [x * y for x in (a0, a1) for y in (b0, b1)]
        return min(corners), max(corners)
    if op == "neg":
        return -a[1], -a[0]
    if op == "abs":
        if a[0] >= 0:
            return a
        if a[1] <= 0:
            return -a[1], -a[0]
        return 0, max(-a[0], a[1])
    if op == "/":
        divisors = [d for d in (b[0], b[1], -1, 1) if b[0] <= d <= b[1] and d != 0]
        values = [_truncated(x, d) for x in a for d in divisors] or [0]
        if b[0] <= 0 <= b[1]:
            values.append(0)
        return min(values), max(values)
    return None
