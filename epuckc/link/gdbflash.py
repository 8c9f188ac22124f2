"""The e-puck2's flash: GDB (gdb-multiarch or arm-none-eabi-gdb) through
the robot's on-board programmer, a Black Magic Probe firmware on the
second microcontroller, over the programmer's GDB port.

The steps are GDB's own (`target extended-remote PORT`, `monitor
swdp_scan`, attach, `load`, `compare-sections`, `kill`), each waited for
with a bound, and each failure said in one line with its cause and fix.
One step is not the textbook's: the attach is sent as the raw packet
`vAttach;1`, and GDB then connects again to the halted processor. GDB 11
and later stop with an internal error (inferior_thread: Assertion
`current_thread_ != nullptr') when `attach` meets a probe that reports no
thread, and the e-puck2 programmer's firmware (the probe's code of 2020)
reports none; connecting to a halted target, GDB makes the thread itself.
The same steps work with probes that do report one.
"""
from __future__ import annotations

import os
import re
import shutil
from pathlib import Path
from typing import Callable, Optional

from ..base.records import record
from .gdbmi import Gdb, GdbStopped
from .ports import LinkError, check_access

GDB_NAMES = ("gdb-multiarch", "arm-none-eabi-gdb")
GDB_MISSING = ("neither gdb-multiarch nor arm-none-eabi-gdb is installed, and the e-puck2 is "
               "flashed through GDB: install one (Debian, Ubuntu: sudo apt-get install "
               "gdb-multiarch; Fedora: sudo dnf install arm-none-eabi-gdb; macOS: brew install "
               "--cask gcc-arm-embedded)")
# The STM32F407's flash: a program for the e-puck2 is linked there.
FLASH_START, FLASH_END = 0x08000000, 0x08100000

# Bounds of the steps (seconds); the load has what is left of the robot's
# whole time (--timeout).
CONNECT_S, SCAN_S, ATTACH_S, COMPARE_S, KILL_S = 15.0, 15.0, 10.0, 60.0, 10.0


@record(frozen=True)
class ElfImage:
    """A program for the e-puck2: its loadable sections (name, load
    address, size), as GDB's `load` writes them."""
    path: str
    shown: str
    sections: tuple
    size: int


def read_elf(path: Path, shown: str) -> ElfImage:
    """The loadable sections of an e-puck2 program; LinkError when the file
    cannot be read, is not an ARM ELF, or puts code outside the flash."""
    from elftools.common.exceptions import ELFError
    from elftools.elf.constants import SH_FLAGS
    from elftools.elf.elffile import ELFFile
    try:
        with open(path, "rb") as file:
            elf = ELFFile(file)
            machine = elf["e_machine"]
            if machine != "EM_ARM" or elf.elfclass != 32:
                raise LinkError(f"{shown} is a program for {machine.replace('EM_', '')}, not "
                                "for the e-puck2's ARM Cortex-M4: build it with `epuckc build "
                                "--target epuck2`")
            loads = [s for s in elf.iter_segments() if s["p_type"] == "PT_LOAD"]
            sections = []
            for section in elf.iter_sections():
                if not section["sh_flags"] & SH_FLAGS.SHF_ALLOC \
                        or section["sh_type"] == "SHT_NOBITS" or section["sh_size"] == 0:
                    continue
                address = section["sh_addr"]
                for segment in loads:
                    start = segment["p_offset"]
                    if start <= section["sh_offset"] < start + segment["p_filesz"]:
                        address = segment["p_paddr"] + section["sh_offset"] - start
                        break
                sections.append((section.name, address, section["sh_size"]))
    except OSError as exc:
        raise LinkError(f"cannot read {shown}: {exc.strerror or exc}") from None
    except ELFError as exc:
        raise LinkError(f"{shown} is not a program GDB can load (not an ELF file: {exc})") \
            from None
    if not sections:
        raise LinkError(f"{shown} has nothing to load (no section with contents)")
    for name, address, size in sections:
        if address < FLASH_START or address + size > FLASH_END:
            raise LinkError(f"{shown} puts {name} at 0x{address:08x}, outside the e-puck2's "
                            f"flash (0x{FLASH_START:08x}-0x{FLASH_END - 1:08x}): it was not "
                            "linked for the e-puck2; build it with `epuckc build --target "
                            "epuck2`")
    return ElfImage(str(path), shown, tuple(sections), sum(s[2] for s in sections))


def find_gdb(environ: Optional[dict] = None) -> str:
    """The debugger to flash with, first of GDB_NAMES on PATH; LinkError
    (status 3, as a missing toolchain) with the package to install."""
    path = (os.environ if environ is None else environ).get("PATH")
    for name in GDB_NAMES:
        found = shutil.which(name, path=path)
        if found:
            return found
    raise LinkError(GDB_MISSING, status=3)


def _one_line(text: str) -> str:
    return " ".join(text.split())


def _probe_failure(step: str, error: GdbStopped, bound: float) -> LinkError:
    if error.timed_out:
        if step == "connect":
            return LinkError(f"the port did not answer as a GDB server within {bound:.0f} s: is it "
                             "the programmer's GDB port (the first of the robot's two ports)? "
                             "Unplug the robot's USB cable, plug it in again and flash again")
        return LinkError(f"the programmer stopped answering (no answer for "
                         f"{bound:.0f} s while it {step}): unplug the robot's USB cable, plug "
                         "it in again and flash again")
    lines = [line for line in error.output.splitlines() if line.strip()]
    crash = next((line for line in lines if "internal-error" in line), None)
    last = crash or (lines[-1] if lines else "no output")
    return LinkError(f"GDB ended while it {step} ({_one_line(last)[:200]}): run "
                     "`epuckc flash` again; if GDB keeps ending, try the other debugger "
                     f"({' or '.join(GDB_NAMES)})")


