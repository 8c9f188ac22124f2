"""Builds: the host harness executable, and the project for the e-puck.

Both start from one C program: generated from a rule file, or hand-written
against the runtime API (the paper's own way of working).
"""
from __future__ import annotations

import hashlib
import os
import shlex
import shutil
import subprocess
import sys
import tempfile
from dataclasses import dataclass, field
from pathlib import Path
from typing import Optional

from .resources import cache_dir, runtime_dir

HOST_CFLAGS = ["-std=c99", "-Wall", "-Wextra", "-pedantic", "-O2"]
# Generated C is warning-free by design, so a warning there is a bug in
# epuckc; hand-written C (the paper's figure 2 sets variables it never reads)
# gets its warnings shown instead.
GENERATED_CFLAGS = HOST_CFLAGS + ["-Werror"]
# The runtime's files for each target, relative to runtime_c/.
HOST_SOURCES = ["epuckrt.c", "host/platform_host.c", "host/epuck_stub.c"]
HOST_INCLUDES = [".", "epuck_api", "host"]
ROBOT_FILES = ["epuckrt.c", "platform_robot.c", "epuckrt.h", "rt_platform.h", "utility.h"]


EXIT_NO_TOOLCHAIN = 3      # the project is written but XC16, the library or make is missing


class BuildError(Exception):
    """A build step failed; the message says what and how to go on."""

    def __init__(self, message: str, status: int = 1):
        super().__init__(message)
        self.status = status


@dataclass
class Program:
    """A C program ready to build: its text, a name, and the user's files it
    includes (extern actions/events), relative to `base_dir`."""
    name: str
    c_text: str
    base_dir: Path
    user_files: list = field(default_factory=list)
    max_actions: Optional[int] = None
    max_events: Optional[int] = None
    generated: bool = True


def write_atomic(path: Path, data, mode: int = 0o644):
    """Write the whole file or nothing: a temporary file renamed into place."""
    path.parent.mkdir(parents=True, exist_ok=True)
    fd, tmp = tempfile.mkstemp(prefix=f".{path.name}.", dir=path.parent)
    try:
        with os.fdopen(fd, "wb") as f:
            f.write(data.encode("utf-8") if isinstance(data, str) else data)
        os.chmod(tmp, mode)
        os.replace(tmp, path)
    except BaseException:
        try:
            os.unlink(tmp)
        except OSError:
            pass
        raise


def c_compiler() -> list:
    return shlex.split(os.environ.get("CC") or "cc")


def _cflags(program: Program) -> list:
    return GENERATED_CFLAGS if program.generated else HOST_CFLAGS


def _capacity_defines(program: Program) -> list:
    defines = []
    if program.max_actions:
        defines.append(f"-DMAX_ACTIONS={program.max_actions}")
    if program.max_events:
        defines.append(f"-DMAX_EVENTS={program.max_events}")
    return defines


# ---- host ---------------------------------------------------------------------

def host_build_key(program: Program) -> str:
    """Everything the executable depends on: the program, the user's C, the
    runtime's sources, the compiler and the flags."""
    h = hashlib.sha256()
    rt = runtime_dir()

    def add(label: str, data: bytes):
        h.update(label.encode() + b"\0" + len(data).to_bytes(8, "big") + data)

    add("program", program.c_text.encode("utf-8"))
    for rel in program.user_files:
        add(f"user:{rel}", (program.base_dir / rel).read_bytes())
    for path in sorted(rt.rglob("*")):
        if path.is_file() and path.suffix in (".c", ".h") and "build" not in path.relative_to(rt).parts:
            add(f"rt:{path.relative_to(rt).as_posix()}", path.read_bytes())
    add("cc", " ".join(c_compiler() + _cflags(program) + _capacity_defines(program)).encode())
    return h.hexdigest()[:24]


