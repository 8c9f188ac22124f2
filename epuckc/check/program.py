"""What the checker hands to lowering: a checked program, each call with its
arguments converted to the integers the runtime uses."""
from __future__ import annotations

from typing import Optional

from ..base.records import field, record
from ..stdlib.units import Geometry
from ..syntax import ast


@record
class ResolvedCall:
    """A call whose arguments are checked and converted.

    kind: "standard" | "extern" | "named" | "cancel" | "enter" (name: the mode)
    values: parameter name -> integer in runtime units (for an enumerated
    parameter, the C text of its value: `SET_LED_BODY`); for start_curve
    also `outer_steps` and `inner_speed`.
    shown: parameter name -> the argument as the user wrote it.
    """
    kind: str
    name: str
    values: dict
    shown: dict
    node: object


@record
class ResolvedEvent:
    kind: str               # "standard" | "extern"
    name: str
    values: dict            # timer: time (ms); extern: its params
    conditions: tuple = ()  # sensor, ambient: (index, op, threshold), sorted by index
    node: object = None


@record
class ResolvedRule:
    name: Optional[str]
    event: ResolvedEvent
    repeat: bool
    body: list              # steps, each a list of ResolvedCall
    node: ast.Rule
    priority: int = 0
    mode: Optional[str] = None      # the mode whose block holds it


@record
class ExternInfo:
    kind: str               # "action" | "event"
    name: str
    params: tuple           # Param
    file: str
    node: ast.ExternDef


@record
class CheckedProgram:
    file: str
    geometry: Geometry
    actions: dict = field(default_factory=dict)   # name -> list of steps
    action_nodes: dict = field(default_factory=dict)
    externs: dict = field(default_factory=dict)   # name -> ExternInfo
    rules: list = field(default_factory=list)     # ResolvedRule
    robot_given: bool = False
    modes: list = field(default_factory=list)     # mode names, in declared order
    initial_mode: Optional[str] = None
