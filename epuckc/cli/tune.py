"""`epuckc tune FILE.toml`: a search over the programs' constants for the
best values of an objective over the metrics (epuckc/tune/,
docs/experiments.md "Tuning"). This module is the command line's side:
options, the checks before the search, the lines as candidates end, the
final report."""
from __future__ import annotations

import shlex
import sys
from pathlib import Path

from .experiment import (EXIT_ERRORS, EXIT_INTERRUPTED, EXIT_OK, EXIT_USAGE,
                         add_engine_options, program_loader, say_error)

OPTUNA_MISSING = ("epuckc tune needs Optuna, which is not installed; install it with: "
                  "pip install 'epuckc[tune]' (or: pip install optuna)")


def add_parser(sub, run):
    p = sub.add_parser("tune", help="search the programs' constants for the best value of an "
                                    "objective over the metrics",
                       description="Search the constants of FILE.toml's [search] ranges (an "
                                   "experiment file: programs, world, duration, design seeds, "
                                   "metrics; docs/experiments.md, \"Tuning\") for the best "
                                   "value of its objective, with Optuna, candidates stopped "
                                   "early when their first seeds are worse than the others'; "
                                   "then the best on fresh test seeds. DIR/history.csv has a "
                                   "row per candidate, DIR/best.toml and DIR/best.defines the "
                                   "best values, DIR/test.csv the test runs, "
                                   "DIR/convergence.svg and DIR/params.svg the pictures. Runs "
                                   "already in DIR are not run again. Exit status: 0 done, 1 a "
                                   "program has errors, the engine cannot start or no candidate "
                                   "finished, 2 a bad file, 130 interrupted.")
    p.add_argument("file", metavar="FILE.toml")
    p.add_argument("-o", "--output", metavar="DIR",
                   help="the tune's folder (default: FILE's name without .toml, plus -tune, "
                        "beside it)")
    add_engine_options(p)
    p.set_defaults(run=run)


def _read(path: Path, shown: str):
    """(experiment, search), the metrics the objective needs added."""
    from ..experiment.spec import read_experiment
    from ..tune.space import read_search
    exp = read_experiment(path, shown, extensions={"search": read_search})
    search = exp.extra["search"]
    for m in search.objective.metrics:
        if m not in exp.metrics:
            exp.metrics.append(m)
    return exp, search


def _check_fixed(exp, search):
    """[params] of a tune fix constants; the searched ones are in [search]."""
    from ..experiment.plan import error_at as located
    for name, values in exp.params.items():
        if len(values) > 1:
            raise located(exp, f"params.{name}", f"a tune searches [search]: {name} has "
                          f"{len(values)} values here", f"give [params] one value each, or "
                          f"search it: {name} = {{ choices = [...] }} under [search]")
        if any(p.name == name for p in search.params):
            raise located(exp, f"params.{name}", f"{name} is both fixed and searched",
                          "keep it in one of [params] and [search]")


def _check_ends(planner, exp, search):
    """Each range's ends and choices check with the programs: a search
    whose values the checker refuses stops before it starts."""
    from ..experiment.plan import error_at as located
    from ..experiment.spec import ExperimentError
    fixed = {k: v[0] for k, v in exp.params.items()}
    for p in search.params:
        if not planner.constant_defined(p.name):
            raise located(exp, "search", f"no program of the experiment has a constant "
                          f"{p.name}", "a searched name is a `const` of a program")
    corners = [{p.name: p.text(p.low) for p in search.params
                if p.kind != "choice"},
               {p.name: p.text(p.high) for p in search.params if p.kind != "choice"}]
    for p in search.params:
        if p.kind == "choice":
            corners += [{p.name: c} for c in p.choices]
    for values in corners:
        try:
            planner.job(-1, dict(fixed, **values))
        except ExperimentError as exc:
            raise ExperimentError(f"{exc}\nnote: the search reaches these values: "
                                  + ", ".join(f"{k}={v}" for k, v in values.items())
                                  + "; narrow the range", exc.status) from None
    planner.check_variables()


