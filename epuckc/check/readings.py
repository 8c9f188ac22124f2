"""Readings of one of several things, written like a call: `seen(red)`,
`bearing(green)` (stdlib/table.py, `Reading.param`). Each becomes a reading
of its own name (`seen(red)`), so that every analysis of readings (intervals,
conditions, arbitration) tells `seen(red)` from `seen(green)`."""
from __future__ import annotations

from typing import Optional

from ..stdlib.table import CHOICE_READINGS, STANDARD_READINGS
from ..syntax import ast
from . import devices
from .messages import _code
from .program import Expr


def choice_reading(checker, node: ast.FuncCall) -> Optional[Expr]:
    """The Expr of `NAME(CHOICE)`, or None after reporting."""
    spec = CHOICE_READINGS[node.name.name]
    if not devices.require(checker, spec.device, spec.signature, node.name.span):
        return None
    p = spec.param
    args = node.args or ()
    example = f"{spec.name}({p.choices.values[0].name})"
    if len(args) != 1 or not isinstance(args[0], ast.PositionalArg):
        checker.diags.error("E017" if not args else "E016", node.span,
                            f"{_code(spec.name)} reads one {p.choices.what}: "
                            f"`{spec.signature}`",
                            help=f"write one of {p.choices.describe()}, e.g. `{example}`")
        return None
    c = checker._choice(args[0].value, p)
    if c is None:
        return None
    choice = next(x for x in p.choices.values if x.c == c)
    name = f"{spec.name}({choice.name})"
    reading = STANDARD_READINGS[name]
    return Expr("read", reading.kind, reading.lo, reading.hi, name=name, node=node)
