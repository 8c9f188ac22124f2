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
          | "assign" (name: the variable; values: {"value": Expr}, the value
          given, `+=` and `-=` included)
          | "if" (values: {"branches": ((condition Expr, [ResolvedCall]), ...),
          "otherwise": [ResolvedCall] or None}; see branches_of)
    values: parameter name -> integer in runtime units (for an enumerated
    parameter, the C text of its value: `SET_LED_BODY`); for start_curve
    also `outer_steps` and `inner_speed`. An argument computed while the
    program runs is an Expr (in its natural unit); `dynamic` is then True.
    shown: parameter name -> the argument as the user wrote it.
    """
    kind: str
    name: str
    values: dict
    shown: dict
    node: object
    dynamic: bool = False


def branches_of(call: ResolvedCall) -> list:
    """The calls of each branch of an `if` (kind "if": values["branches"]
    are (condition, calls) pairs, values["otherwise"] the `else` calls or
    None), its `else` last."""
    found = [calls for _, calls in call.values["branches"]]
    if call.values["otherwise"] is not None:
        found.append(call.values["otherwise"])
    return found


def calls_within(calls) -> list:
    """`calls` and, inside each `if`, every call of every branch, in order
    (named actions are not looked into: modes.may_run splices them)."""
    out, todo = [], list(reversed(calls))
    while todo:
        call = todo.pop()
        out.append(call)
        if call.kind == "if":
            todo.extend(reversed([c for branch in branches_of(call) for c in branch]))
    return out


BOOL = "bool"          # the kind of a condition's value


@record
class Expr:
    """An expression, checked: its kind (units.py, or BOOL) and the interval
    [lo, hi] of its value in the kind's natural unit (mm, steps/s, deg, ms;
    a BOOL is 0..1).

    op: "num" (value), "var" and "read" (name), "neg", "abs", "not", a binary
    operator (`+ - * / %`, a comparison, "and", "or") or a function ("min",
    "max", "clamp", "random") over args. `bare`: a number written without a
    unit, which takes the kind of what it is combined with."""
    op: str
    kind: str
    lo: int
    hi: int
    args: tuple = ()
    value: Optional[int] = None
    name: Optional[str] = None
    node: object = None
    bare: bool = False

    @property
    def constant(self) -> bool:
        return self.op == "num"


@record
class VarInfo:
    """A variable: its kind (from its initial value), initial value, the
    interval every value it is given lies in, and its number (its order of
    declaration: the trace's id)."""
    name: str
    kind: str
    init: int
    lo: int
    hi: int
    index: int
    node: ast.VarDef
    size: int = 0           # an array's number of elements (0: not an array)
    inits: tuple = ()       # an array's initial values

    def traced(self) -> list:
        """(name, initial value) of each value the trace follows: the
        variable, or each element of an array (`counts[2]`), in the order
        of their numbers in the trace."""
        if self.size:
            return [(f"{self.name}[{k}]", v) for k, v in enumerate(self.inits)]
        return [(self.name, self.init)]


def with_interval(info: VarInfo, bounds: tuple) -> VarInfo:
    """A VarInfo of its own: `info` with the interval `bounds` (a variable
    narrowed by a condition, or solved: the declared one is never changed
    by either)."""
    lo, hi = bounds
    return VarInfo(info.name, info.kind, info.init, lo, hi, info.index, info.node, info.size,
                   info.inits)


@record
class ResolvedEvent:
    kind: str               # "standard" | "extern"
    name: str
    values: dict            # timer: time (ms); extern: its params; when: condition (Expr)
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
    guard: Optional[Expr] = None    # `if COND`


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
    const_arrays: dict = field(default_factory=dict)   # name -> its values (check/arrays.py)
    devices: frozenset = frozenset()   # the devices it uses (stdlib DEVICES)
