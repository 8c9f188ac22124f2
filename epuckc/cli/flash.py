"""`epuckc flash PROG`: a rule file or C program built first (through
`epuckc build`'s own command, with its options), or a built .hex (the
e-puck) or .elf (the e-puck2), put on one robot or several at once
(epuckc/link/). Exit status: 0 every robot flashed, 1 a robot failed (or
none was found), 2 a bad request or file, 3 a missing tool; a build that
fails gives the build's status."""
from __future__ import annotations

import argparse
import re
import sys
from pathlib import Path

from .commands import EXIT_ERRORS, EXIT_OK, EXIT_USAGE, _error, display_name

# The file kinds the target follows from; a rule file or C needs --target.
_BUILT = {".hex": "epuck", ".elf": "epuck2"}
_SOURCES = (".epk", ".c")
_BUILD_TARGET = {"epuck": "dspic", "epuck2": "epuck2"}
_ROBOT = {"epuck": "e-puck", "epuck2": "e-puck2"}
MAX_WAIT_S = 3600


def _robot_id(text: str) -> int:
    if not (text.isascii() and text.isdigit()) or int(text) > 0xFFFF:
        raise argparse.ArgumentTypeError(f"{text[:24]!r} is not a robot number: give the e-puck's "
                                         "number, 0 to 65535 (on its sticker; its Bluetooth PIN)")
    return int(text)


def _seconds(text: str) -> float:
    """A wait with its unit (30s, 2min, 500ms), up to an hour."""
    found = re.fullmatch(r"\s*([0-9]{1,7}(?:\.[0-9]{1,3})?)\s*(ms|s|min)\s*", text)
    if not found:
        raise argparse.ArgumentTypeError(f"{text[:24]!r} is not a duration with its unit, such "
                                         "as 30s, 2min or 500ms")
    seconds = float(found.group(1)) * {"ms": 0.001, "s": 1, "min": 60}[found.group(2)]
    if not 0.1 <= seconds <= MAX_WAIT_S:
        raise argparse.ArgumentTypeError(f"{text.strip()} is out of range: give 100ms to 60min")
    return seconds


def add_parser(sub, run, add_program_settings, add_build_options):
    """`flash`'s parser; after its own options, the program's settings and
    the build's options as args.py gives them to `build`."""
    p = sub.add_parser(
        "flash", help="put a program on e-pucks or e-puck2s (building it first)",
        description="Build PROG as `epuckc build --target` does (a rule file or a C program), or "
                    "take it built (.hex for the e-puck, .elf for the e-puck2), and flash it: "
                    "the e-puck2 through its USB programmer with GDB (gdb-multiarch or "
                    "arm-none-eabi-gdb), the e-puck through its Bluetooth bootloader. Several "
                    "--port flash several robots at once. docs/robots.md has the set-up. Exit "
                    "status: 0 every robot flashed, 1 a robot failed or none was found, 2 a bad "
                    "request or file, 3 a missing tool.")
    p.add_argument("file", metavar="PROG", nargs="?",
                   help="a rule file (.epk) or C program, or a built .hex (e-puck) or .elf "
                        "(e-puck2)")
    p.add_argument("--target", choices=("epuck", "epuck2", "dspic"),
                   help="the robot: epuck (dspic, as `build` names it) or epuck2; a .hex is for "
                        "the e-puck and an .elf for the e-puck2, a rule file or C needs it")
    p.add_argument("--port", action="append", metavar="PORT", dest="ports",
                   help="the robot's serial port (the e-puck2's programmer, /dev/ttyACM0; the "
                        "e-puck's Bluetooth port, /dev/rfcomm0); give it once per robot to flash "
                        "several at once (default: the one robot connected)")
    p.add_argument("--robot-id", action="append", type=_robot_id, metavar="N", dest="robot_ids",
                   help="e-puck: the robot's number (its sticker, its Bluetooth PIN), which the "
                        "bootloader keeps; one per --port, in the same order (default: the "
                        "number in the port's name, as macOS names it)")
    p.add_argument("--all", action="store_true",
                   help="flash every robot of the target found connected")
    p.add_argument("--list", action="store_true",
                   help="list the robots' ports found, and flash nothing")
    p.add_argument("--reset-window", type=_seconds, default=30.0, metavar="DURATION",
                   help="e-puck: the time to press the robot's reset button when asked "
                        "(default 30s)")
    p.add_argument("--timeout", type=_seconds, default=120.0, metavar="DURATION",
                   help="the longest one robot's flash may take once it answers (default 2min)")
    add_program_settings(p)
    add_build_options(p)
    p.set_defaults(run=run)


