"""`epuckc experiment FILE.toml`: many seeded runs of a world over a grid
of constants, on the local cores or a Dask cluster (epuckc/experiment/,
docs/experiments.md). This module is the command line's side: options,
loading programs with their constants, the progress line, messages."""
from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

EXIT_OK, EXIT_ERRORS, EXIT_USAGE = 0, 1, 2
EXIT_INTERRUPTED = 130


def _error(message: str):
    print(f"epuckc: error: {message}", file=sys.stderr)


def _workers(text: str) -> int:
    if not text.isdigit() or not 1 <= int(text) <= 4096:
        raise argparse.ArgumentTypeError(f"{text} is not a number of workers (1 to 4096)")
    return int(text)


def add_parser(sub, run):
    p = sub.add_parser("experiment", help="run a world for many seeds and a grid of constants, "
                                          "in parallel, and summarise the metrics",
                       description="Run the experiment of FILE.toml (programs, world, duration, "
                                   "seeds, metrics, a grid of constants; docs/experiments.md): "
                                   "DIR/runs.csv has a row per run and robot, DIR/summary.csv "
                                   "and DIR/summary.svg the mean and 95% interval of each "
                                   "metric per grid point. Runs already in DIR are not run "
                                   "again. Exit status: 0 done (failed runs are rows with "
                                   "their error), 1 a program has errors or the engine "
                                   "cannot start, 2 a bad experiment or world file, 130 "
                                   "interrupted.")
    p.add_argument("file", metavar="FILE.toml")
    p.add_argument("-o", "--output", metavar="DIR",
                   help="the results' folder (default: FILE's name without .toml, plus "
                        "-results, beside it)")
    p.add_argument("--workers", type=_workers, metavar="N",
                   help="runs at a time (default: this machine's cores; with --engine dask "
                        "and no --scheduler, the local cluster's workers)")
    p.add_argument("--engine", choices=("local", "dask"), default="local",
                   help="local: a process pool on this machine (default); dask: a Dask "
                        "cluster (pip install 'epuckc[cluster]')")
    p.add_argument("--scheduler", metavar="ADDRESS",
                   help="with --engine dask: the scheduler, e.g. tcp://10.0.0.5:8786 "
                        "(default: a local cluster)")
    p.set_defaults(run=run)


class Progress:
    """Runs done, failures and the time left: one line redrawn on a
    terminal, a plain line per run otherwise."""

    def __init__(self, total: int, already: int, stream=None):
        self.total, self.done, self.failed = total, already, 0
        self.new = 0
        self.start = time.monotonic()
        self.stream = stream if stream is not None else sys.stderr
        self.tty = self.stream.isatty()

    def update(self, task, result):
        self.done += 1
        self.new += 1
        failed = bool(result.error or any(r.get("error") for r in result.rows))
        self.failed += failed
        elapsed = time.monotonic() - self.start
        left = elapsed / self.new * (self.total - self.done)
        eta = f"{left:.0f} s left" if self.done < self.total else f"{elapsed:.1f} s"
        if self.tty:
            width = 30
            fill = int(width * self.done / max(self.total, 1))
            self.stream.write(f"\r[{'#' * fill}{'.' * (width - fill)}] {self.done}/{self.total} "
                              f"runs, {self.failed} failed, {eta}   ")
            if self.done == self.total:
                self.stream.write("\n")
        else:
            values = " ".join(f"{k}={v}" for k, v in task.values.items())
            status = f"failed: {result.error or next(r['error'] for r in result.rows if r.get('error'))}" \
                if failed else "ok"
            self.stream.write(f"run {self.done}/{self.total} (point {task.point}{' ' + values if values else ''}, "
                              f"seed {task.seed}): {status}; {eta}\n")
        self.stream.flush()


def cmd_experiment(args) -> int:
    from ..build.common import BuildError
    from ..check.defines import DefineError
    from ..experiment import engines
    from ..experiment.plan import plan
    from ..experiment.results import load_done, save, write_results
    from ..experiment.spec import ExperimentError, read_experiment
    from .commands import display_name
    shown = display_name(args.file)
    try:
        exp = read_experiment(Path(args.file), shown)
    except ExperimentError as exc:
        print(exc, file=sys.stderr)
        return EXIT_USAGE
    if args.engine == "dask" and not engines.dask_available():
        _error(engines.DASK_MISSING)
        return EXIT_ERRORS
    if args.scheduler and args.engine != "dask":
        _error("--scheduler is for --engine dask")
        return EXIT_USAGE
    try:
        tasks = plan(exp, _loader())
    except ExperimentError as exc:
        print(exc, file=sys.stderr)
        return exc.status
    except (DefineError, BuildError) as exc:
        _error(str(exc))
        return EXIT_ERRORS
    folder = Path(args.output) if args.output else \
        Path(args.file).parent / (Path(args.file).stem + "-results")
    (folder / "runs").mkdir(parents=True, exist_ok=True)
    results = load_done(folder, tasks)
    todo = [t for t in tasks if t.key not in results]
    if results:
        print(f"resuming: {len(results)} of {len(tasks)} runs are already in {folder}",
              file=sys.stderr)
    progress = Progress(len(tasks), len(results))

    def done(task, result):
        save(folder, result, task)
        results[task.key] = result
        progress.update(task, result)

    workers = args.workers or engines.default_workers()
    try:
        engines.run(args.engine, todo, workers, args.scheduler, done)
    except engines.EngineError as exc:
        _error(str(exc))
        return EXIT_ERRORS
    except KeyboardInterrupt:
        print(f"\ninterrupted: {progress.done} of {len(tasks)} runs are saved in {folder}; "
              f"the same command goes on from there", file=sys.stderr)
        return EXIT_INTERRUPTED
    write_results(folder, tasks, results, exp.metrics, title=f"{Path(args.file).name}: "
                  f"{len(exp.seeds)} seeds per point, {exp.duration_ms / 1000:g} s")
    failed = sum(1 for r in results.values() if r.error or any(x.get("error") for x in r.rows))
    print(f"{len(tasks)} runs ({failed} failed): {folder / 'runs.csv'}, "
          f"{folder / 'summary.csv'}, {folder / 'summary.svg'}", file=sys.stderr)
    return EXIT_OK


def _loader():
    """load(path, defines): a program checked and compiled with its
    constants; None after printing its diagnostics."""
    from ..check.frontend import InputError
    from ..diagnostics import Report
    from .commands import _print_report
    from .driver import load_program

    def load(path: Path, defines: dict):
        report = Report()
        try:
            program = load_program(path, report, defines=defines)
        except InputError as exc:
            _error(str(exc))
            return None
        if report.error_count:
            _print_report(report, "human")
        return program if report.error_count == 0 else None
    return load
