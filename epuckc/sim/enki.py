"""Runs programs in an Enki world: the second provider of the e-puck library
on the host.

Each robot is its program + the runtime + the host platform layer + the stub
e-puck library + runtime_c/enki/robot_glue.c, linked into one shared object
(`build_robot`); the world runner (runtime_c/enki/world_runner.cpp, built
once, `build_runner`) loads one copy of that object per robot and steps
them in lockstep with Enki's physics. docs/world.md explains why.

`run_world` writes the merged trace: a `world` record, then every robot's
records (with a `robot` key) in time order, then a `contacts` record per
robot with the physics steps it touched walls, obstacles, robots and
anything in (runtime_c/enki/contacts.h).
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

from ..base import cache
from ..base.records import record
from ..build.common import BuildError, Program, _run_compiler, c_compiler
from ..base.resources import (LIBRARY_SIMULATION, RUNTIME_CORE, RUNTIME_DEVICES,
                              RUNTIME_SIMULATED, runtime_dir)
from .contacts import contact_words
from .physics import CHIPMUNK_ABOVE
from .world import World, runner_spec

ROBOT_SOURCES = [*RUNTIME_CORE, *RUNTIME_SIMULATED, *RUNTIME_DEVICES, "platform/platform_host.c",
                 "host/scenario.c", "host/cmain.c", *LIBRARY_SIMULATION, "enki/robot_glue.c"]
ROBOT_INCLUDES = [".", "epuck_api", "host", "enki", "epuck_api_unsimulated"]
# robot_glue.c's header comment says why each of these is wrapped
WRAPPED = ["stub_motors_1ms", "stub_motors_ms", "stub_motors_ms_end", "stub_pose",
           "stub_set_geometry", "getenv", "exit", "stub_set_observer", "stub_set_micro", "main"]
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
    """Build `cached`, a file in a folder entry of the cache's `enki` area,
    with produce(tmp_path) unless it is there (then marked used); the
    entry is built aside and renamed into place whole (base/cache.py). The
    path of the file built: in a temporary folder of the process when the
    cache cannot take it."""
    entry = cached.parent

    def complete(folder: Path) -> bool:
        return cache.used(folder) and (folder / cached.name).is_file()
    if complete(entry):
        return cached
    area = cache.writable_area("enki")
    entry = area / entry.name
    cached = entry / cached.name
    if complete(entry):
        return cached
    tmp = cache.temporary_folder(area)
    try:
        work = tmp / "build"
        work.mkdir()
        produce(work / cached.name)
        os.replace(work / cached.name, tmp / cached.name)
        shutil.rmtree(work, ignore_errors=True)     # what produce left beside it
        cache.commit_folder(tmp, entry, complete)
    finally:
        if tmp.exists():
            shutil.rmtree(tmp, ignore_errors=True)
    return cached


RUNNER_CORE = "enki/world_runner.cpp"
CHIPMUNK_MISSING = ("a world with `physics chipmunk` needs Chipmunk 7, its headers and a C++ "
                    "compiler (Debian/Ubuntu: apt-get install libchipmunk-dev g++)")


@record
class Provider:
    """A physics provider of the world runner (runtime_c/enki/physics.h):
    its source beside the core, the libraries it links, a header that says
    it is installed, and what to install when it is not."""
    name: str
    source: str
    libraries: list
    header: Path
    missing: str


PROVIDERS = {
    "enki": Provider("enki", "enki/physics_enki.cpp", ["-lenki"], ENKI_HEADER, ENKI_MISSING),
    "chipmunk": Provider("chipmunk", "enki/physics_chipmunk.cpp", ["-lchipmunk"],
                         Path("/usr/include/chipmunk/chipmunk.h"), CHIPMUNK_MISSING),
}


def provider_available(physics: str) -> bool:
    """The provider's headers and library are installed and a C++ compiler found."""
    return PROVIDERS[physics].header.is_file() and shutil.which(cxx_compiler()[0]) is not None


def _runner_sources(rt: Path, physics: str) -> list:
    """The runner's core, the provider's source and every header beside
    them (a header added there is part of the runner's key without a list
    to update)."""
    return [rt / RUNNER_CORE, rt / PROVIDERS[physics].source, *sorted((rt / "enki").glob("*.h"))]


def physics_for(world: World) -> str:
    """The provider a world runs on: its own (World.resolved_physics), but
    Enki where the choice was the robot count's and Chipmunk is missing."""
    physics = world.resolved_physics
    if world.physics is None and not provider_available(physics):
        return "enki"
    return physics


def runner_command(physics: str, out: Path, extra: tuple = ()) -> list:
    """The compiler's command that builds the world runner on `physics`."""
    rt = runtime_dir()
    provider = PROVIDERS[physics]
    return (cxx_compiler() + RUNNER_FLAGS + list(extra)
            + [f"-I{rt / 'enki'}", str(rt / RUNNER_CORE), str(rt / provider.source), "-o", str(out)]
            + provider.libraries + ["-ldl", "-pthread"])


