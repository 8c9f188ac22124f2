"""The metrics of one run, from each robot's trace and Enki's contact
counts: per robot, and for the swarm.

| metric | columns | per robot | swarm |
|---|---|---|---|
| contacts | contacts, contacts_walls, contacts_objects, contacts_robots | physics steps touching anything; walls, obstacles, robots | sum |
| distance | distance_mm | length of the path through the poses (every 100 ms) | sum |
| coverage | coverage_cells | 5 cm cells of the floor the path crossed | cells of all paths |
| still | still_s | time still, as the pictures' band (< 5 mm in any 1 s, for more than 2 s) | mean |
| exit | exit_s | time of `exit_main`, or the duration | latest |
| pose | final_x_mm, final_y_mm, final_heading_deg | the last pose | - |
| var:NAME | var:NAME | the variable's final value | mean |
| mean:NAME | mean:NAME | its time average over the run | mean |
"""
from __future__ import annotations

import json
import math
from dataclasses import dataclass
from typing import Optional

CELL_MM = 50.0
SAMPLE_MM = 5.0


def columns(metrics: list) -> list:
    out = []
    for m in metrics:
        out.extend({"contacts": ["contacts", "contacts_walls", "contacts_objects",
                                 "contacts_robots"],
                    "distance": ["distance_mm"], "coverage": ["coverage_cells"],
                    "still": ["still_s"], "exit": ["exit_s"],
                    "pose": ["final_x_mm", "final_y_mm", "final_heading_deg"]}.get(m, [m]))
    return out


def _cells(poses: list) -> set:
    """The 5 cm cells a path crosses (the segments between poses sampled
    every 5 mm)."""
    return {cell for _, cell in crossed(poses)}


def crossed(poses: list):
    """(t_ms, cell) for each 5 cm cell the path reaches, at the pose that
    ends the segment where it does (a cell may come more than once)."""
    for i, (t, x, y, _h) in enumerate(poses):
        if i:
            _, x0, y0, _ = poses[i - 1]
            n = int(math.hypot(x - x0, y - y0) // SAMPLE_MM)
            for k in range(1, n + 1):
                f = k / (n + 1)
                yield t, (math.floor((x0 + (x - x0) * f) / CELL_MM),
                          math.floor((y0 + (y - y0) * f) / CELL_MM))
        yield t, (math.floor(x / CELL_MM), math.floor(y / CELL_MM))


@dataclass
class Track:
    """What one robot's trace says for the metrics: its poses (t_ms, x, y,
    heading; the first its start), each variable's changes (t_ms, value,
    from its initial value at 0) and when it exited (None: it did not)."""
    poses: list
    changes: dict
    exit_ms: Optional[int]

    def end_ms(self, duration_ms: int) -> int:
        return self.exit_ms if self.exit_ms is not None else duration_ms


def track(trace: str, start: tuple, variables: list) -> Track:
    """One robot's Track from its trace; `start` is its (x_mm, y_mm,
    heading) at 0 ms, `variables` its program's (name, initial value)."""
    poses = [(0, start[0], start[1], start[2])]
    exit_ms = None
    changes = {name: [(0, v)] for name, v in variables}
    for line in trace.splitlines():
        if not line.startswith("{"):
            continue
        rec = json.loads(line)
        kind = rec.get("kind")
        if kind == "set":
            changes.setdefault(rec["var"], [(0, 0)]).append((rec["t_ms"], rec["value"]))
            continue
        if "x_mm" in rec:
            poses.append((rec["t_ms"], rec["x_mm"], rec["y_mm"], rec["heading_deg"]))
        if kind == "exit" and exit_ms is None:
            exit_ms = rec["t_ms"]
    return Track(poses, changes, exit_ms)


def measure(robot: Track, result, metrics: list, duration_ms: int) -> tuple:
    """(values, cells): one robot's metrics (column -> number) and the set
    of cells it covered; `result` is its sim.enki.RobotResult."""
    poses = robot.poses
    end_ms = robot.end_ms(duration_ms)
    out = {}
    cells = set()
    for m in metrics:
        kind, _, name = m.partition(":")
        if m == "contacts":
            out["contacts_walls"] = result.wall_contacts
            out["contacts_objects"] = result.object_contacts
            out["contacts_robots"] = result.robot_contacts
            out["contacts"] = result.contact_steps
        elif m == "distance":
            out["distance_mm"] = sum(math.hypot(b[1] - a[1], b[2] - a[2])
                                     for a, b in zip(poses, poses[1:]))
        elif m == "coverage":
            cells = _cells(poses)
            out["coverage_cells"] = len(cells)
        elif m == "still":
            from ..sim.timeline import still_intervals
            out["still_s"] = sum(b - a for a, b in still_intervals(poses, end_ms)) / 1000
        elif m == "exit":
            out["exit_s"] = end_ms / 1000
        elif m == "pose":
            _, x, y, h = poses[-1]
            out.update(final_x_mm=x, final_y_mm=y, final_heading_deg=h)
        elif kind == "var":
            changes = robot.changes.get(name)
            out[m] = changes[-1][1] if changes else ""
        elif kind == "mean":
            out[m] = time_mean(robot.changes.get(name), end_ms)
    return out, cells


def time_mean(changes, end_ms: int):
    """The time average over [0, end_ms] of a value that holds from each
    change to the next."""
    if not changes:
        return ""
    if end_ms <= 0:
        return changes[-1][1]
    total = 0.0
    for (t, v), nxt in zip(changes, changes[1:] + [(end_ms, None)]):
        total += v * (min(nxt[0], end_ms) - min(t, end_ms))
    return total / end_ms


def swarm(per_robot: list, cells: list, metrics: list) -> dict:
    """The swarm's values from its robots' (see the module's table)."""
    out = {}
    cols = columns(metrics)
    for col in cols:
        vals = [r[col] for r in per_robot if r.get(col, "") != ""]
        if col.startswith("final_"):
            out[col] = ""
        elif col == "coverage_cells":
            out[col] = len(set().union(*cells))
        elif not vals:
            out[col] = ""
        elif col.startswith("contacts") or col == "distance_mm":
            out[col] = sum(vals)
        elif col == "exit_s":
            out[col] = max(vals)
        else:
            out[col] = sum(vals) / len(vals)
    return out


def fmt(value) -> str:
    """A metric as runs.csv writes it: whole numbers as they are, others
    with 3 decimals (the same text on every engine and machine)."""
    if value == "" or value is None:
        return ""
    if isinstance(value, bool):
        return str(int(value))
    if isinstance(value, int):
        return str(value)
    text = f"{value:.3f}"
    return "0.000" if text == "-0.000" else text
