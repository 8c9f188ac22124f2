"""The robot count as an axis of the grid: N copies of the world's robots
(its robot lines are the templates, copied in turn: with one line, N
copies of it), each run placed at random without overlap, as SIERRA's
population criteria vary a swarm:

- in the world's arena (population size: the same floor, more crowded);
- or at a density (`[placement] density = 20`, robots per square metre:
  the arena grows or shrinks with the count, its proportions kept, the
  obstacles where they were relative to the walls, their sizes kept; on
  open ground, a square of that area about the origin).

The placement is a function of the run's seed: the same seed, the same
positions and headings (uniform in the free floor and in 0..360 deg),
whichever worker runs it. Positions come from `random.Random` seeded
with a string, which is the same on every platform and Python version."""
from __future__ import annotations

import copy
import math
import random
from typing import Optional

from ..base.records import record
from ..sim.world import ROBOT_RADIUS_MM, RobotPlacement, World, box_distance

ATTEMPTS = 2000          # tries for one robot before the placement gives up
# random sequential placement of discs jams at about 0.547 of the floor;
# well before that it takes many tries
MAX_COVER = 0.45


class PlacementError(Exception):
    """The robots do not fit; str() says why and what to change."""


@record
class Placement:
    """How the copies are placed. `density`: robots per square metre (None:
    in the world's arena as it is); `margin_mm`: free space kept between a
    robot and anything else at the start."""
    density: Optional[float] = None
    margin_mm: float = 5.0

    def to_json(self) -> dict:
        return {"density": self.density, "margin_mm": self.margin_mm}


def sized_world(world: World, count: int, placement: Placement) -> World:
    """The world the copies are placed in: the arena resized to the density
    (obstacles moved with it), or the world as it is. No robots yet."""
    out = copy.deepcopy(world)
    out.robots = []
    if placement.density is None:
        return out
    area_mm2 = count / placement.density * 1e6
    if out.walled:
        scale = math.sqrt(area_mm2 / (out.width_mm * out.height_mm))
        out.width_mm *= scale
        out.height_mm *= scale
        for obj in out.boxes + out.cylinders:
            obj.x_mm *= scale
            obj.y_mm *= scale
    return out


def _region(world: World, count: int, placement: Placement) -> tuple:
    """(x0, y0, x1, y1) of the robots' centres."""
    r = ROBOT_RADIUS_MM + placement.margin_mm
    if world.walled:
        return r, r, world.width_mm - r, world.height_mm - r
    if placement.density is None:
        raise PlacementError("the world is open ground (no `arena` line): give the robots a "
                             "density to place them at ([placement] density = 20, robots "
                             "per square metre)")
    half = math.sqrt(count / placement.density * 1e6) / 2
    return -half, -half, half, half


def _blocked(world: World, x: float, y: float, gap: float) -> bool:
    for c in world.cylinders:
        if math.hypot(x - c.x_mm, y - c.y_mm) < c.radius_mm + gap:
            return True
    return any(box_distance(b, x, y) < gap for b in world.boxes)


def check_fit(world: World, count: int, placement: Placement) -> Optional[str]:
    """Why `count` robots cannot be placed (too dense a floor), or None."""
    try:
        x0, y0, x1, y1 = _region(sized_world(world, count, placement), count, placement)
    except PlacementError as exc:
        return str(exc)
    if x1 <= x0 or y1 <= y0:
        return "the arena is too small for one robot"
    floor = (x1 - x0 + 2 * ROBOT_RADIUS_MM) * (y1 - y0 + 2 * ROBOT_RADIUS_MM)
    disc = math.pi * (ROBOT_RADIUS_MM + placement.margin_mm / 2) ** 2
    if count * disc > MAX_COVER * floor:
        most = int(MAX_COVER * floor / disc)
        return (f"they would cover more than {MAX_COVER:.0%} of the floor, where random "
                f"places without overlap run out (about {most} fit)")
    return None


def place(world: World, templates: list, count: int, placement: Placement,
          seed: int) -> World:
    """The run's world: `count` copies of `templates` (RobotPlacement, used
    in turn), named r1..rN, at random free places; PlacementError when one
    does not fit."""
    out = sized_world(world, count, placement)
    x0, y0, x1, y1 = _region(out, count, placement)
    rng = random.Random(f"epuckc placement {seed}")
    gap = ROBOT_RADIUS_MM + placement.margin_mm
    near = 2 * ROBOT_RADIUS_MM + placement.margin_mm
    cell = near
    grid = {}           # (i, j) -> [(x, y)] of the robots placed: a neighbour search in O(1)
    for k in range(count):
        for _ in range(ATTEMPTS):
            x, y = rng.uniform(x0, x1), rng.uniform(y0, y1)
            i, j = math.floor(x / cell), math.floor(y / cell)
            if any(math.hypot(x - px, y - py) < near
                   for di in (-1, 0, 1) for dj in (-1, 0, 1)
                   for px, py in grid.get((i + di, j + dj), ())):
                continue
            if _blocked(out, x, y, gap):
                continue
            break
        else:
            raise PlacementError(f"robot {k + 1} of {count} found no free place in "
                                 f"{ATTEMPTS} tries: the floor is too crowded")
        grid.setdefault((i, j), []).append((x, y))
        t = templates[k % len(templates)]
        out.robots.append(RobotPlacement(f"r{k + 1}", round(x, 1), round(y, 1),
                                         round(rng.uniform(0.0, 360.0), 1), t.program,
                                         colour=t.colour, more_c=t.more_c))
    return out
