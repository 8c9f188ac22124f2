"""The language's integer math, bit-exact as the runtime computes it
(runtime_c/rt_math.c): `atan2`, `hypot`, `sqrt`, `sin`, `cos`. The checker
folds constants with these functions and bounds results with `interval`;
tests/runtime/test_math.py runs them against the C (gcc and 16-bit avr-gcc
under simavr) and against Python's math. Conventions and error bounds:
docs/runtime.md, "Integer math".

sqrt, hypot and atan2 take 32-bit values: beyond +-(2^31 - 1) an argument
counts as +-(2^31 - 1). sin and cos reduce any integer modulo 360 exactly.
"""
from __future__ import annotations

import math

L32_MAX = 2**31 - 1

# round(1000 * sin(d deg)), d = 0..90 (rt_sin_table). Only 0, 30 and 90
# degrees give a rational sine (Niven), so no other entry is a tie and the
# float rounds correctly (tests check the margin).
SIN_TABLE = tuple(round(1000 * math.sin(math.radians(d))) for d in range(91))
# ceil(65536 * tan((j + 1/2) deg)), j = 0..44 (rt_tan_half)
TAN_HALF = tuple(math.ceil(65536 * math.tan(math.radians(j + 0.5))) for j in range(45))

# How far atan2's result may be from the exact angle, in degrees: half a
# degree of rounding, plus the table's and the halving's error (measured
# under 0.004 deg; tests hold the C to this bound).
ATAN2_ERROR = 0.5 + 0.01


def _clamp32(v: int) -> int:
    return -L32_MAX if v < -L32_MAX else L32_MAX if v > L32_MAX else v


def _round_sqrt(v: int) -> int:
    r = math.isqrt(v)
    return r + 1 if v - r * r > r else r


def sqrt(v: int) -> int:
    """round(sqrt(v)); 0 for v <= 0."""
    return 0 if v <= 0 else _round_sqrt(_clamp32(v))


def hypot(x: int, y: int) -> int:
    """round(sqrt(x*x + y*y)), saturated at 2^31 - 1."""
    x, y = _clamp32(x), _clamp32(y)
    return min(_round_sqrt(x * x + y * y), L32_MAX)


def atan2(y: int, x: int) -> int:
    """The angle of (x, y) in whole degrees, -180..180, rounded to nearest
    (to within ATAN2_ERROR); 0 at (0, 0), the sign of y (180 on the negative
    x axis)."""
    ax, ay = abs(_clamp32(x)), abs(_clamp32(y))
    while ax > 0xFFFF or ay > 0xFFFF:
        ax >>= 1
        ay >>= 1
    if ax == 0 and ay == 0:
        return 0
    swapped = ay > ax
    if swapped:
        ax, ay = ay, ax
    lo, hi = 0, 45
    while lo < hi:
        mid = (lo + hi) // 2
        if ay << 16 >= TAN_HALF[mid] * ax:
            lo = mid + 1
        else:
            hi = mid
    a = 90 - lo if swapped else lo
    if x < 0:
        a = 180 - a
    return -a if y < 0 else a


def _sin360(d: int) -> int:
    if d <= 90:
        return SIN_TABLE[d]
    if d <= 180:
        return SIN_TABLE[180 - d]
    if d <= 270:
        return -SIN_TABLE[d - 180]
    return -SIN_TABLE[360 - d]


def sin(deg: int) -> int:
    """round(1000 * sin(deg degrees)): -1000..1000, any integer deg."""
    return _sin360(deg % 360)


def cos(deg: int) -> int:
    """round(1000 * cos(deg degrees)): -1000..1000, any integer deg."""
    return _sin360((deg % 360 + 90) % 360)


FUNCTIONS = {"atan2": atan2, "hypot": hypot, "sqrt": sqrt, "sin": sin, "cos": cos}


# ---- intervals: [lo, hi] that hold every value a function can give ----------

def _min_abs(a: tuple) -> int:
    return 0 if a[0] <= 0 <= a[1] else min(abs(a[0]), abs(a[1]))


def _max_abs(a: tuple) -> int:
    return max(abs(a[0]), abs(a[1]))


def _periodic(f, a: tuple) -> tuple:
    """sin or cos over an interval of degrees: the table is monotonic
    between multiples of 90, so the extremes are at the ends or at a
    multiple of 90 inside: the exact range."""
    lo, hi = a
    if hi - lo >= 359:
        lo, hi = 0, 359
    points = [lo, hi] + list(range(lo + (-lo) % 90, hi + 1, 90))
    values = [f(d) for d in points]
    return min(values), max(values)


def _atan2_interval(y: tuple, x: tuple) -> tuple:
    """The exact angles of the box's corners (the extremes of a box that
    misses the origin, on one side of the negative x axis), widened by the
    error bound, then rounded inwards to whole degrees."""
    y = (_clamp32(y[0]), _clamp32(y[1]))
    x = (_clamp32(x[0]), _clamp32(x[1]))
    angles = []
    origin = x[0] <= 0 <= x[1] and y[0] <= 0 <= y[1]
    # the upper half plane with the x axis (0..180) and the lower (-180..0)
    for part in ((max(y[0], 0), y[1]), (y[0], min(y[1], -1))):
        if part[0] > part[1]:
            continue
        corners = [(py, px) for py in part for px in x if (py, px) != (0, 0)]
        if not corners:
            continue
        degrees = [math.degrees(math.atan2(py, px)) for py, px in corners]
        # (0, 0) is in the part: every direction between its corners' is too
        angles += [min(degrees), max(degrees)]
    if not angles:
        return 0, 0
    lo = max(-180, math.ceil(min(angles) - ATAN2_ERROR))
    hi = min(180, math.floor(max(angles) + ATAN2_ERROR))
    if origin:
        lo, hi = min(lo, 0), max(hi, 0)
    return lo, hi


def interval(name: str, a: tuple, b: tuple = None) -> tuple:
    """The interval of `name` (atan2(a, b), hypot(a, b), sqrt(a), sin(a),
    cos(a)) over argument intervals (lo, hi)."""
    if name == "sqrt":   # non-decreasing
        return sqrt(a[0]), sqrt(a[1])
    if name == "hypot":   # non-decreasing in |x| and in |y|
        return hypot(_min_abs(a), _min_abs(b)), hypot(_max_abs(a), _max_abs(b))
    if name in ("sin", "cos"):
        return _periodic(FUNCTIONS[name], a)
    if name == "atan2":
        return _atan2_interval(a, b)
    raise ValueError(name)
