"""The pose of a robot trace: the robot sends its wheels' step counters,
not a pose, and this is the odometry of those steps, as the host harness's
virtual robot computes its pose from its own (runtime_c/host/epuck_stub.c):
the heading exact from the two totals, the position moved along the mean
heading. Between two samples the wheels are taken to turn at constant
speeds (true of every motion a rule program commands, between the records
that change it), so the path between them is an arc: its chord, along the
mean heading."""
from __future__ import annotations

import math


def _tidy(v: float) -> float:
    """One decimal, as the host's %.1f, never -0.0."""
    return 0.0 if -0.05 < v < 0.05 else round(v, 1)


class Odometry:
    """Fed the wheels' total steps since the start, in order; `pose()` the
    trace's x_mm, y_mm, heading_deg (one decimal)."""

    def __init__(self, geometry: dict):
        self.mm_per_step = geometry["wheel_circumference_um"] / 1000.0 / geometry["steps_per_rev"]
        self.axle_mm = geometry["axle_um"] / 1000.0
        self.left = self.right = 0
        self.x = self.y = 0.0

    def _heading(self, left: int, right: int) -> float:
        return (right - left) * self.mm_per_step / self.axle_mm

    def move_to(self, left: int, right: int) -> None:
        dl, dr = left - self.left, right - self.right
        if dl == 0 and dr == 0:
            return
        before, after = self._heading(self.left, self.right), self._heading(left, right)
        ds = (dl + dr) * 0.5 * self.mm_per_step
        half = (after - before) / 2.0
        chord = ds if abs(half) < 1e-12 else ds * math.sin(half) / half
        mid = (before + after) / 2.0
        self.x += chord * math.cos(mid)
        self.y += chord * math.sin(mid)
        self.left, self.right = left, right

    def pose(self) -> tuple:
        h = math.fmod(self._heading(self.left, self.right), 2.0 * math.pi)
        if h > math.pi:
            h -= 2.0 * math.pi
        elif h <= -math.pi:
            h += 2.0 * math.pi
        return _tidy(self.x), _tidy(self.y), _tidy(math.degrees(h))
