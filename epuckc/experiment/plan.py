"""From an experiment to its tasks: the grid of points (the programs, the
worlds, then each constant of `[params]`, in the file's order), each
point's programs checked and compiled once with its constants (`Planner`,
which a tune asks for the jobs of its candidates too), one `Job` per point
and one `Task` per (point, seed), and the tasks in `Batch`es of one job
that travel together. Everything a worker needs travels in the job: the
generated C (and any user C), the world, the settings. Nothing runs here;
every problem (a bad world, a program with errors, a constant no program
defines, a value of the wrong unit, more robots than fit) is found before
the first run."""
from __future__ import annotations

import copy
import hashlib
import itertools
import json
import os
from dataclasses import dataclass, field
from pathlib import Path
from typing import Optional

from ..sim.world import WorldError, parse_world
from .axes import ROBOTS
from .spec import Experiment, ExperimentError

POSE_MS = 100           # pose records for the metrics: every 100 ms


@dataclass
class Payload:
    """A program as it travels to a worker: the C and the files beside it."""
    name: str
    c_text: str
    generated: bool
    header_name: Optional[str]
    header_text: Optional[str]
    files: list                 # (name relative to the program's folder, text)
    variables: list             # (name, initial value)
    digest: str = ""
    # the devices it reads (stdlib DEVICES; None: not known): only a robot
    # whose program reads the camera or the ToF sensor gets them in Enki
    devices: Optional[list] = None

    def __post_init__(self):
        h = hashlib.sha256()
        for part in (self.name, self.c_text, str(self.generated), self.header_name or "",
                     self.header_text or "", json.dumps(self.files)):
            h.update(part.encode("utf-8", "surrogateescape") + b"\0")
        self.digest = h.hexdigest()


@dataclass
class Point:
    index: int
    values: dict                # column -> value text ("program", "world" too, with several)


@dataclass
class Job:
    """One grid point as it travels to a worker: everything its runs depend
    on but the seed. With `count` (the robot count) or a `placement`, the
    world's robots are templates, and each run's world has `count` copies
    placed by its seed (swarm.py)."""
    point: int
    values: dict
    world: object               # sim.world.World, robots' programs as indices below
    robot_programs: list        # for each robot (each template), an index into payloads
    payloads: list
    duration_ms: int
    timeout_s: float
    metrics: list
    series: list = field(default_factory=list)
    period_ms: int = 1000
    traces: bool = False
    count: Optional[int] = None
    placement: object = None    # swarm.Placement, or None
    pose_ms: int = POSE_MS
    robot_names: list = field(default_factory=list)
    digest: str = ""

    @property
    def placed(self) -> bool:
        return self.count is not None or self.placement is not None

    def world_for(self, seed: int):
        """The world of the run with this seed (its robots placed when they
        are copies); swarm.PlacementError when they do not fit."""
        if not self.placed:
            world = copy.copy(self.world)
        else:
            from .swarm import Placement, place
            world = place(self.world, self.world.robots, self.count or len(self.world.robots),
                          self.placement or Placement(), seed)
        world.seed = seed
        return world

    def program_of(self, robot: int) -> int:
        """The payload index of the world's robot number `robot`."""
        return self.robot_programs[robot % len(self.robot_programs)]


@dataclass
class Task:
    """One run: a job and a seed."""
    key: str
    point: int
    seed: int
    values: dict
    job: Job


@dataclass
class Batch:
    """Runs of one job that travel and run together (the job once)."""
    key: str
    job: Job
    tasks: list


def batches(tasks: list, size: int) -> list:
    """The tasks in batches of at most `size` runs, each of one job,
    in the tasks' order."""
    out, current = [], []
    for task in tasks:
        if current and (len(current) >= size or current[-1].job is not task.job):
            out.append(_batch(current))
            current = []
        current.append(task)
    if current:
        out.append(_batch(current))
    return out


def _batch(tasks: list) -> Batch:
    h = hashlib.sha256("\0".join(t.key for t in tasks).encode()).hexdigest()[:20]
    return Batch(h, tasks[0].job, tasks)


