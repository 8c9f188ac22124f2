"""Runs of the page's Run button: `epuckc run` itself, in a child process
(and Monitor's `epuckc monitor PORT --trace -`, a robot's run, the same way).

The child is what a student would type in the program's folder,
`epuckc run PROG.epk [--world W | --scenario S] --time-limit T
--pose-interval P --trace -`: the same checks, the same build cache, the
same runner (a world's merged trace comes out as the robots write it,
sim/live.py). Its standard output, the JSON-lines trace, goes to the page
in batches as it is read and, line for line, into a file the page can
download (the trace `epuckc run --trace FILE` writes); its standard error
(diagnostics, warnings, the collision summary) goes to the page as text.

The child and everything it starts (the harness, the world runner) are one
process group of their own; Stop, a new Run on the same socket, and a page
that goes away kill the whole group, and the run's end is waited for, so
no process is left behind (tests/studio/test_server.py).
"""
from __future__ import annotations

import asyncio
import itertools
import os
import signal
import sys
from pathlib import Path
from typing import Optional

from .workspace import PathRefused, Workspace

MAX_TIME_LIMIT_MS = 600_000        # ten minutes of simulated time
DEFAULT_TIME_LIMIT_MS = 20_000
POSE_MS = 50
KEEP_TRACES = 20
_ids = itertools.count(1)


def _package_root() -> str:
    return str(Path(__file__).resolve().parents[2])


def child_env() -> dict:
    """The environment of a child `epuckc`: the same epuckc as this process."""
    env = dict(os.environ)
    root = _package_root()
    if not {"site-packages", "dist-packages"} & set(Path(root).parts):
        env["PYTHONPATH"] = os.pathsep.join([root] + [p for p in
                                            env.get("PYTHONPATH", "").split(os.pathsep) if p])
    env["NO_COLOR"] = "1"
    for setting in ("EPUCK_QUIET", "EPUCK_POSE_MS", "EPUCK_TRACE", "EPUCK_SCENARIO"):
        env.pop(setting, None)
    return env


class RunRequestError(Exception):
    """What the page asked for cannot be run; the message says why."""


def command_for(workspace: Workspace, request: dict) -> tuple:
    """(argv, cwd) of the run the page asked for; RunRequestError or
    PathRefused for a request that names something it may not."""
    program = workspace.resolve(str(request.get("program", "")))
    if program.suffix not in (".epk", ".c"):
        raise RunRequestError("Run takes a rule file (.epk) or a C program (.c)")
    folder = program.parent
    argv = [sys.executable, "-m", "epuckc", "run", program.name, "--trace", "-",
            "--pose-interval", f"{POSE_MS}ms"]
    limit = request.get("time_limit_ms", DEFAULT_TIME_LIMIT_MS)
    if not isinstance(limit, int) or isinstance(limit, bool) or not 1 <= limit <= MAX_TIME_LIMIT_MS:
        raise RunRequestError(f"the time limit is a whole number of ms, 1 to {MAX_TIME_LIMIT_MS}")
    argv += ["--time-limit", f"{limit}ms"]
    seed = request.get("seed")
    if seed is not None:
        if not isinstance(seed, int) or isinstance(seed, bool) or not 0 <= seed < 2 ** 32:
            raise RunRequestError("the seed is a whole number from 0")
        argv += ["--seed", str(seed)]
    for key, flag, suffix in (("world", "--world", ".world"), ("scenario", "--scenario", ".scn")):
        name = request.get(key)
        if name:
            path = workspace.resolve(str(name))
            if path.suffix != suffix:
                raise RunRequestError(f"{flag} takes a {suffix} file")
            argv += [flag, os.path.relpath(path, folder)]
    if request.get("world") and request.get("scenario"):
        raise RunRequestError("a run takes a world or a scenario, not both")
    return argv, folder


