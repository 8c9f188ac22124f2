"""A world run's merged trace as the robots write it: `epuckc run --world
W --trace -` and the studio's arena (epuckc/studio/runs.py) read it while
the world runner is still simulating.

Each robot writes its own trace file, a record per line, flushed at each
record (runtime_c/platform/platform_host.c), and the runner steps the robots in
lockstep. A record of time t can be placed in the merged order once every
robot still running has written a record later than t (it can write no
more at t or before); a robot whose last record ended its run (`exit`,
`timeout`, `watchdog`) holds nothing back. When the runner has finished,
whatever is left is placed. The lines come out exactly as
`enki.merge_traces` orders and writes them (tests/sim/test_live.py).
"""
from __future__ import annotations

import json
import re
from pathlib import Path

_T_MS = re.compile(r'\{"t_ms": (-?\d+), ')
_LAST = re.compile(r'"kind": "(exit|timeout|watchdog)"')


class LiveMerge:
    """Reads the robots' trace files (in the world's order) as they grow and
    hands the merged lines, in merge_traces's order, to `emit(lines)`."""

    def __init__(self, names: list, paths: list, emit):
        self.names = [json.dumps(name) for name in names]
        self.paths = [Path(p) for p in paths]
        self.emit = emit
        self._files = [None] * len(paths)
        self._partial = [""] * len(paths)
        self._latest = [None] * len(paths)     # each robot's last time, None: none yet
        self._done = [False] * len(paths)
        self._orders = [0] * len(paths)
        self._pending = []          # (t, robot, order, line), not yet placed

    def _read(self, i: int) -> None:
        if self._files[i] is None:
            try:
                self._files[i] = open(self.paths[i], "r", encoding="utf-8", newline="")
            except FileNotFoundError:
                return              # the robot has not started yet
        chunk = self._files[i].read()
        if not chunk:
            return
        text = self._partial[i] + chunk
        lines = text.split("\n")
        self._partial[i] = lines.pop()       # a line not yet ended waits for its end
        for line in lines:
            m = _T_MS.match(line)
            if m is None:
                continue
            t = int(m.group(1))
            self._latest[i] = t
            if _LAST.search(line, m.end()):
                self._done[i] = True
            self._pending.append((t, i, self._orders[i],
                                  f'{{"t_ms": {m.group(1)}, "robot": {self.names[i]}, '
                                  + line[m.end():]))
            self._orders[i] += 1

    def poll(self) -> None:
        """Place what can be placed now."""
        for i in range(len(self.paths)):
            self._read(i)
        running = [t for t, done in zip(self._latest, self._done) if not done]
        if None in running:
            return                  # a robot that wrote nothing yet may write at 0
        horizon = min(running) if running else None
        self._place(horizon)

    def finish(self) -> None:
        """The runner has ended: every line left, in order."""
        for i in range(len(self.paths)):
            self._read(i)
            if self._partial[i]:        # a last line without its newline
                self._take_last(i, self._partial[i])
                self._partial[i] = ""
        self._place(None)
        for f in self._files:
            if f is not None:
                f.close()

    def _take_last(self, i: int, text: str) -> None:
        line = text
        m = _T_MS.match(line)
        if m is not None:
            self._pending.append((int(m.group(1)), i, self._orders[i],
                                  f'{{"t_ms": {m.group(1)}, "robot": {self.names[i]}, '
                                  + line[m.end():]))
            self._orders[i] += 1

    def _place(self, horizon) -> None:
        if not self._pending:
            return
        self._pending.sort(key=lambda r: r[:3])
        if horizon is None:
            ready, self._pending = self._pending, []
        else:
            cut = 0
            while cut < len(self._pending) and self._pending[cut][0] < horizon:
                cut += 1
            ready, self._pending = self._pending[:cut], self._pending[cut:]
        if ready:
            self.emit([r[3] for r in ready])
