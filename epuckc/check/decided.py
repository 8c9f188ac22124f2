"""The comparisons the checker decides, and why: a comparison whose value
is the same whatever the variables and readings are is folded to that
value (with W016, exprs.py), so that the C never holds one. A C compiler
decides some itself and, under -Werror, refuses the program for it (gcc's
-Wtautological-compare on `(x & 0x8001) == -1`, the AVR's and the dsPIC's
-Wstrict-overflow on `c + v >= v` with a `c` it knows): whatever it can
decide from the same facts, the checker decides first.

Three deciders (`decide`), each sound (a comparison it decides has that
value for every value its sides can take), each blind where the others see:
- by the sides' intervals (`by_intervals`): they do not overlap;
- by `difference`: the interval of `a - b`, the two sides taken as sums of
  parts times numbers where the parts they share cancel (`v + 5 > v`,
  `c + v >= v` with `c` >= 0);
- by their bits (`differing_bits`): `==` and `!=` whose sides always
  differ in a bit known in both, from the constants of `&`, `|`, `^`, `~`
  and shifts (`known_bits`)."""
from __future__ import annotations

from dataclasses import dataclass
from typing import Optional

from ..stdlib import arith
from .program import Expr

_COMMUTATIVE = {"+", "*", "min", "max", "==", "!=", "and", "or", "hypot"}
_LINEAR = ("+", "-", "neg", "*")
_BITWISE = ("&", "|", "^", "~", "<<", ">>")
_ALL = 0xFFFF
_DEPTH = 24         # known_bits looks this deep through bitwise operators


@dataclass(frozen=True)
class Decision:
    """A comparison decided: its value (1 or 0), and why: by the sides'
    intervals, by `difference` (the interval of `a - b`), or by `bits` (the
    bits in which the sides always differ)."""
    value: int
    difference: Optional[tuple] = None
    bits: int = 0


def decide(op: str, a: Expr, b: Expr) -> Optional[Decision]:
    """`a op b` decided by the first decider that can, else None."""
    value = by_intervals(op, a, b)
    if value is not None:
        return Decision(value)
    d = difference(a, b)
    if d is not None:
        truths = {arith.COMPARE[op](d[0], 0), arith.COMPARE[op](d[1], 0)}
        straddles = op in ("==", "!=") and d[0] < 0 < d[1]     # 0, and others, in it
        if len(truths) == 1 and not straddles:
            return Decision(int(truths.pop()), difference=d)
    if op in ("==", "!="):
        bits = differing_bits(a, b)
        if bits:
            return Decision(int(op == "!="), bits=bits)
    return None


def by_intervals(op: str, a: Expr, b: Expr) -> Optional[int]:
    """The value (1 or 0) of `a op b` where the intervals of its sides
    decide it, else None."""
    if a.hi < b.lo or a.lo > b.hi or (a.lo == a.hi == b.lo == b.hi):
        corners = {arith.COMPARE[op](x, y) for x in (a.lo, a.hi) for y in (b.lo, b.hi)}
        if len(corners) == 1:
            return int(corners.pop())
    return None


def difference(a: Expr, b: Expr) -> Optional[tuple]:
    """The interval of `a - b` (one value when it is the same whatever the
    variables and readings are: `v + 5 - 200` and `v`, -195), else None:
    both as sums of numbers times parts that are not sums (a variable, a
    reading, `v / 2`), where equal parts are the same tree up to the order
    of the operands of `+`, `*`, `min`, ... , and cancel; the parts left
    give their intervals. None with a `random` (each call draws anew). A C
    compiler folds such a comparison itself (`X - c <= X`) and warns, on
    the dsPIC's and the AVR's gcc, that it assumes no overflow."""
    table: dict = {}
    bounds: dict = {}
    fa, fb = _linear(a, table, bounds), _linear(b, table, bounds)
    if fa is None or fb is None:
        return None
    terms = dict(fa[1])
    for key, k in fb[1].items():
        terms[key] = terms.get(key, 0) - k
    lo = hi = fa[0] - fb[0]
    for key, k in terms.items():
        if k:
            low, high = bounds[key]
            lo, hi = lo + min(k * low, k * high), hi + max(k * low, k * high)
    return lo, hi


def linear_atom(a: Expr, b: Expr) -> Optional[tuple]:
    """(part, k, c) where `a - b` is `c + k * part` whatever the values
    are, `part` a variable or a reading and k not 0 (`v0 - 1000 == -v0`:
    2 * v0 - 1000), else None: what conditions.py reads as a bound of it."""
    table: dict = {}
    bounds: dict = {}
    trees: dict = {}
    fa, fb = _linear(a, table, bounds, trees), _linear(b, table, bounds, trees)
    if fa is None or fb is None:
        return None
    terms = dict(fa[1])
    for key, k in fb[1].items():
        terms[key] = terms.get(key, 0) - k
    terms = {key: k for key, k in terms.items() if k}
    if len(terms) != 1:
        return None
    (key, k), = terms.items()
    part = trees[key]
    if part.op not in ("var", "read"):
        return None
    return part, k, fa[0] - fb[0]


