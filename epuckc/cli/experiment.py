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


def say_error(message: str):
    print(f"epuckc: error: {message}", file=sys.stderr)


def _workers(text: str) -> int:
    if not text.isdigit() or not 1 <= int(text) <= 4096:
        raise argparse.ArgumentTypeError(f"{text} is not a number of workers (1 to 4096)")
    return int(text)


def _batch(text: str) -> int:
    if not text.isdigit() or not 1 <= int(text) <= 100_000:
        raise argparse.ArgumentTypeError(f"{text} is not a number of runs per task (1 to 100000)")
    return int(text)


def add_engine_options(p, engines=("local", "dask")):
    """--workers, --engine, --scheduler: shared with `epuckc tune`."""
    p.add_argument("--workers", type=_workers, metavar="N",
                   help="runs at a time (default: this machine's cores; with --engine dask "
                        "and no --scheduler, the local cluster's workers"
                        + ("; with --engine slurm, the job array's tasks at once, default no "
                           "limit)" if "slurm" in engines else ")"))
    p.add_argument("--engine", choices=engines, default="local",
                   help="local: a process pool on this machine (default); dask: a Dask "
                        "cluster (pip install 'epuckc[cluster]')"
                        + ("; slurm: a job array of sbatch" if "slurm" in engines else ""))
    p.add_argument("--scheduler", metavar="ADDRESS",
                   help="with --engine dask: the scheduler, e.g. tcp://10.0.0.5:8786 "
                        "(default: a local cluster)")


def add_parser(sub, run):
    p = sub.add_parser("experiment", help="run a world for many seeds and a grid of constants, "
                                          "in parallel, and summarise the metrics",
                       description="Run the experiment of FILE.toml (programs, worlds, robot "
                                   "counts, duration, seeds, metrics and series over time, a "
                                   "grid of constants; docs/experiments.md): DIR/runs.csv has "
                                   "a row per run and robot, DIR/summary.csv and "
                                   "DIR/summary.svg the mean and 95% interval of each metric "
                                   "per grid point, DIR/series.csv and DIR/series.svg the "
                                   "series over time, DIR/times.csv each run's own time. Runs "
                                   "already in DIR are not run again. Exit status: 0 done "
                                   "(failed runs are rows with their error), 1 a program has "
                                   "errors or the engine cannot start, 2 a bad experiment or "
                                   "world file, 130 interrupted.")
    p.add_argument("file", metavar="FILE.toml", nargs="?")
    p.add_argument("-o", "--output", metavar="DIR",
                   help="the results' folder (default: FILE's name without .toml, plus "
                        "-results, beside it)")
    add_engine_options(p, ("local", "dask", "slurm"))
    p.add_argument("--batch", type=_batch, metavar="N",
                   help="runs of one grid point per task (default: enough tasks to keep "
                        "the workers busy, at most 200 runs each)")
    p.add_argument("--report-only", action="store_true",
                   help="simulate nothing: write the tables and pictures again from the runs "
                        "saved in DIR")
    p.add_argument("--sbatch-options", metavar="OPTIONS", default="",
                   help="with --engine slurm: options for sbatch, e.g. "
                        "\"--partition=short --time=01:00:00\"")
    p.add_argument("--detach", action="store_true",
                   help="with --engine slurm: submit the job array and return; the same "
                        "command, or --report-only, collects the runs later")
    p.add_argument("--worker", metavar="JOBS", help=argparse.SUPPRESS)
    p.add_argument("--index", type=int, metavar="I", help=argparse.SUPPRESS)
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


def _problem(args) -> str:
    """What is wrong with the options' combination, or ""."""
    if args.file is None:
        return "give the experiment file: epuckc experiment FILE.toml"
    if args.scheduler and args.engine != "dask":
        return "--scheduler is for --engine dask"
    if (args.sbatch_options or args.detach) and args.engine != "slurm":
        return "--sbatch-options and --detach are for --engine slurm"
    return ""