def auto_batch(runs: int, workers: int, most: int = 200) -> int:
    """Runs per batch when not told: enough batches to keep `workers` busy
    to the end (four each), at most `most` runs in one."""
    return max(1, min(most, runs // max(1, workers * 4)))


def _c_text(path) -> str:
    """A C file's bytes as text that gives them back (task.py writes them
    with the same errors): C is bytes, a Latin-1 comment included."""
    return Path(path).read_text(encoding="utf-8", errors="surrogateescape")


def payload_of(program) -> Payload:
    """A build.common.Program as a Payload (its user C read now)."""
    files = []
    if program.source_path is not None:
        files.append((Path(program.source_path).name, _c_text(program.source_path)))
    for path in program.user_files:
        rel = Path(path).relative_to(program.base_dir) if Path(path).is_relative_to(
            program.base_dir) else Path(Path(path).name)
        files.append((rel.as_posix(), _c_text(path)))
    return Payload(program.name, program.c_text, program.generated, program.header_name,
                   program.header_text, files, list(program.variables),
                   devices=None if program.devices is None else sorted(program.devices))


def world_label(exp: Experiment, path: Path) -> str:
    """A world as its column shows it: the path as the file gives it."""
    return Path(os.path.relpath(path, exp.path.parent)).as_posix()


def grid(exp: Experiment) -> list:
    axes = []
    if len(exp.programs) > 1:
        axes.append(("program", [p.name for p in exp.programs]))
    if len(exp.worlds) > 1:
        axes.append(("world", [world_label(exp, w) for w in exp.worlds]))
    axes.extend(exp.params.items())
    points = []
    for i, combo in enumerate(itertools.product(*[values for _, values in axes])):
        points.append(Point(i, dict(zip([name for name, _ in axes], combo))))
    return points


def error_at(exp: Experiment, key: str, message: str, help: str = "") -> ExperimentError:
    from .spec import _Positions
    pos = _Positions(exp.path.read_text(encoding="utf-8"))
    return pos.error(exp.shown or str(exp.path), exp.where(key), message, help)


def plan(exp: Experiment, load) -> list:
    """The experiment's tasks, in (point, seed) order. `load(path, defines)`
    checks and compiles one program with its constants overridden (a
    build.common.Program), or returns None after printing its diagnostics.
    ExperimentError for anything that stops the experiment before a run."""
    planner = Planner(exp, load)
    tasks = []
    for point in grid(exp):
        tasks.extend(planner.tasks(planner.job(point.index, point.values), exp.seeds))
    planner.check_variables()
    return tasks


class Planner:
    """Jobs of an experiment's programs and worlds for any values of its
    constants (a grid's points, a tune's candidates): each program checked
    and compiled once per set of constants."""

    def __init__(self, exp: Experiment, load):
        from ..check.defines import constants_of
        self.exp, self.load = exp, load
        self.worlds = {}
        for path in exp.worlds or [exp.world]:
            try:
                self.worlds[path] = parse_world(path)
            except WorldError as exc:
                raise ExperimentError(str(exc)) from None
        for world in self.worlds.values():
            if not exp.programs and any(r.program is None for r in world.robots):
                missing = next(r for r in world.robots if r.program is None)
                raise error_at(exp, "world", f"robot {missing.name} of the world has no program, "
                             "and the experiment names none", 'add a line: program = "prog.epk"')
            several = next((r for r in world.robots if r.more_c), None)
            if several is not None:
                raise error_at(exp, "world", f"robot {several.name} of the world runs a C program "
                             f"of several files, which experiments do not build yet",
                             "run it with `epuckc run --world`")
        used = set(exp.programs) | {r.program for w in self.worlds.values()
                                    for r in w.robots if r.program}
        self.defined = {}
        for path in used:
            self.defined[path] = (set(constants_of(path.read_text(encoding="utf-8"), str(path)))
                                  if path.suffix == ".epk" else set())
        for name in exp.params:
            if name != ROBOTS and not self.constant_defined(name):
                raise error_at(exp, f"params.{name}", f"no program of the experiment has a "
                             f"constant {name}", "a parameter is a `const` of a program")
        self.compiled = {}
        self.declared = set()
        self.fits = set()

    def constant_defined(self, name: str) -> bool:
        return any(name in consts for consts in self.defined.values())

    def job(self, index: int, values: dict) -> Job:
        """The job of a point: `values` gives the program, the world and the
        robot count when they vary, and the constants' value texts."""
        exp = self.exp
        main = None
        if exp.programs:
            main = (exp.programs[[p.name for p in exp.programs].index(values["program"])]
                    if "program" in values else exp.programs[0])
        worlds = exp.worlds or [exp.world]
        path = (next(w for w in worlds if world_label(exp, w) == values["world"])
                if "world" in values else worlds[0])
        world = self.worlds[path]
        count = int(values[ROBOTS]) if ROBOTS in values else None
        constants = {k: v for k, v in values.items() if k not in ("program", "world", ROBOTS)}
        payloads, index_of, robot_programs = [], {}, []
        for robot in world.robots:
            program = robot.program or main
            defines = {k: v for k, v in constants.items() if k in self.defined[program]}
            ck = (program, tuple(sorted(defines.items())))
            if ck not in self.compiled:
                built = self.load(program, defines)
                if built is None:
                    where = "; ".join(f"{k}={v}" for k, v in defines.items())
                    raise ExperimentError(f"{program} has errors (above)"
                                          + (f" with {where}" if where else "")
                                          + "; nothing was run", status=1)
                self.compiled[ck] = payload_of(built)
            payload = self.compiled[ck]
            self.declared.update(name for name, _ in payload.variables)
            if payload.digest not in index_of:
                index_of[payload.digest] = len(payloads)
                payloads.append(payload)
            robot_programs.append(index_of[payload.digest])
        bare = copy.deepcopy(world)
        for robot in bare.robots:
            robot.program = None
        bare.path = Path(path.name)
        bare.seed = 0
        job = Job(index, dict(values), bare, robot_programs, payloads, exp.duration_ms,
                  exp.timeout_s, exp.metrics, exp.series, exp.period_ms, exp.traces,
                  count=count, placement=exp.placement)
        n = count or len(bare.robots)
        job.robot_names = ([f"r{k + 1}" for k in range(n)] if job.placed
                           else [r.name for r in bare.robots])
        if job.placed:
            self._check_fit(job, path, n)
        job.digest = _job_digest(job)
        return job

    def _check_fit(self, job: Job, path: Path, count: int):
        from .swarm import Placement, PlacementError, check_fit
        if (path, count) in self.fits:
            return
        key = f"params.{ROBOTS}" if ROBOTS in job.values else "placement"
        why = check_fit(job.world, count, job.placement or Placement())
        if why is None:
            try:
                job.world_for(self.exp.seeds[0] if self.exp.seeds else 1)
            except PlacementError as exc:
                why = str(exc)
        if why is not None:
            raise error_at(self.exp, key, f"{count} robots in {path.name}: {why}",
                         "fewer robots, a lower density ([placement] density) or a larger "
                         "arena")
        self.fits.add((path, count))

    def tasks(self, job: Job, seeds) -> list:
        return [Task(run_key(job, seed), job.point, seed, job.values, job) for seed in seeds]

    def check_variables(self):
        """Every var:NAME and mean:NAME of the metrics and series names a
        variable of a program (known once the programs are compiled)."""
        exp = self.exp
        for key, names in (("metrics", exp.metrics), ("series", exp.series)):
            for m in names:
                kind, _, name = m.partition(":")
                if kind in ("var", "mean") and name not in self.declared:
                    raise error_at(exp, key, f"`{m}`: no program of the experiment declares a "
                                 f"variable {name}",
                                 f"declared: {', '.join(sorted(self.declared)) or 'none'}")


def _job_digest(job: Job) -> str:
    """What a run is a pure function of, but its seed (what it measures is
    not part of it: results.py takes a saved run that measured more)."""
    h = hashlib.sha256()
    h.update(json.dumps({"world": job.world.to_json(), "robots": job.robot_programs,
                         "programs": [p.digest for p in job.payloads],
                         "duration_ms": job.duration_ms, "pose_ms": job.pose_ms,
                         "count": job.count,
                         "placement": job.placement.to_json() if job.placement else None},
                        sort_keys=True).encode())
    return h.hexdigest()


def run_key(job: Job, seed: int) -> str:
    """A run already in DIR with this key is not run again."""
    return hashlib.sha256(f"{job.digest} {seed}".encode()).hexdigest()[:20]
