"""The bitwise operators in expressions (`&`, `|`, `^`, `~`, `<<`, `>>`):
their operands are plain numbers taken as their 16 bits, their intervals
and values those of stdlib/arith.py; W020 for a shift that can drop bits is
overflow.py's. The checker (a `Checker`) is passed in."""
from __future__ import annotations

from typing import Optional

from ..stdlib import arith
from ..stdlib.units import ANGLE, DISTANCE, DURATION, INT, SPEED
from .messages import _kind_word
from .program import Expr

_UNIT = {DISTANCE: "mm", SPEED: "steps/s", ANGLE: "deg", DURATION: "ms"}


def operand(ck, e: Expr, op: str) -> Optional[Expr]:
    """An operand of a bitwise operator: a plain number [E048], taken as its
    16 bits (saturated first where it can leave them, which W020 says)."""
    if not ck._is_number(e, f"`{op}`"):
        return None
    if e.kind != INT:
        text = ck._text(e.node)
        ck.diags.error("E048", e.node.span,
                       f"`{op}` works on the bits of plain numbers, but `{text}` is "
                       f"{_kind_word(e.kind)}",
                       help=f"divide it by its unit first (`{text} / 1 "
                            f"{_UNIT.get(e.kind, 'mm')}`), or keep the bits in a plain variable")
        return None
    return ck._store(e)


def operation(ck, op: str, args: tuple, node) -> Optional[Expr]:
    """`a op b`, or `~a`: its Expr with its interval, folded where constant."""
    checked = [operand(ck, a, op) for a in args]
    if None in checked:
        return None
    lo, hi = arith.bits_interval(op, *[(a.lo, a.hi) for a in checked])
    return ck._fold(Expr(op, INT, lo, hi, tuple(checked), node=node,
                         bare=all(a.bare for a in checked)))
