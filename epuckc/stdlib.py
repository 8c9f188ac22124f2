"""The standard actions and events of the paper's tables 2 and 3, and their
parameters in the paper's order (which is the order of positional arguments)."""
from __future__ import annotations

from dataclasses import dataclass

from .units import ANGLE, DISTANCE, DURATION, SPEED


@dataclass(frozen=True)
class Param:
    name: str
    kind: str


STANDARD_ACTIONS = {
    "start_straight": (Param("speed", SPEED), Param("distance", DISTANCE)),
    "start_curve": (Param("radius", DISTANCE), Param("degrees", ANGLE), Param("speed", SPEED)),
    "stop_motor": (),
    "set_timer": (),
    "reset_timer": (),
    "start_sensor": (),
    "stop_sensor": (),
    "exit_main": (),
}
MOTION_ACTIONS = {"start_straight", "start_curve"}

# `sensor` takes conditions (`ir0 > 300`) rather than parameters.
STANDARD_EVENTS = {
    "immediate": (),
    "stop_motor": (),
    "timer": (Param("time", DURATION),),
    "sensor": None,
}

SENSOR_COUNT = 8
THRESHOLD_MAX = 4095

# The paper's long spellings are accepted too (`action_start_straight`,
# `event_timer`), so that its tables can be copied as they are.
ACTION_ALIASES = {f"action_{name}": name for name in STANDARD_ACTIONS}
EVENT_ALIASES = {f"event_{name}": name for name in STANDARD_EVENTS}

EXTERN_TYPES = ("int", "distance", "speed", "angle", "duration")
