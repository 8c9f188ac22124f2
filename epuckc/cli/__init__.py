"""The epuckc command line."""
from __future__ import annotations

import argparse
import gc
import os
import sys
from pathlib import Path

from .. import __version__

# The front end, the diagnostics and the rest are imported by the commands
# that use them: `epuckc run` of a file built before needs none of them
# (see runcache.py), and every command starts faster.

EXIT_OK, EXIT_ERRORS, EXIT_USAGE, EXIT_INTERNAL = 0, 1, 2, 4   # 3: build.EXIT_NO_TOOLCHAIN


def _colour_wanted(stream) -> bool:
    return stream.isatty() and not os.environ.get("NO_COLOR")


def _add_check_options(p: argparse.ArgumentParser):
    p.add_argument("--format", choices=("human", "gcc", "short", "json", "sarif"),
                   default="human",
                   help="how diagnostics are printed (default: human); json and sarif (SARIF "
                        "2.1.0, for code scanning in CI) go to standard output")
    p.add_argument("--werror", action="store_true", help="treat warnings as errors")
    _add_capacity_options(p)


def _add_capacity_options(p: argparse.ArgumentParser):
    p.add_argument("--max-actions", type=_capacity, metavar="N",
                   help="capacity of the runtime's array for register_action calls from C, 1.."
                        f"{MAX_CAPACITY} (a rule file's own rules are tables and need none)")
    p.add_argument("--max-events", type=_capacity, metavar="N",
                   help="capacity of the runtime's array for register_event calls from C, 1.."
                        f"{MAX_CAPACITY} (a rule file's own rules are tables and need none)")


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
    diagnostic (E005, in every format) and the others are still checked."""
    from ..diagnostics import Report
    from ..check.frontend import InputError, check_file
    report = Report()
    unreadable = False
    for name in args.files:
        shown = display_name(name)
        if Path(name).suffix in (".c", ".h"):
            report.diagnostics.append(c_file_diagnostic(shown))
            continue
        try:
            check_file(Path(name), report, shown_name=shown)
        except InputError as exc:
            unreadable = True
            report.diagnostics.append(exc.diagnostic(shown))
    _print_report(report, args.format)
    if unreadable:
        return EXIT_USAGE
    return EXIT_ERRORS if _failed(report, args.werror) else EXIT_OK


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
    from ..ide.fmt import run
    return run(args.files, check=args.check, diff=args.diff,
               colour=_colour_wanted(sys.stderr))


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


def _error(message: str):
    print(f"epuckc: error: {message}", file=sys.stderr)


def _load(args, report=None):
    """The C program for FILE (a rule file, compiled, or hand-written C), or
    an exit status after printing why there is none."""
    from ..diagnostics import Report
    from .driver import load_program
    from ..check.frontend import InputError
    report = Report() if report is None else report
    try:
        program = load_program(Path(args.file), report, args.max_actions, args.max_events,
                               shown_name=display_name(args.file))
    except InputError as exc:
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


def cmd_build(args) -> int:
    from ..base.output import is_stdout
    if args.output is not None and is_stdout(args.output):
        _error("`build -o -`: build writes a folder (the executable and its C, or the dspic "
               "project); `-o -` is for `epuckc compile`")
        return EXIT_USAGE
    if args.target == "host":
        _start_runtime_early(Path(args.file), None, args)
    try:
        return _load_and_build(args)
    finally:
        _stop_runtime_started()


def _load_and_build(args) -> int:
    from ..build.common import BuildError
    from .driver import build
    from ..base.output import OutputError, describe_os_error
    program, status = _load(args)
    if program is None:
        return status
    try:
        message = build(program, args.target, Path(args.output) if args.output else None)
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
    return EXIT_OK


def cmd_run(args) -> int:
    from . import world as world_cli
    wants_world = world_cli.wants_extension(args)
    # A rule file built before goes straight to its executable (runcache.py).
    path, key, data = Path(args.file), None, None
    if path.suffix != ".c" and not wants_world:
        from ..build import runcache
        try:
            data = path.read_bytes()
        except OSError:
            data = None         # the normal path says why
        if data is not None:
            key = runcache.input_key(path, data, args.file, args.max_actions, args.max_events)
            entry = runcache.lookup(key) if key is not None else None
            if entry is not None:
                _show_report_text(entry.shown_colour if _colour_wanted(sys.stderr)
                                  else entry.shown, "human")
                if args.werror and entry.warnings:
                    return EXIT_ERRORS
                problem = args.scenario and _scenario_problem(args.scenario)
                if problem:
                    _error(problem)
                    return EXIT_USAGE
                from ..sim.harness import run_executable
                try:
                    return run_executable(Path(entry.exe), scenario=args.scenario,
                                          time_limit_ms=args.time_limit, trace=args.trace)
                except OSError:
                    pass        # gone since: build it again below
    if not wants_world:
        _start_runtime_early(path, data, args)
    try:
        return _load_and_run(args, path, key, data, wants_world)
    finally:
        _stop_runtime_started()


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
    if wants_world:
        return world_cli.run(args, program, _robot_program_loader(args), run_host)

    def remember(exe):
        if key is None:
            return
        try:
            unchanged = path.read_bytes() == data
        except OSError:
            unchanged = False
        if unchanged:
            from ..build.common import user_headers
            runcache.record(key, exe, program.user_files
                            + [header for _, header, _ in user_headers(program)],
                            render_report(report, "human"),
                            render_report(report, "human", colour=True), report.warning_count)
    try:
        return run_host(program, scenario=args.scenario, time_limit_ms=args.time_limit,
                        trace=args.trace, on_built=remember)
    except BuildError as exc:
        _error(str(exc))
        return exc.status
    except OSError as exc:
        _error(f"{exc.strerror or exc}: {exc.filename or ''}".rstrip(": "))
        return EXIT_USAGE


def _robot_program_loader(args):
    """For a world's robots with their own `program`: load it as FILE is."""
    def load(path: Path):
        from ..build.common import BuildError
        from ..diagnostics import Report
        from .driver import load_program
        from ..check.frontend import InputError
        report = Report()
        try:
            program = load_program(path, report, args.max_actions, args.max_events)
        except InputError as exc:
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
        with open(path, "rb"):
            pass
    except OSError as exc:
        return f"--scenario {shown}: {exc.strerror or exc}"
    return None