def _linear(e: Expr, table: dict, bounds: dict, trees: Optional[dict] = None):
    """`e` as (number, {part: factor}): the sum of its parts times their
    factors plus the number, computed as the runtime does (exactly) where
    no sum or product in it can leave 32 bits, and a part where one can
    (it saturates); None with a `random` in it. A part is a number that
    stands for its tree: `table` gives each tree (its operation and the
    numbers of its operands) its number, the same for equal trees of the
    two sides compared (a key of its own that held its operands' keys
    grew with each level, their quotes escaped again, twice as long: a
    depth of 200 did not fit in memory); `bounds` each part's interval
    (its first tree's: equal trees have equal intervals), `trees` (when
    given) that tree. A loop, not recursion (limits.py)."""
    keys: dict = {}     # id -> the tree's number in `table`, None with a random
    forms: dict = {}    # id -> (number, parts), None with a random
    stack = [(e, False)]
    while stack:
        x, done = stack.pop()
        if not done:
            stack.append((x, True))
            stack.extend((arg, False) for arg in x.args)
            continue
        parts = [keys[id(arg)] for arg in x.args]
        if x.op == "random" or None in parts:
            keys[id(x)] = forms[id(x)] = None
            continue
        if x.op in _COMMUTATIVE:
            parts.sort()
        shape = (x.op, repr(x.value), x.name, tuple(parts))
        key = table.get(shape)
        if key is None:
            key = table[shape] = len(table)
        keys[id(x)] = key
        args = [forms[id(arg)] for arg in x.args]
        exact = arith.exact(x.op, *[(arg.lo, arg.hi) for arg in x.args]) \
            if x.op in _LINEAR else None
        if x.op == "num":
            forms[id(x)] = (x.value, {})
        elif exact is None or not arith.fits32(*exact):
            forms[id(x)] = (0, {key: 1})            # a part (or it may saturate)
            bounds.setdefault(key, (x.lo, x.hi))
            if trees is not None:
                trees.setdefault(key, x)
        elif x.op == "neg":
            forms[id(x)] = _scaled(args[0], -1)
        elif x.op == "*":
            (n, p), (m, q) = args
            if p and q:
                forms[id(x)] = (0, {key: 1})        # a product of two variables
                bounds.setdefault(key, (x.lo, x.hi))
                if trees is not None:
                    trees.setdefault(key, x)
            else:
                forms[id(x)] = _scaled(args[1], n) if not p else _scaled(args[0], m)
        else:
            forms[id(x)] = _summed(args[0], args[1], 1 if x.op == "+" else -1)
    return forms[id(e)]


def _scaled(form, k: int):
    n, parts = form
    return n * k, {key: v * k for key, v in parts.items()}


def _summed(a, b, sign: int):
    parts = dict(a[1])
    for key, v in b[1].items():
        parts[key] = parts.get(key, 0) + sign * v
    return a[0] + sign * b[0], parts


def differing_bits(a: Expr, b: Expr) -> int:
    """The bits (of the low 16) in which `a` and `b` always differ: known
    in both, and not the same. Two ints that differ in a low bit differ."""
    if a.op not in _BITWISE and b.op not in _BITWISE:
        return 0
    (ma, va), (mb, vb) = known_bits(a), known_bits(b)
    return ma & mb & (va ^ vb)


def known_bits(e: Expr, depth: int = _DEPTH, seen: Optional[dict] = None) -> tuple:
    """(mask, bits): the bits of the low 16 of `e`'s value that are the
    same for every value it can take (mask), and what they are. The
    operands of the bitwise operators are 16-bit ints (check/bits.py).
    Each node once (`seen`: a tree that shares a node costs its nodes)."""
    if seen is None:
        seen = {}
    key = id(e)
    if key not in seen:
        seen[key] = _known_bits(e, depth, seen)
    return seen[key]


def _known_bits(e: Expr, depth: int, seen: dict) -> tuple:
    if e.lo == e.hi:
        return _ALL, e.lo & _ALL
    if e.op in _BITWISE and depth > 0:
        sides = [known_bits(arg, depth - 1, seen) for arg in e.args]
        if e.op == "~":
            (m, v), = sides
            return m, ~v & m
        (ma, va), (mb, vb) = sides
        zeros_a, zeros_b = ma & ~va, mb & ~vb
        if e.op == "&":
            ones, zeros = va & vb & ma & mb, zeros_a | zeros_b
            return ones | zeros, ones
        if e.op == "|":
            ones, zeros = (va & ma) | (vb & mb), zeros_a & zeros_b
            return ones | zeros, ones
        if e.op == "^":
            return ma & mb, (va ^ vb) & ma & mb
        count = e.args[1]
        if count.lo == count.hi and 0 <= count.lo < 16:
            n = count.lo
            if e.op == "<<":
                low = (1 << n) - 1
                return ((ma << n) | low) & _ALL, (va << n) & _ALL
            top = _ALL & ~(_ALL >> n)           # `>>` copies the sign bit
            sign_mask, sign = (top, top if va & 0x8000 else 0) if ma & 0x8000 else (0, 0)
            return (ma >> n) | sign_mask, (va >> n) | sign
    return _of_interval(e.lo, e.hi)


def _of_interval(lo: int, hi: int) -> tuple:
    """The known bits of every int in [lo, hi]: the common high bits of
    its ends, where it lies on one side of 0 within 16 bits (where the low
    16 bits of its ints grow with them)."""
    if not (0 <= lo or hi < 0) or not arith.fits16(lo, hi):
        return 0, 0
    a, b = lo & _ALL, hi & _ALL
    mask = _ALL & ~((1 << (a ^ b).bit_length()) - 1)
    return mask, a & mask
