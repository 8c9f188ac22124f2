"""The commands: check, explain, fmt, lsp, compile, build and run, each a
function of its parsed arguments returning the exit status. Every command
imports the stages it uses when it runs: `epuckc run` of a file built
before needs none of them (build/runcache.py), and every command starts
faster."""
from __future__ import annotations


import gc
import os
import sys
from pathlib import Path


EXIT_OK, EXIT_ERRORS, EXIT_USAGE, EXIT_INTERNAL = 0, 1, 2, 4   # 3: build.EXIT_NO_TOOLCHAIN


def _colour_wanted(stream) -> bool:
    return stream.isatty() and not os.environ.get("NO_COLOR")


def display_name(name: str) -> str:
    """A file name as typed, printable: bytes that are not UTF-8 (a name
    from another system) become U+FFFD instead of breaking the output."""
    return name.encode("utf-8", "surrogateescape").decode("utf-8", "replace")


def c_file_diagnostic(shown: str) -> Diagnostic:
    from ..diagnostics import ERROR, Diagnostic
    from ..base.source import Span
    return Diagnostic(
        "E006", ERROR, "this is a C file, not a rule file", shown, Span(1, 1, 1, 1),
        help=f"`epuckc build {shown}` and `epuckc run {shown}` take a C program that uses the "
             "runtime as it is; `epuckc check` reads rule files (.epk)")


def _print_report(report: Report, fmt: str):
    from ..diagnostics.render import render_report
    text = render_report(report, fmt, colour=_colour_wanted(sys.stderr) and fmt == "human")
    _show_report_text(text, fmt)


def _show_report_text(text: str, fmt: str):
    if fmt in ("json", "sarif"):
        sys.stdout.write(text)
    elif text:
        sys.stderr.write(text)


def _failed(report: Report, werror: bool) -> bool:
    return report.error_count > 0 or (werror and report.warning_count > 0)


def cmd_check(args) -> int:
    """Every file is checked; one that cannot be read is reported as a
    diagnostic (E005, in every format) and the others are still checked.
    A file checked before is checked again only if something its result
    depends on changed (check/cache.py)."""
    from ..diagnostics import Report
    from ..check.cache import check_cached
    from ..check.frontend import InputError
    report = Report()
    unreadable = False
    others = 0          # world files with errors, checked as world files
    for name in args.files:
        shown = display_name(name)
        if Path(name).suffix in (".c", ".h"):
            report.diagnostics.append(c_file_diagnostic(shown))
            continue
        if Path(name).suffix in (".world", ".scn"):
            others += _check_other_file(Path(name), shown)
            continue
        try:
            check_cached(Path(name), report, shown, target=args.target,
                         use=not args.no_cache, world=not args.no_world)
        except InputError as exc:
            unreadable = True
            report.diagnostics.append(exc.diagnostic(shown))
    if report.diagnostics or not others:
        _print_report(report, args.format)
    if unreadable:
        return EXIT_USAGE
    return EXIT_ERRORS if others or _failed(report, args.werror) else EXIT_OK


def _check_other_file(path: Path, shown: str) -> int:
    """`epuckc check` of a world or scenario file: a world is checked as
    one (all its errors on stderr), a scenario is said to be one; both say
    how they are used. 1 when the file has errors or cannot be read."""
    if path.suffix == ".scn":
        from ..sim.scenario import check_scenario
        try:
            problems = check_scenario(path, shown)
        except OSError as exc:
            print(f"epuckc: error: cannot read {shown}: {exc.strerror or exc}", file=sys.stderr)
            return 1
        if problems:
            print("\n\n".join(problems) + f"\n\n{len(problems)} error"
                  f"{'s' if len(problems) > 1 else ''} in {shown}", file=sys.stderr)
            return 1
        print(f"{shown}: a scenario file (sensor inputs over time), without errors: run a "
              f"program with it: `epuckc run PROG.epk --scenario {shown}`", file=sys.stderr)
        return 0
    from ..sim.world import WorldError, parse_world
    try:
        world = parse_world(path, shown=shown)
    except WorldError as exc:
        print(str(exc), file=sys.stderr)
        return 1
    robots = len(world.robots)
    print(f"{shown}: a world file, without errors ({robots} robot{'s' if robots > 1 else ''}); "
          f"run a program in it: `epuckc run PROG.epk --world {shown}`", file=sys.stderr)
    return 0