def cmd_experiment(args) -> int:
    from ..build.common import BuildError
    from ..check.defines import DefineError
    from ..experiment import engines, launch
    from ..experiment.plan import auto_batch, batches, plan
    from ..experiment.results import Saver, failed, load_done, write_results
    from ..experiment.spec import ExperimentError, read_experiment
    from .commands import display_name
    if args.worker:
        from ..experiment.slurm import run_worker
        return run_worker(Path(args.worker), args.index or 0)
    problem = _problem(args)
    if problem:
        say_error(problem)
        return EXIT_USAGE
    shown = display_name(args.file)
    try:
        exp = read_experiment(Path(args.file), shown)
    except ExperimentError as exc:
        print(exc, file=sys.stderr)
        return EXIT_USAGE
    if args.engine == "dask" and not engines.dask_available() and not args.report_only:
        say_error(engines.DASK_MISSING)
        return EXIT_ERRORS
    try:
        tasks = plan(exp, program_loader())
    except ExperimentError as exc:
        print(exc, file=sys.stderr)
        return exc.status
    except (DefineError, BuildError) as exc:
        say_error(str(exc))
        return EXIT_ERRORS
    folder = Path(args.output) if args.output else \
        Path(args.file).parent / (Path(args.file).stem + "-results")
    title = (f"{Path(args.file).name}: {len(exp.seeds)} seeds per point, "
             f"{exp.duration_ms / 1000:g} s")

    def report(results):
        return write_results(folder, tasks, results, exp.metrics, title, exp.series,
                             exp.period_ms, exp.duration_ms)

    results = load_done(folder, tasks)
    if args.report_only:
        if not results:
            say_error(f"no run of this experiment is saved in {folder} yet; run it without "
                   f"--report-only")
            return EXIT_ERRORS
        report(results)
        print(f"report of {len(results)} of {len(tasks)} runs saved in {folder}"
              + (f" ({len(tasks) - len(results)} not run yet)" if len(results) < len(tasks)
                 else "") + f": {_outputs(folder, exp)}", file=sys.stderr)
        return EXIT_OK
    (folder / "runs").mkdir(parents=True, exist_ok=True)
    todo = [t for t in tasks if t.key not in results]
    if results:
        print(f"resuming: {len(results)} of {len(tasks)} runs are already in {folder}",
              file=sys.stderr)
    workers = args.workers or (None if args.engine == "slurm" else engines.default_workers())
    size = args.batch or (max(20, -(-len(todo) // 1000)) if args.engine == "slurm"
                          else auto_batch(len(todo), workers))
    work = batches(todo, size)
    progress = Progress(len(tasks), len(results))
    saver = Saver(folder, work)

    def done(task, result):
        results[task.key] = result
        progress.update(task, result)
        saver(task, result)

    options = ({"folder": folder, "sbatch_options": args.sbatch_options, "detach": args.detach,
                "name": f"epuckc-{Path(args.file).stem}"} if args.engine == "slurm" else {})
    try:
        session = launch.open_engine(args.engine, workers, args.scheduler, **options)
        saver.enabled = not getattr(session, "saves", False)
        try:
            session.run(work, done)
        finally:
            session.close()
    except engines.EngineError as exc:
        say_error(str(exc))
        return EXIT_ERRORS
    except KeyboardInterrupt:
        more = ("; the job array goes on (scancel stops it)" if args.engine == "slurm" else "")
        print(f"\ninterrupted: {progress.done} of {len(tasks)} runs are saved in {folder}; "
              f"the same command goes on from there{more}", file=sys.stderr)
        return EXIT_INTERRUPTED
    if getattr(session, "detached", False):
        return EXIT_OK
    report(results)
    count = sum(1 for r in results.values() if failed(r))
    print(f"{len(tasks)} runs ({count} failed): {_outputs(folder, exp)}", file=sys.stderr)
    return EXIT_OK


def _outputs(folder: Path, exp) -> str:
    names = ["runs.csv", "summary.csv", "summary.svg"]
    names += ["series.csv", "series.svg"] if exp.series else []
    return ", ".join(str(folder / n) for n in names + ["times.csv"])


def program_loader(quiet: bool = False):
    """load(path, defines): a program checked and compiled with its
    constants; None after printing its diagnostics (`quiet`: printing
    nothing, for a tune's candidates)."""
    from ..check.frontend import InputError
    from ..diagnostics import Report
    from .commands import _print_report
    from .driver import load_program

    def load(path: Path, defines: dict):
        report = Report()
        try:
            program = load_program(path, report, defines=defines)
        except InputError as exc:
            if not quiet:
                say_error(str(exc))
            return None
        if report.error_count and not quiet:
            _print_report(report, "human")
        return program if report.error_count == 0 else None
    return load
