"""Metrics over time: each of `series` sampled at 0, period, 2 x period,
... up to the duration, as if the run ended at that time:

| series | column | per robot at t | swarm at t |
|---|---|---|---|
| distance | distance_mm | path length so far | sum |
| coverage | coverage_cells | 5 cm cells crossed so far | cells any robot crossed so far |
| still | still_s | time still so far (the intervals of the whole run, up to t) | mean |
| var:NAME | var:NAME | the variable's value at t | mean |
| mean:NAME | mean:NAME | its time average over 0..t | mean |

A run keeps its swarm's series (its robot's, with one robot); series.csv
has, per grid point, column and time, the mean over the seeds and its 95%
confidence interval (the band of series.svg)."""
from __future__ import annotations

import bisect
import math

from . import metrics as M
from .stats import describe


def times(duration_ms: int, period_ms: int) -> list:
    return list(range(0, duration_ms + 1, period_ms))


def robot_series(robot: M.Track, names: list, at: list, duration_ms: int) -> tuple:
    """(column -> [value at each time], {cell: first t_ms}) of one robot."""
    out = {}
    first = {}
    poses = robot.poses
    pose_t = [p[0] for p in poses]
    for name in names:
        kind, _, var = name.partition(":")
        if name == "distance":
            run, total = [0.0], 0.0
            for a, b in zip(poses, poses[1:]):
                total += math.hypot(b[1] - a[1], b[2] - a[2])
                run.append(total)
            out["distance_mm"] = [run[bisect.bisect_right(pose_t, t) - 1] for t in at]
        elif name == "coverage":
            for t, cell in M.crossed(poses):
                first.setdefault(cell, t)
            ordered = sorted(first.values())
            out["coverage_cells"] = [bisect.bisect_right(ordered, t) for t in at]
        elif name == "still":
            from ..sim.timeline import still_intervals
            spans = still_intervals(poses, robot.end_ms(duration_ms))
            out["still_s"] = [sum(max(0, min(b, t) - a) for a, b in spans) / 1000 for t in at]
        elif kind in ("var", "mean"):
            changes = robot.changes.get(var) or []
            ct = [c[0] for c in changes]
            value = [changes[bisect.bisect_right(ct, t) - 1][1] if changes else "" for t in at]
            if kind == "mean":      # at 0 the average is the value at 0
                value = [M.time_mean(changes, t) if changes and t > 0 else v
                         for t, v in zip(at, value)]
            out[name] = value
    return out, first


def swarm_series(per_robot: list, firsts: list, names: list, at: list) -> dict:
    """The swarm's series from its robots' (the module's table)."""
    out = {}
    for col in M.columns(names):
        if col == "coverage_cells":
            first = {}
            for cells in firsts:
                for cell, t in cells.items():
                    if t < first.get(cell, math.inf):
                        first[cell] = t
            ordered = sorted(first.values())
            out[col] = [bisect.bisect_right(ordered, t) for t in at]
            continue
        values = [r[col] for r in per_robot if col in r]
        combine = sum if col == "distance_mm" else (lambda v: sum(v) / len(v))
        out[col] = [combine(vs) if vs and all(v != "" for v in vs) else ""
                    for vs in zip(*values)]
    return out


def summarise(tasks: list, results: dict, names: list, at: list) -> list:
    """Per grid point and column: (point, values, column, [describe() at
    each time]) over the runs that did not fail."""
    by_point = {}
    for task in sorted(tasks, key=lambda t: (t.point, t.seed)):
        result = results.get(task.key)
        if result is None:
            continue
        entry = by_point.setdefault(task.point, (task.values, []))
        if not result.error and not (result.rows and result.rows[-1].get("error")):
            entry[1].append(result.series)
    out = []
    for point, (values, runs) in sorted(by_point.items()):
        for col in M.columns(names):
            stats = []
            for k in range(len(at)):
                vals = [s[col][k] for s in runs if col in s and k < len(s[col])
                        and isinstance(s[col][k], (int, float))]
                stats.append(describe(vals))
            out.append((point, values, col, stats))
    return out


def series_rows(params: list, summary: list, at: list) -> tuple:
    """series.csv's header and rows."""
    header = ["point"] + params + ["series", "t_s", "n", "mean", "sd", "ci95_low", "ci95_high"]
    rows = []
    for point, values, col, stats in summary:
        for t, s in zip(at, stats):
            rows.append([point] + [values[p] for p in params]
                        + [col, M.fmt(t / 1000), s["n"]]
                        + [M.fmt(s[k]) if s[k] is not None else ""
                           for k in ("mean", "sd", "ci_low", "ci_high")])
    return header, rows
