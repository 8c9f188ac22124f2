"""Flashing several robots at once: one thread per robot (each waits on
its own port and debugger, all waits bounded), each robot's progress and
outcome told to a reporter (progress.py), every outcome returned."""
from __future__ import annotations

import threading
import time
from pathlib import Path
from typing import Optional

from ..base.records import record
from .ports import LinkError

EPUCK, EPUCK2 = "epuck", "epuck2"


@record(frozen=True)
class Robot:
    """A robot to flash: its kind (EPUCK or EPUCK2), its port, and for the
    e-puck its number (its bootloader keeps it)."""
    kind: str
    port: str
    robot_id: Optional[int] = None

    @property
    def name(self) -> str:
        if self.kind == EPUCK2:
            return f"e-puck2 on {self.port}"
        return f"e-puck {self.robot_id} on {self.port}"


@record(frozen=True)
class Settings:
    """How long a robot's flash may take once it answers (timeout_s), and
    how long the user has to press an e-puck's reset button."""
    timeout_s: float = 120.0
    reset_window_s: float = 30.0


@record
class Outcome:
    """What became of one robot: `message` says how it went (the summary,
    or the one line of cause and fix), `status` the exit status it calls
    for."""
    robot: Robot
    ok: bool
    message: str
    status: int = 0


def read_program(path: Path, shown: str, kind: str):
    """The image to flash: an ElfImage (e-puck2) or a ProgramImage
    (e-puck); LinkError when the file is not one."""
    if kind == EPUCK2:
        from .gdbflash import read_elf
        return read_elf(path, shown)
    from .dspic_image import read_hex
    return read_hex(path, shown)


def _flash_one(robot: Robot, image, settings: Settings, gdb: Optional[str], reporter) -> str:
    if robot.kind == EPUCK2:
        from .gdbflash import flash_epuck2
        return flash_epuck2(image, robot.port, gdb, settings.timeout_s,
                            lambda fraction, text: reporter.update(robot, fraction, text))
    from .dspic_image import packets
    from .tinybld import upload
    data = packets(image, robot.robot_id)

    def prompt(seconds_left: int):
        reporter.prompt(robot, "press the robot's reset button now", seconds_left)

    def progress(done: int, total: int):
        reporter.update(robot, done / total, f"packet {done} of {total}")
    upload(robot.port, data, window_s=settings.reset_window_s, timeout_s=settings.timeout_s,
           prompt=prompt, progress=progress)
    return f"{len(data)} rows of 32 instructions"


def flash_robots(robots: list, image, settings: Settings, reporter,
                 gdb: Optional[str] = None) -> list:
    """Flash every robot at once; their outcomes, in the robots' order.
    `gdb` is the debugger for e-puck2s (gdbflash.find_gdb)."""
    outcomes: list = [None] * len(robots)

    def work(index: int, robot: Robot):
        reporter.start(robot)
        try:
            message = _flash_one(robot, image, settings, gdb, reporter)
            outcome = Outcome(robot, True, message)
        except LinkError as exc:
            outcome = Outcome(robot, False, str(exc), exc.status)
        except Exception as exc:    # a bug: this robot fails, the others go on
            outcome = Outcome(robot, False, f"internal error ({type(exc).__name__}: {exc}); "
                                            "this is a bug in epuckc, please report it", 4)
        outcomes[index] = outcome
        reporter.finish(outcome)

    threads = [threading.Thread(target=work, args=(i, robot), daemon=True,
                                name=f"flash {robot.port}") for i, robot in enumerate(robots)]
    for thread in threads:
        thread.start()
    # every wait inside is bounded; this bound only guards against a bug
    deadline = time.monotonic() + settings.reset_window_s + settings.timeout_s + 120
    for thread in threads:
        thread.join(max(0.0, deadline - time.monotonic()))
    for i, robot in enumerate(robots):
        if outcomes[i] is None:
            outcomes[i] = Outcome(robot, False, "did not finish in time (a bug in epuckc: "
                                                "every wait is bounded)", 4)
            reporter.finish(outcomes[i])
    return outcomes
