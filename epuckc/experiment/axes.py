"""The experiment file's keys beyond the first grid (spec.py calls these,
with its own positions and error list, so that every problem of the file
is still reported at its line, all at once):

    world = ["open.world", "maze.world"]     # a list: the world is an axis too
    series = ["coverage", "distance"]        # metrics over time, sampled at
    period = "1 s"                           #   every period
    [params]
    robots = [10, 50, 200]                   # the robot count: copies of the world's robots
    [placement]                              # how the copies are placed (swarm.py)
    density = 20                             # robots per square metre (else: the world's arena)
    margin = "5 mm"                          # free space around each at the start

docs/experiments.md is the reference."""
from __future__ import annotations

import math
import re
from pathlib import Path

from ..sim.world import LENGTH_UNITS, MAX_ROBOTS
from .swarm import Placement

ROBOTS = "robots"               # the parameter that is the robot count, not a constant
SERIES_METRICS = ("distance", "coverage", "still")
MIN_PERIOD_MS = 100             # the poses' period (plan.POSE_MS): nothing changes in between
MAX_SAMPLES = 10_000
PLACEMENT_KEYS = ("density", "margin")


def worlds(data, pos, base: Path, fail) -> list:
    """`world = [...]`: the world files, in order (each must exist)."""
    out = []
    for item in data["world"]:
        if not isinstance(item, str):
            fail(pos.key("world"), "a world is a file name in quotes",
                 'world = ["open.world", "maze.world"]')
            continue
        path = base / item
        if not path.is_file():
            fail(pos.item("world", item), f"the world file {item} does not exist",
                 "the path is relative to the experiment file's folder")
        elif path in out:
            fail(pos.item("world", item), f"{item} is named twice")
        else:
            out.append(path)
    if not data["world"]:
        fail(pos.key("world"), "the list of worlds is empty", 'world = ["arena.world"]')
    return out


def robot_counts(values: list, pos, fail) -> list:
    """`robots = [10, 50, 200]` under [params]: whole numbers of robots."""
    out = []
    for v in values:
        if isinstance(v, bool) or not isinstance(v, int) or not 1 <= v <= MAX_ROBOTS:
            fail(pos.item(ROBOTS, v, "params"), f"{v!r} is not a robot count: a whole number "
                 f"from 1 to {MAX_ROBOTS}", "robots = [10, 50, 200]")
        else:
            out.append(str(v))
    return out


def series(data, pos, fail, duration_ms, parse_duration) -> tuple:
    """(series metrics, period in ms): `series` and `period` (a time read
    by spec.py's `parse_duration`)."""
    from ..check.defines import NAME_RE
    value = data.get("series", [])
    names = []
    if not isinstance(value, list) or not all(isinstance(m, str) for m in value):
        fail(pos.key("series"), "series is a list of metrics in quotes",
             'series = ["coverage", "distance"]')
        value = []
    for m in value:
        kind, _, name = m.partition(":")
        if m in SERIES_METRICS or (kind in ("var", "mean") and NAME_RE.match(name)):
            if m not in names:
                names.append(m)
        elif m in ("contacts", "exit", "pose"):
            why = {"contacts": "Enki counts the contacts for the whole run, not over time",
                   "exit": "it happens once", "pose": "the poses are in the traces"}[m]
            fail(pos.item("series", m), f"`{m}` is not a metric over time: {why}",
                 f"the series are {', '.join(SERIES_METRICS)}, var:NAME and mean:NAME; "
                 f"`{m}` belongs in metrics")
        else:
            fail(pos.item("series", m), f"unknown series `{m}`",
                 f"the series are {', '.join(SERIES_METRICS)}, var:NAME (a variable's value) "
                 "and mean:NAME (its time average so far)")
    period = 1000
    if "period" in data:
        period = parse_duration(data["period"])
        if period is None or period < MIN_PERIOD_MS:
            fail(pos.key("period"), f"the period is a time in quotes with its unit, at least "
                 f"{MIN_PERIOD_MS} ms (the poses' period)", 'period = "1 s"')
            period = 1000
        elif not names:
            fail(pos.key("period"), "a period without series samples nothing",
                 'add the metrics to sample: series = ["coverage"]')
    if names and duration_ms and duration_ms // period > MAX_SAMPLES:
        fail(pos.key("period"), f"{duration_ms // period} samples per run: at most "
             f"{MAX_SAMPLES}", "give a longer period")
    return names, period


def parse_length(text: str):
    """"5 mm", "1.5cm", "0.2 m" -> mm, or None."""
    m = re.fullmatch(r"\s*([0-9]+(?:\.[0-9]+)?)\s*(mm|cm|m)\s*", text)
    return float(m.group(1)) * LENGTH_UNITS[m.group(2)] if m else None


def placement(data, pos, fail):
    """`[placement]`: a Placement, or None when the table is absent."""
    table = data.get("placement")
    if table is None:
        return None
    if not isinstance(table, dict):
        fail(pos.key("placement"), "placement is a table", "[placement]\ndensity = 20")
        return None
    out = Placement()
    for key in table:
        if key not in PLACEMENT_KEYS:
            fail(pos.key(key, "placement"), f"unknown key `{key}` of [placement]",
                 f"[placement] has {', '.join(PLACEMENT_KEYS)}")
    if "density" in table:
        d = table["density"]
        if isinstance(d, bool) or not isinstance(d, (int, float)) or not (
                math.isfinite(d) and 0 < d <= 200):
            fail(pos.key("density", "placement"), "the density is a number of robots per "
                 "square metre, above 0 and at most 200", "density = 20")
        else:
            out.density = float(d)
    if "margin" in table:
        m = parse_length(table["margin"]) if isinstance(table["margin"], str) else None
        if m is None or not 0 <= m <= 1000:
            fail(pos.key("margin", "placement"), "the margin is a length in quotes, from "
                 "0 mm to 1 m", 'margin = "5 mm"')
        else:
            out.margin_mm = m
    return out