def _lost(message: str) -> bool:
    lowered = message.lower()
    return any(mark in lowered for mark in ("connection closed", "disconnected",
                                            "input/output error", "no such device"))


def _lost_error(message: str, step: str) -> LinkError:
    return LinkError(f"the connection to the programmer was lost while it {step} "
                     f"({_one_line(message)}): check the USB cable (plugged in, a data cable), "
                     "then flash again")


def scan_targets(text: str) -> list:
    """The targets `monitor swdp_scan` lists (number, driver)."""
    found, listing = [], False
    for line in text.splitlines():
        if line.startswith("No. Att Driver"):
            listing = True
            continue
        row = re.match(r"\s*(\d+)\s+\*?\s*(\S.*?)\s*$", line) if listing else None
        if row:
            found.append((int(row.group(1)), row.group(2)))
    return found


def flash_epuck2(image: ElfImage, port: str, gdb: str, timeout_s: float,
                 progress: Callable = lambda fraction, text: None) -> str:
    """Flash `image` through the programmer on `port`; what to tell the
    user on success, LinkError with the one line otherwise."""
    import time
    check_access(port)
    deadline = time.monotonic() + timeout_s
    starts = {}
    done = 0
    for name, _, size in image.sections:
        starts.setdefault(name, done)
        done += size

    def on_download(section: str, sent: Optional[int]):
        sent = starts.get(section, 0) if sent is None else sent
        progress(0.1 + 0.8 * min(1.0, sent / image.size), f"loading {section}")

    try:
        session = Gdb(gdb, image.path, on_download)
    except OSError as exc:
        raise LinkError(f"cannot run {gdb} ({exc.strerror or exc}): install gdb-multiarch again "
                        "(sudo apt-get install --reinstall gdb-multiarch)", status=3) from None
    try:
        def run(command: str, step: str, bound: float):
            bound = max(1.0, min(bound, deadline - time.monotonic()))
            try:
                return session.command(command, bound)
            except GdbStopped as exc:
                raise _probe_failure(step, exc, bound) from None

        connect = f"-target-select extended-remote {port}"
        progress(0.0, "connecting")
        result = run(connect, "connect", CONNECT_S)
        if result.kind == "error":
            if _lost(result.message):
                raise _lost_error(result.message, "connected")
            raise LinkError(f"GDB could not connect to the programmer "
                            f"({_one_line(result.message)}): unplug the robot's USB cable, plug "
                            "it in again and flash again")
        progress(0.03, "scanning")
        result = run('-interpreter-exec console "monitor swdp_scan"', "scanned", SCAN_S)
        targets = scan_targets(result.text)
        if not targets:
            said = "; ".join(line.strip() for line in result.text.splitlines() if line.strip())
            raise LinkError(f"the programmer found no processor to flash ("
                            f"{said or _one_line(result.message) or 'an empty scan'}): switch "
                            "the robot on with a charged battery in place, then flash again")
        progress(0.06, "attaching")
        result = run('-interpreter-exec console "maint packet vAttach;1"', "attached", ATTACH_S)
        answer = re.search(r'received: "(.*)"', result.text)
        if result.kind == "error" or not answer or not answer.group(1)[:1] in ("T", "S"):
            said = answer.group(1) if answer else _one_line(result.message or result.text)
            raise LinkError(f"the programmer found {targets[0][1]} but could not "
                            f"attach to it (it answered {said!r}): switch the robot off and on "
                            "(hold its power button), then flash again")
        result = run(connect, "connected again", CONNECT_S)
        if result.kind == "error":
            raise _lost_error(result.message, "connected again")
        progress(0.1, "loading")
        result = run("-target-download", "loaded the program", deadline - time.monotonic())
        if result.kind == "error":
            if _lost(result.message):
                raise _lost_error(result.message, "loaded the program")
            raise LinkError(f"the programmer could not write the flash "
                            f"({_one_line(result.message)}): switch the robot off and on, then "
                            "flash again")
        progress(0.9, "verifying")
        result = run('-interpreter-exec console "compare-sections"', "compared the sections",
                     COMPARE_S)
        if result.kind == "error":
            if _lost(result.message):
                raise _lost_error(result.message, "compared the sections")
            raise LinkError(f"GDB could not compare the robot's flash with {image.shown} "
                            f"({_one_line(result.message)}): flash again")
        differ = re.findall(r"Section (\S+), range .*: MIS-MATCHED", result.text)
        if differ:
            raise LinkError(f"after the load, {', '.join(differ)} on the robot differ"
                            f"{'s' if len(differ) == 1 else ''} from {image.shown} "
                            "(compare-sections): flash again; if it differs again, the flash "
                            "may be write-protected or worn (docs/robots.md)")
        result = run('-interpreter-exec console "kill"', "started the program", KILL_S)
        progress(1.0, "done")
        started = "" if result.kind != "error" else ": press the robot's reset button to start it"
        return (f"{image.size:,} bytes in {len(image.sections)} section"
                f"{'s' if len(image.sections) != 1 else ''}, verified{started}")
    finally:
        session.close()
