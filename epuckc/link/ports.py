"""The serial ports the robots appear on, told apart in pyserial's list of
the system's ports, and opening one with a message that says what to do
when it cannot be opened.

- The e-puck2's on-board programmer (a Black Magic Probe firmware) is one
  USB device with the probe's ids (1d50:6018), "GCtronic/EPFL" "e-puck2",
  a serial number holding "EPUCK", and two serial ports: interface 00, "e-puck2
  GDB Server", is the GDB server a flash goes through; interface 02 is the
  serial monitor (the main processor's UART3).
- The e-puck talks over Bluetooth: the port is `/dev/rfcommN` after
  `rfcomm bind` on Linux, `/dev/cu.e-puck_NNNN-...` on macOS, a COM port of
  a Bluetooth link on Windows; the robot's number (its PIN) is in the name
  where the system puts the device's name there.
"""
from __future__ import annotations

import os
import re
import sys
from typing import Iterable, Optional

from ..base.records import record

EPUCK2_USB_IDS = (0x1D50, 0x6018)       # the Black Magic Probe's, which the programmer keeps
EPUCK2_SERIAL_MARK = "EPUCK"
# "e-puck_3112", "epuck3112"; not "e-puck2", the robot's model
_ROBOT_NUMBER = re.compile(r"e-?puck(?:[ _-](\d{1,5})|(\d{3,5}))(?!\d)", re.IGNORECASE)
_INTERFACE = re.compile(r":(?:\d+|x)\.(\d+)$")


class LinkError(Exception):
    """A robot could not be reached or did not take its program: one line
    that says what went wrong and what to do. `status` is the exit status
    it calls for (3: a tool is missing, as for builds)."""

    def __init__(self, message: str, status: int = 1):
        super().__init__(message)
        self.status = status


@record(frozen=True)
class RobotPort:
    """A port a robot is on: `kind` is "epuck2" or "epuck"; `robot_id` the
    e-puck's number when its port's name gives it; `description` what the
    system says of the port."""
    device: str
    kind: str
    robot_id: Optional[int] = None
    description: str = ""


def system_ports() -> list:
    """pyserial's list of the system's serial ports (ListPortInfo)."""
    from serial.tools import list_ports
    return list(list_ports.comports())


def _interface_number(info) -> Optional[int]:
    found = _INTERFACE.search(info.location or "")
    return int(found.group(1)) if found else None


def _is_programmer(info) -> bool:
    if (info.vid, info.pid) != EPUCK2_USB_IDS:
        return False
    said = " ".join(filter(None, (info.serial_number, info.product, info.manufacturer,
                                  info.description)))
    return EPUCK2_SERIAL_MARK in said.upper() or "e-puck2" in said.lower()


def epuck2_programmers(infos: Iterable) -> list:
    """The GDB ports of the e-puck2 programmers among `infos`, one per
    robot: the port of interface 00 (or named "GDB Server"); where the
    system tells neither (macOS, Windows), the first of the robot's ports
    in name order, as its first interface is the first port it gets."""
    by_robot: dict = {}
    for info in infos:
        if _is_programmer(info):
            by_robot.setdefault(_robot_key(info), []).append(info)
    found = []
    for ports in by_robot.values():
        named = [p for p in ports if "gdb" in (p.interface or "").lower()]
        numbered = [p for p in ports if _interface_number(p) == 0]
        if named or numbered:
            chosen = (named or numbered)[0]
        elif any(p.interface or _interface_number(p) is not None for p in ports):
            continue            # the robot's other ports, and its GDB port is not listed
        else:
            chosen = min(ports, key=lambda p: _natural(p.device))
        found.append(RobotPort(chosen.device, "epuck2", None,
                               chosen.description or "e-puck2 GDB Server"))
    return sorted(found, key=lambda p: _natural(p.device))


def epuck2_monitor_ports(infos: Iterable) -> list:
    """The e-puck2 programmers' other ports among `infos`: the serial
    monitor (the main processor's UART3, where a `--trace` build sends its
    trace), every port of a programmer that is not its GDB port."""
    infos = list(infos)
    gdb = {os.path.realpath(p.device) for p in epuck2_programmers(infos)}
    found = [RobotPort(i.device, "epuck2", None, i.description or "e-puck2 serial monitor")
             for i in infos if _is_programmer(i) and os.path.realpath(i.device) not in gdb]
    return sorted(found, key=lambda p: _natural(p.device))


def _robot_key(info) -> tuple:
    """What the ports of one robot share: the USB device's serial number
    and place (its location without the interface)."""
    where = info.location or ""
    return info.serial_number, where.rsplit(":", 1)[0] if ":" in where else where


def _natural(text: str) -> list:
    return [int(part) if part.isdigit() else part for part in re.split(r"(\d+)", text)]


def robot_number(text: str) -> Optional[int]:
    """The e-puck's number in a port's name ("e-puck_3112"), or None."""
    found = _ROBOT_NUMBER.search(text or "")
    number = int(found.group(1) or found.group(2)) if found else None
    return number if number is not None and number <= 0xFFFF else None