def _line(stream):
    def say(cand, tuner):
        values = ", ".join(f"{k}={v}" for k, v in cand.values.items())
        budget = tuner.search.budget_runs
        used = f"{tuner.used}/{budget} runs" if budget else f"{tuner.used} runs"
        what = {"complete": f"{cand.value:.6g} over {len(cand.per_seed)} seeds",
                "pruned": f"stopped after {len(cand.per_seed)} seeds ({cand.value:.6g})",
                }.get(cand.state, f"{cand.state}: {cand.note}")
        stream.write(f"trial {cand.number} ({values}): {what}; {used}\n")
        stream.flush()
    return say


def cmd_tune(args) -> int:
    from ..build.common import BuildError
    from ..check.defines import DefineError
    from ..experiment import engines, launch
    from ..experiment.plan import Planner
    from ..experiment.spec import ExperimentError
    from .commands import display_name
    try:
        import optuna  # noqa: F401
    except ImportError:
        say_error(OPTUNA_MISSING)
        return EXIT_ERRORS
    from ..tune.race import Tuner
    from ..tune.race import test_summary
    from ..tune.report import seeds_text, write_report
    if args.scheduler and args.engine != "dask":
        say_error("--scheduler is for --engine dask")
        return EXIT_USAGE
    shown = display_name(args.file)
    try:
        exp, search = _read(Path(args.file), shown)
    except ExperimentError as exc:
        print(exc, file=sys.stderr)
        return EXIT_USAGE
    if args.engine == "dask" and not engines.dask_available():
        say_error(engines.DASK_MISSING)
        return EXIT_ERRORS
    folder = Path(args.output) if args.output else \
        Path(args.file).parent / (Path(args.file).stem + "-tune")
    try:
        _check_fixed(exp, search)
        planner = Planner(exp, program_loader())
        _check_ends(planner, exp, search)
        planner.load = program_loader(quiet=True)
        (folder / "runs").mkdir(parents=True, exist_ok=True)
        session = launch.open_engine(args.engine, args.workers or engines.default_workers(),
                                     args.scheduler)
        try:
            tuner = Tuner(exp, search, planner, session, folder, _line(sys.stderr))
            result = tuner.run()
        finally:
            session.close()
    except ExperimentError as exc:
        print(exc, file=sys.stderr)
        return exc.status
    except (DefineError, BuildError) as exc:
        say_error(str(exc))
        return EXIT_ERRORS
    except engines.EngineError as exc:
        say_error(str(exc))
        return EXIT_ERRORS
    except KeyboardInterrupt:
        print(f"\ninterrupted: the runs so far are saved in {folder}; the same command goes "
              f"on from there", file=sys.stderr)
        return EXIT_INTERRUPTED
    fixed = {k: v[0] for k, v in exp.params.items()}
    title = f"{Path(args.file).name}: {len(exp.seeds)} design seeds, {exp.duration_ms / 1000:g} s"
    write_report(folder, search, result, shown, fixed, title)
    ended = "the time budget" if result.stopped == "time" else "the budget"
    print(f"{len(result.candidates)} candidates in {result.runs} runs ({ended}; "
          f"{tuner.simulated} runs simulated now, the test seeds' included): "
          f"{folder / 'history.csv'}, "
          f"{folder / 'convergence.svg'}, {folder / 'params.svg'}", file=sys.stderr)
    if result.best is None:
        say_error("no candidate ran every design seed within the budget: give a larger budget")
        return EXIT_ERRORS
    best = result.best
    test = test_summary(result.test["best"])
    line = (f"best: trial {best.number}, {', '.join(f'{k}={v}' for k, v in best.values.items())}"
            f": {best.value:.6g} on the design seeds")
    if test["mean"] is not None:
        line += f", {test['mean']:.6g} on the test seeds {seeds_text(result.test_seeds)}"
    own = test_summary(result.test["program"])["mean"] if "program" in result.test else None
    if own is not None:
        line += f" (the programs' own constants: {own:.6g})"
    print(line, file=sys.stderr)
    defines = " ".join(f"-D {shlex.quote(f'{k}={v}')}" for k, v in dict(fixed, **best.values).items())
    print(f"{folder / 'best.toml'}, {folder / 'best.defines'}, {folder / 'test.csv'}; run it: "
          f"epuckc run PROGRAM {defines}", file=sys.stderr)
    return EXIT_OK
