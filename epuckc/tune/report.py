"""What a tune writes in its folder:

- history.csv: one row per candidate, in the order they were asked for:
  its number, state (complete, pruned, failed, stopped), the searched
  values, the design seeds it ran, its objective (the aggregate over
  those), the objective on each, the runs the search had taken when it
  ended, and the best complete value so far. Nothing in it depends on the
  machine: the same file and seed give the same bytes.
- best.toml: the best values as the `[params]` table of an experiment
  file, with the objective on the design and the test seeds in comments;
  best.defines: the same as `-D` options, one a line.
- test.csv: the best and the programs' own constants on the test seeds,
  a row per run with the objective and the metrics.
- convergence.svg and params.svg (svg.py)."""
from __future__ import annotations

import csv
import io
import shlex

from ..base.output import write_atomic
from ..experiment import metrics as M
from .objective import describe_aggregate
from .race import test_summary


def _csv(header: list, rows: list) -> str:
    out = io.StringIO()
    w = csv.writer(out, lineterminator="\n")
    w.writerow(header)
    w.writerows(rows)
    return out.getvalue()


def history_csv(search, result) -> str:
    names = [p.name for p in search.params]
    header = ["trial", "state"] + names + ["seeds", "objective", "per_seed", "runs", "best"]
    rows = []
    best = None
    for c in sorted(result.candidates, key=lambda c: c.number):
        if c.state == "complete" and (best is None or search.better(c.value, best)):
            best = c.value
        rows.append([c.number, c.state] + [c.values.get(n, "") for n in names]
                    + [len(c.per_seed), M.fmt(c.value) if c.value is not None else "",
                       " ".join(M.fmt(v) for v in c.per_seed), c.runs_at_end,
                       M.fmt(best) if best is not None else ""])
    return _csv(header, rows)


def _interval(s: dict) -> str:
    if s["mean"] is None:
        return "no value (every run failed)"
    if s["ci_low"] is None:
        return M.fmt(s["mean"])
    return f"{M.fmt(s['mean'])} (95% interval {M.fmt(s['ci_low'])} .. {M.fmt(s['ci_high'])})"


def seeds_text(seeds: list) -> str:
    if seeds == list(range(seeds[0], seeds[0] + len(seeds))) and len(seeds) > 2:
        return f"{seeds[0]}..{seeds[-1]}"
    return ", ".join(map(str, seeds))


def best_toml(search, result, shown: str, fixed: dict) -> str:
    best = result.best
    done = sum(1 for c in result.candidates if c.state == "complete")
    lines = [f"# epuckc tune {shown}: the best of {len(result.candidates)} candidates "
             f"({done} complete), trial {best.number}, in {result.runs} runs",
             f'# objective "{search.objective.text}" ({search.direction}, '
             f"{describe_aggregate(search.aggregate)} over the design seeds): "
             f"{M.fmt(best.value)}"]
    for name, label in (("best", "these values"), ("program", "the programs' own constants")):
        if name in result.test:
            lines.append(f"# on the test seeds {seeds_text(result.test_seeds)}, {label}: "
                         f"{_interval(test_summary(result.test[name]))}")
    lines.append("[params]")
    params = {p.name: p for p in search.params}
    for name, text in fixed.items():
        lines.append(f"{name} = {_toml(text)}")
    for name in params:
        lines.append(f"{name} = {_toml(best.values[name])}")
    return "\n".join(lines) + "\n"


def _toml(text: str) -> str:
    import re
    return text if re.fullmatch(r"-?[0-9]+(\.[0-9]+)?", text) else f'"{text}"'


def best_defines(search, result, fixed: dict) -> str:
    values = dict(fixed, **result.best.values)
    return "".join(f"-D {shlex.quote(f'{k}={v}')}\n" for k, v in values.items())


def test_csv(search, result) -> str:
    cols = M.columns(search.objective.metrics)
    header = ["candidate", "seed", "objective"] + cols
    rows = []
    for name in ("best", "program"):
        for r in result.test.get(name, []):
            rows.append([name, r.seed, M.fmt(r.value) if r.value is not None else ""]
                        + [M.fmt(r.row.get(c, "")) for c in cols])
    return _csv(header, rows)


def write_report(folder, search, result, shown: str, fixed: dict, title: str):
    from .svg import convergence_svg, params_svg
    write_atomic(folder / "history.csv", history_csv(search, result))
    write_atomic(folder / "convergence.svg", convergence_svg(search, result, title))
    write_atomic(folder / "params.svg", params_svg(search, result, title))
    if result.best is not None:
        write_atomic(folder / "best.toml", best_toml(search, result, shown, fixed))
        write_atomic(folder / "best.defines", best_defines(search, result, fixed))
        write_atomic(folder / "test.csv", test_csv(search, result))