def bluetooth_ports(infos: Iterable) -> list:
    """The ports among `infos` an e-puck may be on: rfcomm ports, ports
    named after an e-puck, and Windows' Bluetooth links. On macOS each
    device has a /dev/tty. and a /dev/cu. port: the cu. one is kept (the
    tty. one waits for a carrier the robot never raises)."""
    found, seen = [], set()
    for info in infos:
        device = info.device
        said = " ".join(filter(None, (device, info.description, info.product)))
        bluetooth = (re.search(r"/rfcomm\d+$", device) or "e-puck" in said.lower()
                     or "epuck" in said.lower() or (info.hwid or "").upper().startswith("BTHENUM"))
        if not bluetooth or (info.vid, info.pid) == EPUCK2_USB_IDS:
            continue
        if device.startswith("/dev/tty.") and device.replace("/dev/tty.", "/dev/cu.", 1) in {
                i.device for i in infos}:
            continue
        if device in seen:
            continue
        seen.add(device)
        found.append(RobotPort(device, "epuck", robot_number(said),
                               info.description if info.description != "n/a" else "Bluetooth"))
    return sorted(found, key=lambda p: _natural(p.device))


def robot_ports(kind: str, infos: Optional[list] = None) -> list:
    infos = system_ports() if infos is None else list(infos)
    return epuck2_programmers(infos) if kind == "epuck2" else bluetooth_ports(infos)


def wrong_port(device: str, kind: str, infos: Iterable) -> Optional[str]:
    """Why `device` is not a port to flash a robot of `kind` through, when
    the system's list says so (an e-puck2's serial monitor port instead of
    its GDB port, an e-puck2 given for an e-puck), or None."""
    infos = list(infos)
    real = os.path.realpath(device)
    this = next((i for i in infos if os.path.realpath(i.device) == real), None)
    if this is None or not _is_programmer(this):
        return None
    if kind == "epuck":
        return (f"{device} is an e-puck2's programmer, and this program is for the e-puck: give "
                "the e-puck's Bluetooth port, or build for the e-puck2 (--target epuck2)")
    gdb_ports = epuck2_programmers(infos)
    if any(os.path.realpath(p.device) == real for p in gdb_ports):
        return None
    by_device = {i.device: i for i in infos}
    sibling = next((p for p in gdb_ports if p.device in by_device
                    and _robot_key(by_device[p.device]) == _robot_key(this)), None)
    better = f": its GDB port is {sibling.device}" if sibling else ""
    return (f"{device} is the e-puck2's serial monitor port, not its GDB port (the first of its "
            f"two){better}")


def not_found(kind: str) -> str:
    if kind == "epuck2":
        return ("no e-puck2 is connected: plug the robot's USB cable in (a data cable, not a "
                "charge-only one) and switch the robot on, or name its port with --port "
                "(`epuckc flash --list` shows the ports found)")
    return ("no Bluetooth port of an e-puck was found: pair the robot (its PIN is its number) "
            "and bind a port to it (Linux: sudo rfcomm bind 0 ADDRESS 1, see docs/robots.md), "
            "then give it with --port (`epuckc flash --list` shows the ports found)")


def open_error(device: str, exc: OSError) -> str:
    """Why `device` cannot be opened, and what to do, in one line."""
    import errno
    code = exc.errno
    if code == errno.ENOENT:
        return (f"there is no port {device}: plug the robot in (its USB cable, or pair and bind "
                "its Bluetooth), or name another port with --port (`epuckc flash --list`)")
    if code in (errno.EACCES, errno.EPERM):
        return f"cannot open {device}: permission denied: {permission_fix(device)}"
    if code == errno.EBUSY:
        return (f"{device} is busy: another program has it open (a serial terminal, "
                "ModemManager, another epuckc): close it and try again")
    if code in (errno.ENXIO, errno.ENODEV, errno.EIO):
        return (f"{device} does not answer ({os.strerror(code)}): the robot went away; plug it "
                "in again (or switch its Bluetooth on) and try again")
    return f"cannot open {device}: {exc.strerror or exc}"


def permission_fix(device: str) -> str:
    """What lets this user open `device`: its group, joined (or a new
    session, when the user joined it since this one started), or a udev
    rule (docs/robots.md)."""
    if sys.platform != "linux":
        return "run as a user who may use serial ports (docs/robots.md)"
    try:
        import grp
        import pwd
        gid = os.stat(device).st_gid
        group = grp.getgrgid(gid).gr_name
        user = pwd.getpwuid(os.getuid()).pw_name
    except (OSError, KeyError, ImportError):
        return ("add yourself to the group that owns it (sudo usermod -aG dialout $USER, then "
                "log out and in) or install the udev rule in docs/robots.md")
    if group == "root":
        return ("install the udev rule in docs/robots.md (the port belongs to root alone), then "
                "plug the robot in again")
    members = grp.getgrgid(gid).gr_mem
    if user in members and gid not in os.getgroups():
        return (f"you are in the {group} group, but this session started before you joined it: "
                f"log out and in again (or run `newgrp {group}`)")
    return (f"add yourself to the {group} group (sudo usermod -aG {group} $USER, then log out "
            "and in) or install the udev rule in docs/robots.md")


def check_access(device: str) -> None:
    """LinkError with the one-line reason when `device` cannot be opened
    for reading and writing (opened without waiting for a carrier, and
    closed again). On Windows a COM port is opened by name only by the
    program that uses it: nothing is checked there."""
    if os.name == "nt":
        return
    try:
        fd = os.open(device, os.O_RDWR | os.O_NOCTTY | os.O_NONBLOCK)
    except OSError as exc:
        raise LinkError(open_error(device, exc)) from None
    os.close(fd)
