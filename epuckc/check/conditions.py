"""What conditions say about the values they compare: a checked condition
(an Expr of kind BOOL) seen as a formula over atoms `NAME OP NUMBER`, where
NAME is a variable or a reading (a comparison whose sides differ by
`k * NAME + c` is one: `v0 - 1000 != -v0` is `v0 != 500`). Arbitration asks whether two rules'
conditions can hold together (W009); the checker narrows a variable's
interval after a guard (W020, W013, W014 in the rule's first step).

The formula keeps what it can read and over-approximates the rest: a
comparison of anything else, a `random(...)`, a deep tree, counts as
"true" (it may hold), so that every conclusion drawn from it is sound:
"cannot hold together" only where no values can make both true.
"""
from __future__ import annotations

import math
from fractions import Fraction
from typing import Optional

from . import decided
from .program import BOOL, Expr

TRUE, FALSE = ("true",), ("false",)
_FLIP = {"<": ">", "<=": ">=", ">": "<", ">=": "<=", "==": "==", "!=": "!="}
_NEGATE = {"<": ">=", "<=": ">", ">": "<=", ">=": "<", "==": "!=", "!=": "=="}
MAX_DEPTH = 40          # deeper conditions count as "may hold"
MAX_CLAUSES = 256       # the disjunctive form is given up beyond this


def formula(e: Optional[Expr], positive: bool = True, depth: int = 0) -> tuple:
    """The condition `e` (or its negation) in negation normal form:
    ("and", parts), ("or", parts), ("atom", name, op, value), TRUE, FALSE."""
    if e is None or depth > MAX_DEPTH:
        return TRUE
    op = e.op
    if op == "num" and e.kind == BOOL:
        return TRUE if bool(e.value) == positive else FALSE
    if op == "not":
        return formula(e.args[0], not positive, depth + 1)
    if op in ("and", "or"):
        joined = op if positive else ("or" if op == "and" else "and")
        return (joined, tuple(formula(a, positive, depth + 1) for a in e.args))
    if op in _FLIP:
        a, b = e.args
        if a.op in ("var", "read") and b.constant:
            name, cmp, value = a.name, op, b.value
        elif b.op in ("var", "read") and a.constant:
            name, cmp, value = b.name, _FLIP[op], a.value
        else:
            return _linear_atom(op, a, b, positive)
        return ("atom", name, cmp if positive else _NEGATE[cmp], value)
    return TRUE


def _linear_atom(op: str, a: Expr, b: Expr, positive: bool) -> tuple:
    """`a op b` where `a - b` is `k * v + c` for one variable or reading v
    (`v0 - 1000 != -v0`: 2 * v0 - 1000 != 0): the atom on v it says
    (v0 != 500), or TRUE where it says nothing that atoms can hold."""
    found = decided.linear_atom(a, b)
    if found is None:
        return TRUE
    part, k, c = found
    cmp = op if positive else _NEGATE[op]
    if k < 0:                       # k * v + c op 0: -k * v - c flip(op) 0
        k, c, cmp = -k, -c, _FLIP[cmp]
    q = Fraction(-c, k)             # v op q
    whole = q.denominator == 1
    if cmp in ("==", "!="):
        if not whole:
            return FALSE if cmp == "==" else TRUE
        return ("atom", part.name, cmp, int(q))
    low, high = math.floor(q), math.ceil(q)
    value = {"<": high if not whole else int(q), "<=": low,
             ">": low, ">=": high}[cmp]
    return ("atom", part.name, cmp, value)


def conjoin(*parts) -> tuple:
    return ("and", tuple(parts))


def without(f: tuple, names) -> tuple:
    """`f` with its atoms on `names` made "may hold" (values that can change
    between the evaluations compared)."""
    if f[0] == "atom":
        return TRUE if f[1] in names else f
    if f[0] in ("and", "or"):
        return (f[0], tuple(without(p, names) for p in f[1]))
    return f


def names_of(f: tuple) -> set:
    if f[0] == "atom":
        return {f[1]}
    if f[0] in ("and", "or"):
        return set().union(*(names_of(p) for p in f[1])) if f[1] else set()
    return set()