def cmd_explain(args) -> int:
    from ..diagnostics.codes import CODES, explanation, normalise
    code = normalise(args.code)
    text = explanation(code)
    if text is None:
        known = ", ".join(sorted(CODES))
        print(f"epuckc: error: no diagnostic has the code {args.code!r}; the codes are {known}",
              file=sys.stderr)
        return EXIT_USAGE
    sys.stdout.write(text if text.endswith("\n") else text + "\n")
    return EXIT_OK


def cmd_fmt(args) -> int:
    from .fmt import run
    return run(args.files, check=args.check, diff=args.diff,
               colour=_colour_wanted(sys.stderr), errors=args.errors)


def cmd_lsp(args) -> int:
    # pygls and lsprotocol are imported here only: the other commands never load them.
    gc.enable()     # a long-running server: see main()
    try:
        from ..ide.lsp import main as serve
    except ImportError as exc:
        _error(f"`epuckc lsp` needs pygls 2 and lsprotocol ({exc}); "
               "install them with: pip install 'pygls>=2' lsprotocol")
        return EXIT_USAGE
    return serve()


def cmd_studio(args) -> int:
    gc.enable()     # a long-running server, as lsp
    folder = Path(args.dir)
    if not folder.is_dir():
        _error(f"{display_name(args.dir)} is not a folder: `epuckc studio DIR` opens the rule "
               "files of a folder")
        return EXIT_USAGE
    try:
        from ..studio.server import DEFAULT_PORT, serve
    except ImportError as exc:
        _error(f"`epuckc studio` needs aiohttp and pygls ({exc}); install them with: "
               "pip install aiohttp 'pygls>=2'")
        return EXIT_USAGE
    try:
        return serve(folder, DEFAULT_PORT if args.port is None else args.port,
                     open_browser=not args.no_browser)
    except OSError as exc:
        _error(f"cannot serve on 127.0.0.1 port {args.port}: {exc.strerror or exc}")
        return EXIT_USAGE


def _error(message: str):
    print(f"epuckc: error: {message}", file=sys.stderr)


def _defines_of(args, path: Path) -> dict:
    """The -D a program takes: all of them, but in a world (whose robots may
    run other programs) only those its rule file declares (a C program:
    none); _world_defines_problem checks that each is some program's."""
    defines = dict(getattr(args, "defines", None) or ())
    if not defines or not getattr(args, "world", None):
        return defines
    if path.suffix == ".c":
        return {}
    from ..check.defines import constants_of
    try:
        declared = set(constants_of(path.read_text(encoding="utf-8"), str(path)))
    except (OSError, UnicodeDecodeError):
        return defines          # the front end says why it cannot be read
    return {name: value for name, value in defines.items() if name in declared}


def _world_defines_problem(args):
    """Why a -D of a world run applies to no program of it (FILE and the
    world's own), or None."""
    defines = dict(getattr(args, "defines", None) or ())
    if not defines or not args.world:
        return None
    from ..sim.world import WorldError, parse_world
    try:
        world = parse_world(Path(args.world), shown=args.world)
    except WorldError:
        return None             # the world's own diagnostics come after
    programs = [Path(args.file)] + [r.program for r in world.robots if r.program is not None]
    taken = set()
    for program in programs:
        taken.update(_defines_of(args, program))
    missing = [name for name in defines if name not in taken]
    if not missing:
        return None
    rules = [display_name(str(p)) for p in dict.fromkeys(programs) if p.suffix != ".c"]
    which = ("the rule files: " + ", ".join(rules) if rules
             else "its programs are C, which has no constants")
    return f"-D {missing[0]}: no program of the run declares a constant {missing[0]} ({which})"


def _load(args, report=None):
    """The C program for FILE (a rule file, compiled, or hand-written C), or
    an exit status after printing why there is none."""
    from ..diagnostics import Report
    from .driver import load_program
    from ..check.frontend import InputError
    from ..check.defines import DefineError
    report = Report() if report is None else report
    problem = _world_defines_problem(args) if getattr(args, "world", None) else None
    if problem:
        _error(problem)
        return None, EXIT_USAGE
    try:
        program = load_program(Path(args.file), report, args.max_actions, args.max_events,
                               shown_name=display_name(args.file),
                               defines=_defines_of(args, Path(args.file)),
                               target=getattr(args, "target", "host"),
                               more_c=getattr(args, "more", None) or (),
                               # `run` alone: what only a world gives is W070
                               world=getattr(args, "command", None) != "run"
                               or bool(getattr(args, "world", None)))
    except (InputError, DefineError) as exc:
        _error(str(exc))
        return None, EXIT_USAGE
    _print_report(report, "human")
    if program is None or _failed(report, getattr(args, "werror", False)):
        return None, EXIT_ERRORS
    return program, EXIT_OK


