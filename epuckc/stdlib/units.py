"""Quantities, units and the robot's geometry.

Every parameter has a kind. A number written with a unit must have a unit of
that kind; a bare number takes the kind's natural unit. The compiler turns
every quantity into the integers the runtime uses: motor steps, steps per
second, degrees and milliseconds, rounding to the nearest.
"""
from __future__ import annotations

import math

from ..base.records import record

DISTANCE, SPEED, ANGLE, DURATION, INT = "distance", "speed", "angle", "duration", "int"
KINDS = (INT, DISTANCE, SPEED, ANGLE, DURATION)

# unit -> (kind, factor to the kind's reference unit); `steps` and the
# speeds in steps are converted with the geometry, hence the None factor.
UNITS = {
    "mm": (DISTANCE, 1.0), "cm": (DISTANCE, 10.0), "m": (DISTANCE, 1000.0),
    "steps": (DISTANCE, None), "step": (DISTANCE, None),
    "steps/s": (SPEED, None), "step/s": (SPEED, None),
    "mm/s": (SPEED, 1.0), "cm/s": (SPEED, 10.0), "m/s": (SPEED, 1000.0),
    "deg": (ANGLE, 1.0), "ms": (DURATION, 1.0), "s": (DURATION, 1000.0),
}
NATURAL_UNIT = {DISTANCE: "mm", SPEED: "steps/s", ANGLE: "deg", DURATION: "ms"}
KIND_UNITS = {k: sorted({u for u, (kind, _) in UNITS.items() if kind == k} - {"step", "step/s"})
              for k in (DISTANCE, SPEED, ANGLE, DURATION)}
ARTICLE = {INT: "a plain number", DISTANCE: "a distance", SPEED: "a speed",
           ANGLE: "an angle", DURATION: "a duration"}

INT16_MIN, INT16_MAX = -32768, 32767
INT32_MAX = 2**31 - 1


def describe_kind(kind: str) -> str:
    if kind == INT:
        return "a plain number (no unit)"
    return f"{ARTICLE[kind]} ({', '.join(KIND_UNITS[kind])})"


def round_nearest(x: float) -> int:
    """Round half away from zero, as the runtime's integer conversions do."""
    n = math.floor(abs(x) + 0.5)        # an int
    return n if x >= 0 else -n


@record(frozen=True)
class Geometry:
    wheel_circumference_mm: float = math.pi * 41.0
    axle_mm: float = 53.0
    steps_per_rev: int = 1000
    max_speed: float = 1000.0        # steps/s

    @property
    def step_mm(self) -> float:
        return self.wheel_circumference_mm / self.steps_per_rev


@record(frozen=True)
class Quantity:
    """A value of a kind in its reference unit: mm, mm/s, deg, ms, or a
    plain number; `in_steps` marks distances and speeds written in steps."""
    kind: str
    value: float
    in_steps: bool = False

    def steps(self, geo: Geometry) -> float:
        """Distance in motor steps, or speed in steps per second."""
        return self.value if self.in_steps else self.value / geo.step_mm

    def mm(self, geo: Geometry) -> float:
        return self.value * geo.step_mm if self.in_steps else self.value


def quantity(number: float, unit: str | None, expected_kind: str) -> Quantity:
    """The quantity a literal denotes where `expected_kind` is wanted. The
    caller has checked that the unit exists and is of the expected kind."""
    if unit is None:
        # the natural units: mm, steps/s, deg, ms
        return Quantity(expected_kind, number, in_steps=expected_kind == SPEED)
    kind, factor = UNITS[unit]
    if factor is None:
        return Quantity(kind, number, in_steps=True)
    return Quantity(kind, number * factor)


def curve_wheels(radius_mm: float, degrees: float, speed_steps: float,
                 geo: Geometry) -> tuple[float, float]:
    """Outer-wheel step count and inner-wheel speed of an arc through the
    robot's centre (wheel speeds in the ratio (r - axle/2) : (r + axle/2))."""
    half = geo.axle_mm / 2.0
    outer_mm = (radius_mm + half) * math.radians(abs(degrees))
    inner_speed = speed_steps * (radius_mm - half) / (radius_mm + half)
    return outer_mm / geo.step_mm, inner_speed