class Run:
    """One run: its child, the trace file being written, what the page is sent."""

    def __init__(self, ident: int, trace_path: Path, argv: list, cwd: Path, send):
        self.id = ident
        self.argv = argv
        self.cwd = cwd
        self.trace_path = trace_path
        self.send = send
        self.proc: Optional[asyncio.subprocess.Process] = None
        self.stopped = False
        self.status: Optional[int] = None
        self.done = asyncio.Event()

    async def start(self):
        self.proc = await asyncio.create_subprocess_exec(
            *self.argv, cwd=str(self.cwd), env=child_env(), stdin=asyncio.subprocess.DEVNULL,
            stdout=asyncio.subprocess.PIPE, stderr=asyncio.subprocess.PIPE,
            start_new_session=True, limit=2 ** 20)
        self._task = asyncio.ensure_future(self._pump())

    async def _pump(self):
        try:
            with open(self.trace_path, "wb") as out:
                await asyncio.gather(self._stdout(out), self._stderr())
            self.status = await self.proc.wait()
            await self._send({"type": "end", "run": self.id, "status": self.status,
                              "stopped": self.stopped, "trace": f"/api/trace/{self.id}"})
        finally:
            self.done.set()

    async def _send(self, message: dict):
        try:
            await self.send(message)
        except Exception:           # the page went away: the run is stopped by its owner
            pass

    async def _stdout(self, out):
        """What the child wrote, as soon as it is there: a read returns what
        is available, so a batch is whatever came since the last one."""
        reader = self.proc.stdout
        partial = b""
        while True:
            chunk = await reader.read(1 << 16)
            if not chunk:
                break
            out.write(chunk)
            out.flush()
            lines = (partial + chunk).split(b"\n")
            partial = lines.pop()
            if lines:
                await self._send({"type": "records", "run": self.id,
                                  "lines": [line.decode("utf-8", "replace") for line in lines]})
        if partial:
            await self._send({"type": "records", "run": self.id,
                              "lines": [partial.decode("utf-8", "replace")]})

    async def _stderr(self):
        """What the child says (diagnostics, warnings, the collision
        summary), in the pieces it comes in: one message per read, not per
        line (a program with many warnings prints hundreds)."""
        while True:
            chunk = await self.proc.stderr.read(1 << 16)
            if not chunk:
                break
            await self._send({"type": "stderr", "run": self.id,
                              "text": chunk.decode("utf-8", "replace")})

    def kill(self):
        """The whole process group: the child and whatever it started."""
        if self.proc is None or self.proc.returncode is not None:
            return
        self.stopped = True
        try:
            os.killpg(self.proc.pid, signal.SIGKILL)
        except (ProcessLookupError, PermissionError):
            pass

    async def stop(self):
        self.kill()
        await self.done.wait()


class Runs:
    """The runs of one studio: the traces kept for download (the last
    KEEP_TRACES), each in the studio's own temporary folder."""

    def __init__(self, state_dir: Path):
        self.state_dir = state_dir
        self.traces: dict = {}      # id -> Path

    def new_trace(self) -> tuple:
        """(id, path) of a new trace file (the oldest beyond KEEP_TRACES go)."""
        ident = next(_ids)
        path = self.state_dir / f"trace-{ident}.jsonl"
        self.traces[ident] = path
        while len(self.traces) > KEEP_TRACES:
            old = self.traces.pop(min(self.traces))
            try:
                old.unlink()
            except OSError:
                pass
        return ident, path

    def new(self, workspace: Workspace, request: dict, send) -> Run:
        """The run the page asked for: Run's `epuckc run`, or Monitor's
        `epuckc monitor` (robots.py), whose trace is a robot's."""
        if request.get("type") == "monitor":
            from .robots import monitor_command
            argv, cwd = monitor_command(workspace, request)
        else:
            argv, cwd = command_for(workspace, request)
        return Run(*self.new_trace(), argv, cwd, send)

    def trace(self, ident: int) -> Optional[Path]:
        path = self.traces.get(ident)
        return path if path is not None and path.is_file() else None


__all__ = ["Run", "Runs", "RunRequestError", "command_for", "PathRefused"]
