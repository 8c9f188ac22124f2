"""The command line of worlds and pictures: `epuckc run --world/--svg/
--pose-interval` and `epuckc plot`. Kept apart from cli.py, which only
registers these options and hands over."""
from __future__ import annotations

import argparse
import sys
import tempfile
from pathlib import Path

EXIT_USAGE = 2
DEFAULT_SVG_POSE_MS = 100


def _error(message: str):
    print(f"epuckc: error: {message}", file=sys.stderr)


def add_run_options(p: argparse.ArgumentParser, duration):
    p.add_argument("--world", metavar="FILE.world",
                   help="run in an Enki world (arena, obstacles, several robots; docs/world.md) "
                        "instead of replaying a scenario")
    p.add_argument("--svg", metavar="OUT.svg",
                   help="also draw the run: world, paths, rule firings, the robots' LEDs at the "
                        "end, a timeline with who holds the motors and when the robot is still")
    p.add_argument("--html", metavar="OUT.html",
                   help="also write a page that replays the run (robots moving with their LEDs, "
                        "play/pause, a time slider, the rules fired and the variables at the "
                        "cursor); it needs no network")
    p.add_argument("--pose-interval", type=duration, metavar="DURATION",
                   help=f"add a pose record to the trace every DURATION (default with --svg "
                        f"or --html: "
                        f"{DEFAULT_SVG_POSE_MS}ms; otherwise none)")


def add_plot_parser(sub, run):
    p = sub.add_parser("plot", help="draw a saved trace as an SVG picture",
                       description="Draw a trace written by `epuckc run --trace` (the world, each "
                                   "robot's path, markers where rules fired labelled file:line, "
                                   "the final poses, and a timeline with one row per rule).")
    p.add_argument("trace", metavar="TRACE.jsonl")
    p.add_argument("-o", "--output", metavar="OUT.svg", required=True,
                   help="the SVG picture; OUT.html: the page that replays the run")
    p.add_argument("--title", help="a title above the picture (default: the trace's file name)")
    p.set_defaults(run=run)


def wants_extension(args) -> bool:
    return bool(getattr(args, "world", None) or getattr(args, "svg", None)
                or getattr(args, "html", None)
                or getattr(args, "pose_interval", None))


def _unused_file(args, world) -> bool:
    """FILE given, every robot of the world naming its own program, none of
    them FILE."""
    import os
    for robot in world.robots:
        try:
            if os.path.samefile(robot.program, args.file):
                return False
        except OSError:
            continue
    return True


def file_problem(args):
    """Why FILE cannot be what `run` runs with the world given (or
    without one), or None: without a world FILE is needed; in a world it
    runs on the robots the world gives no `program`, so it is needed when
    some have none, and when all have theirs it must be one of them (a
    FILE that nothing runs is a mistake, not something to ignore)."""
    from ..sim.world import WorldError, parse_world
    if not args.world:
        if args.file is None:
            return ("`epuckc run` needs FILE, the program to run (a rule file, or a C program "
                    "and its MORE.c files); only a --world whose robots each name their "
                    "`program` runs without one")
        return None
    try:
        world = parse_world(Path(args.world), shown=args.world)
    except WorldError:
        return None             # run() reports it
    unnamed = [r.name for r in world.robots if r.program is None]
    if args.file is None and unnamed:
        they = "they run" if len(unnamed) > 1 else "it runs"
        return (f"{_robots(unnamed)} of {args.world} {'have' if len(unnamed) > 1 else 'has'} "
                f"no `program`: give FILE, the program {they}, or name "
                f"{'theirs' if len(unnamed) > 1 else 'its program'} in the world (`robot {unnamed[0]} "
                f"at ... program PROG.epk`)")
    if args.file is not None and not unnamed and _unused_file(args, world):
        return (f"{args.file} would not run: every robot of {args.world} names its own "
                f"program ({ran_by(world, None)}); leave FILE out, or take `program ...` off "
                f"the robots that should run it")
    return None


def _robots(names: list) -> str:
    return ("robot " if len(names) == 1 else "robots ") + ", ".join(names)


def ran_by(world, file) -> str:
    """Which program each robot runs: `leader.epk on leader; follower.epk on
    follower`, FILE's robots as `prog.epk (FILE) on b, c`."""
    by_program: dict = {}
    for robot in world.robots:
        shown = robot.program.name if robot.program is not None else f"{Path(file).name} (FILE)"
        by_program.setdefault(shown, []).append(robot.name)
    return "; ".join(f"{name} on {', '.join(robots)}" for name, robots in by_program.items())