def _list_ports() -> int:
    from ..link.ports import bluetooth_ports, epuck2_programmers, system_ports
    infos = system_ports()
    found = epuck2_programmers(infos) + bluetooth_ports(infos)
    if not found:
        print("epuckc: no robot's port was found (an e-puck2's USB programmer, an e-puck's "
              "Bluetooth port); docs/robots.md says how to connect them", file=sys.stderr)
    for port in found:
        what = ("e-puck2 programmer (GDB port)" if port.kind == "epuck2" else
                f"e-puck {port.robot_id}" if port.robot_id is not None else "Bluetooth port")
        print(f"{port.device}\t{what}\t{port.description}")
    return EXIT_OK


class _Refused(Exception):
    """The request cannot be carried out: the message, and the status."""

    def __init__(self, message: str, status: int = EXIT_USAGE):
        super().__init__(message)
        self.status = status


def _kind(args, shown: str) -> str:
    """The robot the program is for."""
    suffix = Path(args.file).suffix.lower()
    wanted = "epuck" if args.target == "dspic" else args.target
    if suffix in _BUILT:
        kind = _BUILT[suffix]
        if wanted and wanted != kind:
            raise _Refused(f"{shown} is built for the {_ROBOT[kind]} ({suffix}), not the "
                           f"{_ROBOT[wanted]}: leave out --target, or give the "
                           f"{'.elf' if wanted == 'epuck2' else '.hex'} built for the "
                           f"{_ROBOT[wanted]}")
        return kind
    if suffix in _SOURCES:
        if not wanted:
            raise _Refused(f"which robot is {shown} for? give --target epuck or --target "
                           "epuck2 (it is built first, as `epuckc build --target` builds it)")
        return wanted
    hint = " (give the .elf beside it: GDB takes the addresses from it)" if suffix == ".bin" \
        else ""
    raise _Refused(f"{shown}: flash takes a rule file (.epk), a C program (.c), or a built "
                   f"program: .hex for the e-puck, .elf for the e-puck2{hint}")


def _robots(args, kind: str) -> list:
    """The robots to flash: the --port ones, else the one found (or with
    --all every one found); an e-puck's number from --robot-id, else from
    its port's name."""
    from ..link.flash import Robot
    from ..link.ports import not_found, robot_number, robot_ports, system_ports, wrong_port
    ids = list(args.robot_ids or [])
    if kind == "epuck2" and ids:
        raise _Refused("--robot-id is the e-puck's number for its bootloader; the e-puck2 has "
                       "none: leave it out")
    if args.ports:
        if args.all:
            raise _Refused("--all flashes every robot found: give either --port or --all")
        ports = list(dict.fromkeys(args.ports))
        if len(ports) != len(args.ports):
            raise _Refused("a port is given twice with --port: give each robot's port once")
        listed = system_ports()
        for given in ports:
            problem = wrong_port(given, kind, listed)
            if problem:
                raise _Refused(problem)
        numbers = [robot_number(port) for port in ports]
    else:
        found = robot_ports(kind)
        if not found:
            raise _Refused(not_found(kind), EXIT_ERRORS)
        if len(found) > 1 and not args.all:
            raise _Refused(f"{len(found)} {_ROBOT[kind]} ports were found ("
                           f"{', '.join(p.device for p in found)}): name the ones to flash "
                           "with --port, or flash them all with --all")
        ports = [p.device for p in found]
        numbers = [p.robot_id for p in found]
    if kind == "epuck2":
        return [Robot(kind, port) for port in ports]
    if ids:
        if len(ids) != len(ports):
            raise _Refused(f"{len(ids)} --robot-id for {len(ports)} port"
                           f"{'s' if len(ports) > 1 else ''}: give one robot number per "
                           "--port, in the same order")
        numbers = ids
    for port, number in zip(ports, numbers):
        if number is None:
            raise _Refused(f"which e-puck is on {port}? give --robot-id N (the number on its "
                           "sticker, its Bluetooth PIN): the bootloader keeps it in the robot")
    return [Robot(kind, port, number) for port, number in zip(ports, numbers)]


