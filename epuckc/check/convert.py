"""The unit help: how to turn a value of one kind into another where the
program needs it, and what a fraction of a whole unit should be written as.

Kinds do not convert by themselves (an angle is not a speed), so the help
writes the conversion the docs use: divide by the value's own unit, which
leaves a plain number, and multiply by the unit wanted. A plain factor
already there takes the wanted unit: `turn = err * 6`, an angle where a
speed is wanted, becomes `err / 1 deg * 6 steps/s` (the same number, now a
speed). Values are whole numbers of their kind's natural unit (mm,
steps/s, deg, ms), so `0.8` where an angle is compared is no angle at all:
the help says the unit and, where one is, the finer unit to write it in
(`0.8 s` is `800 ms`; angles are degrees, not radians: 0.8 rad is 46 deg).
"""
from __future__ import annotations

import math
from typing import Optional

from ..diagnostics import Fix
from ..stdlib.units import ANGLE, DISTANCE, DURATION, SPEED, round_nearest
from ..syntax import ast
from .messages import _shown

UNIT = {DISTANCE: "mm", SPEED: "steps/s", ANGLE: "deg", DURATION: "ms"}
WORD = {DISTANCE: "a distance", SPEED: "a speed", ANGLE: "an angle", DURATION: "a duration"}


def _operand(node) -> str:
    """`node`'s text where `/ 1 deg` follows it: a sum in parentheses."""
    text = _shown(node)
    if isinstance(node, ast.BinOp) and node.op in ("+", "-"):
        return f"({text})"
    return text


def _bare_factor(node):
    """(the quantity, the plain number) of `X * 6` or `6 * X`, else None."""
    if not isinstance(node, ast.BinOp) or node.op != "*":
        return None
    for quantity, factor in ((node.left, node.right), (node.right, node.left)):
        if isinstance(factor, ast.Number) and factor.unit is None:
            return quantity, factor
    return None


def converted(node, have: str, want: str) -> Optional[str]:
    """The text of `node`, of kind `have`, as kind `want` (both quantities)."""
    if have not in UNIT or want not in UNIT or have == want:
        return None
    product = _bare_factor(node)
    if product is not None:
        quantity, factor = product
        return f"{_operand(quantity)} / 1 {UNIT[have]} * {_shown(factor)} {UNIT[want]}"
    return f"{_operand(node)} / 1 {UNIT[have]} * 1 {UNIT[want]}"


def conversion(node, have: str, want: str) -> Optional[Fix]:
    """A fix that turns `node` (of kind `have`) into `want` where the
    program stores or passes it, or None when the two are not quantities."""
    text = converted(node, have, want)
    if text is None:
        return None
    if _bare_factor(node) is not None:
        why = (f"{WORD[have]} does not become {WORD[want]} by itself: divide it by its unit "
               f"and give the factor the unit wanted, `{text}`")
    else:
        why = (f"{WORD[have]} does not become {WORD[want]} by itself: divide it by its unit "
               f"and multiply by the unit wanted, `{text}` (1 {UNIT[want]} for each "
               f"{UNIT[have]}: put the factor you want in place of the 1)")
    return Fix(node.span, text, why)


def mixed(op: str, left, right, a: str, b: str) -> Optional[str]:
    """The help for `left op right` of two kinds that do not combine."""
    if a not in UNIT or b not in UNIT:
        return None
    if op == "*":
        return (f"a quantity times a quantity has no kind here: make one of them a plain "
                f"number, `{_operand(left)} / 1 {UNIT[a]} * {_shown(right)}`")
    if op in ("/", "%"):
        return (f"divide like by like, or make them plain numbers first: "
                f"`{_operand(left)} / 1 {UNIT[a]}` and `{_operand(right)} / 1 {UNIT[b]}`")
    # convert the side that is not a number written with its unit (`5 steps/s`
    # says which kind is meant)
    if isinstance(right, ast.Number) and right.unit is not None \
            and not (isinstance(left, ast.Number) and left.unit is not None):
        left, right, a, b = right, left, b, a
    verb = "add or subtract" if op in ("+", "-") else "compare"
    return (f"{verb} like with like; to use {WORD[b]} as {WORD[a]}, convert it: "
            f"`{converted(right, b, a)}`")


def is_fraction(node) -> bool:
    """A number without a unit that is not whole (`0.8`)."""
    return node.__class__ is ast.Number and node.unit is None and node.value != int(node.value)


def fraction_beside(checker, node: ast.BinOp) -> None:
    """E038 for `abs(err) > 0.8`: the other side says what unit the
    fraction is in, and the help what to write."""
    number, other = (node.left, node.right) if is_fraction(node.left) else (node.right, node.left)
    kind = None
    if not is_fraction(other):
        e = checker._expr(other)
        kind = e.kind if e is not None and node.op not in ("*", "/", "%") else None
    checker._whole(number, number.value, kind)
    return None


def fraction(number: float, kind: Optional[str]) -> Optional[str]:
    """What a fraction where `kind` is wanted should be written as, or None
    (a plain number: no unit to speak of)."""
    if kind == ANGLE:
        degrees = round_nearest(math.degrees(number))
        return (f"angles are whole degrees, not radians: `{number:g}` is {number:g} deg, "
                f"which would round to {round_nearest(number)}; if radians were meant, "
                f"{number:g} rad is `{degrees} deg`")
    if kind == DISTANCE:
        return (f"distances are whole millimetres: `{number:g}` is {number:g} mm; write "
                f"`{round_nearest(number)}`, or the unit it is in: `{number:g} cm` is "
                f"{round_nearest(number * 10)} mm, `{number:g} m` {round_nearest(number * 1000)} mm")
    if kind == DURATION:
        return (f"durations are whole milliseconds: write `{number:g} s`, which is "
                f"{round_nearest(number * 1000)} ms, or `{round_nearest(number)} ms`")
    if kind == SPEED:
        return (f"speeds are whole steps/s: write `{round_nearest(number)}`, or in mm/s: "
                f"`{number:g} mm/s`, `{number:g} cm/s`")
    return None