def _clauses(f: tuple) -> Optional[list]:
    """The disjunctive form: a list of clauses, each a list of atoms; None
    when it grows beyond MAX_CLAUSES."""
    kind = f[0]
    if kind == "atom":
        return [[f]]
    if kind == "true":
        return [[]]
    if kind == "false":
        return []
    if kind == "or":
        out = []
        for p in f[1]:
            c = _clauses(p)
            if c is None:
                return None
            out += c
            if len(out) > MAX_CLAUSES:
                return None
        return out
    out = [[]]
    for p in f[1]:
        c = _clauses(p)
        if c is None:
            return None
        out = [a + b for a in out for b in c]
        if len(out) > MAX_CLAUSES:
            return None
    return out


def _clause_bounds(clause, base) -> Optional[dict]:
    """Each name's interval under a conjunction of atoms (None: no value
    satisfies it); `base`: name -> the interval its values lie in."""
    bounds, excluded = {}, {}
    for _, name, op, v in clause:
        lo, hi = _bound(*(bounds.get(name) or base.get(name, _WHOLE)), op, v)
        if op == "!=":
            excluded.setdefault(name, set()).add(v)
        if lo > hi:
            return None
        bounds[name] = (lo, hi)
    for name, points in excluded.items():
        lo, hi = _trim(*(bounds.get(name) or base.get(name, _WHOLE)), points)
        if lo > hi:
            return None
        bounds[name] = (lo, hi)
    return bounds


def boxes(f: tuple, base: dict) -> Optional[list]:
    """The values where `f` holds, as boxes: per clause of its disjunctive
    form that some values satisfy, each name's interval and the values
    `!=` excludes from it, (bounds, excluded); None when too large."""
    found = _clauses(f)
    if found is None:
        return None
    out = []
    for clause in found:
        bounds = _clause_bounds(clause, base)
        if bounds is not None:
            excluded = {}
            for _, name, op, v in clause:
                if op == "!=":
                    excluded.setdefault(name, set()).add(v)
            out.append((bounds, excluded))
    return out


def _meet(x: tuple, y: tuple) -> bool:
    """Whether two boxes share a value."""
    (bx, ex), (by, ey) = x, y
    if len(by) < len(bx):
        bx, by = by, bx
    for name, (lo, hi) in bx.items():
        other = by.get(name)
        if other is None:
            continue
        lo, hi = max(lo, other[0]), min(hi, other[1])
        if lo > hi:
            return False
        points = ex.get(name, set()) | ey.get(name, set())
        if points and hi - lo + 1 <= len(points) and \
                sum(lo <= p <= hi for p in points) == hi - lo + 1:
            return False
    return True


def boxes_meet(a: list, b: list) -> bool:
    """Whether some box of `a` and some box of `b` share a value."""
    for x in a:
        for y in b:
            if _meet(x, y):
                return True
    return False


def satisfiable_together(a: Optional[list], b: Optional[list]) -> bool:
    """Whether two formulas, given by their boxes, can hold together (True
    when either was too large to tell)."""
    if a is None or b is None:
        return True
    return any(_meet(x, y) for x in a for y in b)


def satisfiable(f: tuple, base: dict) -> bool:
    """Whether some values (each name within its `base` interval) make `f`
    true; True when the question is too large to answer."""
    clauses = _clauses(f)
    if clauses is None:
        return True
    return any(_clause_bounds(c, base) is not None for c in clauses)


def overlap(f: tuple, base: dict) -> Optional[dict]:
    """The intervals of the names in a clause of `f` that some values
    satisfy (for a message: where two guards overlap); None if none."""
    clauses = _clauses(f)
    for c in clauses or ():
        found = _clause_bounds(c, base)
        if found is not None:
            return found
    return None


def narrowed(f: tuple, base: dict) -> dict:
    """Each name's interval wherever `f` holds: the hull over its clauses
    (a name a clause does not constrain keeps its `base` interval). Names
    of no clause are left out."""
    clauses = _clauses(f)
    if clauses is None:
        return {}
    hull: dict = {}
    live = [b for b in (_clause_bounds(c, base) for c in clauses) if b is not None]
    if not live:
        return {}
    for name in set().union(*live):
        ranges = [b.get(name, base.get(name, (-32768, 32767))) for b in live]
        hull[name] = (min(r[0] for r in ranges), max(r[1] for r in ranges))
    return hull


