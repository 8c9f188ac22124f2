"""The command line's arguments: one argparse parser per command, built only
for the command that runs, and the checks of numbers and durations given
on it."""
from __future__ import annotations

import argparse

from .. import __version__
from .commands import (cmd_build, cmd_check, cmd_compile, cmd_explain, cmd_fmt, cmd_lsp, cmd_run,
                       cmd_test)


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


# Bounds of the numbers given on the command line: the runtime's ids are
# 16-bit ints on the robot, and the harness counts at most MAX_TIME_LIMIT_MS
# of virtual time (MAX_SCENARIO_MS in runtime_c/host/host_harness.h).
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
    m = re.fullmatch(r"\s*([0-9]+)(?:\.([0-9]+))?\s*(ms|s|min)?\s*", value)
    if not m:
        raise argparse.ArgumentTypeError(f"{_clip(value)!r} is not a duration such as 60s or 500ms")
    whole, fraction, unit = m.group(1), m.group(2) or "", m.group(3)
    if unit is None:
        number = whole + ("." + fraction if fraction else "")
        raise argparse.ArgumentTypeError(
            f"{_clip(value)} needs a unit: write {_clip(number)}s for seconds or "
            f"{_clip(number)}ms for milliseconds")
    # exactly, in whole numbers: the value is scaled / 10**len(fraction) ms
    # (the decimal module's import would cost every `epuckc run` 5 ms)
    if len(whole) + len(fraction) > 40:
        scaled, denominator = MAX_TIME_LIMIT_MS + 1, 1
    else:
        scaled, denominator = int(whole + fraction) * _UNIT_MS[unit], 10 ** len(fraction)
    if scaled < denominator:
        raise argparse.ArgumentTypeError("the time limit must be at least 1 ms")
    if scaled > MAX_TIME_LIMIT_MS * denominator:
        raise argparse.ArgumentTypeError(
            f"{_clip(value)} is too long: the harness runs at most {MAX_TIME_LIMIT_MS // 1000} s "
            "of virtual time")
    if scaled % denominator:
        raise argparse.ArgumentTypeError(f"{_clip(value)} is not a whole number of milliseconds")
    return scaled // denominator


def _add_program_options(p: argparse.ArgumentParser, file_optional: bool = False):
    if file_optional:       # `run --world`: a world may name every robot's program
        p.add_argument("file", metavar="FILE", nargs="?",
                       help="a rule file (.epk) or a C program using the runtime; with "
                            "--world, the program of the robots the world names none for "
                            "(left out when the world names every robot's)")
    else:
        p.add_argument("file", metavar="FILE",
                       help="a rule file (.epk) or a C program using the runtime")
    _add_program_settings(p)


def _add_program_settings(p: argparse.ArgumentParser):
    """The options of a program read from a file (after its FILE)."""
    _add_capacity_options(p)
    p.add_argument("--werror", action="store_true", help="treat warnings as errors")
    p.add_argument("-D", dest="defines", action="append", type=_define, metavar="NAME=VALUE",
                   help="give the constant NAME the value VALUE (a number with its unit, e.g. "
                        "-D SPEED=400steps/s) instead of its `const` line's; checked as if "
                        "written there")


def add_trace_options(p: argparse.ArgumentParser):
    """The robot's trace, an option of every command that builds for a robot
    (`build`, and what builds before it uploads)."""
    p.add_argument("--trace", action="store_true",
                   help="dspic, epuck2: build the robot's tracer in: the trace the host "
                        "harness gives, compact, on the robot's serial link (the e-puck's "
                        "Bluetooth; the e-puck2's UART3 through its programmer), for "
                        "`epuckc monitor`; writes NAME.trace.json beside the program")
    p.add_argument("--trace-link", choices=("uart", "usb"), metavar="LINK",
                   help="epuck2 with --trace: uart (UART3, the programmer's second serial "
                        "port; the default) or usb (the main processor's own USB serial port)")


def _define(text: str) -> tuple:
    from ..check.defines import DefineError, parse_define
    try:
        return parse_define(text)
    except DefineError as exc:
        raise argparse.ArgumentTypeError(str(exc)) from None


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
    p.add_argument("--target", choices=("host", "dspic", "epuck2"), default="host",
                   help="the robot it is for: a device the target lacks is an error (E070); "
                        "host (the simulation) has every device")
    p.add_argument("--no-world", action="store_true",
                   help="the files are to run without a world (`epuckc run FILE` alone): a "
                        "device only a world gives (IR messages, the camera's colours, the "
                        "ToF sensor's obstacles) is a warning, W070, as at run time")
    p.add_argument("--no-cache", action="store_true",
                   help="check every file again (by default a file is checked again only when "
                        "it, its extern C files or epuckc changed; the results are kept in "
                        "epuckc's cache folder, $EPUCKC_CACHE_DIR); EPUCKC_NO_CACHE does the same")
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
                                   "`-` reads standard input and writes standard output, the "
                                   "text unchanged when it has syntax errors (an editor's filter "
                                   "keeps it). Exit status: 0 done, 1 syntax errors (nothing is "
                                   "written) "
                                   "or, with --check, files that would change, 2 I/O error.")
    p.add_argument("files", nargs="+", metavar="FILE")
    p.add_argument("--check", action="store_true",
                   help="write nothing; name the files that would change and exit 1 if any")
    p.add_argument("--diff", action="store_true",
                   help="write nothing; print a unified diff of the changes")
    p.add_argument("--errors", action="store_true",
                   help="with `-`: also print the diagnostics of a text that cannot be "
                        "formatted on stderr (it is always given back unchanged on stdout)")
    p.set_defaults(run=cmd_fmt)


