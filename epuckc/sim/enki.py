"""Runs programs in an Enki world: the second provider of the e-puck library
on the host.

Each robot is its program + the runtime + the host platform layer + the stub
e-puck library + runtime_c/enki/robot_glue.c, linked into one shared object
(`build_robot`); the world runner (runtime_c/enki/world_runner.cpp, built
once, `build_runner`) loads one copy of that object per robot and steps
them in lockstep with Enki's physics. docs/world.md explains why.

`run_world` writes the merged trace: a `world` record, then every robot's
records (with a `robot` key) in time order, then a `contacts` record per
robot with Enki's collision counts.
"""
from __future__ import annotations

import os
import re
import shlex
import shutil
import subprocess
import sys
import tempfile
import zlib
from pathlib import Path
from typing import Optional

from ..base.records import record
from ..build.common import BuildError, Program, _run_compiler, c_compiler
from ..base.resources import (RUNTIME_CORE, RUNTIME_DEVICES, RUNTIME_SIMULATED, cache_dir,
                              runtime_dir)
from .world import World, runner_spec

ROBOT_SOURCES = [*RUNTIME_CORE, *RUNTIME_SIMULATED, *RUNTIME_DEVICES, "host/platform_host.c", "host/scenario.c",
                 "host/epuck_stub.c", "host/stub_devices.c", "host/cmain.c", "host/epuck_more.c", "enki/robot_glue.c"]
ROBOT_INCLUDES = [".", "epuck_api", "host", "enki", "epuck_api_unsimulated"]
# robot_glue.c's header comment says why each of these is wrapped
WRAPPED = ["stub_motors_1ms", "stub_motors_ms", "stub_motors_ms_end", "stub_pose",
           "stub_set_geometry", "getenv", "exit"]
RUNNER_FLAGS = ["-std=c++14", "-O2", "-Wall", "-Wextra"]
# A robot is built once and run by every robot of every run of a world or
# an experiment, so its code gets -O2 (the host's executables get -O1,
# which takes gcc 40% less time: a run is often shorter than its build);
# the copies are bound to themselves (-Bsymbolic), so gcc may inline
# across the object's global functions (-fno-semantic-interposition).
ROBOT_CODE_FLAGS = ["-fPIC", "-O2", "-fno-semantic-interposition"]
# In a world the pose is Enki's (the glue wraps stub_pose): the stub's own
# dead reckoning, sines and cosines at every ms of every robot, was a fifth
# of a run's time for nothing (docs/performance.md)
ROBOT_RUNTIME_FLAGS = ROBOT_CODE_FLAGS + ["-DEPUCK_STUB_NO_POSE"]
ENKI_HEADER = Path("/usr/include/enki/PhysicalEngine.h")
ENKI_MISSING = ("running in a world needs Enki, its headers and a C++ compiler "
                "(Debian/Ubuntu: apt-get install libenki-dev g++)")


def cxx_compiler() -> list:
    return shlex.split(os.environ.get("CXX") or "c++")


def enki_available() -> bool:
    """Enki's headers and library are installed and a C++ compiler found."""
    return ENKI_HEADER.is_file() and shutil.which(cxx_compiler()[0]) is not None


def _atomic_copy_into(cached: Path, produce) -> Path:
    """Build `cached` with produce(tmp_path) unless it exists; never leaves
    a half-written file."""
    if cached.is_file():
        return cached
    cached.parent.mkdir(parents=True, exist_ok=True)
    with tempfile.TemporaryDirectory(dir=cached.parent) as tmp:
        out = Path(tmp) / cached.name
        produce(out)
        os.replace(out, cached)
    return cached


RUNNER_MAIN = "enki/world_runner.cpp"


def _runner_sources(rt: Path) -> list:
    """The runner's source and every header beside it (a header added there
    is part of the runner's key without a list to update)."""
    return [rt / RUNNER_MAIN, *sorted((rt / "enki").glob("*.h"))]


def build_runner() -> Path:
    """The world runner executable, cached by its sources and the compiler.
    Found again from the sources' sizes and times (a stamp file of the
    cache, compared whole), so that a run hashes them only after a change:
    hashing took a tenth of the Python around a world run."""
    rt = runtime_dir()
    paths = [*_runner_sources(rt), ENKI_HEADER]
    try:
        stamp = "\n".join([" ".join(cxx_compiler() + RUNNER_FLAGS)] + [
            f"{path} {st.st_size} {st.st_mtime_ns}" for path, st in zip(paths, map(os.stat, paths))])
    except OSError:
        stamp = None
    stamps = cache_dir() / "enki" / "stamps"
    if stamp is not None:
        known = stamps / f"{zlib.crc32(stamp.encode()):08x}"
        try:
            text = known.read_text(encoding="utf-8")
        except (OSError, UnicodeDecodeError):
            text = ""
        seen, _, exe = text.rpartition("\n")
        if seen == stamp and Path(exe).is_file():
            return Path(exe)
    if not enki_available():
        raise BuildError(ENKI_MISSING)
    import hashlib
    h = hashlib.sha256()
    for path in paths:
        h.update(path.read_bytes())
    h.update(" ".join(cxx_compiler() + RUNNER_FLAGS).encode())
    exe = cache_dir() / "enki" / f"runner-{h.hexdigest()[:24]}" / "epuck-world"

    def produce(out: Path):
        _run_compiler(cxx_compiler() + RUNNER_FLAGS + [f"-I{rt / 'enki'}",
                      str(rt / RUNNER_MAIN), "-o", str(out), "-lenki", "-ldl"],
                      "the Enki world runner")
    _atomic_copy_into(exe, produce)
    if stamp is not None:
        from ..base.output import write_atomic
        try:
            known.parent.mkdir(parents=True, exist_ok=True)
            write_atomic(known, f"{stamp}\n{exe}")
        except OSError:
            pass            # found by hashing next time
    return exe


