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
prove the operation inside the range.
"""
from __future__ import annotations

from typing import Optional

from ..stdlib.arith import INT16_MAX, INT16_MIN
from ..stdlib.units import ANGLE, DISTANCE, DURATION, SPEED
from ..syntax import ast
from . import conditions
from .messages import _shown
from .program import Expr

_UNIT = {DISTANCE: " mm", SPEED: " steps/s", ANGLE: " deg", DURATION: " ms"}
_FUNCTIONS = ("abs", "min", "max", "clamp", "random")


def op_of(e: Expr) -> str:
    """The operation of an Expr; a folded constant (op "num") that was an
    operation keeps its operands, and its node says which one it was."""
    if e.op != "num" or not e.args:
        return e.op
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
    if op in ("+", "-", "*"):
        (a0, a1), (b0, b1) = [(a.lo, a.hi) for a in args]
        if op == "+":
            return a0 + b0, a1 + b1
        if op == "-":
            return a0 - b1, a1 - b0
        corners = [x * y for x in (a0, a1) for y in (b0, b1)]
        return min(corners), max(corners)
    if op == "neg":
        return -args[0].hi, -args[0].lo
    if op == "abs":
        a = args[0]
        if a.lo >= 0:
            return a.lo, a.hi
        if a.hi <= 0:
            return -a.hi, -a.lo
        return 0, max(-a.lo, a.hi)
    if op == "/":
        a, b = args
        divisors = [d for d in (b.lo, b.hi, -1, 1) if b.lo <= d <= b.hi and d != 0]
        values = [_div(x, d) for x in (a.lo, a.hi) for d in divisors] or [0]
        if b.lo <= 0 <= b.hi:
            values.append(0)
        return min(values), max(values)
    return None                         # `%`, min, max, clamp, random, comparisons


def _div(a: int, b: int) -> int:
    q = abs(a) // abs(b)
    return q if (a < 0) == (b < 0) else -q


def _outside(interval) -> bool:
    return interval[0] < INT16_MIN or interval[1] > INT16_MAX


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
            interval = exact(op, node.args) if node.args else None
            if interval is not None and _outside(interval):
                saturating.add(id(node))
                self._report_overflow(node, op, interval)

    def _report_overflow(self, e: Expr, op: str, interval: tuple) -> None:
        text = _text_of(e)
        lo, hi = interval
        edge = INT16_MAX if hi > INT16_MAX else INT16_MIN
        if hi > INT16_MAX and lo < INT16_MIN:
            where = f"it saturates at {INT16_MIN} and {INT16_MAX}"
        else:
            where = f"it saturates at {edge}"
        operands = ", ".join(f"`{_text_of(a)}` is {_range(a.lo, a.hi, a.kind)}" for a in e.args
                             if not isinstance(a.node, ast.Number))
        witness = _witness(e, op, hi if hi > INT16_MAX else lo) if lo != hi else ""
        self.diags.warning(
            "W020", e.node.span,
            f"`{text}` can be {_range(lo, hi, e.kind)}, outside the 16-bit range "
            f"({INT16_MIN}..{INT16_MAX}){witness}: {where}"
            + (f" ({operands})" if operands else ""),
            help=_fix(e, op, interval))


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
    if isinstance(node, ast.Assign):
        return f"{node.target.name} {node.op} {_shown(node.value)}"
    return _shown(node)


def _parens(e: Expr) -> str:
    text = _text_of(e)
    return text if isinstance(e.node, (ast.Number, ast.ConstRef, ast.Ident, ast.Paren,
                                       ast.FuncCall)) else f"({text})"


def _fix(e: Expr, op: str, interval: tuple) -> str:
    """The fix that fits the operation: divide first, or bound it."""
    lo, hi = interval
    worst = max(hi, -lo)
    d = -(-worst // INT16_MAX)                  # the smallest divisor that fits
    if isinstance(e.node, ast.Assign):
        name, value = e.node.target.name, _shown(e.node.value)
        b = e.args[1]
        if op == "+":
            bound = f"min({name} + {value}, {INT16_MAX - max(b.hi, 0)})"
        else:
            bound = f"max({name} - {value}, {INT16_MIN + max(b.hi, 0)})"
        return (f"`{name}` keeps growing: bound it where it is given its value "
                f"(`{name} = {bound}`), or reset it")
    if op in ("+", "-", "*"):
        a, b = e.args
        clamp = "clamp an operand to the range that fits (`clamp(..., lo, hi)`)"
        if op == "*":
            scaled = b if a.op == "num" and not a.args else a
            if scaled.op == "num" and not scaled.args:
                return f"compute with smaller numbers: the product is {worst}"
            other = a if scaled is b else b
            shown = (f"{_parens(other)} * ({_parens(scaled)} / {d})" if scaled is b
                     else f"({_parens(scaled)} / {d}) * {_parens(other)}")
            return (f"divide first: `{shown}` stays inside (the result {d} times smaller), "
                    f"or {clamp}")
        fixed = [x for x in (a, b) if x.op == "num" and not x.args]
        if len(fixed) == 1:
            c, x = fixed[0].value, (b if fixed[0] is a else a)
            sign = -1 if (op == "-" and x is b) else 1       # c - x
            shift = c if op == "+" else (-c if x is a else c)
            # x (or -x) + shift within the range
            lo_x, hi_x = INT16_MIN - shift, INT16_MAX - shift
            if sign < 0:
                lo_x, hi_x = -hi_x, -lo_x
            lo_x, hi_x = max(lo_x, x.lo), min(hi_x, x.hi)
            bound = f"clamp({_text_of(x)}, {lo_x}, {hi_x})"
            shown = f"{bound} {op} {_text_of(b)}" if x is a else f"{_text_of(a)} {op} {bound}"
            return f"bound `{_text_of(x)}` first: `{shown}` stays inside"
        return (f"divide the operands first: `{_parens(a)} / {d} {op} {_parens(b)} / {d}` stays "
                f"inside (the result {d} times smaller), or {clamp}")
    return (f"clamp the operand first: `{op if op != 'neg' else '-'}"
            f"{'(' if op != 'neg' else ''}clamp({_text_of(e.args[0])}, {INT16_MIN + 1}, "
            f"{INT16_MAX}){')' if op != 'neg' else ''}`"
            if op in ("neg", "abs") else
            f"`{INT16_MIN} / -1` is {INT16_MAX + 1}: keep the dividend above {INT16_MIN} "
            f"(`clamp(..., {INT16_MIN + 1}, {INT16_MAX})`) or the divisor away from -1")