def build_runner(physics: str = "enki") -> Path:
    """The world runner executable on `physics` ("enki" or "chipmunk"),
    cached by its sources and the compiler. Found again from the sources'
    sizes and times (a stamp file of the cache, compared whole), so that a
    run hashes them only after a change: hashing took a tenth of the Python
    around a world run."""
    rt = runtime_dir()
    provider = PROVIDERS[physics]
    paths = [*_runner_sources(rt, physics), provider.header]
    try:
        stamp = "\n".join([" ".join(cxx_compiler() + RUNNER_FLAGS)] + [
            f"{path} {st.st_size} {st.st_mtime_ns}" for path, st in zip(paths, map(os.stat, paths))])
    except OSError:
        stamp = None
    stamps = cache.area("enki") / "stamps"
    if stamp is not None:
        known = stamps / f"{zlib.crc32(stamp.encode()):08x}"
        try:
            text = known.read_text(encoding="utf-8")
        except (OSError, UnicodeDecodeError):
            text = ""
        seen, _, exe = text.rpartition("\n")
        if seen == stamp and cache.used(Path(exe).parent) and Path(exe).is_file():
            cache.used(stamps)
            return Path(exe)
    if not provider_available(physics):
        raise BuildError(provider.missing)
    import hashlib
    h = hashlib.sha256()
    for path in paths:
        h.update(path.read_bytes())
    h.update(" ".join(cxx_compiler() + RUNNER_FLAGS + provider.libraries).encode())
    exe = cache.area("enki") / f"runner-{h.hexdigest()[:24]}" / f"epuck-world-{physics}"

    def produce(out: Path):
        _run_compiler(runner_command(physics, out), f"the world runner on {physics}")
    exe = _atomic_copy_into(exe, produce)
    if stamp is not None and exe.parent.parent == cache.area("enki"):
        cache.write_entry(known, f"{stamp}\n{exe}".encode("utf-8"))    # else: hashed next time
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
    lib = cache.area("enki") / key / f"{program.name}.so"

    def produce(out: Path):
        # as on the host: the user's C on its own without -Werror, the
        # generated program and the runtime with it, all at once; the
        # runtime's objects (position-independent) kept for the next robot
        objects, runtime = compile_objects(
            program, out.parent, ROBOT_SOURCES,
            runtime_flags(program, ROBOT_INCLUDES, ROBOT_RUNTIME_FLAGS),
            cache.usable(runtime_cache_dir()), ROBOT_CODE_FLAGS)
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
    contact_steps: int          # in contact with anything (runtime_c/enki/contacts.h)

    def counts(self) -> dict:
        """As the trace's `contacts` record has them."""
        return {"walls": self.wall_contacts, "objects": self.object_contacts,
                "robots": self.robot_contacts, "steps": self.contact_steps}


def world_record(world: World) -> dict:
    """The trace's first record: the world, and the physics it ran on."""
    return dict(world.to_json(), physics=physics_for(world))


_T_MS = re.compile(r'\{"t_ms": (-?\d+), ')


def merge_traces(world: World, traces: list, results: list, end_ms: int) -> str:
    """One trace for the run: the world, every robot's records in time order
    (ties: robots in the world's order, each robot's own order kept), and
    each robot's collision counts."""
    import json
    lines = [json.dumps(world_record(world))]
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
        lines.append(json.dumps(_contacts_record(r, end_ms)))
    return "\n".join(lines) + "\n"


def _contacts_record(r: "RobotResult", end_ms: int) -> dict:
    return {"t_ms": end_ms, "robot": r.name, "kind": "contacts", **r.counts(),
            "first_ms": r.first_contact_ms}


def _contact_line(r: RobotResult) -> str:
    if r.contact_steps == 0:
        return f"{r.name}: no collision"
    return f"{r.name}: {contact_words(r.counts(), 'physics steps')}; the first at " \
           f"{r.first_contact_ms} ms"


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


def _robot_scenario(world: World, index: int, folder: Path) -> Optional[Path]:
    """Robot `index`'s inputs at set times: its own scenario, else the
    world's, after its selector's position at start (a line at 0 ms of a
    scenario written for it into `folder`)."""
    placement = world.robots[index]
    scenario = placement.scenario or world.scenario
    if placement.selector is None:
        return scenario
    path = folder / f"robot{index}.scn"
    data = scenario.read_bytes() if scenario is not None else b""
    if data.startswith(b"\xef\xbb\xbf"):
        data = data[3:]
    path.write_bytes(f"0 ms selector={placement.selector}\n".encode() + data)
    return path