@record
class BuiltRobot:
    """A program built before as a robot (build/runcache.py found it): its
    shared object and what a world run reads of its Program."""
    lib: Path
    devices: Optional[frozenset]
    variables: list


def robot_library(program) -> Path:
    """The shared object of a Program, or of a BuiltRobot."""
    return program.lib if isinstance(program, BuiltRobot) else build_robot(program)


def build_robot(program: Program) -> Path:
    """The program as a robot of a world: a shared object, cached."""
    import hashlib
    from ..build.host import compile_objects, host_build_key, runtime_cache_dir, runtime_flags
    key = hashlib.sha256(("enki-robot\0" + " ".join(ROBOT_RUNTIME_FLAGS) + "\0"
                          + host_build_key(program)).encode()).hexdigest()[:24]
    lib = cache_dir() / "enki" / key / f"{program.name}.so"

    def produce(out: Path):
        # as on the host: the user's C on its own without -Werror, the
        # generated program and the runtime with it, all at once; the
        # runtime's objects (position-independent) kept for the next robot
        objects, runtime = compile_objects(
            program, out.parent, ROBOT_SOURCES,
            runtime_flags(program, ROBOT_INCLUDES, ROBOT_RUNTIME_FLAGS),
            runtime_cache_dir(), ROBOT_CODE_FLAGS)
        command = (c_compiler() + ["-shared"] + [str(o) for o in objects + runtime]
                   + ["-Wl,--wrap=" + ",--wrap=".join(WRAPPED), "-Wl,-Bsymbolic",
                      "-o", str(out), "-lm"])
        _run_compiler(command, f"{program.name} for the Enki world")
    return _atomic_copy_into(lib, produce)


@record
class RobotResult:
    name: str
    status: int
    wall_contacts: int
    object_contacts: int
    robot_contacts: int
    first_contact_ms: int


_T_MS = re.compile(r'\{"t_ms": (-?\d+), ')


def merge_traces(world: World, traces: list, results: list, end_ms: int) -> str:
    """One trace for the run: the world, every robot's records in time order
    (ties: robots in the world's order, each robot's own order kept), and
    each robot's collision counts."""
    import json
    lines = [json.dumps(world.to_json())]
    records = []
    for index, (placement, text) in enumerate(zip(world.robots, traces)):
        name = json.dumps(placement.name)
        for order, line in enumerate(text.splitlines()):
            m = _T_MS.match(line)
            if m is None:
                continue
            records.append((int(m.group(1)), index, order,
                            f'{{"t_ms": {m.group(1)}, "robot": {name}, ' + line[m.end():]))
    records.sort(key=lambda r: r[:3])
    lines.extend(r[3] for r in records)
    for r in results:
        lines.append(json.dumps({"t_ms": end_ms, "robot": r.name, "kind": "contacts",
                                 "walls": r.wall_contacts, "objects": r.object_contacts,
                                 "robots": r.robot_contacts, "first_ms": r.first_contact_ms}))
    return "\n".join(lines) + "\n"


def _contact_line(r: RobotResult) -> str:
    total = r.wall_contacts + r.object_contacts + r.robot_contacts
    if total == 0:
        return f"{r.name}: no collision"
    parts = [f"{n} {what}" for n, what in ((r.wall_contacts, "with walls"),
                                           (r.object_contacts, "with obstacles"),
                                           (r.robot_contacts, "with robots")) if n]
    return (f"{r.name}: collisions in {total} physics steps ({', '.join(parts)}), "
            f"the first at {r.first_contact_ms} ms")


@record
class WorldRun:
    """What one run of a world gave: each robot's result (status and
    contacts, in the world's order), each robot's own trace (JSON lines),
    and the last time any robot reached."""
    results: list
    traces: list
    end_ms: int


class WorldTimeout(Exception):
    """The runner ran longer than the wall-clock limit it was given."""


