"""The e-puck's Bluetooth bootloader (tinybld on the dsPIC's UART1, 115200
8N1): the handshake, the packets, and the end.

- `V\\n` (its answer, if a program answers, is ignored) and `R\\n` (the
  reset of GCtronic's sercom program, when that is what runs); then 0xC1
  every second until the bootloader, which listens for a moment after a
  reset, answers `q` then `K`, or the time the user was given to press the
  robot's reset button runs out.
- Each packet (dspic_image.packet) is answered `K` (written) or `N` (its
  checksum did not match: bytes were lost or changed on the way); a
  refused packet is sent again, at most RESENDS times. A packet that gets
  no answer means the bootloader lost the packet's bytes and gave up
  waiting (it then starts the program): the robot needs a reset.
- The end is the four bytes 0x95 0x00 0x00 0xFF; the robot then starts
  the new program.
"""
from __future__ import annotations

import math
import time
from typing import Callable

from .ports import LinkError, open_error

BAUD = 115200
HANDSHAKE = b"\xc1"
END = bytes([0x95, 0x00, 0x00, 0xFF])
RESENDS = 4            # a packet refused (N) is sent again at most this many times
ANSWER_S = 3.0         # the longest a packet's answer may take (a Bluetooth round trip is ~50 ms)
HANDSHAKE_EVERY_S = 1.0


def open_port(port: str):
    """The port at 115200 8N1; LinkError with the one line when it cannot
    be opened."""
    import serial
    try:
        return serial.Serial(port, BAUD, timeout=0.1, write_timeout=ANSWER_S)
    except serial.SerialException as exc:
        cause = exc if isinstance(exc, OSError) else getattr(exc, "__context__", None)
        if isinstance(cause, OSError) and cause.errno is not None:
            raise LinkError(open_error(port, cause)) from None
        errno_value = getattr(exc, "errno", None)
        if errno_value is not None:
            raise LinkError(open_error(port, OSError(errno_value, str(exc)))) from None
        raise LinkError(f"cannot open {port}: {exc}") from None


def _read_until(link, wanted: bytes, deadline: float) -> bool:
    """Read until the bytes of `wanted` came in that order (other bytes in
    between are skipped), or the deadline."""
    index = 0
    while time.monotonic() < deadline:
        chunk = link.read(1)
        if not chunk:
            continue
        if chunk[0] == wanted[index]:
            index += 1
            if index == len(wanted):
                return True
    return False


def handshake(link, window_s: float, waiting: Callable = lambda seconds_left: None) -> None:
    """Wake the bootloader: LinkError when it did not answer within
    window_s. `waiting(seconds_left)` is told once a second, to keep the
    user's prompt up to date."""
    link.reset_input_buffer()
    link.write(b"V\n")
    link.flush()
    _drain(link, 0.3)
    link.write(b"R\n")
    link.flush()
    deadline = time.monotonic() + window_s
    while time.monotonic() < deadline:
        waiting(max(0, math.ceil(deadline - time.monotonic() - 0.05)))
        link.write(HANDSHAKE)
        link.flush()
        if _read_until(link, b"qK", min(deadline, time.monotonic() + HANDSHAKE_EVERY_S)):
            return
    raise LinkError(f"no answer from the bootloader in {window_s:g} s: press the robot's reset "
                    "button when asked (the bootloader listens for a moment after a reset); is "
                    "the robot switched on and paired (its PIN is its number)?")


def _drain(link, seconds: float):
    end = time.monotonic() + seconds
    while time.monotonic() < end:
        link.read(64)


def send_packets(link, packets: list, deadline: float,
                 progress: Callable = lambda done, total: None) -> None:
    """Send every packet, each until it is taken (`K`), then the end;
    LinkError when one is refused RESENDS + 1 times, gets no answer, or
    the robot's time (deadline) runs out."""
    total = len(packets)
    for number, data in enumerate(packets, 1):
        address = int.from_bytes(data[:3], "little")
        for attempt in range(RESENDS + 1):
            if time.monotonic() > deadline:
                raise LinkError(f"the upload ran out of time at packet {number} of {total} "
                                "(--timeout): move the robot closer to the computer and flash "
                                "again")
            link.write(data)
            link.flush()
            answer = _answer(link, min(deadline, time.monotonic() + ANSWER_S))
            if answer == b"K":
                break
            if answer == b"":
                raise LinkError(f"the robot stopped answering at packet {number} of {total} "
                                f"(address 0x{address:06x}): bytes were lost on the Bluetooth "
                                "link and the bootloader gave up; flash again and press the "
                                "reset button when asked")
        else:
            raise LinkError(f"packet {number} of {total} (address 0x{address:06x}) was refused "
                            f"{RESENDS + 1} times (checksum errors: the Bluetooth link changes "
                            "bytes): move the robot closer to the computer, away from other "
                            "radios, and flash again")
        progress(number, total)
    link.write(END)
    link.flush()


def _answer(link, deadline: float) -> bytes:
    while time.monotonic() < deadline:
        byte = link.read(1)
        if byte:
            return byte
    return b""


def upload(port: str, packets: list, *, window_s: float, timeout_s: float,
           prompt: Callable = lambda seconds_left: None,
           progress: Callable = lambda done, total: None) -> None:
    """The whole upload to the robot on `port`: open, handshake (the user
    has window_s to press reset), the packets (timeout_s from then on)."""
    import serial
    link = open_port(port)
    try:
        try:
            handshake(link, window_s, prompt)
            send_packets(link, packets, time.monotonic() + timeout_s, progress)
        except serial.SerialException as exc:
            raise LinkError(f"the link to {port} broke ({exc}): switch the robot's Bluetooth "
                            "on again (or pair it again) and flash again") from None
        except OSError as exc:
            raise LinkError(open_error(port, exc)) from None
    finally:
        link.close()