# Bounds of the numbers given on the command line: the runtime's ids are
# 16-bit ints on the robot, and the harness counts at most MAX_TIME_LIMIT_MS
# of virtual time (MAX_SCENARIO_MS in runtime_c/host/platform_host.c).
MAX_CAPACITY = 32767
MAX_TIME_LIMIT_MS = 1_000_000_000


def _capacity(value: str) -> int:
    text = value.strip()
    if not (text.isascii() and text.isdigit()):
        raise argparse.ArgumentTypeError(f"{value!r} is not a whole number")
    if len(text) > 6 or not 1 <= int(text) <= MAX_CAPACITY:
        raise argparse.ArgumentTypeError(
            f"{_clip(value)} is out of range: give 1 to {MAX_CAPACITY} (the robot's ids are 16-bit ints)")
    return int(text)


def _clip(value: str, limit: int = 24) -> str:
    return value if len(value) <= limit else value[:limit] + "..."


_UNIT_MS = {"ms": 1, "s": 1000, "min": 60000}


def _duration_ms(value: str) -> int:
    """`60s`, `1500ms`, `2min`, `0.5s`. A unit is required: a bare `5` is
    5 ms in the language, but on the command line it was almost always
    meant as seconds, so it is refused rather than guessed."""
    import re
    from decimal import Decimal
    m = re.fullmatch(r"\s*([0-9]+(?:\.[0-9]+)?)\s*(ms|s|min)?\s*", value)
    if not m:
        raise argparse.ArgumentTypeError(f"{_clip(value)!r} is not a duration such as 60s or 500ms")
    if m.group(2) is None:
        raise argparse.ArgumentTypeError(
            f"{_clip(value)} needs a unit: write {_clip(m.group(1))}s for seconds or "
            f"{_clip(m.group(1))}ms for milliseconds")
    if len(m.group(1)) > 40:
        ms = Decimal(MAX_TIME_LIMIT_MS + 1)
    else:
        ms = Decimal(m.group(1)) * _UNIT_MS[m.group(2)]
    if ms < 1:
        raise argparse.ArgumentTypeError("the time limit must be at least 1 ms")
    if ms > MAX_TIME_LIMIT_MS:
        raise argparse.ArgumentTypeError(
            f"{_clip(value)} is too long: the harness runs at most {MAX_TIME_LIMIT_MS // 1000} s "
            "of virtual time")
    if ms != ms.to_integral_value():
        raise argparse.ArgumentTypeError(f"{_clip(value)} is not a whole number of milliseconds")
    return int(ms)


