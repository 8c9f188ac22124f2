"""The one table of the standard actions and events.

Each entry says what the language accepts (its parameters in the paper's
order, which is the order of positional arguments, with their kinds and
ranges), what it means (one line of documentation) and what it becomes
(the runtime call). The checker, lowering, the language reference
(docs/language.md section 3, kept equal to `reference_markdown()` by a test)
and the editor's hover and completion all read this table; none keeps a
list of its own.
"""
from __future__ import annotations

from typing import Optional

from .records import record
from .units import ANGLE, DISTANCE, DURATION, NATURAL_UNIT, SPEED

SENSOR_COUNT = 8
THRESHOLD_MAX = 4095


@record(frozen=True)
class Param:
    """A parameter: its name, its kind (units.py), and for the standard
    ones a short description and the range the checker enforces, in words
    with the codes that enforce it."""
    name: str
    kind: str
    doc: str = ""
    range: str = ""


@record(frozen=True)
class ActionSpec:
    name: str
    params: tuple
    doc: str
    runtime: str              # the runtime's action function the call becomes
    motion: bool = False      # starts a motion (ends with a `stop_motor` event)
    runtime_param: Optional[str] = None   # its parameter struct, if any

    @property
    def signature(self) -> str:
        return signature(self.name, self.params)


@record(frozen=True)
class EventSpec:
    name: str
    params: Optional[tuple]   # None: takes conditions (`sensor(ir0 > 300)`)
    doc: str
    runtime: str              # the runtime's event function
    runtime_param: Optional[str] = None   # its parameter struct, if any
    # the function keeps status->memory between polls: a compiled program
    # gives the rule a long of RAM for it (False: the function never reads it)
    memory: bool = True

    @property
    def signature(self) -> str:
        if self.params is None:
            return f"{self.name}(irN > T, irM < T, ...)"
        return signature(self.name, self.params)


_SPEED_RANGE = "-max_speed..max_speed (1000 steps/s on the e-puck) [E030]"
_STEPS_RANGE = "a 16-bit int of motor steps [E034]"

ACTIONS = (
    ActionSpec("start_straight",
               (Param("speed", SPEED, "wheel speed; negative drives backwards", _SPEED_RANGE),
                Param("distance", DISTANCE, "how far; negative drives backwards", _STEPS_RANGE)),
               "drives straight; backwards when exactly one of them is negative",
               # compiled to exact steps: the runtime's extension, so the
               # paper's param_start_straight stays the paper's
               "straight_steps", motion=True, runtime_param="param_straight_steps"),
    ActionSpec("start_curve",
               (Param("radius", DISTANCE, "from the robot's centre to the circle's centre",
                      ">= 0 [E036], a 16-bit int of mm [E034]"),
                Param("degrees", ANGLE, "arc angle; positive turns left, negative right",
                      "the outer wheel's steps fit a 16-bit int [E034]"),
                Param("speed", SPEED, "the outer wheel's speed; negative drives backwards",
                      _SPEED_RANGE)),
               "drives an arc through the robot's centre; positive degrees turn left, negative "
               "right; `speed` is the outer wheel's; radius 0 turns on the spot",
               "curve_steps", motion=True, runtime_param="param_curve_steps"),
    ActionSpec("stop_motor", (), "stops the wheels; the current motion ends", "stop_motor"),
    ActionSpec("set_timer", (), "(re)starts the one timer at 0", "set_timer"),
    ActionSpec("reset_timer", (), "stops the timer", "reset_timer"),
    ActionSpec("start_sensor", (), "starts polling the proximity sensors", "start_sensor"),
    ActionSpec("stop_sensor", (), "stops it; sensor conditions are then false", "stop_sensor"),
    ActionSpec("exit_main", (), "ends the main loop", "exit_main"),
)

EVENTS = (
    EventSpec("immediate", (), "at the first poll", "immediate", memory=False),
    EventSpec("stop_motor", (),
              "when a motion has ended (reached its distance or stopped by `stop_motor`)",
              "event_stop_motor", memory=False),
    EventSpec("timer",
              (Param("time", DURATION, "time since `set_timer`",
                     "> 0 [E033], at most 2147483647 ms [E034]"),),
              "when the timer has run `time` since `set_timer`",
              "timer", "param_event_timer"),
    EventSpec("sensor", None,
              "when some listed sensor's reading passes its threshold",
              "sensor", "param_event_sensor"),
)

STANDARD_ACTIONS = {spec.name: spec for spec in ACTIONS}
STANDARD_EVENTS = {spec.name: spec for spec in EVENTS}
MOTION_ACTIONS = frozenset(spec.name for spec in ACTIONS if spec.motion)

# The paper's long spellings are accepted too (`action_start_straight`,
# `event_timer`), so that its tables can be copied as they are.
ACTION_ALIASES = {f"action_{name}": name for name in STANDARD_ACTIONS}
EVENT_ALIASES = {f"event_{name}": name for name in STANDARD_EVENTS}

SENSOR_NAMES = tuple(f"ir{i}" for i in range(SENSOR_COUNT))
SENSOR_CONDITION_DOC = (f"`{SENSOR_NAMES[0]}`..`{SENSOR_NAMES[-1]}` `>` or `<` a whole "
                        f"threshold in 0..{THRESHOLD_MAX} [E032] (0: nothing near, "
                        f"{THRESHOLD_MAX}: touching)")

EXTERN_TYPES = ("int", "distance", "speed", "angle", "duration")


def signature(name: str, params) -> str:
    if not params:
        return name
    return f"{name}({', '.join(f'{p.name}: {p.kind}' for p in params)})"


def describe_param(p: Param) -> str:
    """`speed` (speed, RANGE): a parameter in the reference's tables."""
    return f"`{p.name}` ({p.kind}{', ' + p.range if p.range else ''})"


def bare_unit(p: Param) -> str:
    """What a bare number means for this parameter (`steps/s`, `mm`, ...)."""
    return NATURAL_UNIT.get(p.kind, "a plain number")


def reference_markdown() -> str:
    """The tables of docs/language.md section 3, from this table."""
    lines = ["### 3.1 Actions", "", "| action | parameters | does |", "|---|---|---|"]
    for a in ACTIONS:
        params = ", ".join(describe_param(p) for p in a.params) or "-"
        lines.append(f"| `{a.name}` | {params} | {a.doc} |")
    lines += ["", "### 3.2 Events", "", "| event | parameters | occurs |", "|---|---|---|"]
    for e in EVENTS:
        params = ("conditions: " + SENSOR_CONDITION_DOC if e.params is None
                  else ", ".join(describe_param(p) for p in e.params) or "-")
        lines.append(f"| `{e.name}` | {params} | {e.doc} |")
    return "\n".join(lines) + "\n"


if __name__ == "__main__":      # python3 -m epuckc.stdlib > section 3's tables
    print(reference_markdown(), end="")
