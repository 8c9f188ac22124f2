"""The epuckc command line."""
from __future__ import annotations

import argparse
import os
import sys
from pathlib import Path

from . import __version__
from .codes import CODES, explanation, normalise
from .diagnostics import Report, render_report
from .frontend import InputError, check_file

EXIT_OK, EXIT_ERRORS, EXIT_USAGE = 0, 1, 2


def _colour_wanted(stream) -> bool:
    return stream.isatty() and not os.environ.get("NO_COLOR")


def _add_check_options(p: argparse.ArgumentParser):
    p.add_argument("--format", choices=("human", "gcc", "short", "json"), default="human",
                   help="how diagnostics are printed (default: human)")
    p.add_argument("--werror", action="store_true", help="treat warnings as errors")
    p.add_argument("--max-actions", type=int, metavar="N",
                   help="capacity of the runtime's action array (default: the runtime's MAX_ACTIONS)")
    p.add_argument("--max-events", type=int, metavar="N",
                   help="capacity of the runtime's event array (default: the runtime's MAX_EVENTS)")


def _print_report(report: Report, fmt: str):
    text = render_report(report, fmt, colour=_colour_wanted(sys.stderr) and fmt == "human")
    if fmt == "json":
        sys.stdout.write(text)
    elif text:
        sys.stderr.write(text)


def _failed(report: Report, werror: bool) -> bool:
    return report.error_count > 0 or (werror and report.warning_count > 0)


def cmd_check(args) -> int:
    report = Report()
    for name in args.files:
        try:
            check_file(Path(name), report, shown_name=name,
                       max_actions=args.max_actions, max_events=args.max_events)
        except InputError as exc:
            print(f"epuckc: error: {exc}", file=sys.stderr)
            return EXIT_USAGE
    _print_report(report, args.format)
    return EXIT_ERRORS if _failed(report, args.werror) else EXIT_OK


def cmd_explain(args) -> int:
    code = normalise(args.code)
    text = explanation(code)
    if text is None:
        known = ", ".join(sorted(CODES))
        print(f"epuckc: error: no diagnostic has the code {args.code!r}; the codes are {known}",
              file=sys.stderr)
        return EXIT_USAGE
    sys.stdout.write(text if text.endswith("\n") else text + "\n")
    return EXIT_OK


def _positive(value: str) -> int:
    n = int(value)
    if n <= 0:
        raise argparse.ArgumentTypeError("must be a positive number")
    return n


def build_parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(
        prog="epuckc",
        description="Compile e-puck rule files (.epk) to C for the paper's event-driven runtime.")
    parser.add_argument("--version", action="version", version=f"epuckc {__version__}")
    sub = parser.add_subparsers(dest="command", metavar="COMMAND")

    p = sub.add_parser("check", help="check rule files and report every problem",
                       description="Check rule files. Exit status: 0 no errors, 1 errors "
                                   "(or warnings with --werror), 2 usage or I/O error.")
    p.add_argument("files", nargs="+", metavar="FILE")
    _add_check_options(p)
    p.set_defaults(run=cmd_check)

    p = sub.add_parser("explain", help="explain a diagnostic code such as E012",
                       description="Print the long explanation of a diagnostic code.")
    p.add_argument("code", metavar="CODE")
    p.set_defaults(run=cmd_explain)
    return parser


def main(argv=None) -> int:
    parser = build_parser()
    args = parser.parse_args(argv)
    if getattr(args, "command", None) is None:
        parser.print_help(sys.stderr)
        return EXIT_USAGE
    for option in ("max_actions", "max_events"):
        if getattr(args, option, None) is not None and getattr(args, option) <= 0:
            parser.error(f"--{option.replace('_', '-')} must be positive")
    try:
        return args.run(args)
    except KeyboardInterrupt:
        return 130