# A conjunction built one formula at a time (an `if` chain's branches: the
# conditions before a branch failed, its own held), as boxes over the whole
# 16-bit range: each formula's disjunctive form met with the boxes so far,
# so that a chain of n branches costs n meets, not n²/2 (issue 42). The
# intervals the names have where it is evaluated are met last
# (`narrowed_where`). A box is (bounds, excluded): each name's interval and
# the values `!=` excludes from it, at most MAX_EXCLUDED per name (beyond,
# an exclusion is forgotten: it may hold). More than MAX_BOXES boxes are
# replaced by the one box that holds them all (their hull: it may hold
# where none of them did), so that each meet costs at most 2 x MAX_BOXES.
TRUE_BOXES = (({}, {}),)
MAX_EXCLUDED = 64
MAX_BOXES = 16
_WHOLE = (-32768, 32767)


def _bound(lo: int, hi: int, op: str, v: int) -> tuple:
    """lo..hi where `x OP v` holds too (`!=` leaves it: its points are
    trimmed off the ends, _trim)."""
    if op == ">":
        return max(lo, v + 1), hi
    if op == ">=":
        return max(lo, v), hi
    if op == "<":
        return lo, min(hi, v - 1)
    if op == "<=":
        return lo, min(hi, v)
    if op == "==":
        return max(lo, v), min(hi, v)
    return lo, hi


def _trim(lo: int, hi: int, points) -> tuple:
    if points:
        while lo <= hi and lo in points:
            lo += 1
        while hi >= lo and hi in points:
            hi -= 1
    return lo, hi


def _met(box: tuple, clause: list) -> Optional[tuple]:
    """`box` and a clause (a list of atoms): None when no value satisfies both."""
    bounds, excluded = box
    bounds, touched = dict(bounds), set()
    for _, name, op, v in clause:
        lo, hi = _bound(*bounds.get(name, _WHOLE), op, v)
        if op == "!=":
            points = excluded.get(name, frozenset())
            if lo <= v <= hi and v not in points and len(points) < MAX_EXCLUDED:
                if excluded is box[1]:
                    excluded = dict(excluded)
                excluded[name] = points | {v}
        if lo > hi:
            return None
        bounds[name] = (lo, hi)
        touched.add(name)
    for name in touched:
        points = excluded.get(name)
        lo, hi = _trim(*bounds[name], points)
        if lo > hi:
            return None
        bounds[name] = (lo, hi)
    return bounds, excluded


def conjoined(boxes: tuple, f: tuple) -> tuple:
    """The boxes of the conjunction `boxes` stands for and `f`: each box met
    with each clause of `f`'s disjunctive form, those no value satisfies
    dropped; `boxes` alone when `f` is too large to tell (it may hold);
    their hull when they are more than MAX_BOXES."""
    clauses = _clauses(f)
    if clauses is None or clauses == [[]]:
        return boxes
    out = []
    for box in boxes:
        for clause in clauses:
            met = _met(box, clause)
            if met is not None:
                out.append(met)
    if len(out) > MAX_BOXES:
        return (_hull_box(out),)
    return tuple(out)


def _hull_box(boxes: list) -> tuple:
    """The one box that holds `boxes`: the names all of them bound, each
    within the hull of its intervals (the others unbounded), no exclusion."""
    names = set(boxes[0][0]).intersection(*(b[0] for b in boxes[1:]))
    return ({n: (min(b[0][n][0] for b in boxes), max(b[0][n][1] for b in boxes))
             for n in sorted(names)}, {})


def narrowed_where(boxes: tuple, base: dict) -> dict:
    """Each name of `base` (name -> the interval its values lie in) that a
    box constrains: its interval where the conjunction of `boxes` holds,
    the hull over the boxes that some values within `base` satisfy; None
    when none does (the conjunction cannot hold there)."""
    live = []
    for bounds, excluded in boxes:
        met = {}
        for name, (lo, hi) in bounds.items():
            within = base.get(name)
            if within is None:
                continue
            lo, hi = _trim(max(lo, within[0]), min(hi, within[1]), excluded.get(name))
            if lo > hi:
                break
            met[name] = (lo, hi)
        else:
            live.append(met)
    if not live:
        return None
    hull: dict = {}
    for name in sorted(set().union(*live)):
        ranges = [b.get(name, base[name]) for b in live]
        hull[name] = (min(r[0] for r in ranges), max(r[1] for r in ranges))
    return hull