def host_compile_command(c_file: Path, output: Path, program: Program) -> list:
    rt = runtime_dir()
    return (c_compiler() + _cflags(program) + _capacity_defines(program)
            + [f"-I{rt / inc}" for inc in HOST_INCLUDES]
            + [f"-I{program.base_dir}", str(c_file)]
            + [str(rt / src) for src in HOST_SOURCES]
            + ["-o", str(output), "-lm"])


def _run_compiler(command: list, what: str):
    try:
        result = subprocess.run(command, capture_output=True, text=True)
    except FileNotFoundError:
        raise BuildError(f"the C compiler `{command[0]}` was not found; install one "
                         f"(e.g. `apt-get install gcc`) or set CC") from None
    if result.stderr and result.returncode == 0:
        sys.stderr.write(result.stderr)      # warnings in hand-written C
    if result.returncode != 0:
        output = (result.stdout + result.stderr).rstrip()
        raise BuildError(f"the C compiler failed to build {what}:\n{output}\n"
                         f"command: {shlex.join(command)}")


def build_host(program: Program, out_dir: Optional[Path] = None) -> Path:
    """The harness executable. Cached by content hash: a second build of the
    same program is a file lookup. With out_dir, the C file and executable
    are also copied there."""
    key = host_build_key(program)
    cached_dir = cache_dir() / "host" / key
    exe = cached_dir / program.name
    if not exe.is_file():
        cached_dir.mkdir(parents=True, exist_ok=True)
        with tempfile.TemporaryDirectory(dir=cached_dir) as tmp:
            c_file = Path(tmp) / f"{program.name}.c"
            c_file.write_text(program.c_text, encoding="utf-8")
            tmp_exe = Path(tmp) / program.name
            _run_compiler(host_compile_command(c_file, tmp_exe, program), program.name)
            shutil.copy2(c_file, cached_dir / c_file.name)
            os.replace(tmp_exe, exe)
    if out_dir is not None:
        write_atomic(out_dir / f"{program.name}.c", program.c_text)
        write_atomic(out_dir / program.name, exe.read_bytes(), mode=0o755)
        return out_dir / program.name
    return exe


# ---- dsPIC --------------------------------------------------------------------

def find_xc16() -> Optional[Path]:
    xc16_dir = os.environ.get("XC16_DIR")
    if xc16_dir:
        candidate = Path(xc16_dir) / "bin" / "xc16-gcc"
        if candidate.is_file() and os.access(candidate, os.X_OK):
            return candidate
    found = shutil.which("xc16-gcc")
    return Path(found) if found else None


def write_dspic_project(program: Program, out_dir: Path, template_render) -> None:
    """A self-contained project: the program, the runtime files the robot
    needs, the user's C, and a Makefile for XC16."""
    rt = runtime_dir()
    write_atomic(out_dir / f"{program.name}.c", program.c_text)
    for rel in ROBOT_FILES:
        write_atomic(out_dir / rel, (rt / rel).read_bytes())
    for rel in program.user_files:
        write_atomic(out_dir / rel, (program.base_dir / rel).read_bytes())
    sources = [f"{program.name}.c", "epuckrt.c", "platform_robot.c"]
    defines = [d[2:] for d in _capacity_defines(program)]
    write_atomic(out_dir / "Makefile", template_render("dspic.mk.j2", name=program.name,
                                                       sources=sources, defines=defines))


def run_make(out_dir: Path, xc16: Path) -> None:
    env = dict(os.environ)
    env["PATH"] = f"{xc16.parent}{os.pathsep}{env.get('PATH', '')}"
    make = shutil.which("make")
    if make is None:
        raise BuildError(f"`make` was not found; the project is in {out_dir}",
                         status=EXIT_NO_TOOLCHAIN)
    result = subprocess.run([make, "-C", str(out_dir), f"XC16_BIN={xc16.parent}"],
                            capture_output=True, text=True, env=env)
    if result.returncode != 0:
        raise BuildError(f"make failed in {out_dir}:\n{(result.stdout + result.stderr).rstrip()}")