def simulate(world: World, libs: list, time_limit_ms: int, seed: int = 1,
             pose_ms: Optional[int] = None, quiet: bool = False, capture: bool = False,
             timeout_s: Optional[float] = None, devices: Optional[list] = None,
             with_traces: bool = True, on_lines=None) -> WorldRun:
    """Run the world once: `libs` are the robots' built shared objects, in
    the world's order; Enki's generator is seeded by the world's `seed`,
    robot k's `random` by `seed + k`. `quiet`: the robots print nothing;
    `capture`: the runner's output is kept from stdout and stderr (its last
    line of stderr then says why it failed). After `timeout_s` seconds of wall clock it is
    killed (WorldTimeout). `devices`: each robot's devices its program reads
    (stdlib DEVICES; None: all), so that only those robots get Enki's
    camera and the ToF ray. `with_traces`: the robots write their traces (without
    them the run's traces are empty and its end_ms 0). `on_lines(lines)`:
    the merged trace's records, handed over while the world runs (live.py;
    with_traces). BuildError when the runner fails."""
    runner = build_runner(physics_for(world))
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
            if "EPUCK_TRACE_VARS" in os.environ:        # `run --trace-vars` (tracevars.py)
                settings["EPUCK_TRACE_VARS"] = os.environ["EPUCK_TRACE_VARS"]
            if quiet:
                settings["EPUCK_QUIET"] = "1"
            scenario = _robot_scenario(world, i, tmpdir)
            if scenario is not None:
                settings["EPUCK_SCENARIO"] = str(scenario)
            entries.append((lib, settings, None if devices is None else devices[i]))
        spec = tmpdir / "world.spec"
        spec.write_text(runner_spec(world, entries, tmpdir / "floor.rgb"), encoding="utf-8")
        results_file = tmpdir / "results"
        sys.stdout.flush()
        capture = subprocess.PIPE if capture else None
        try:
            if on_lines is not None and with_traces:
                proc = _run_live(world, [runner, spec, results_file], capture, timeout_s,
                                 [tmpdir / f"robot{i}.jsonl" for i in range(len(libs))],
                                 on_lines)
            else:
                proc = subprocess.run([str(runner), str(spec), str(results_file)],
                                      stdout=capture, stderr=capture, timeout=timeout_s)
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
            raise BuildError(f"the world runner failed (exit status {proc.returncode}, "
                             f"physics {physics_for(world)})" + why)
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


def _run_live(world: World, command: list, capture, timeout_s: Optional[float], traces: list,
              on_lines) -> subprocess.CompletedProcess:
    """The runner, its robots' traces merged and handed to `on_lines` as
    they are written (live.py)."""
    import time
    from .live import LiveMerge
    merge = LiveMerge([r.name for r in world.robots], traces, on_lines)
    deadline = None if timeout_s is None else time.monotonic() + timeout_s
    with subprocess.Popen([str(c) for c in command], stdout=capture, stderr=capture) as proc:
        try:
            while True:
                try:
                    proc.wait(timeout=0.01)
                    break
                except subprocess.TimeoutExpired:
                    merge.poll()
                if deadline is not None and time.monotonic() > deadline:
                    raise subprocess.TimeoutExpired(command, timeout_s)
            out, err = proc.communicate()
        except BaseException:
            proc.kill()         # a watchdog, Ctrl-C or a reader gone: no runner left behind
            raise
    if proc.returncode == 0:
        merge.finish()
    return subprocess.CompletedProcess(command, proc.returncode, out, err)


def run_world(world: World, default_program, load_program, time_limit_ms: int,
              trace: Optional[Path], pose_ms: Optional[int] = None, stream=None) -> int:
    """Build and run every robot of the world (a program: a Program, or a
    BuiltRobot found in the run cache); print the robots' readable traces
    and a collision summary; write the merged trace to `trace`.
    `load_program(path, more_c)` gives the Program of a robot's own
    `program` (and its other C files), or raises BuildError. `stream` (a
    text file, `--trace -`): the merged trace written to it as the world
    runs, the robots quiet and the collision summary on stderr. Returns the
    highest of the robots' exit statuses."""
    physics = physics_for(world)
    build_runner(physics)
    if world.physics is None and physics != "enki":
        print(f"epuckc: {len(world.robots):,} robots: the world runs on Chipmunk, faster than "
              f"Enki above {CHIPMUNK_ABOVE} robots (`physics enki` in the world keeps Enki)",
              file=sys.stderr)
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
    quiet = bool(quiet and quiet != "0") or stream is not None
    on_lines = None
    if stream is not None:
        import json
        stream.write(json.dumps(world_record(world)) + "\n")
        stream.flush()

        def on_lines(lines):
            stream.write("\n".join(lines) + "\n")
            stream.flush()
    run = simulate(world, robots, time_limit_ms, seed, pose_ms, quiet=quiet, devices=devices,
                   with_traces=trace is not None or stream is not None, on_lines=on_lines)
    if stream is not None:
        import json
        for r in run.results:
            stream.write(json.dumps(_contacts_record(r, run.end_ms)) + "\n")
            print(_contact_line(r), file=sys.stderr)
        stream.flush()
    elif not quiet:
        for r in run.results:
            print(_contact_line(r))
    if trace is not None:
        from ..base.output import write_atomic
        write_atomic(trace, merge_traces(world, run.traces, run.results, run.end_ms))
    sys.stdout.flush()
    return max(r.status for r in run.results)
