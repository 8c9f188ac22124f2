"""The command line of the robot's trace: `epuckc monitor PORT` and `epuckc
run PROG --int16 --robot-trace` (the same decoding of the same tracer,
the 16-bit simulator's UART in place of a robot's port); the decoding and
the session are epuckc/link/'s."""
from __future__ import annotations

import json
import sys
import tempfile
from pathlib import Path
from typing import Optional

EXIT_USAGE = 2


def _error(message: str):
    print(f"epuckc: error: {message}", file=sys.stderr)


def add_parser(sub, run, duration):
    p = sub.add_parser(
        "monitor", help="show the trace of a robot running a program built with --trace",
        description="Read the robot's trace from its serial port (the e-puck's Bluetooth "
                    "port, /dev/rfcommN; the e-puck2's programmer's second port or its own USB "
                    "port), or from a file of bytes captured from one, and show it as `epuckc "
                    "run` shows a run: the readable trace as it comes, the JSON lines with "
                    "--trace, the replay page with --html. Stops at the program's exit, at "
                    "--time-limit, when the robot starts again, or at Ctrl-C (what came is "
                    "kept). Exit status: 0, 3 after a time limit of the robot's own, 1 a "
                    "stream of another program (a table that does not match), 2 usage or a "
                    "port that cannot be read (docs/robots.md).")
    p.add_argument("port", metavar="PORT", help="the serial port, or a file of captured bytes")
    p.add_argument("--program", metavar="PROG",
                   help="what the robot runs, for the names of its rules, actions and "
                        "variables: its rule file (.epk), its NAME.trace.json, its build "
                        "folder, .hex or .elf (the table beside it), or a C program (shown by "
                        "number); without it the records are shown by number")
    p.add_argument("--trace", metavar="OUT.jsonl",
                   help="also write the trace as JSON lines; `-`: to standard output, instead "
                        "of the readable trace")
    p.add_argument("--html", metavar="OUT.html",
                   help="at the end, write a page that replays the run")
    p.add_argument("--baud", type=int, default=115200, help="the port's speed (default 115200)")
    p.add_argument("--time-limit", type=duration, metavar="DURATION",
                   help="stop after this much of the robot's time (default: at its exit)")
    p.set_defaults(run=run)


def _read_table(path: Path):
    from ..build.trace_table import TableError, read_table
    try:
        return read_table(path)
    except TableError as exc:
        raise _Refused(str(exc)) from None


class _Refused(Exception):
    pass


def find_table(given: str):
    """(table, program or None) for --program: a rule file is compiled (the
    table is a function of the program), a table read, a build's found
    beside it."""
    from ..build.trace_table import SUFFIX, trace_table
    path = Path(given)
    if path.name.endswith(SUFFIX):
        return _read_table(path), None
    if path.is_dir():
        tables = sorted(path.glob(f"*{SUFFIX}"))
        if len(tables) != 1:
            raise _Refused(f"--program {given}: a build folder holds one NAME{SUFFIX} (`epuckc "
                           f"build --trace` writes it); this one has "
                           f"{len(tables) or 'none'}{'' if not tables else ': name one'}")
        return _read_table(tables[0]), None
    if path.suffix in (".hex", ".elf", ".bin"):
        for folder in (path.parent, path.parent.parent):     # the e-puck2's build/NAME.elf
            beside = folder / f"{path.stem}{SUFFIX}"
            if beside.is_file():
                return _read_table(beside), None
        raise _Refused(f"--program {given}: no {path.stem}{SUFFIX} beside it: was it built with "
                       f"--trace? (give the table itself, or the rule file)")
    if not path.is_file():
        raise _Refused(f"--program {given}: the file does not exist")
    program = _compile(path)
    return trace_table(program), program


def _compile(path: Path):
    from ..diagnostics import Report
    from ..diagnostics.render import render_report
    from ..check.frontend import InputError
    from .driver import load_program
    report = Report()
    try:
        program = load_program(path, report, shown_name=str(path))
    except InputError as exc:
        raise _Refused(str(exc)) from None
    if program is None:
        sys.stderr.write(render_report(report, "human"))
        raise _Refused(f"--program {path} has errors (above): its table cannot be made")
    return program


