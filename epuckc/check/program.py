"""What the checker hands to lowering: a checked program, each call with its
arguments converted to the integers the runtime uses."""
from __future__ import annotations

from typing import Optional

from ..base.records import field, record
from ..stdlib.units import Geometry
from ..syntax import ast


BOOL = "bool"               # the kind of a condition (a comparison, and/or/not)


@record(frozen=True)
class Expr:
    """A checked expression: the contract between the checker and lowering.

    op is one of
      "num"                                a constant: `value`
      "var"                                a variable: `name`
      "read"                               a reading: `name`, a key of stdlib READINGS
      "neg", "abs"                         one operand
      "add", "sub", "mul", "div", "mod"    two operands
      "min", "max"                         two operands
      "clamp"                              three operands: x, lo, hi
      "random"                             two operands: lo, hi (uniform, inclusive)
      "lt", "le", "gt", "ge", "eq", "ne"   two operands of one kind; a BOOL
      "and", "or"                          two BOOL operands; "not" one
    Semantics, the same on every target: values are 16-bit; every result
    saturates at -32768..32767; division truncates; division or `%` by 0
    gives 0 at run time (the checker refuses a divisor it can see is 0).

    kind: the value's unit kind (stdlib.units: INT for a plain count,
    DISTANCE in mm, SPEED in steps/s, ANGLE in degrees, DURATION in ms, the
    natural units), or BOOL. A constant is folded to "num" in those units.
    lo, hi: the interval the value lies in (0..1 for a BOOL).
    node: the AST node it was checked from (comments, diagnostics, hover).
    """
    op: str
    kind: str
    lo: int
    hi: int
    args: tuple = ()
    value: int = 0
    name: str = ""
    node: object = None


@record
class VarInfo:
    """A variable (`var NAME = VALUE`): 16-bit, of the kind of its initial
    value; `init` in that kind's natural units; lo..hi every value an
    assignment can give it (the initial value included)."""
    name: str
    kind: str
    init: int
    lo: int
    hi: int
    node: object = None


@record
class ResolvedCall:
    """A call whose arguments are checked and converted.

    kind: "standard" | "extern" | "named" | "cancel" | "enter" (name: the mode)
          | "assign" (name: the variable)
    values: parameter name -> integer in runtime units (for an enumerated
    parameter, the C text of its value: `SET_LED_BODY`); for start_curve
    also `outer_steps` and `inner_speed`. An argument that is not constant
    is an Expr in the parameter's natural units (a distance in mm, which
    the runtime converts to steps); a constant one stays an integer,
    converted exactly as before. "assign": {"op": "=" | "+=" | "-=",
    "expr": Expr}. `set_speed`: {"left", "right"} in steps/s; `wait`:
    {"time"} in ms (a step of a sequence).
    shown: parameter name -> the argument as the user wrote it.
    """
    kind: str
    name: str
    values: dict
    shown: dict
    node: object


@record
class ResolvedEvent:
    # "standard" | "extern" | "when" (values: {"condition": Expr}, a BOOL,
    # fires on its rising edge) | "every" (values: {"time": ms}, periodic)
    # | "after" (values: {"time": ms}, once); every/after have their own
    # timer, armed when the rule is (program start, or its mode's entry)
    kind: str
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
    guard: Optional[Expr] = None    # `if COND`: a BOOL evaluated when the event fires


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
    variables: dict = field(default_factory=dict)  # name -> VarInfo, in declared order
