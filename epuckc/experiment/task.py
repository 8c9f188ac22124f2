"""One run on a worker: the task's programs written into the worker's
cache (by their digest, so the build cache finds them next time), each
built once per worker into a robot, the world simulated under the
watchdog, and the run measured. A run that fails is a result with its
error, never an exception: the experiment goes on."""
from __future__ import annotations

import os
from dataclasses import dataclass, field
from pathlib import Path
from typing import Optional

from ..base.resources import cache_dir
from ..build.common import BuildError, Program
from . import metrics as M

_built = {}             # payload digest -> robot's shared object, in this worker
_pool_worker = False    # a process of the local pool (worker_started)


def worker_started():
    """A local pool's process: Ctrl-C on the terminal is the parent's to
    handle (it stops the experiment); here it would only print tracebacks."""
    global _pool_worker
    import signal
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    _pool_worker = True


@dataclass
class RunResult:
    key: str
    point: int
    seed: int
    values: dict
    rows: list = field(default_factory=list)    # one dict per robot (+ the swarm)
    error: str = ""
    transient: bool = False     # a lost worker, not the run's fault: run it again on resume
    trace: Optional[str] = None


def _program(payload) -> Program:
    """The payload's files in a folder of the worker's cache, as a Program."""
    folder = cache_dir() / "experiment" / payload.digest[:24]
    for name, text in payload.files:
        path = folder / name
        if not path.is_file() or path.read_text(encoding="utf-8") != text:
            path.parent.mkdir(parents=True, exist_ok=True)
            tmp = path.with_name(f".{path.name}.{os.getpid()}")
            tmp.write_text(text, encoding="utf-8")
            os.replace(tmp, path)
    files = [folder / name for name, _ in payload.files]
    if payload.generated:
        return Program(payload.name, payload.c_text, folder, files,
                       header_name=payload.header_name, header_text=payload.header_text,
                       variables=payload.variables)
    return Program(payload.name, payload.c_text, folder, [], generated=False,
                   source_path=files[0])


def _robot(payload) -> Path:
    from ..sim.enki import build_robot
    lib = _built.get(payload.digest)
    if lib is None or not lib.is_file():
        lib = _built[payload.digest] = build_robot(_program(payload))
    return lib


def execute(task) -> RunResult:
    """Run one task; every failure is the result's `error`."""
    from ..sim.enki import WorldTimeout, merge_traces, simulate
    out = RunResult(task.key, task.point, task.seed, dict(task.values))
    try:
        libs = [_robot(task.payloads[i]) for i in task.robot_programs]
        devices = [task.payloads[i].devices for i in task.robot_programs]
        run = simulate(task.world, libs, task.duration_ms, task.seed, task.pose_ms,
                       quiet=True, capture=True, timeout_s=task.timeout_s, devices=devices)
    except KeyboardInterrupt:
        if not _pool_worker:
            raise
        return lost(task, "interrupted")
    except (BuildError, WorldTimeout) as exc:
        out.error = str(exc).strip().splitlines()[0] if str(exc).strip() else type(exc).__name__
        return _failed(task, out)
    except Exception as exc:        # the worker survives anything a run does
        out.error = f"{type(exc).__name__}: {exc}".splitlines()[0]
        return _failed(task, out)
    per_robot, cells = [], []
    for robot, result, text, index in zip(task.world.robots, run.results, run.traces,
                                          task.robot_programs):
        values, covered = M.measure(text, result, (robot.x_mm, robot.y_mm, robot.heading_deg),
                                    task.metrics, task.duration_ms,
                                    task.payloads[index].variables)
        error = ""
        if result.status not in (0, 3):
            error = f"the program stopped with exit status {result.status}"
        per_robot.append(dict(values, robot=robot.name, status=result.status, error=error))
        cells.append(covered)
    if len(per_robot) > 1:
        errors = [r["error"] for r in per_robot if r["error"]]
        per_robot.append(dict(M.swarm(per_robot, cells, task.metrics), robot="swarm",
                              status=max(r["status"] for r in per_robot),
                              error=errors[0] if errors else ""))
    out.rows = per_robot
    if task.traces:
        out.trace = merge_traces(task.world, run.traces, run.results, run.end_ms)
    return out


def _failed(task, out: RunResult) -> RunResult:
    names = list(task.robot_names) + (["swarm"] if len(task.robot_names) > 1 else [])
    out.rows = [{"robot": name, "status": "", "error": out.error} for name in names]
    return out


def lost(task, why: str) -> RunResult:
    """The result of a task whose worker was lost (crashed, killed)."""
    out = RunResult(task.key, task.point, task.seed, dict(task.values), error=why,
                    transient=True)
    return _failed(task, out)
