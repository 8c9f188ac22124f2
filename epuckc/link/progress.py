"""What the user sees while robots are flashed. On a terminal, a block of
progress bars at the bottom of stderr, a line per robot still going,
redrawn in place, each finished robot's line printed above the block; on
anything else, one line per robot when it is done, and the prompts the
user must act on (press a reset button) as lines of their own."""
from __future__ import annotations

import os
import shutil
import sys
import threading
import time

BAR = 24
REDRAW_S = 0.1


def wants_live(stream) -> bool:
    return stream.isatty() and os.environ.get("TERM", "") not in ("", "dumb")


class Reporter:
    def __init__(self, program: str, err=None, out=None, live=None):
        self.program = program
        self.err = err if err is not None else sys.stderr
        self.out = out if out is not None else sys.stdout
        self.live = wants_live(self.err) if live is None else live
        self._lock = threading.Lock()
        self._rows: dict = {}          # robot -> (fraction, text), in start order
        self._prompted: set = set()
        self._drawn = 0
        self._last_draw = 0.0

    # -- what the flashes report -----------------------------------------

    def start(self, robot):
        with self._lock:
            self._rows[robot] = (0.0, "starting", False)
            self._draw(force=True)

    def update(self, robot, fraction: float, text: str):
        with self._lock:
            self._rows[robot] = (fraction, text, False)
            self._draw()

    def prompt(self, robot, text: str, seconds_left: int):
        """Something the user must do now, with the seconds left for it."""
        with self._lock:
            if self.live:
                self._rows[robot] = (0.0, f"{text} ({seconds_left} s left)", True)
                self._draw(force=True)
            elif robot not in self._prompted:
                self._prompted.add(robot)
                self._print(self.err, f"the {robot.name}: {text} (you have {seconds_left} s)")

    def finish(self, outcome):
        with self._lock:
            self._rows.pop(outcome.robot, None)
            if outcome.ok:
                line = f"flashed {self.program} to the {outcome.robot.name} ({outcome.message})"
                self._print(self.out, line)
            else:
                self._print(self.err, f"epuckc: error: the {outcome.robot.name}: "
                                      f"{outcome.message}")
            self._draw(force=True)

    def close(self):
        with self._lock:
            self._clear()

    # -- drawing ---------------------------------------------------------

    def _print(self, stream, line: str):
        self._clear()
        self.err.flush()
        stream.write(line + "\n")
        stream.flush()

    def _clear(self):
        if self.live and self._drawn:
            self.err.write(f"\x1b[{self._drawn}F\x1b[J")
            self.err.flush()
            self._drawn = 0

    def _draw(self, force: bool = False):
        if not self.live:
            return
        now = time.monotonic()
        if not force and now - self._last_draw < REDRAW_S:
            return
        self._last_draw = now
        self._clear()
        width = shutil.get_terminal_size((80, 24)).columns
        names = [robot.name for robot in self._rows]
        pad = max((len(n) for n in names), default=0)
        for robot, (fraction, text, asking) in self._rows.items():
            if asking:          # what the user must do: the whole line for it
                line = f"{robot.name:<{pad}}  {text}"
            else:
                bar = max(8, min(BAR, width - 1 - pad - 8 - len(text)))
                filled = int(round(bar * max(0.0, min(1.0, fraction))))
                line = (f"{robot.name:<{pad}} [{'#' * filled}{'-' * (bar - filled)}] "
                        f"{int(100 * fraction):3d}% {text}")
            self.err.write(line[:max(10, width - 1)] + "\n")
        self._drawn = len(self._rows)
        self.err.flush()
