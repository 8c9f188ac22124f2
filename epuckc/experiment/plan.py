"""From an experiment to its tasks: the grid of points (the programs, then
each constant of `[params]`, in the file's order), each point's programs
checked and compiled once with its constants, and one self-contained task
per (point, seed). Everything a worker needs travels in the task: the
generated C (and any user C), the world, the settings. Nothing runs here;
every problem (a bad world, a program with errors, a constant no program
defines, a value of the wrong unit) is found before the first run."""
from __future__ import annotations

import copy
import hashlib
import itertools
import json
from dataclasses import dataclass, field
from pathlib import Path
from typing import Optional

from ..sim.world import WorldError, parse_world
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
            h.update(part.encode("utf-8") + b"\0")
        self.digest = h.hexdigest()


@dataclass
class Point:
    index: int
    values: dict                # column -> value text ("program" too, with several)


@dataclass
class Task:
    key: str
    point: int
    seed: int
    values: dict
    duration_ms: int
    world: object               # sim.world.World, robots' programs as indices below
    robot_programs: list        # for each robot, an index into payloads
    payloads: list
    metrics: list
    timeout_s: float
    traces: bool
    pose_ms: int = POSE_MS
    robot_names: list = field(default_factory=list)


def payload_of(program) -> Payload:
    """A build.common.Program as a Payload (its user C read now)."""
    files = []
    if program.source_path is not None:
        files.append((Path(program.source_path).name,
                      Path(program.source_path).read_text(encoding="utf-8")))
    for path in program.user_files:
        rel = Path(path).relative_to(program.base_dir) if Path(path).is_relative_to(
            program.base_dir) else Path(Path(path).name)
        files.append((rel.as_posix(), Path(path).read_text(encoding="utf-8")))
    return Payload(program.name, program.c_text, program.generated, program.header_name,
                   program.header_text, files, list(program.variables),
                   devices=None if program.devices is None else sorted(program.devices))


def grid(exp: Experiment) -> list:
    axes = []
    if len(exp.programs) > 1:
        axes.append(("program", [p.name for p in exp.programs]))
    axes.extend(exp.params.items())
    points = []
    for i, combo in enumerate(itertools.product(*[values for _, values in axes])):
        points.append(Point(i, dict(zip([name for name, _ in axes], combo))))
    return points


def _error(exp: Experiment, key: str, message: str, help: str = "") -> ExperimentError:
    from .spec import _Positions
    pos = _Positions(exp.path.read_text(encoding="utf-8"))
    return pos.error(exp.shown or str(exp.path), exp.where(key), message, help)


def plan(exp: Experiment, load) -> list:
    """The experiment's tasks, in (point, seed) order. `load(path, defines)`
    checks and compiles one program with its constants overridden (a
    build.common.Program), or returns None after printing its diagnostics.
    ExperimentError for anything that stops the experiment before a run."""
    from ..check.defines import constants_of
    try:
        world = parse_world(exp.world)
    except WorldError as exc:
        raise ExperimentError(str(exc)) from None
    if not exp.programs and any(r.program is None for r in world.robots):
        missing = next(r for r in world.robots if r.program is None)
        raise _error(exp, "world", f"robot {missing.name} of the world has no program, and "
                     "the experiment names none", 'add a line: program = "prog.epk"')
    several = next((r for r in world.robots if r.more_c), None)
    if several is not None:
        raise _error(exp, "world", f"robot {several.name} of the world runs a C program of "
                     f"several files, which experiments do not build yet",
                     "run it with `epuckc run --world`")
    used = {p for p in exp.programs} | {r.program for r in world.robots if r.program}
    defined = {}
    for path in used:
        if path.suffix == ".epk":
            defined[path] = set(constants_of(path.read_text(encoding="utf-8"), str(path)))
        else:
            defined[path] = set()
    for name in exp.params:
        if not any(name in consts for consts in defined.values()):
            raise _error(exp, f"params.{name}", f"no program of the experiment has a "
                         f"constant {name}", "a parameter is a `const` of a program")
    declared = set()
    tasks = []
    compiled = {}
    for point in grid(exp):
        main = None
        if exp.programs:
            main = (exp.programs[[p.name for p in exp.programs].index(point.values["program"])]
                    if "program" in point.values else exp.programs[0])
        payloads, index, robot_programs = [], {}, []
        for robot in world.robots:
            path = robot.program or main
            defines = {k: v for k, v in point.values.items()
                       if k != "program" and k in defined[path]}
            ck = (path, tuple(sorted(defines.items())))
            if ck not in compiled:
                program = load(path, defines)
                if program is None:
                    where = "; ".join(f"{k}={v}" for k, v in defines.items())
                    raise ExperimentError(f"{path} has errors (above)"
                                          + (f" with {where}" if where else "")
                                          + "; nothing was run", status=1)
                compiled[ck] = payload_of(program)
            payload = compiled[ck]
            declared.update(name for name, _ in payload.variables)
            if payload.digest not in index:
                index[payload.digest] = len(payloads)
                payloads.append(payload)
            robot_programs.append(index[payload.digest])
        bare = copy.deepcopy(world)
        for robot in bare.robots:
            robot.program = None
        bare.path = Path(exp.world.name)
        for seed in exp.seeds:
            bare_seeded = copy.copy(bare)
            bare_seeded.seed = seed
            key = _task_key(bare_seeded, robot_programs, payloads, seed, exp)
            tasks.append(Task(key, point.index, seed, point.values, exp.duration_ms,
                              bare_seeded, robot_programs, payloads, exp.metrics,
                              exp.timeout_s, exp.traces,
                              robot_names=[r.name for r in world.robots]))
    for m in exp.metrics:
        kind, _, name = m.partition(":")
        if kind in ("var", "mean") and name not in declared:
            raise _error(exp, "metrics", f"`{m}`: no program of the experiment declares a "
                         f"variable {name}", f"declared: {', '.join(sorted(declared)) or 'none'}")
    return tasks


def _task_key(world, robot_programs, payloads, seed, exp) -> str:
    """What a run is a pure function of: a run already in DIR with this key
    is not run again."""
    h = hashlib.sha256()
    h.update(json.dumps({"world": world.to_json(), "robots": robot_programs,
                         "programs": [p.digest for p in payloads], "seed": seed,
                         "duration_ms": exp.duration_ms, "metrics": exp.metrics,
                         "pose_ms": POSE_MS}, sort_keys=True).encode())
    return h.hexdigest()[:20]
