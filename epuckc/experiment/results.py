"""An experiment's folder: each finished run as DIR/runs/KEY.json as soon
as it ends (so an interrupted experiment resumes: a run whose key is
there is not run again), the traces when asked (DIR/traces/), and at the
end runs.csv (one row per run and robot, sorted by grid point, seed and
robot), summary.csv (per grid point: n, mean, sd, 95% interval of each
metric) and summary.svg."""
from __future__ import annotations

import csv
import io
import json
from dataclasses import asdict
from pathlib import Path

from ..base.output import write_atomic
from . import metrics as M
from .stats import describe
from .task import RunResult


def load_done(folder: Path, tasks: list) -> dict:
    """The runs of `tasks` already in the folder: key -> RunResult. Runs
    lost with their worker are run again."""
    done = {}
    runs = folder / "runs"
    for task in tasks:
        path = runs / f"{task.key}.json"
        try:
            data = json.loads(path.read_text(encoding="utf-8"))
            result = RunResult(**data)
        except (OSError, ValueError, TypeError):
            continue
        if not result.transient and result.key == task.key:
            done[task.key] = result
    return done


def save(folder: Path, result: RunResult, task):
    """One finished run, written whole (a run cut off half-written is run
    again)."""
    data = asdict(result)
    trace = data.pop("trace")
    data["trace"] = None
    if trace is not None:
        write_atomic(folder / "traces" / f"p{task.point}-s{task.seed}.jsonl", trace)
    if result.transient:
        return
    write_atomic(folder / "runs" / f"{result.key}.json", json.dumps(data, sort_keys=True) + "\n")


def _param_columns(tasks: list) -> list:
    return list(tasks[0].values) if tasks else []


def _csv(header: list, rows: list) -> str:
    out = io.StringIO()
    w = csv.writer(out, lineterminator="\n")
    w.writerow(header)
    w.writerows(rows)
    return out.getvalue()


def runs_csv(tasks: list, results: dict, metrics: list) -> str:
    params = _param_columns(tasks)
    cols = M.columns(metrics)
    header = ["point"] + params + ["seed", "robot", "status", "error"] + cols
    rows = []
    for task in sorted(tasks, key=lambda t: (t.point, t.seed)):
        result = results[task.key]
        for row in result.rows:
            rows.append([task.point] + [task.values[p] for p in params]
                        + [task.seed, row["robot"], row.get("status", ""), row.get("error", "")]
                        + [M.fmt(row.get(c, "")) for c in cols])
    return _csv(header, rows)


def summarise(tasks: list, results: dict, metrics: list) -> list:
    """Per grid point: (point, values, runs, failures, {column: describe()}),
    over each run's swarm row (its only row with one robot)."""
    cols = M.columns(metrics)
    by_point = {}
    for task in sorted(tasks, key=lambda t: (t.point, t.seed)):
        by_point.setdefault(task.point, (task.values, []))[1].append(results[task.key])
    out = []
    for point, (values, runs) in sorted(by_point.items()):
        good = [r.rows[-1] for r in runs if not r.error and not r.rows[-1].get("error")]
        stats = {c: describe([row[c] for row in good if isinstance(row.get(c), (int, float))])
                 for c in cols}
        out.append((point, values, len(runs), len(runs) - len(good), stats))
    return out


def summary_csv(tasks: list, summary: list, metrics: list) -> str:
    params = _param_columns(tasks)
    cols = M.columns(metrics)
    header = ["point"] + params + ["runs", "failed"]
    for c in cols:
        header += [f"{c}:n", f"{c}:mean", f"{c}:sd", f"{c}:ci95_low", f"{c}:ci95_high"]
    rows = []
    for point, values, runs, failed, stats in summary:
        row = [point] + [values[p] for p in params] + [runs, failed]
        for c in cols:
            s = stats[c]
            row += [s["n"]] + [M.fmt(s[k]) if s[k] is not None else ""
                               for k in ("mean", "sd", "ci_low", "ci_high")]
        rows.append(row)
    return _csv(header, rows)


def write_results(folder: Path, tasks: list, results: dict, metrics: list, title: str) -> list:
    """runs.csv, summary.csv and summary.svg; returns the summary."""
    from .svg import summary_svg
    summary = summarise(tasks, results, metrics)
    write_atomic(folder / "runs.csv", runs_csv(tasks, results, metrics))
    write_atomic(folder / "summary.csv", summary_csv(tasks, summary, metrics))
    write_atomic(folder / "summary.svg", summary_svg(tasks, results, summary, metrics, title))
    return summary