def simulate(world: World, libs: list, time_limit_ms: int, seed: int = 1,
             pose_ms: Optional[int] = None, quiet: bool = False, capture: bool = False,
             timeout_s: Optional[float] = None, devices: Optional[list] = None,
             with_traces: bool = True) -> WorldRun:
    """Run the world once: `libs` are the robots' built shared objects, in
    the world's order; Enki's generator is seeded by the world's `seed`,
    robot k's `random` by `seed + k`. `quiet`: the robots print nothing;
    `capture`: the runner's output is kept from stdout and stderr (its last
    line of stderr then says why it failed). After `timeout_s` seconds of wall clock it is
    killed (WorldTimeout). `devices`: each robot's devices its program reads
    (stdlib DEVICES; None: all), so that only those robots get Enki's
    camera and the ToF ray. `with_traces`: the robots write their traces (without
    them the run's traces are empty and its end_ms 0). BuildError when the
    runner fails."""
    runner = build_runner()
    with tempfile.TemporaryDirectory(prefix="epuckc-world-") as tmp:
        tmpdir = Path(tmp)
        entries = []
        for i, lib in enumerate(libs):
            # the runner loads a copy for each robot, beside the spec: its own
            # globals (docs/world.md)
            settings = {"EPUCK_TIME_LIMIT_MS": str(time_limit_ms),
                        # each robot its own `random` (`run --seed N`: N + i)
                        "EPUCK_SEED": str((seed + i) & 0xFFFFFFFF)}
            if with_traces:
                settings["EPUCK_TRACE"] = str(tmpdir / f"robot{i}.jsonl")
            if pose_ms:
                settings["EPUCK_POSE_MS"] = str(pose_ms)
            if os.environ.get("EPUCK_WATCHDOG_MS"):     # `run --watchdog`
                settings["EPUCK_WATCHDOG_MS"] = os.environ["EPUCK_WATCHDOG_MS"]
            for name in ("EPUCK_POLL_EVERY_MS", "EPUCK_POLL_STATS"):    # tests, benches
                if os.environ.get(name):
                    settings[name] = os.environ[name]
            if quiet:
                settings["EPUCK_QUIET"] = "1"
            entries.append((lib, settings, None if devices is None else devices[i]))
        spec = tmpdir / "world.spec"
        spec.write_text(runner_spec(world, entries), encoding="utf-8")
        results_file = tmpdir / "results"
        sys.stdout.flush()
        capture = subprocess.PIPE if capture else None
        try:
            proc = subprocess.run([str(runner), str(spec), str(results_file)], stdout=capture,
                                  stderr=capture, timeout=timeout_s)
        except subprocess.TimeoutExpired:
            raise WorldTimeout(f"the run took more than {timeout_s:g} s of wall-clock time "
                               f"and was stopped (the watchdog)") from None
        except OSError as exc:
            raise BuildError(f"cannot run {runner}: {exc.strerror or exc}") from None
        if proc.returncode == -2:          # SIGINT: Ctrl-C on the terminal reached it too
            raise KeyboardInterrupt
        if proc.returncode != 0 or not results_file.is_file():
            why = ""
            if capture and proc.stderr:
                why = ": " + proc.stderr.decode("utf-8", "replace").strip().splitlines()[-1]
            elif proc.returncode < 0:
                why = f": killed by signal {-proc.returncode}"
            raise BuildError(f"the Enki world runner failed (exit status {proc.returncode})"
                             + why)
        results = []
        for line in results_file.read_text().splitlines():
            name, *numbers = line.split()
            results.append(RobotResult(name, *map(int, numbers)))
        traces = []
        end_ms = 0
        for i in range(len(libs)):
            path = tmpdir / f"robot{i}.jsonl"
            text = path.read_text(encoding="utf-8") if path.is_file() else ""
            traces.append(text)
            for m in _T_MS.finditer(text):
                end_ms = max(end_ms, int(m.group(1)))
    return WorldRun(results, traces, end_ms)


def run_world(world: World, default_program, load_program, time_limit_ms: int,
              trace: Optional[Path], pose_ms: Optional[int] = None) -> int:
    """Build and run every robot of the world (a program: a Program, or a
    BuiltRobot found in the run cache); print the robots' readable traces
    and a collision summary; write the merged trace to `trace`.
    `load_program(path, more_c)` gives the Program of a robot's own
    `program` (and its other C files), or raises BuildError. Returns the highest of the robots' exit statuses."""
    build_runner()
    text = os.environ.get("EPUCK_SEED", "")
    seed = int(text) if text.isdigit() else 1
    libs = {}
    robots, devices = [], []
    for placement in world.robots:
        program = default_program if placement.program is None else \
            load_program(placement.program, placement.more_c)
        if id(program) not in libs:
            libs[id(program)] = (program, robot_library(program))
        robots.append(libs[id(program)][1])
        devices.append(program.devices)
    quiet = os.environ.get("EPUCK_QUIET", "")
    quiet = bool(quiet and quiet != "0")
    run = simulate(world, robots, time_limit_ms, seed, pose_ms, quiet=quiet, devices=devices,
                   with_traces=trace is not None)
    if not quiet:
        for r in run.results:
            print(_contact_line(r))
    if trace is not None:
        from ..base.output import write_atomic
        write_atomic(trace, merge_traces(world, run.traces, run.results, run.end_ms))
    sys.stdout.flush()
    return max(r.status for r in run.results)
