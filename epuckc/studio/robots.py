"""The page's robot link (docs/studio.md, docs/robots.md): the robots'
serial ports as epuckc/link finds them, Flash and Monitor.

Flash is `epuckc flash PROG --port P ...` and Monitor `epuckc monitor P
--program PROG --trace -`, each what a student would type in the program's
folder, in a child process as Run and Check are: the same builds, the same
one-line failures, the same decoder. Monitor's JSON lines go to the page
as a run's do (runs.py), so the arena shows the robot's own run as it
comes. A port is the name of a character device the page gives (the ports
found are offered; a robot's port that the system does not list, such as
a Bluetooth port bound by hand, may be typed), never a file.
"""
from __future__ import annotations

import os
import stat
import sys

from .workspace import Workspace

FLASH_SUFFIXES = (".epk", ".c", ".hex", ".elf")
MONITOR_SUFFIXES = (".epk", ".c", ".json", ".hex", ".elf")
TARGETS = ("epuck", "epuck2")


class RobotRequestError(Exception):
    """What the page asked of a robot cannot be done; the message says why."""


def link_available() -> bool:
    """Whether this epuckc can reach robots (pyserial, flash's and monitor's)."""
    from importlib.util import find_spec
    return find_spec("serial") is not None


def robot_ports() -> list:
    """The robots' ports found (epuckc/link/ports.py), each with what it is
    for: an e-puck's Bluetooth port flashes and monitors; an e-puck2's
    programmer has a GDB port (flash) and a serial monitor (monitor)."""
    from ..link.ports import (bluetooth_ports, epuck2_monitor_ports, epuck2_programmers,
                              system_ports)
    try:
        infos = system_ports()
    except Exception as exc:        # a system whose list pyserial cannot read
        return [{"error": f"the system's serial ports cannot be listed: {exc}"}]
    found = [(p, ["flash"]) for p in epuck2_programmers(infos)]
    found += [(p, ["monitor"]) for p in epuck2_monitor_ports(infos)]
    found += [(p, ["flash", "monitor"]) for p in bluetooth_ports(infos)]
    return [{"device": p.device, "kind": p.kind, "robot_id": p.robot_id,
             "description": p.description, "uses": uses} for p, uses in found]


def checked_port(given) -> str:
    """A serial port the page names: a COM port on Windows, else a
    character device (a tty, an rfcomm port, a pseudo-terminal)."""
    if not isinstance(given, str) or not given or len(given) > 200 or "\0" in given:
        raise RobotRequestError("give the robot's serial port")
    if sys.platform == "win32":
        if not given.upper().startswith("COM") or not given[3:].isdigit():
            raise RobotRequestError(f"{given!r} is not a serial port (COM1, COM2, ...)")
        return given
    if not given.startswith("/dev/"):
        raise RobotRequestError(f"{given!r} is not a serial port: give its device "
                                "(/dev/rfcomm0, /dev/ttyACM1, ...)")
    try:
        mode = os.stat(given).st_mode
    except OSError:
        raise RobotRequestError(f"{given} is not there: is the robot connected (its USB "
                                "cable, its Bluetooth port bound)?") from None
    if not stat.S_ISCHR(mode):
        raise RobotRequestError(f"{given} is not a serial port")
    return given


def _program(workspace: Workspace, request: dict, suffixes: tuple, what: str):
    program = workspace.resolve(str(request.get("program", "")))
    name = program.name
    if not any(name.endswith(s) for s in suffixes) or (
            name.endswith(".json") and not name.endswith(".trace.json")):
        shown = ", ".join("NAME.trace.json" if s == ".json" else s for s in suffixes)
        raise RobotRequestError(f"{what} takes a program: {shown}")
    return program


def _epuckc(*words) -> list:
    return [sys.executable, "-m", "epuckc", *words]


def flash_command(workspace: Workspace, request: dict) -> tuple:
    """(argv, cwd) of `epuckc flash` as the page asked for it:
    {program, port, target?, robot_id?, trace?}; RobotRequestError or
    workspace.PathRefused for what it may not ask."""
    program = _program(workspace, request, FLASH_SUFFIXES, "Flash")
    argv = _epuckc("flash", program.name, "--port", checked_port(request.get("port")))
    target = request.get("target")
    built = program.suffix in (".hex", ".elf")
    if target is not None and target not in TARGETS:
        raise RobotRequestError("the robot is epuck or epuck2")
    if not built:
        if target is None:
            raise RobotRequestError("which robot is the program for? epuck or epuck2")
        argv += ["--target", target]
    robot_id = request.get("robot_id")
    if robot_id is not None:
        if not isinstance(robot_id, int) or isinstance(robot_id, bool) or \
                not 0 <= robot_id <= 0xFFFF:
            raise RobotRequestError("the e-puck's number is a whole number, 0 to 65535")
        argv += ["--robot-id", str(robot_id)]
    trace = request.get("trace", False)
    if not isinstance(trace, bool):
        raise RobotRequestError("trace is true or false")
    if trace:
        argv.append("--trace")
    return argv, program.parent


def monitor_command(workspace: Workspace, request: dict) -> tuple:
    """(argv, cwd) of `epuckc monitor PORT --program PROG --trace -` as the
    page asked for it: {program, port}."""
    program = _program(workspace, request, MONITOR_SUFFIXES, "Monitor")
    port = checked_port(request.get("port"))
    return _epuckc("monitor", port, "--program", program.name, "--trace", "-"), program.parent


__all__ = ["RobotRequestError", "checked_port", "flash_command", "link_available",
           "monitor_command", "robot_ports"]