def _add_program_options(p: argparse.ArgumentParser):
    p.add_argument("file", metavar="FILE", help="a rule file (.epk) or a C program using the runtime")
    _add_capacity_options(p)
    p.add_argument("--werror", action="store_true", help="treat warnings as errors")


def build_parser(only: str | None = None) -> argparse.ArgumentParser:
    """The command line's parser; with `only`, the parser of that one
    command's arguments and no other command (building every command's
    arguments took ~5 ms of each `check`)."""
    parser = argparse.ArgumentParser(
        prog="epuckc",
        description="Compile e-puck rule files (.epk) to C for the paper's event-driven runtime.")
    parser.add_argument("--version", action="version", version=f"epuckc {__version__}")
    sub = parser.add_subparsers(dest="command", metavar="COMMAND")
    for name, add in _COMMANDS.items():
        if only is None or name == only:
            add(sub)
    return parser


def _check_parser(sub):
    p = sub.add_parser("check", help="check rule files and report every problem",
                       description="Check rule files. Exit status: 0 no errors, 1 errors "
                                   "(or warnings with --werror), 2 usage or I/O error.")
    p.add_argument("files", nargs="+", metavar="FILE")
    _add_check_options(p)
    p.set_defaults(run=cmd_check)


def _explain_parser(sub):
    p = sub.add_parser("explain", help="explain a diagnostic code such as E012",
                       description="Print the long explanation of a diagnostic code.")
    p.add_argument("code", metavar="CODE")
    p.set_defaults(run=cmd_explain)


def _fmt_parser(sub):
    p = sub.add_parser("fmt", help="lay rule files out in the one canonical layout",
                       description="Rewrite rule files (or the .epk files under a folder) "
                                   "in place, in the canonical layout (docs/formatting.md); "
                                   "`-` reads standard input and writes standard output. "
                                   "Exit status: 0 done, 1 syntax errors (nothing is written) "
                                   "or, with --check, files that would change, 2 I/O error.")
    p.add_argument("files", nargs="+", metavar="FILE")
    p.add_argument("--check", action="store_true",
                   help="write nothing; name the files that would change and exit 1 if any")
    p.add_argument("--diff", action="store_true",
                   help="write nothing; print a unified diff of the changes")
    p.set_defaults(run=cmd_fmt)


def _lsp_parser(sub):
    p = sub.add_parser("lsp", help="run the language server on standard input/output",
                       description="The language server for editors (LSP over stdio): "
                                   "diagnostics as you type, hover, completion, go to "
                                   "definition, references, outline, rename, quick fixes, "
                                   "formatting. See docs/language-server.md and "
                                   "editors/README.md.")
    p.set_defaults(run=cmd_lsp)


def _compile_parser(sub):
    p = sub.add_parser("compile", help="compile a rule file to C",
                       description="Compile a rule file to one C file for the runtime. Nothing is "
                                   "written when the file has errors.")
    _add_program_options(p)
    p.add_argument("-o", "--output", metavar="OUT.c",
                   help="the C file (default: FILE with .c); `-` is standard output")
    p.add_argument("--target", choices=("host", "dspic"), default="host",
                   help="the C is the same for both targets; accepted for symmetry with build")
    p.set_defaults(run=cmd_compile)


def _build_parser(sub):
    p = sub.add_parser("build", help="build for the host harness or the e-puck",
                       description="host: the harness executable, built with the system C compiler "
                                   "(CC honoured). dspic: a project directory with a Makefile for "
                                   "Microchip XC16, built when xc16-gcc is found (PATH or XC16_DIR); "
                                   "exit status 3 when it is not.")
    _add_program_options(p)
    p.add_argument("--target", choices=("host", "dspic"), default="host")
    p.add_argument("-o", "--output", metavar="DIR",
                   help="output directory (default: build/NAME-TARGET)")
    p.set_defaults(run=cmd_build)


