"""Which robots of a world stand too near each other: a grid of cells as
wide as the distance, each robot tried against those of its own cell and
the eight around it, so that a world of ten thousand robots is checked in
linear time (all pairs: 50 million). Imports nothing of epuckc."""
from __future__ import annotations

import math


def overlapping(robots: list, near: float) -> list:
    """The pairs (i, j), i < j, of robots whose centres are less than
    `near` apart, in order: from a grid of `near` cells, each robot
    against the robots of its cell and the eight around it."""
    grid = {}
    for k, robot in enumerate(robots):
        grid.setdefault((math.floor(robot.x_mm / near), math.floor(robot.y_mm / near)),
                        []).append(k)
    pairs = []
    for (ci, cj), members in grid.items():
        for di in (-1, 0, 1):
            for dj in (-1, 0, 1):
                for j in grid.get((ci + di, cj + dj), ()):
                    for i in members:
                        a, b = robots[i], robots[j]
                        if i < j and math.hypot(a.x_mm - b.x_mm, a.y_mm - b.y_mm) < near:
                            pairs.append((i, j))
    return sorted(pairs)