def cmd_compile(args) -> int:
    from ..build.common import BuildError
    from .driver import write_compiled
    from ..base.output import OutputError
    if Path(args.file).suffix == ".c":
        _error(f"{display_name(args.file)} is already C; `epuckc build` and `epuckc run` "
               "take it as it is")
        return EXIT_USAGE
    program, status = _load(args)
    if program is None:
        return status
    out = args.output if args.output else Path(args.file).with_suffix(".c")
    try:
        write_compiled(program, out)
    except BuildError as exc:
        _error(str(exc))
        return exc.status
    except OutputError as exc:
        _error(str(exc))
        return EXIT_USAGE
    return EXIT_OK


def cmd_build(args, on_built=None) -> int:
    """`epuckc build`; `on_built(program)` is called after a build that
    worked (`epuckc flash` goes on from there)."""
    from ..base.output import is_stdout
    if args.output is not None and is_stdout(args.output):
        _error("`build -o -`: build writes a folder (the executable and its C, or the dspic "
               "project); `-o -` is for `epuckc compile`")
        return EXIT_USAGE
    if args.target == "host":
        _start_runtime_early(Path(args.file), None, args)
    try:
        return _load_and_build(args, on_built)
    finally:
        _stop_runtime_started()


def trace_options(args):
    """`--trace [--trace-link L]` as the build takes them (None: off);
    BuildError for a link without --trace."""
    from ..build.common import BuildError
    from ..build.trace_table import TraceOptions
    link = getattr(args, "trace_link", None)
    if not getattr(args, "trace", False):
        if link:
            raise BuildError(f"--trace-link {link} chooses the link of the robot's trace: "
                             "give --trace with it", status=EXIT_USAGE)
        return None
    return TraceOptions(link=link or "uart")


def _load_and_build(args, on_built=None) -> int:
    from ..build.common import BuildError
    from .driver import build
    from ..base.output import OutputError, describe_os_error
    try:
        trace = trace_options(args)
        if trace is not None:
            from ..build.trace_table import check_trace_target
            check_trace_target(args.target, trace)
    except BuildError as exc:
        _error(str(exc))
        return exc.status
    program, status = _load(args)
    if program is None:
        return status
    try:
        message = build(program, args.target, Path(args.output) if args.output else None,
                        getattr(args, "firmware", None), trace)
    except BuildError as exc:
        _error(str(exc))
        return exc.status
    except OutputError as exc:
        _error(str(exc))
        return EXIT_USAGE
    except OSError as exc:
        _error(describe_os_error(exc, exc.filename, "use"))
        return EXIT_USAGE
    print(message)
    if on_built is not None:
        on_built(program)
    return EXIT_OK


