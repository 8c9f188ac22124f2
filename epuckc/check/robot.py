"""The `robot { ... }` block: geometry settings, their units and the ranges the
runtime takes (read from epuckrt.h)."""
from __future__ import annotations

import math
import re
from functools import lru_cache

from ..base.resources import runtime_dir
from ..diagnostics import Fix, Note
from ..stdlib.units import DISTANCE, INT, SPEED, Geometry, Quantity, round_nearest
from .messages import _clip, _code, _shown, did_you_mean

_ROBOT_EXAMPLE = {"wheel_diameter": "41 mm", "wheel_circumference": "128.8 mm",
                  "axle": "53 mm", "steps_per_rev": "1000", "max_speed": "1000 steps/s"}


@lru_cache(maxsize=1)
def runtime_geometry_limits() -> tuple[int, int]:
    """EPUCK_MAX_GEOMETRY_UM and EPUCK_MAX_STEPS_PER_REV of the runtime
    header, so that the checker and the runtime cannot disagree."""
    header = (runtime_dir() / "epuckrt.h").read_text(encoding="utf-8")
    found = dict(re.findall(r"#define\s+(EPUCK_MAX_GEOMETRY_UM|EPUCK_MAX_STEPS_PER_REV)\s+(\d+)",
                            header))
    return int(found["EPUCK_MAX_GEOMETRY_UM"]), int(found["EPUCK_MAX_STEPS_PER_REV"])


class RobotSettings:
    """The checker's robot block (a part of Checker)."""

    def _robot(self, blocks: list):
        for extra in blocks[1:]:
            self.diags.error("E022", extra.span, "the robot is described twice",
                             help="merge the two `robot { ... }` blocks into one",
                             notes=[Note("first described here", blocks[0].span)])
        if not blocks:
            return
        kinds = {"wheel_diameter": DISTANCE, "wheel_circumference": DISTANCE,
                 "axle": DISTANCE, "steps_per_rev": INT, "max_speed": SPEED}
        given: dict = {}
        for setting in blocks[0].settings:
            name = setting.name.name
            if name not in kinds:
                settings = "the settings are " + ", ".join(map(_code, kinds))
                guess = did_you_mean(setting.name, kinds)
                self.diags.error("E022", setting.name.span, f"unknown robot setting {_code(name)}",
                                 help=guess.then(settings) if guess else settings)
                continue
            if name in given:
                self.diags.error("E018", setting.name.span, f"{_code(name)} is given twice",
                                 notes=[Note("first given here", given[name][0].span)])
                continue
            q = self._value(setting.value, kinds[name], name)
            if q is None:
                continue
            if kinds[name] == DISTANCE and q.in_steps:
                self.diags.error("E019", setting.value.span,
                                 f"{_code(name)} cannot be given in steps: it defines what a step is",
                                 help="give it in mm")
                continue
            if q.value <= 0:
                self.diags.error("E037", setting.value.span, f"{_code(name)} must be positive",
                                 help=Fix(setting.value.span, _ROBOT_EXAMPLE[name],
                                          f"for the e-puck, write `{name}: {_ROBOT_EXAMPLE[name]}`"))
                continue
            if kinds[name] == INT and not self._whole(setting.value, q.value):
                continue
            if not self._robot_range(name, setting, q):
                continue
            given[name] = (setting, q)
        if "wheel_diameter" in given and "wheel_circumference" in given:
            self.diags.error("E037", given["wheel_circumference"][0].span,
                             "give the wheel's diameter or its circumference, not both",
                             notes=[Note("the diameter is given here", given["wheel_diameter"][0].span)])
            return
        geo = Geometry()
        circumference = geo.wheel_circumference_mm
        if "wheel_diameter" in given:
            circumference = math.pi * given["wheel_diameter"][1].value
        if "wheel_circumference" in given:
            circumference = given["wheel_circumference"][1].value
        steps_per_rev = int(given["steps_per_rev"][1].value) if "steps_per_rev" in given else geo.steps_per_rev
        axle = given["axle"][1].value if "axle" in given else geo.axle_mm
        max_speed = geo.max_speed
        if "max_speed" in given:
            # mm/s converts with the new geometry, so build it first.
            partial = Geometry(circumference, axle, steps_per_rev)
            max_speed = given["max_speed"][1].steps(partial)
            if max_speed > 1000:
                self.diags.error("E030", given["max_speed"][0].value.span,
                                 f"`max_speed` of {max_speed:.0f} steps/s is above the 1000 steps/s "
                                 "that the e-puck library allows", help="use at most 1000 steps/s")
                max_speed = 1000.0
        self.geo = Geometry(circumference, axle, steps_per_rev, max_speed)

    def _robot_range(self, name: str, setting, q: Quantity) -> bool:
        """The runtime takes the wheel and the axle in micrometres and the
        steps per turn as 32-bit longs (set_robot_geometry), up to its limits
        EPUCK_MAX_GEOMETRY_UM and EPUCK_MAX_STEPS_PER_REV (epuckrt.h), within
        which its conversions cannot overflow: each setting must fit, which
        also keeps every derived quantity finite."""
        max_um, max_steps = runtime_geometry_limits()
        if name in ("wheel_diameter", "wheel_circumference", "axle"):
            factor = math.pi if name == "wheel_diameter" else 1
            um = q.value * 1000 * factor
            if 1 <= round_nearest(um) <= max_um:
                return True
            low = 0.001 / factor
            high = math.floor(max_um / 1000 / factor)
            what = {"wheel_diameter": "the wheel's circumference", "axle": "the axle",
                    "wheel_circumference": "the wheel's circumference"}[name]
            self.diags.error("E037", setting.value.span,
                             f"`{name}` of `{_clip(_shown(setting.value))}` is out of range: "
                             f"give {low:.4g} mm to {high} mm",
                             help=f"the runtime keeps {what} in micrometres, at most "
                                  f"{max_um // 1000000} m; for the e-puck, write "
                                  f"`{name}: {_ROBOT_EXAMPLE[name]}`")
            return False
        if name == "steps_per_rev" and q.value > max_steps:
            self.diags.error("E037", setting.value.span,
                             f"`steps_per_rev` of `{_clip(_shown(setting.value))}` is out of range: "
                             f"give 1 to {max_steps}",
                             help=f"the runtime takes at most {max_steps} steps per turn; for the "
                                  "e-puck, write `steps_per_rev: 1000`")
            return False
        return True