def _lsp_parser(sub):
    p = sub.add_parser("lsp", help="run the language server on standard input/output",
                       description="The language server for editors (LSP over stdio): "
                                   "diagnostics as you type, hover, completion, go to "
                                   "definition, references, outline, rename, quick fixes, "
                                   "formatting. See docs/language-server.md and "
                                   "editors/README.md.")
    p.set_defaults(run=cmd_lsp)


def _studio_parser(sub):
    from .commands import cmd_studio
    p = sub.add_parser("studio", help="write, check, run and replay programs in the browser",
                       description="Serve a page on 127.0.0.1 (a random token in its URL) with "
                                   "an editor of DIR's rule files (diagnostics as you type, "
                                   "quick fixes, hover, completion, formatting, saving), Run in "
                                   "a world or scenario streamed into an arena, replay, the "
                                   "generated C, and a class folder's exercises with Check "
                                   "(docs/studio.md).")
    p.add_argument("dir", nargs="?", default=".", metavar="DIR",
                   help="the folder of the programs (default: the current folder)")
    p.add_argument("--port", type=_port, default=None, metavar="N",
                   help="the port on 127.0.0.1 (default 8743, or a free one when it is taken)")
    p.add_argument("--no-browser", action="store_true",
                   help="print the URL only; do not open a browser")
    p.set_defaults(run=cmd_studio)


def _port(text: str) -> int:
    if not (text.isascii() and text.isdigit()) or not 0 <= int(text) <= 65535:
        raise argparse.ArgumentTypeError(f"{_clip(text)} is not a port: give 0 to 65535 "
                                         "(0: any free port)")
    return int(text)


def _compile_parser(sub):
    p = sub.add_parser("compile", help="compile a rule file to C",
                       description="Compile a rule file to one C file for the runtime. Nothing is "
                                   "written when the file has errors.")
    _add_program_options(p)
    p.add_argument("-o", "--output", metavar="OUT.c",
                   help="the C file (default: FILE with .c); `-` is standard output")
    p.add_argument("--target", choices=("host", "dspic", "epuck2"), default="host",
                   help="the robot it is for: a device the target lacks is an error (E070); "
                        "otherwise the C is the same for every target")
    p.set_defaults(run=cmd_compile)


def _build_parser(sub):
    p = sub.add_parser("build", help="build for the host harness, the e-puck or the e-puck2",
                       description="host: the harness executable, built with the system C compiler "
                                   "(CC honoured). dspic: a project directory with a Makefile for "
                                   "Microchip XC16, built when xc16-gcc is found (PATH or XC16_DIR); "
                                   "epuck2: a project on GCtronic's e-puck2 firmware (--firmware or "
                                   "EPUCK2_FIRMWARE), built with arm-none-eabi-gcc; "
                                   "exit status 3 when a toolchain or the firmware is missing.")
    _add_program_options(p)
    p.add_argument("--target", choices=("host", "dspic", "epuck2"), default="host")
    add_build_options(p)
    p.set_defaults(run=cmd_build)


def add_build_options(p: argparse.ArgumentParser):
    """The options of how `build` builds, besides the program's and the
    target: `epuckc flash` takes them too (it builds a rule file first,
    through cmd_build), so a build option added here works for both."""
    p.add_argument("--firmware", metavar="DIR",
                   help="epuck2: the e-puck2_main-processor folder (default: $EPUCK2_FIRMWARE)")
    p.add_argument("-o", "--output", metavar="DIR",
                   help="output directory (default: build/NAME-TARGET)")
    add_trace_options(p)


def _seed(text: str) -> int:
    if not text.isdigit() or int(text) > 0xFFFFFFFF:
        raise argparse.ArgumentTypeError(f"{text} is not a seed: write a whole number from 0 "
                                         f"to 4294967295")
    return int(text)


def _watchdog_ms(text: str) -> int:
    """--watchdog SECONDS, as whole ms for the harness."""
    from decimal import Decimal, InvalidOperation
    try:
        seconds = Decimal(text)
    except InvalidOperation:
        seconds = None
    if seconds is None or not seconds.is_finite() or not Decimal("0.1") <= seconds <= 3600:
        raise argparse.ArgumentTypeError(f"{_clip(text)} is not a number of seconds from 0.1 "
                                         f"to 3600")
    return int(seconds * 1000)