def cmd_run(args) -> int:
    from . import world as world_cli
    wants_world = world_cli.wants_extension(args)
    problem = world_cli.file_problem(args)      # FILE and the world's own programs
    if problem is not None:
        _error(problem)
        return EXIT_USAGE
    if args.seed is not None:       # the harness reads it (platform/platform_host.c)
        os.environ["EPUCK_SEED"] = str(args.seed)
    if args.watchdog is not None:   # and this (host/cmain.c)
        os.environ["EPUCK_WATCHDOG_MS"] = str(args.watchdog)
    from . import outputs
    from ..sim.tracevars import TraceVarsError
    try:
        outputs.selection(args)
    except TraceVarsError as exc:
        _error(str(exc))
        return EXIT_USAGE
    if args.file is None:           # the world names every robot's program
        return world_cli.run(args, None, _robot_program_loader(args), None)
    # A rule file built before goes straight to its executable, or in a
    # world to its robot (runcache.py).
    path, key, data = Path(args.file), None, None
    in_world = bool(args.world)     # (pictures of a run without a world: not cached)
    if args.robot_trace and not args.int16:
        _error("--robot-trace runs the 16-bit build with the robot's tracer: give --int16 "
               "with it")
        return EXIT_USAGE
    if path.suffix != ".c" and (in_world or not wants_world) and not args.defines \
            and not args.more and not args.int16:
        from ..build import runcache
        try:
            data = path.read_bytes()
        except OSError:
            data = None         # the normal path says why
        if data is not None:
            key = runcache.input_key(path, data, args.file, args.max_actions, args.max_events,
                                     kind="world" if in_world else "host")
            entry = runcache.lookup(key) if key is not None else None
            if entry is not None and args.trace_vars is not None and not in_world \
                    and "variables" not in entry.extra:
                entry = None            # recorded before its variables were: built again
            if entry is not None:
                _show_report_text(entry.shown_colour if _colour_wanted(sys.stderr)
                                  else entry.shown, "human")
                if args.werror and entry.warnings:
                    return EXIT_ERRORS
                if in_world:
                    return _run_built_robot(args, entry)
                problem = args.scenario and _scenario_problem(args.scenario)
                if problem:
                    _error(problem)
                    return EXIT_USAGE
                from ..sim.harness import run_executable
                bad = outputs.set_trace_vars(args, [entry.extra.get("variables")])
                if bad is not None:
                    return bad
                try:
                    status = run_executable(Path(entry.exe), scenario=args.scenario,
                                            time_limit_ms=args.time_limit, trace=args.trace)
                    outputs.warn_if_large(args.trace, [args.trace])
                    return status
                except OSError:
                    pass        # gone since: build it again below
    if not wants_world:
        _start_runtime_early(path, data, args)
    try:
        return _load_and_run(args, path, key, data, wants_world)
    finally:
        _stop_runtime_started()


def _run_built_robot(args, entry) -> int:
    """`run --world` of a rule file whose robot was built before."""
    from . import world as world_cli
    from ..sim.enki import BuiltRobot
    extra = entry.extra
    robot = BuiltRobot(Path(entry.exe), extra.get("devices"), list(extra.get("variables", ())))
    return world_cli.run(args, robot, _robot_program_loader(args), None)


def _remember_robot(key, program, report) -> None:
    """After a rule file was checked for a world run: its robot, built now
    (run_world finds it in the build cache), goes in the run cache."""
    from ..build import runcache
    from ..build.common import BuildError, user_headers
    from ..diagnostics.render import render_report
    from ..sim.enki import build_robot, enki_available
    if not enki_available():
        return                  # run_world says what is missing
    try:
        lib = build_robot(program)
    except BuildError:
        return                  # and what does not build
    runcache.record(key, lib, program.user_files + [h for _, h, _ in user_headers(program)],
                    render_report(report, "human"), render_report(report, "human", colour=True),
                    report.warning_count,
                    {"devices": program.devices, "variables": list(program.variables)})


def _start_runtime_early(path: Path, data, args) -> None:
    """The host runtime compiles on the other processors while the front
    end works, when its flags can be told now: for hand-written C, and for
    a rule file without `extern` (no user C can change the capacities)."""
    if path.suffix != ".c":
        try:
            data = path.read_bytes() if data is None else data
        except OSError:
            return              # the front end says why
        if b"extern" in data:
            return
    from ..build.host import start_host_runtime
    start_host_runtime(path.suffix != ".c", args.max_actions, args.max_events)


def _stop_runtime_started() -> None:
    """What no build took (an error in the file, a build found in the cache)."""
    from ..build.host import stop_started_runtime
    stop_started_runtime()