def cmd_monitor(args) -> int:
    from ..link.monitor import MonitorError, Session, read_file, read_serial
    from ..link.stream import TableMismatch, TraceError
    table = program = None
    try:
        if args.program:
            table, program = find_table(args.program)
    except _Refused as exc:
        _error(str(exc))
        return EXIT_USAGE
    problem = _outputs_problem(args, [args.program] if args.program else [])
    if problem:
        _error(problem)
        return EXIT_USAGE
    try:
        session = Session(table, trace=args.trace, html=args.html,
                          title=Path(args.program).name if args.program else args.port,
                          variables=program.variables if program is not None else None,
                          time_limit_ms=args.time_limit)
    except OSError as exc:
        _error(f"cannot write {args.trace}: {exc.strerror or exc}")
        return EXIT_USAGE
    try:
        port = Path(args.port)
        if port.is_file():
            read_file(args.port, session)
        else:
            read_serial(args.port, session, args.baud)
        return session.finish()
    except KeyboardInterrupt:
        try:
            session.finish()
        except MonitorError:
            pass
        return 130
    except TableMismatch as exc:
        _error(str(exc))
        return 1
    except TraceError as exc:
        _error(str(exc))
        return EXIT_USAGE
    except MonitorError as exc:
        session.close_files()       # what came before the port went away is kept
        _error(str(exc))
        return EXIT_USAGE


def _outputs_problem(args, inputs) -> Optional[str]:
    """An output that is one of the inputs, or cannot be written."""
    from ..build.common import BuildError, check_outputs
    outputs = [Path(o) for o in (getattr(args, "trace", None), getattr(args, "html", None))
               if o and o != "-"]
    try:
        check_outputs(outputs, [Path(i) for i in inputs if i])
    except BuildError as exc:
        return str(exc)
    for out in outputs:
        if out.is_dir():
            return f"{out} is a folder: give a file"
    return None


def run_robot_trace(args, program) -> int:
    """`run PROG --int16 --robot-trace`: the 16-bit build with the robot's
    tracer on simavr, its UART's bytes through the monitor's decoder."""
    from ..build.common import BuildError
    from ..build.trace_table import trace_table
    from ..link.monitor import MonitorError, Session
    from ..link.stream import TraceError
    from ..sim.int16 import run_int16_robot
    if args.world:
        _error("--robot-trace runs the program against a scenario (--int16), not in a world")
        return EXIT_USAGE
    problem = _outputs_problem(args, [args.file] + ([args.scenario] if args.scenario else []))
    if problem:
        _error(problem)
        return EXIT_USAGE
    try:
        run = run_int16_robot(program, args.scenario, args.time_limit)
    except BuildError as exc:
        _error(str(exc))
        return exc.status
    try:
        session = Session(trace_table(program), trace=args.trace, html=args.html,
                          title=Path(args.file).name, variables=program.variables)
    except OSError as exc:
        _error(f"cannot write {args.trace}: {exc.strerror or exc}")
        return EXIT_USAGE
    if run.overruns:
        print(f"epuckc: note: {run.overruns} of the {run.polls} polls took longer than their "
              f"1 ms on the AVR (the longest {run.max_cycles} cycles of 16000, at "
              f"{run.max_ms} ms): a robot would have run those polls late; the trace "
              f"shows each at its own ms", file=sys.stderr)
    try:
        session.feed(run.uart)
        status = session.finish()
    except (TraceError, MonitorError) as exc:
        _error(f"the robot's trace of the 16-bit build: {exc}")
        return 1
    if args.svg:
        from .world import _plot
        with tempfile.TemporaryDirectory(prefix="epuckc-robot-") as tmp:
            trace = Path(tmp) / "trace.jsonl"
            trace.write_text("".join(json.dumps(r) + "\n" for r in session.records),
                             encoding="utf-8")
            plotted = _plot(trace, Path(args.svg), title=Path(args.file).name)
            if plotted:
                return plotted
    return status


def robot_trace_allowed(args) -> Optional[str]:
    """Why `--robot-trace` cannot be given with these options, or None."""
    if not getattr(args, "int16", False):
        return "--robot-trace runs the 16-bit build (give --int16 with it)"
    return None