def _run_parser(sub):
    p = sub.add_parser("run", help="build for the host and run on the simulated e-puck",
                       description="Build for the host harness (cached) and run, printing the trace. "
                                   "Exit status: 0 when the program reached exit_main, 3 on a "
                                   "time-out, 1 when it does not build.")
    _add_program_options(p, file_optional=True)
    p.add_argument("more", nargs="*", metavar="MORE.c",
                   help="the C program's other files, when FILE is a C main written against "
                        "the e-puck library (docs/runtime.md, C programs)")
    p.add_argument("--watchdog", type=_watchdog_ms, metavar="SECONDS",
                   help="stop the run when the program's C (an extern action, an agenda, a "
                        "C main) keeps the simulator waiting this long in wall-clock time "
                        "(default 5)")
    p.add_argument("--scenario", metavar="FILE.scn", help="proximity readings over time")
    p.add_argument("--int16", action="store_true",
                   help="run on the 16-bit path (avr-gcc and simavr: int is 16 bits, as on the "
                        "dsPIC) against the scenario, so that the extern C's int overflows wrap "
                        "as on the robot")
    p.add_argument("--robot-trace", action="store_true",
                   help="with --int16: the trace from the robot's own tracer (the build's "
                        "--trace) over the simulated UART, decoded as `epuckc monitor` decodes "
                        "a robot's, in the robot's time (each poll within its ms)")
    p.add_argument("--time-limit", type=_duration_ms, default=60000, metavar="DURATION",
                   help="virtual time limit with its unit, e.g. 60s, 500ms or 2min (default 60s)")
    p.add_argument("--trace", metavar="OUT.jsonl",
                   help="also write the trace as JSON lines; `-`: to standard output, "
                        "instead of the readable trace")
    p.add_argument("--trace-vars", metavar="NAMES",
                   help="the variables whose changes the trace writes, separated by commas (an "
                        "array's name for its elements); `none`: none (default: all)")
    p.add_argument("--seed", type=_seed, metavar="N",
                   help="seed of `random` (default 1: every run is the same); in a world, "
                        "robot k gets N + k, and Enki's noise comes from the world's own "
                        "`seed` line")
    from . import world as world_cli
    world_cli.add_run_options(p, _duration_ms)
    p.set_defaults(run=cmd_run)


def _jobs(text: str) -> int:
    if not (text.isascii() and text.isdigit()) or not 1 <= int(text) <= 1024:
        raise argparse.ArgumentTypeError(f"{_clip(text)} is not a number of jobs: give 1 to 1024")
    return int(text)


def _test_parser(sub):
    p = sub.add_parser("test", help="run golden-output tests of rule files",
                       description="Run each rule file under the paths (folders recursively) as "
                                   "a case: its scenario NAME.scn or world NAME.world and options "
                                   "NAME.toml beside it, its output compared with NAME.trace, "
                                   "NAME.diag (and NAME.c when asked) beside it (docs/testing.md)."
                                   " Exit status: 0 all passed, 1 some failed, 2 a bad path or "
                                   "options file.")
    p.add_argument("paths", nargs="*", metavar="PATH", help="folders or rule files (default: .)")
    p.add_argument("--bless", action="store_true",
                   help="write or rewrite the expected files from what the cases produce now, "
                        "and say which changed")
    p.add_argument("-j", "--jobs", type=_jobs, metavar="N",
                   help="cases run at once (default: the number of processors)")
    p.add_argument("-v", "--verbose", action="store_true", help="also name the cases that pass")
    p.set_defaults(run=cmd_test)


def _plot_parser(sub):
    from . import world as world_cli
    world_cli.add_plot_parser(sub, world_cli.cmd_plot)


def _monitor_parser(sub):
    from . import monitor
    monitor.add_parser(sub, monitor.cmd_monitor, _duration_ms)


def _experiment_parser(sub):
    from . import experiment
    experiment.add_parser(sub, experiment.cmd_experiment)


def _flash_parser(sub):
    from . import flash
    flash.add_parser(sub, flash.cmd_flash, _add_program_settings, add_build_options)


def _tune_parser(sub):
    from . import tune
    tune.add_parser(sub, tune.cmd_tune)


def _cache_parser(sub):
    from . import cache
    cache.add_parser(sub, cache.cmd_cache)


# The commands in the order `epuckc --help` lists them.
_COMMANDS = {"check": _check_parser, "explain": _explain_parser, "fmt": _fmt_parser,
             "lsp": _lsp_parser, "compile": _compile_parser, "build": _build_parser,
             "run": _run_parser, "test": _test_parser, "plot": _plot_parser,
             "monitor": _monitor_parser, "experiment": _experiment_parser, "tune": _tune_parser,
             "flash": _flash_parser, "studio": _studio_parser, "cache": _cache_parser}