def _load_and_run(args, path: Path, key, data, wants_world: bool) -> int:
    from ..build import runcache
    from . import world as world_cli
    from ..build.common import BuildError
    from ..diagnostics import Report
    from ..diagnostics.render import render_report
    from .driver import run_host
    report = Report()
    program, status = _load(args, report)
    if program is None:
        return status
    if args.scenario:
        problem = _scenario_problem(args.scenario)
        if problem:
            _error(problem)
            return EXIT_USAGE
    if args.int16 and args.robot_trace:
        from .monitor import run_robot_trace
        return run_robot_trace(args, program)
    if args.int16:
        return _run_int16(args, program)
    if wants_world:
        if key is not None and args.world and _unchanged(path, data):
            _remember_robot(key, program, report)
        return world_cli.run(args, program, _robot_program_loader(args), run_host)

    def remember(exe):
        if key is not None and _unchanged(path, data):
            from ..build.common import user_headers
            runcache.record(key, exe, program.user_files
                            + [header for _, header, _ in user_headers(program)],
                            render_report(report, "human"),
                            render_report(report, "human", colour=True), report.warning_count,
                            {"variables": list(program.variables)})
    from . import outputs
    bad = outputs.set_trace_vars(args, [program.variables])
    if bad is not None:
        return bad
    try:
        status = run_host(program, scenario=args.scenario, time_limit_ms=args.time_limit,
                          trace=args.trace, on_built=remember)
        outputs.warn_if_large(args.trace, [args.trace])
        return status
    except BuildError as exc:
        _error(str(exc))
        return exc.status
    except OSError as exc:
        _error(f"{exc.strerror or exc}: {exc.filename or ''}".rstrip(": "))
        return EXIT_USAGE


def _unchanged(path: Path, data: bytes) -> bool:
    """The rule file still holds what was checked (else its build is not
    recorded under the key of what was read)."""
    try:
        return path.read_bytes() == data
    except OSError:
        return False


def _run_int16(args, program) -> int:
    """`run --int16`: the 16-bit path (sim/int16.py), alone with a scenario."""
    from ..build.common import BuildError
    from ..sim.int16 import run_int16
    if args.world or args.svg or args.html:
        _error("--int16 runs against a scenario, not in a world nor with pictures: leave out "
               "--world, --svg and --html")
        return EXIT_USAGE
    try:
        return run_int16(program, args.scenario, args.time_limit, args.trace)
    except BuildError as exc:
        _error(str(exc))
        return exc.status


def _robot_program_loader(args):
    """For a world's robots with their own `program`: load it as FILE is."""
    def load(path: Path, more_c=()):
        from ..build.common import BuildError
        from ..diagnostics import Report
        from .driver import load_program
        from ..check.frontend import InputError
        from ..check.defines import DefineError
        report = Report()
        try:
            program = load_program(path, report, args.max_actions, args.max_events,
                                   more_c=more_c, defines=_defines_of(args, path))
        except (InputError, DefineError) as exc:
            raise BuildError(str(exc), status=EXIT_USAGE) from None
        _print_report(report, "human")
        if program is None or _failed(report, getattr(args, "werror", False)):
            raise BuildError(f"{path} has errors (above); the world was not run", status=EXIT_ERRORS)
        return program
    return load


def _scenario_problem(name: str):
    """Why `--scenario NAME` cannot be read, or None."""
    shown = display_name(name)
    path = Path(name)
    try:
        if path.is_dir():
            return (f"--scenario {shown} is a directory; give a scenario file (.scn) "
                    "such as examples/obstacle.scn")
        if not path.exists():
            return f"--scenario {shown}: the file does not exist"
        from ..sim.scenario import check_scenario
        problems = check_scenario(path, shown)
    except OSError as exc:
        return f"--scenario {shown}: {exc.strerror or exc}"
    if problems:
        # every problem, before anything is built (the harness would stop
        # at the first, at run time)
        print("\n\n".join(problems) + "\n", file=sys.stderr)
        return f"{len(problems)} error{'s' if len(problems) > 1 else ''} in the scenario {shown}"
    return None


def cmd_test(args) -> int:
    """`epuckc test`: the golden-output cases under the paths
    (epuckc/testing/). 0 all passed, 1 some failed, 2 a bad path or a bad
    options file."""
    from ..testing.case import UsageError, discover
    from ..testing.runner import FAILED, PASSED, describe, run_cases, summary
    try:
        cases = discover(args.paths or ["."])
    except UsageError as exc:
        if exc.located:
            print(exc, file=sys.stderr)
        else:
            _error(str(exc))
        return EXIT_USAGE
    if not cases:
        _error(f"no rule files (.epk) under {', '.join(args.paths or ['.'])}")
        return EXIT_USAGE

    def show(outcome):
        text = describe(outcome)
        if text:
            print(text, flush=True)
        elif args.verbose and outcome.status == PASSED:
            print(f"ok   {outcome.case.shown}", flush=True)
    outcomes = run_cases(cases, bless=args.bless, jobs=args.jobs, on_done=show)
    print(summary(outcomes))
    return EXIT_ERRORS if any(o.status == FAILED for o in outcomes) else EXIT_OK
