"""An experiment's folder: the runs of each batch as DIR/runs/BATCH.jsonl
as soon as the batch ends (one run a line; so an interrupted experiment
resumes: a run whose key is there, and which measured what is asked now,
is not run again), the traces when asked (DIR/traces/), and at the end
runs.csv (one row per run and robot, sorted by grid point, seed and
robot), summary.csv (per grid point: n, mean, sd, 95% interval of each
metric), summary.svg, with series the same over time (series.csv,
series.svg), and times.csv (each run's own time). `write_results` makes
them from whatever runs are saved, which is also `--report-only`."""
from __future__ import annotations

import csv
import io
import json
from dataclasses import asdict, fields
from pathlib import Path

from ..base.output import write_atomic
from . import metrics as M
from .stats import describe
from .task import RunResult

_FIELDS = {f.name for f in fields(RunResult)}


def read_saved(folder: Path) -> dict:
    """Every run saved in the folder: key -> RunResult (a batch's file, one
    run a line, or a single run's file of earlier versions). Runs lost
    with their worker are left out; a line cut off is skipped."""
    out = {}
    runs = folder / "runs"
    if not runs.is_dir():
        return out
    for path in sorted(runs.iterdir()):
        if path.suffix in (".json", ".jsonl"):
            out.update(read_file(path))
    return out


def read_file(path: Path) -> dict:
    """The runs of one file of DIR/runs: key -> RunResult."""
    out = {}
    try:
        lines = path.read_text(encoding="utf-8").splitlines()
    except (OSError, UnicodeDecodeError):
        return out
    for line in lines:
        try:
            data = json.loads(line)
            result = RunResult(**{k: v for k, v in data.items() if k in _FIELDS})
        except (ValueError, TypeError):
            continue
        if not result.transient:
            out[result.key] = result
    return out


def covers(result: RunResult, task) -> bool:
    """The saved run measured everything the task asks for now."""
    job = task.job
    got = result.measured or {}
    if not set(job.metrics) <= set(got.get("metrics", ())):
        return False
    if job.series and (not set(job.series) <= set(got.get("series", ()))
                       or got.get("period_ms") != job.period_ms):
        return False
    return True


def load_done(folder: Path, tasks: list, saved: dict = None) -> dict:
    """The runs of `tasks` already in the folder: key -> RunResult."""
    saved = read_saved(folder) if saved is None else saved
    done = {}
    for task in tasks:
        result = saved.get(task.key)
        if result is None or not covers(result, task):
            continue
        if task.job.traces and not trace_path(folder, task).is_file():
            continue
        done[task.key] = result
    return done


def trace_path(folder: Path, task) -> Path:
    return folder / "traces" / f"p{task.point}-s{task.seed}.jsonl"


def save_batch(folder: Path, batch_key: str, pairs: list):
    """The finished runs of a batch, (task, result) each, written whole (a
    batch cut off half-written is run again): traces first, then the runs."""
    lines = []
    for task, result in pairs:
        data = asdict(result)
        trace = data.pop("trace")
        data["trace"] = None
        if trace is not None:
            write_atomic(trace_path(folder, task), trace)
        if not result.transient:
            lines.append(json.dumps(data, sort_keys=True))
    if lines:
        write_atomic(folder / "runs" / f"{batch_key}.jsonl", "\n".join(lines) + "\n")


class Saver:
    """`done(task, result)` for an engine: each batch's runs saved when the
    last of them arrives (`enabled` False: the engine's workers save them)."""

    def __init__(self, folder: Path, batches: list, enabled: bool = True):
        self.folder, self.enabled = folder, enabled
        self.waiting = {b.key: (b, {}) for b in batches}
        self.batch_of = {t.key: b.key for b in batches for t in b.tasks}

    def __call__(self, task, result):
        batch, got = self.waiting[self.batch_of[task.key]]
        got[task.key] = result
        if self.enabled and len(got) == len(batch.tasks):
            save_batch(self.folder, batch.key, [(t, got[t.key]) for t in batch.tasks])


def save(folder: Path, result: RunResult, task):
    """One finished run, as a batch of one."""
    save_batch(folder, result.key, [(task, result)])


def _param_columns(tasks: list) -> list:
    return list(tasks[0].values) if tasks else []


def _csv(header: list, rows: list) -> str:
    out = io.StringIO()
    w = csv.writer(out, lineterminator="\n")
    w.writerow(header)
    w.writerows(rows)
    return out.getvalue()


def _with_results(tasks: list, results: dict) -> list:
    return [t for t in sorted(tasks, key=lambda t: (t.point, t.seed)) if t.key in results]


def runs_csv(tasks: list, results: dict, metrics: list) -> str:
    params = _param_columns(tasks)
    cols = M.columns(metrics)
    header = ["point"] + params + ["seed", "robot", "status", "error"] + cols
    rows = []
    for task in _with_results(tasks, results):
        result = results[task.key]
        for row in result.rows:
            rows.append([task.point] + [task.values[p] for p in params]
                        + [task.seed, row["robot"], row.get("status", ""), row.get("error", "")]
                        + [M.fmt(row.get(c, "")) for c in cols])
    return _csv(header, rows)


def times_csv(tasks: list, results: dict) -> str:
    """Each run's own time on its worker (not in runs.csv, whose bytes are
    the same on every engine and machine)."""
    params = _param_columns(tasks)
    rows = [[t.point] + [t.values[p] for p in params]
            + [t.seed, f"{results[t.key].wall_s:.3f}", f"{results[t.key].cpu_s:.3f}"]
            for t in _with_results(tasks, results)]
    return _csv(["point"] + params + ["seed", "wall_s", "cpu_s"], rows)


def failed(result: RunResult) -> bool:
    return bool(result.error or any(r.get("error") for r in result.rows))


def summarise(tasks: list, results: dict, metrics: list) -> list:
    """Per grid point with runs: (point, values, runs, failures, {column:
    describe()}), over each run's swarm row (its only row with one robot)."""
    cols = M.columns(metrics)
    by_point = {}
    for task in _with_results(tasks, results):
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
    for point, values, runs, failures, stats in summary:
        row = [point] + [values[p] for p in params] + [runs, failures]
        for c in cols:
            s = stats[c]
            row += [s["n"]] + [M.fmt(s[k]) if s[k] is not None else ""
                               for k in ("mean", "sd", "ci_low", "ci_high")]
        rows.append(row)
    return _csv(header, rows)


def write_results(folder: Path, tasks: list, results: dict, metrics: list, title: str,
                  series: list = (), period_ms: int = 1000, duration_ms: int = 0) -> list:
    """runs.csv, summary.csv, summary.svg, times.csv, and with series
    series.csv and series.svg, over the tasks' runs in `results` (all of
    them, or those saved so far); returns the summary."""
    from .svg import series_svg, summary_svg
    summary = summarise(tasks, results, metrics)
    write_atomic(folder / "runs.csv", runs_csv(tasks, results, metrics))
    write_atomic(folder / "summary.csv", summary_csv(tasks, summary, metrics))
    write_atomic(folder / "summary.svg", summary_svg(tasks, results, summary, metrics, title))
    write_atomic(folder / "times.csv", times_csv(tasks, results))
    if series:
        from . import series as S
        at = S.times(duration_ms, period_ms)
        over_time = S.summarise(tasks, results, list(series), at)
        header, rows = S.series_rows(_param_columns(tasks), over_time, at)
        write_atomic(folder / "series.csv", _csv(header, rows))
        write_atomic(folder / "series.svg", series_svg(over_time, at, title))
    return summary