def cmd_flash(args) -> int:
    if args.list:
        return _list_ports()
    if not args.file:
        _error("give the program to flash: epuckc flash PROG (a rule file, a C program, a .hex "
               "or an .elf); `epuckc flash --list` lists the robots' ports")
        return EXIT_USAGE
    from ..link.gdbflash import find_gdb
    from ..link.ports import LinkError
    shown = display_name(args.file)
    try:
        kind = _kind(args, shown)
        robots = _robots(args, kind)
        gdb = find_gdb() if kind == "epuck2" else None
    except (_Refused, LinkError) as exc:
        _error(str(exc))
        return exc.status
    path = Path(args.file)
    if path.suffix.lower() not in _SOURCES and (args.trace or args.trace_link):
        _error(f"{shown} is built already, so --trace cannot build the robot's tracer into "
               f"it: flash the rule file with --trace (it is built first), or build it with "
               f"`epuckc build --trace` and flash what that writes")
        return EXIT_USAGE
    folder = None
    if path.suffix.lower() in _SOURCES:
        path, folder, status = _build(args, kind)
        if path is None:
            return status
        shown = display_name(str(path))
    status = _flash(path, shown, kind, robots, gdb, args)
    if status == EXIT_OK and args.trace:
        _say_monitor(args, kind, robots, folder)
    return status


def _say_monitor(args, kind: str, robots: list, folder: Path) -> None:
    """After a flash with --trace: the command that watches the trace (the
    e-puck's on its Bluetooth port, the one flashed through; the e-puck2's
    on the programmer's serial monitor port or its own USB port)."""
    from ..build.trace_table import table_path
    from .driver import _program_name
    table = table_path(folder, _program_name(Path(args.file)))
    if kind == "epuck":
        ports = " / ".join(r.port for r in robots)
    elif args.trace_link == "usb":
        ports = "PORT (the e-puck2's own USB serial port, once it runs)"
    else:
        ports = "PORT (the programmer's second port, its serial monitor)"
    print(f"epuckc: note: the robot sends its trace: epuckc monitor {ports} --program {table}",
          file=sys.stderr)


def _build(args, kind: str):
    """Build as `epuckc build --target` does; (what it left to flash, its
    folder, status)."""
    from .commands import cmd_build
    from .driver import build_folder, build_output
    from ..build.common import EXIT_NO_TOOLCHAIN
    args.target = _BUILD_TARGET[kind]
    built = []
    out_dir = Path(args.output) if args.output else None
    status = cmd_build(args, on_built=lambda program: built.append(
        (build_output(program, args.target, out_dir),
         build_folder(program, args.target, out_dir))))
    if status == EXIT_NO_TOOLCHAIN and kind == "epuck":
        from .driver import _program_name
        name = _program_name(Path(args.file))
        hexfile = Path(args.output or Path("build") / f"{name}-dspic") / f"{name}.hex"
        print(f"epuckc: note: once the .hex is built, flash it with: epuckc flash {hexfile} "
              f"{' '.join(_robot_arguments(args))}", file=sys.stderr)
    if status != EXIT_OK or not built:
        return None, None, status
    made, folder = built[0]
    if not made.is_file():
        _error(f"the build left no {made} to flash")
        return None, None, EXIT_ERRORS
    return made, folder, EXIT_OK


def _robot_arguments(args) -> list:
    """The --port and --robot-id given, to say the next command."""
    words = [f"--port {p}" for p in args.ports or []] or ["--port PORT"]
    words += [f"--robot-id {n}" for n in args.robot_ids or []] or ["--robot-id N"]
    return words


def _flash(path: Path, shown: str, kind: str, robots: list, gdb, args) -> int:
    from ..link.flash import Settings, flash_robots, read_program
    from ..link.ports import LinkError
    from ..link.progress import Reporter
    try:
        image = read_program(path, shown, kind)
    except LinkError as exc:
        _error(str(exc))
        return EXIT_USAGE
    if getattr(image, "eeprom", False):
        print(f"epuckc: note: {shown} has EEPROM data, which the bootloader does not write "
              "(it writes program memory only)", file=sys.stderr)
    reporter = Reporter(shown)
    try:
        outcomes = flash_robots(robots, image, Settings(args.timeout, args.reset_window),
                                reporter, gdb)
    finally:
        reporter.close()
    failed = [o for o in outcomes if not o.ok]
    if failed and len(outcomes) > 1:
        _error(f"{len(failed)} of {len(outcomes)} robots {'was' if len(failed) == 1 else 'were'} "
               "not flashed: "
               + ", ".join(f"the {o.robot.name}" for o in failed))
    return max((o.status or EXIT_ERRORS for o in failed), default=EXIT_OK)
