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
    p.add_argument("-o", "--output", metavar="OUT.svg", required=True)
    p.add_argument("--title", help="a title above the picture (default: the trace's file name)")
    p.set_defaults(run=run)


def wants_extension(args) -> bool:
    return bool(getattr(args, "world", None) or getattr(args, "svg", None)
                or getattr(args, "html", None)
                or getattr(args, "pose_interval", None))


def run(args, program, load_program_file, run_host) -> int:
    """`epuckc run` with a world, a picture or pose records."""
    from ..build.common import BuildError
    from ..sim.world import WorldError, parse_world
    if args.world and args.scenario:
        _error("--world and --scenario cannot be combined: in a world the proximity readings "
               "come from Enki's sensors, not from a scenario")
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
    loaded = {}

    def load(path, more_c=()):
        """A robot's own program, loaded once (its variables are the replay's)."""
        if (path, tuple(more_c)) not in loaded:
            loaded[path, tuple(more_c)] = load_program_file(path, more_c)
        return loaded[path, tuple(more_c)]

    if world is None:
        variables = {"": program.variables}
    with tempfile.TemporaryDirectory(prefix="epuckc-run-") as tmp:
        trace = Path(args.trace) if args.trace else (Path(tmp) / "trace.jsonl" if pictures else None)
        try:
            if world is not None:
                from ..sim.enki import run_world
                status = run_world(world, program, load, args.time_limit,
                                   trace.resolve() if trace else None, pose_ms)
                variables = {r.name: (program if r.program is None
                                      else load(r.program, r.more_c)).variables
                             for r in world.robots}
            else:
                status = run_host(program, scenario=args.scenario, time_limit_ms=args.time_limit,
                                  trace=str(trace) if trace else None, pose_ms=pose_ms)
        except BuildError as exc:
            _error(str(exc))
            return exc.status
        for out, draw in ((args.svg, "svg"), (args.html, "html")):
            if out:
                plot_status = _plot(trace, Path(out), title=picture_title(args.file, world),
                                    form=draw, variables=variables)
                if plot_status:
                    return plot_status
    return status


def picture_title(program: str, world) -> str:
    """The picture's title: the program; in a world whose robots run
    different programs, each program with its robots (`fast.epk: r1, r2;
    slow.epk: r3`)."""
    default = Path(program).name
    if world is None:
        return default
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
    return _plot(Path(args.trace), Path(args.output), title=args.title or Path(args.trace).name)
