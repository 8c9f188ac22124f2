"""Helpers of the runtime tests: build a C program with the runtime and the
host harness into a temporary directory, run it, read its JSON trace."""
import json
import os
import subprocess
from dataclasses import dataclass, field
from pathlib import Path

import pytest

from conftest import REPO, require_tool
from epuckc.base.resources import (LIBRARY_SIMULATION, RUNTIME_CORE, RUNTIME_DEVICES,
                                   RUNTIME_SIMULATED)

RUNTIME = REPO / "runtime_c"
PROGRAMS = Path(__file__).resolve().parent / "programs"
SOURCES = [*(RUNTIME / name for name in (*RUNTIME_CORE, *RUNTIME_SIMULATED, *RUNTIME_DEVICES)),
           RUNTIME / "platform" / "platform_host.c", RUNTIME / "host" / "scenario.c",
           *(RUNTIME / name for name in LIBRARY_SIMULATION)]
INCLUDES = [f"-I{RUNTIME}", f"-I{RUNTIME / 'epuck_api'}", f"-I{RUNTIME / 'host'}",
            f"-I{RUNTIME / 'epuck_api_unsimulated'}"]
STRICT = ["-std=c99", "-Wall", "-Wextra", "-Werror", "-pedantic"]
SANITIZE = ["-g", "-fsanitize=address,undefined", "-fno-sanitize-recover=all"]


@dataclass
class Run:
    returncode: int
    stdout: str
    stderr: str
    trace: list = field(default_factory=list)
    trace_bytes: bytes = b""

    def records(self, kind=None, name=None):
        return [r for r in self.trace
                if (kind is None or r["kind"] == kind) and (name is None or r["name"] == name)]

    def times(self, kind=None, name=None):
        return [r["t_ms"] for r in self.records(kind, name)]


def cc() -> str:
    return require_tool("cc")


# The registration path the programs are built for: "dynamic" (as written:
# register_action/register_event) or "static" (their registrations collected
# into tables for register_program by static_path.c).  Set per test by the
# `registration` fixture below.
REGISTRATION = "dynamic"
HERE = Path(__file__).resolve().parent


def _registration(request, param):
    global REGISTRATION
    REGISTRATION = param
    yield param
    REGISTRATION = "dynamic"


@pytest.fixture(params=["dynamic", "static"])
def registration(request):
    """Runs a test on both registration paths; a test module makes it
    autouse with `both_paths`."""
    yield from _registration(request, request.param)


@pytest.fixture(autouse=True, params=["dynamic", "static"])
def both_paths(request):
    yield from _registration(request, request.param)


def build(tmp_path: Path, program, defines=(), sanitize=False, extra_flags=(),
          name="prog") -> Path:
    """Compile a program (a path, or C source text) with the runtime sources
    (strict flags) into tmp_path, for the current REGISTRATION path; returns
    the executable."""
    compiler = cc()
    if isinstance(program, Path):
        src = program
    else:
        src = tmp_path / f"{name}.c"
        src.write_text(program)
    exe = tmp_path / name
    flags = [*STRICT, "-O1", *INCLUDES, *[f"-D{d}" for d in defines],
             *(SANITIZE if sanitize else []), *extra_flags]
    sources = [str(src)]
    if REGISTRATION == "static":
        obj = tmp_path / f"{name}.static.o"
        cmd = [compiler, *flags, "-include", str(HERE / "static_path.h"), "-c", str(src),
               "-o", str(obj)]
        res = subprocess.run(cmd, capture_output=True, text=True)
        assert res.returncode == 0, f"compile failed: {' '.join(cmd)}\n{res.stderr}"
        sources = [str(obj), str(HERE / "static_path.c")]
    cmd = [compiler, *flags, *sources, *map(str, SOURCES), "-o", str(exe), "-lm"]
    res = subprocess.run(cmd, capture_output=True, text=True)
    assert res.returncode == 0, f"compile failed: {' '.join(cmd)}\n{res.stderr}"
    return exe


def run(exe: Path, tmp_path: Path, scenario=None, time_limit=None, env=None,
        timeout=120) -> Run:
    trace = tmp_path / f"{exe.name}.trace.jsonl"
    if trace.exists():
        trace.unlink()
    environ = {k: v for k, v in os.environ.items() if not k.startswith("EPUCK_")}
    environ["EPUCK_TRACE"] = str(trace)
    if scenario is not None:
        if isinstance(scenario, str) and "\n" in scenario:
            path = tmp_path / f"{exe.name}.scn"
            path.write_text(scenario)
            scenario = path
        environ["EPUCK_SCENARIO"] = str(scenario)
    if time_limit is not None:
        environ["EPUCK_TIME_LIMIT_MS"] = str(time_limit)
    environ.update(env or {})
    res = subprocess.run([str(exe)], capture_output=True, text=True, env=environ,
                         timeout=timeout)
    data = trace.read_bytes() if trace.exists() else b""
    records = [json.loads(line) for line in data.decode().splitlines()]
    return Run(res.returncode, res.stdout, res.stderr, records, data)


def build_and_run(tmp_path, program, defines=(), scenario=None, time_limit=None,
                  env=None, sanitize=False):
    if isinstance(program, str) and program.endswith((".c",)) and "\n" not in program:
        program = PROGRAMS / program
        if scenario is None and program.with_suffix(".scn").exists():
            scenario = program.with_suffix(".scn")
    exe = build(tmp_path, program, defines=defines, sanitize=sanitize)
    return run(exe, tmp_path, scenario=scenario, time_limit=time_limit, env=env)
