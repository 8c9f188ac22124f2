"""The language's 16-bit arithmetic, exactly as the runtime computes it
(runtime_c/rt_lang.c): every result saturates at -32768..32767, division
truncates towards zero, and division or `%` by zero gives 0. The checker
folds constants and bounds intervals with these functions; a property test
runs them against the C runtime (tests/runtime/test_arith.py).
"""
from __future__ import annotations

INT16_MIN, INT16_MAX = -32768, 32767


def sat(v: int) -> int:
    return INT16_MIN if v < INT16_MIN else INT16_MAX if v > INT16_MAX else v


def add(a: int, b: int) -> int:
    return sat(a + b)


def sub(a: int, b: int) -> int:
    return sat(a - b)


def mul(a: int, b: int) -> int:
    return sat(a * b)


def div(a: int, b: int) -> int:
    if b == 0:
        return 0
    q = abs(a) // abs(b)
    return sat(q if (a < 0) == (b < 0) else -q)


def mod(a: int, b: int) -> int:
    if b == 0:
        return 0
    r = abs(a) % abs(b)
    return sat(-r if a < 0 else r)


def neg(a: int) -> int:
    return sat(-a)


def absolute(a: int) -> int:
    return sat(abs(a))


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