def _run_parser(sub):
    p = sub.add_parser("run", help="build for the host and run on the simulated e-puck",
                       description="Build for the host harness (cached) and run, printing the trace. "
                                   "Exit status: 0 when the program reached exit_main, 3 on a "
                                   "time-out, 1 when it does not build.")
    _add_program_options(p)
    p.add_argument("--scenario", metavar="FILE.scn", help="proximity readings over time")
    p.add_argument("--time-limit", type=_duration_ms, default=60000, metavar="DURATION",
                   help="virtual time limit with its unit, e.g. 60s, 500ms or 2min (default 60s)")
    p.add_argument("--trace", metavar="OUT.jsonl",
                   help="also write the trace as JSON lines; `-`: to standard output, "
                        "instead of the readable trace")
    from . import world as world_cli
    world_cli.add_run_options(p, _duration_ms)
    p.set_defaults(run=cmd_run)


def _plot_parser(sub):
    from . import world as world_cli
    world_cli.add_plot_parser(sub, world_cli.cmd_plot)


# The commands in the order `epuckc --help` lists them.
_COMMANDS = {"check": _check_parser, "explain": _explain_parser, "fmt": _fmt_parser,
             "lsp": _lsp_parser, "compile": _compile_parser, "build": _build_parser,
             "run": _run_parser, "plot": _plot_parser}


def _signal_module():
    # `signal` is `_signal` with its numbers made enums, which costs ~1 ms
    # of every command to import; these two calls need only the numbers.
    try:
        import _signal as signal
    except ImportError:         # an interpreter without it
        import signal
    return signal


def _terminate_cleanly():
    """SIGTERM (a `kill`, a CI timeout) unwinds like Ctrl-C, so temporary
    files and folders are removed on the way out."""
    signal = _signal_module()

    def handler(signum, frame):
        raise SystemExit(128 + signum)
    try:
        return signal.signal(signal.SIGTERM, handler)
    except ValueError:          # not the main thread (an embedding tool)
        return None


def _restore_sigterm(previous):
    signal = _signal_module()
    if previous is not None:
        signal.signal(signal.SIGTERM, previous)


EXIT_BROKEN_PIPE = 128 + 13     # what a shell reports for a process killed by SIGPIPE


def _silence_stdout():
    """Point stdout at /dev/null, so that flushing it at exit cannot raise
    BrokenPipeError again."""
    try:
        devnull = os.open(os.devnull, os.O_WRONLY)
        os.dup2(devnull, sys.stdout.fileno())
        os.close(devnull)
    except (OSError, ValueError):
        pass


def main(argv=None) -> int:
    # A command is short-lived, and what it builds (tokens, the AST, the
    # checked program) holds no reference cycles: the cyclic garbage
    # collector would only walk it again and again (~4 ms of a 1,000-rule
    # check), so it is off until the command ends. `lsp` runs for hours and
    # turns it back on.
    collecting = gc.isenabled()
    gc.disable()
    try:
        return _main(argv)
    finally:
        if argv is None:
            # Run as a program (not called from Python): the process ends
            # now, and the collector's last pass over every object at exit
            # would free nothing.
            gc.freeze()
        elif collecting:
            gc.enable()


def _main(argv) -> int:
    words = sys.argv[1:] if argv is None else list(argv)
    # `epuckc COMMAND ...`: only COMMAND's arguments are needed (the
    # top-level options take no value, so the first word is the command);
    # anything else (`--help`, a misspelt command) gets every command.
    command = words[0] if words and words[0] in _COMMANDS else None
    parser = build_parser(command)
    args = parser.parse_args(words)
    if getattr(args, "command", None) is None:
        parser.print_help(sys.stderr)
        return EXIT_USAGE
    previous = _terminate_cleanly()
    try:
        return args.run(args)
    except KeyboardInterrupt:
        return 130
    except BrokenPipeError:
        # The reader went away (`epuckc compile f.epk -o - | head`): stop
        # quietly, as a Unix filter does, with SIGPIPE's status.
        _silence_stdout()
        return EXIT_BROKEN_PIPE
    except Exception as exc:  # a bug in epuckc: say so plainly, no traceback
        if os.environ.get("EPUCKC_DEBUG"):
            raise
        _error(f"internal error ({type(exc).__name__}: {exc}); this is a bug in epuckc, "
               "please report it with the input (EPUCKC_DEBUG=1 shows the traceback)")
        return EXIT_INTERNAL
    finally:
        _restore_sigterm(previous)
