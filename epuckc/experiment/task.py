"""One run on a worker: the job's programs written into the worker's
cache (by their digest, so the build cache finds them next time), each
built once per worker into a robot, the run's world (its robots placed by
its seed when they are copies), simulated under the watchdog, and the run
measured, with its own wall-clock and CPU time. A batch is several runs
of one job in turn. A run that fails is a result with its error, never an
exception: the experiment goes on."""
from __future__ import annotations

import resource
import shutil
import time
from dataclasses import dataclass, field
from pathlib import Path
from typing import Optional

from ..base import cache
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
    # what was measured: {"metrics": [...], "series": [...], "period_ms": N}
    measured: dict = field(default_factory=dict)
    series: dict = field(default_factory=dict)  # the swarm's: column -> [value at each time]
    wall_s: float = 0.0         # the run's own time on its worker: wall clock,
    cpu_s: float = 0.0          # and CPU (this process's and the world runner's)


def _program(payload) -> Program:
    """The payload's files in a folder of the worker's cache, as a Program."""
    folder = cache.area("experiment") / payload.digest[:24]

    # the files' bytes: plan.py's _c_text reads C as bytes (a Latin-1 comment)
    data = [(name, text.encode("utf-8", "surrogateescape")) for name, text in payload.files]

    def complete(entry: Path) -> bool:
        try:
            return cache.used(entry) and all((entry / name).read_bytes() == raw
                                              for name, raw in data)
        except OSError:
            return False
    if not complete(folder):
        folder = cache.writable_area("experiment") / folder.name
    if not complete(folder):
        tmp = cache.temporary_folder(folder.parent)     # written aside, renamed whole
        try:
            for name, raw in data:
                (tmp / name).parent.mkdir(parents=True, exist_ok=True)
                (tmp / name).write_bytes(raw)
            cache.commit_folder(tmp, folder, complete)
        finally:
            if tmp.exists():
                shutil.rmtree(tmp, ignore_errors=True)
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
    if lib is None or not cache.used(lib.parent) or not lib.is_file():
        lib = _built[payload.digest] = build_robot(_program(payload))
    return lib


def _measured(job) -> dict:
    return {"metrics": list(job.metrics), "series": list(job.series),
            "period_ms": job.period_ms}


def execute(task) -> RunResult:
    """Run one task; every failure is the result's `error`."""
    clock, cpu = time.perf_counter(), _cpu()
    result = _execute(task)
    result.wall_s = round(time.perf_counter() - clock, 4)
    result.cpu_s = round(_cpu() - cpu, 4)
    return result


def execute_batch(batch) -> list:
    """Run a batch's tasks in turn: their results, in order."""
    return [execute(task) for task in batch.tasks]


def _cpu() -> float:
    """CPU seconds of this process and of its children that ended (the
    world runners)."""
    r = resource.getrusage(resource.RUSAGE_CHILDREN)
    return time.process_time() + r.ru_utime + r.ru_stime


def _execute(task) -> RunResult:
    from ..sim.enki import WorldTimeout, merge_traces, simulate
    from .series import robot_series, swarm_series, times
    from .swarm import PlacementError
    job = task.job
    out = RunResult(task.key, task.point, task.seed, dict(task.values), measured=_measured(job))
    try:
        world = job.world_for(task.seed)
        programs = [job.program_of(k) for k in range(len(world.robots))]
        libs = {i: _robot(job.payloads[i]) for i in sorted(set(programs))}
        run = simulate(world, [libs[i] for i in programs], job.duration_ms, task.seed,
                       job.pose_ms, quiet=True, capture=True, timeout_s=job.timeout_s,
                       devices=[job.payloads[i].devices for i in programs])
    except KeyboardInterrupt:
        if not _pool_worker:
            raise
        return lost(task, "interrupted")
    except (BuildError, WorldTimeout, PlacementError) as exc:
        out.error = str(exc).strip().splitlines()[0] if str(exc).strip() else type(exc).__name__
        return _failed(task, out)
    except Exception as exc:        # the worker survives anything a run does
        out.error = f"{type(exc).__name__}: {exc}".splitlines()[0]
        return _failed(task, out)
    at = times(job.duration_ms, job.period_ms) if job.series else []
    per_robot, cells, robot_series_, firsts = [], [], [], []
    for robot, result, text, index in zip(world.robots, run.results, run.traces, programs):
        variables = job.payloads[index].variables
        track = M.track(text, (robot.x_mm, robot.y_mm, robot.heading_deg), variables)
        values, covered = M.measure(track, result, job.metrics, job.duration_ms)
        error = ""
        if result.status not in (0, 3):
            error = f"the program stopped with exit status {result.status}"
        per_robot.append(dict(values, robot=robot.name, status=result.status, error=error))
        cells.append(covered)
        if job.series:
            mine, first = robot_series(track, job.series, at, job.duration_ms)
            robot_series_.append(mine)
            firsts.append(first)
    if len(per_robot) > 1:
        errors = [r["error"] for r in per_robot if r["error"]]
        per_robot.append(dict(M.swarm(per_robot, cells, job.metrics), robot="swarm",
                              status=max(r["status"] for r in per_robot),
                              error=errors[0] if errors else ""))
    out.rows = per_robot
    if job.series:
        out.series = (swarm_series(robot_series_, firsts, job.series, at)
                      if len(robot_series_) > 1 else robot_series_[0])
    if job.traces:
        out.trace = merge_traces(world, run.traces, run.results, run.end_ms)
    return out


def _failed(task, out: RunResult) -> RunResult:
    names = list(task.job.robot_names)
    names += ["swarm"] if len(names) > 1 else []
    out.rows = [{"robot": name, "status": "", "error": out.error} for name in names]
    return out


def lost(task, why: str) -> RunResult:
    """The result of a task whose worker was lost (crashed, killed)."""
    out = RunResult(task.key, task.point, task.seed, dict(task.values), error=why,
                    transient=True, measured=_measured(task.job))
    return _failed(task, out)
