"""An assignment's value computed again for other intervals of the
variables it reads, from the checked expression its first evaluation gave.

The fixpoint of check/ranges.py asks each assignment of a component for
its value again and again, each pass with other intervals, and walking the
syntax through the checker each time (kinds, units, constants, devices,
diagnostics captured and dropped) was nearly all of a large component's
solve. What of an assignment's value depends on the intervals is only its
operators' interval arithmetic; the rest (the operators and functions, the
kinds and conversions, the constants folded, the readings' intervals) is
decided by the syntax and the declarations, and the checked expression
(program.Expr) holds it. So the first evaluation's Expr, made into a
`Plan` here, gives the value for any intervals through the same
stdlib/arith.py functions the checker calls, in a loop over its operators.

Only what the checker computes so is planned: numbers, readings, scalar
variables, `+ - * / % neg abs min max clamp`, and the saturation to 16 bits
where the value is stored. Anything else (bitwise operators, arrays'
elements, `random`, the math functions, ...) gives no plan and the checker
evaluates it every time, as before. A plan answers None where the checker
would report an error that depends on an interval (a divisor that is
always 0, E049), and MISMATCH where what it reads is no longer what the
plan was made for (a variable of another kind, or an array): the checker
then evaluates it. tests/check/test_reeval.py compares plans with the
checker over generated programs and intervals.
"""
from __future__ import annotations

from typing import Optional

from ..stdlib import arith
from .program import BOOL, Expr

# the operators a plan computes as the checker does (arith.interval)
_UNARY = frozenset(("neg", "abs"))
_BINARY = frozenset(("+", "-", "*", "min", "max"))
_DIVIDING = frozenset(("/", "%"))

MISMATCH = object()     # what a plan answers when the checker must evaluate


class Plan:
    """An assignment's checked value as steps in postfix order: ("num",
    interval), ("read", name, interval), ("var", name, kind), ("cur",
    name, kind), (operator, its operands' count);
    "cur" is the target's own value in `v += e` (its interval is the
    target's, as the checker gives it); `names`: the variables and
    readings it looks up; `kind` the value's, `target` the kind of the
    variable assigned when it was made (a bare number takes it)."""
    __slots__ = ("steps", "names", "kind", "target")

    def __init__(self, steps: tuple, names: frozenset, kind: str, target: str):
        self.steps, self.names, self.kind, self.target = steps, names, kind, target


def plan_of(value: Expr, target, compound: bool) -> Optional[Plan]:
    """The plan of `value`, the checker's Expr of an assignment to `target`
    (its VarInfo; `compound`: `+=` or `-=`, whose first operand is the target's own
    value), or None where it holds what a plan does not compute."""
    if value.kind == BOOL:
        return None
    root = value.args[0] if value.op == "sat" and value.args else value
    steps: list = []
    names: set = set()
    current = root.args[0] if compound and root.op in ("+", "-") and root.args else None
    todo = [(root, False)]
    while todo:
        e, done = todo.pop()
        op = e.op
        if done:
            steps.append((op, len(e.args)))
        elif op == "num":
            steps.append(("num", (e.lo, e.hi)))
        elif op == "read":          # (looked up as a variable first, and not found)
            if e.name is None:
                return None
            steps.append(("read", e.name, (e.lo, e.hi)))
            names.add(e.name)
        elif op == "var":
            if e is current:
                steps.append(("cur", target.name, e.kind))
            else:
                if e.name is None or "[" in e.name:
                    return None
                steps.append(("var", e.name, e.kind))
                names.add(e.name)
        elif (op in _UNARY and len(e.args) == 1) or (op in _BINARY and len(e.args) == 2) \
                or (op in _DIVIDING and len(e.args) == 2) or (op == "clamp" and len(e.args) == 3):
            todo.append((e, True))
            todo.extend((a, False) for a in reversed(e.args))
        else:
            return None
    if compound and current is None:
        return None
    return Plan(tuple(steps), frozenset(names), value.kind, target.kind)


def evaluate(plan: Plan, variables, bounds: dict, target):
    """The plan's (kind, lo, hi) with the variables' intervals from
    `variables` (each read noted there, as the checker's reads are) except
    those `bounds` narrows; `target` the VarInfo assigned. None where the
    checker reports an error; MISMATCH where it must evaluate."""
    if target.kind != plan.target or target.size:
        return MISMATCH
    stack: list = []
    push, pop = stack.append, stack.pop
    interval = arith.interval
    for step in plan.steps:
        op = step[0]
        if op == "num":
            push(step[1])
        elif op == "read":
            if variables.get(step[1]) is not None:
                return MISMATCH
            push(step[2])
        elif op == "var" or op == "cur":
            name = step[1]
            info = target if op == "cur" else variables.get(name)
            if info is None or info.size or info.kind != step[2]:
                return MISMATCH
            push(bounds.get(name) or (info.lo, info.hi))
        else:
            count = step[1]
            if count == 1:
                push(interval(op, pop()))
            elif count == 2:
                b = pop()
                a = pop()
                if op in _DIVIDING and b == (0, 0):
                    return None             # E049: a divisor that is always 0
                push(interval(op, a, b))
            else:
                c, b = pop(), pop()
                push(interval(op, pop(), b, c))
    lo, hi = stack[-1]
    if not arith.fits16(lo, hi):            # stored: saturated (Exprs._store)
        lo, hi = interval("sat", (lo, hi))
    return plan.kind, lo, hi
