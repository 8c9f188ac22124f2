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


# ---- the bitwise operators: 16-bit patterns ------------------------------------------
#
# `&`, `|`, `^`, `~`, `<<` and `>>` work on the 16-bit two's complement
# pattern of ints in -32768..32767 (the checker saturates an operand
# outside, as where it is stored) and give such an int, on every target
# (runtime_c/rt_lang.c: rt_shl, rt_shr). A shift by a negative count
# shifts the other way; by 16 or more it leaves no bit of the value: `<<`
# gives 0, `>>` the sign (0 or -1). `>>` keeps the sign (it rounds towards
# minus infinity: -5 >> 1 is -3); `<<` drops the bits shifted past the
# 16th, so that its result can differ from a * 2**n.

BITWISE = ("&", "|", "^", "<<", ">>")


def int16(v: int) -> int:
    """The int of a 16-bit pattern (its low 16 bits)."""
    v &= 0xFFFF
    return v - 0x10000 if v & 0x8000 else v


def bit_and(a: int, b: int) -> int:
    return a & b        # Python's ints are two's complement of any width: exact


def bit_or(a: int, b: int) -> int:
    return a | b


def bit_xor(a: int, b: int) -> int:
    return a ^ b


def bit_not(a: int) -> int:
    return ~a


def shl(a: int, n: int) -> int:
    if n < 0:
        return shr(a, -n)
    return 0 if n >= 16 else int16(a << n)


def shr(a: int, n: int) -> int:
    if n < 0:
        return shl(a, -n)
    return a >> min(n, 15)


BITS = {"&": bit_and, "|": bit_or, "^": bit_xor, "<<": shl, ">>": shr}


def _ones(v: int) -> int:
    """The smallest 2**k - 1 >= v (v >= 0)."""
    return (1 << v.bit_length()) - 1


def _nonnegative(op: str, a: tuple, b: tuple) -> tuple:
    """`a op b` over intervals of ints >= 0."""
    if op == "&":
        return 0, min(a[1], b[1])
    if op == "|":
        return max(a[0], b[0]), _ones(max(a[1], b[1]))
    return 0, _ones(max(a[1], b[1]))       # ^


def _not(a: tuple) -> tuple:
    return -a[1] - 1, -a[0] - 1


def _signed(op: str, a: tuple, b: tuple) -> tuple:
    """`a op b` where each interval is on one side of 0, from the identities
    of `~` (which maps the negative ints onto the others): a & b is
    ~(~a | ~b), a | b is ~(~a & ~b), ~a ^ ~b is a ^ b, ..."""
    neg_a, neg_b = a[1] < 0, b[1] < 0
    if neg_a and not neg_b:
        a, b, neg_a, neg_b = b, a, False, True
    if not neg_b:                                       # both >= 0
        return _nonnegative(op, a, b)
    nb = _not(b)
    if not neg_a:                                       # a >= 0 > b
        if op == "&":                                   # a & ~nb: a's bits, fewer
            return 0, a[1]
        if op == "|":                                   # ~(nb & ~a)
            return _not((0, nb[1]))
        return _not(_nonnegative("^", a, nb))           # ~(a ^ nb)
    na = _not(a)                                        # both < 0
    if op == "&":
        return _not(_nonnegative("|", na, nb))
    if op == "|":
        return _not(_nonnegative("&", na, nb))
    return _nonnegative("^", na, nb)


def _sides(a: tuple) -> list:
    """An interval cut at 0: its negative part and the rest."""
    parts = []
    if a[0] < 0:
        parts.append((a[0], min(a[1], -1)))
    if a[1] >= 0:
        parts.append((max(a[0], 0), a[1]))
    return parts


def bits_interval(op: str, a: tuple, b: tuple = None) -> tuple:
    """The interval of a bitwise operation over 16-bit operand intervals:
    every value it can give lies in it (tests/runtime/test_language.py
    draws values inside and checks)."""
    if op == "~":
        return _not(a)
    if op in ("<<", ">>"):
        f = BITS[op]
        lo = hi = None
        # (every count beyond -16..16 gives what -16 or 16 gives)
        for n in range(min(max(b[0], -16), 16), min(max(b[1], -16), 16) + 1):
            left = n if op == "<<" else -n                      # a shift to the left by
            if 0 < left < 16 and not fits16(a[0] << left, a[1] << left):
                low, high = INT16_MIN, INT16_MAX            # bits reach the sign
            else:
                low, high = sorted((f(a[0], n), f(a[1], n)))     # monotone in a
            lo = low if lo is None else min(lo, low)
            hi = high if hi is None else max(hi, high)
        return lo, hi
    found = [_signed(op, x, y) for x in _sides(a) for y in _sides(b)]
    return min(f[0] for f in found), max(f[1] for f in found)


def shift_loses(a: tuple, n: tuple) -> tuple | None:
    """Where `a << n` can differ from a * 2**n (a bit shifted past the 16th
    or into the sign), the exact interval of a * 2**n over the counts >= 0
    that do, with the largest such count; else None (W020)."""
    exact_lo = exact_hi = most = None
    for k in range(min(max(n[0], 0), 16), min(max(n[1], 0), 16) + 1):
        lo, hi = a[0] << k, a[1] << k
        if (lo, hi) != (0, 0) and not fits16(lo, hi):
            exact_lo = lo if exact_lo is None else min(exact_lo, lo)
            exact_hi = hi if exact_hi is None else max(exact_hi, hi)
            most = k
    return None if exact_lo is None else (exact_lo, exact_hi, most)