def run(args, program, load_program_file, run_host) -> int:
    """`epuckc run` with a world, a picture or pose records."""
    from ..build.common import BuildError
    from ..sim.world import WorldError, parse_world
    if args.world and args.scenario:
        # the inputs of every robot without a scenario of its own (the
        # world's `scenario` line, which it replaces); what physics gives is
        # refused there (docs/world.md)
        from ..sim.scenario import world_scenario_problems
        problems = world_scenario_problems(Path(args.scenario), args.scenario)
        if problems:
            print("\n\n".join(problems) + "\n", file=sys.stderr)
            return EXIT_USAGE
    pictures = args.svg or args.html
    pose_ms = args.pose_interval or (DEFAULT_SVG_POSE_MS if pictures else None)
    world = None
    if args.world:
        try:
            world = parse_world(Path(args.world), shown=args.world)
        except WorldError as exc:
            print(exc, file=sys.stderr)
            return EXIT_USAGE
        if any(r.program is not None for r in world.robots):     # which program runs where
            print(f"epuckc: {args.world} runs {ran_by(world, args.file)}", file=sys.stderr)
        if args.scenario:
            world.scenario = Path(args.scenario)
    loaded = {}

    def load(path, more_c=()):
        """A robot's own program, loaded once (its variables are the replay's)."""
        if (path, tuple(more_c)) not in loaded:
            loaded[path, tuple(more_c)] = load_program_file(path, more_c)
        return loaded[path, tuple(more_c)]

    from . import outputs
    try:            # the robots' own programs, whose variables --trace-vars may name
        runs = [program] + ([load(r.program, r.more_c) for r in world.robots if r.program]
                            if world is not None else [])
    except BuildError as exc:
        _error(str(exc))
        return exc.status
    bad = outputs.set_trace_vars(args, [p.variables for p in runs if p is not None])
    if bad is not None:
        return bad
    if world is None:
        variables = {"": program.variables}
    with tempfile.TemporaryDirectory(prefix="epuckc-run-") as tmp:
        # `--trace -` in a world: the merged trace on stdout as the world runs
        stream = sys.stdout if world is not None and args.trace == "-" else None
        trace = Path(args.trace) if args.trace and stream is None else \
            (Path(tmp) / "trace.jsonl" if pictures else None)
        try:
            if world is not None:
                from ..sim.enki import run_world
                status = run_world(world, program, load, args.time_limit,
                                   trace.resolve() if trace else None, pose_ms, stream=stream)
                variables = {r.name: (program if r.program is None
                                      else load(r.program, r.more_c)).variables
                             for r in world.robots}
            else:
                status = run_host(program, scenario=args.scenario, time_limit_ms=args.time_limit,
                                  trace=str(trace) if trace else None, pose_ms=pose_ms)
        except BuildError as exc:
            _error(str(exc))
            return exc.status
        variables = outputs.traced_variables(variables, args)
        for out, draw in ((args.svg, "svg"), (args.html, "html")):
            if out:
                plot_status = _plot(trace, Path(out), title=picture_title(args.file, world),
                                    form=draw, variables=variables)
                if plot_status:
                    return plot_status
        outputs.warn_if_large(trace, [args.trace, args.svg, args.html])
    return status


def picture_title(program, world) -> str:
    """The picture's title: the program; in a world whose robots run
    different programs, each program with its robots (`fast.epk: r1, r2;
    slow.epk: r3`)."""
    if world is None:
        return Path(program).name
    default = Path(program).name if program else Path(world.path).name
    by_program = {}
    for robot in world.robots:
        name = robot.program.name if robot.program is not None else default
        by_program.setdefault(name, []).append(robot.name)
    if len(by_program) == 1:
        return default
    return "; ".join(f"{name}: {', '.join(robots)}" for name, robots in by_program.items())


def _plot(trace: Path, out: Path, title: str, form: str = "svg", variables=None) -> int:
    """Draw a trace as an SVG picture, or as the page that replays it
    (`variables`: each robot's declared ones, replay_html's)."""
    from ..base.output import write_atomic
    from ..sim.plot import PlotError, plot_trace
    from ..sim.replay import replay_html
    try:
        text = trace.read_text(encoding="utf-8")
    except FileNotFoundError:
        _error(f"the trace {trace} does not exist")
        return EXIT_USAGE
    except (OSError, UnicodeDecodeError) as exc:
        _error(f"cannot read {trace}: {getattr(exc, 'strerror', None) or exc}")
        return EXIT_USAGE
    try:
        if form == "svg":
            svg = plot_trace(text, title=title, source=str(trace))
        else:
            svg = replay_html(text, title=title, source=str(trace), variables=variables)
    except PlotError as exc:
        _error(str(exc))
        return EXIT_USAGE
    try:
        write_atomic(out, svg)
    except OSError as exc:
        _error(f"cannot write {out}: {exc.strerror or exc}")
        return EXIT_USAGE
    return 0


def cmd_plot(args) -> int:
    """The picture, or with OUT.html the page that replays the trace."""
    form = "html" if Path(args.output).suffix == ".html" else "svg"
    return _plot(Path(args.trace), Path(args.output), title=args.title or Path(args.trace).name,
                 form=form)
