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

from .output import TEMP_PREFIX, OutputError, describe_os_error, prepare_directory, write_file
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
    """Write the whole file or nothing (see output.py, which every write uses)."""
    write_file(path, data, mode)


def c_compiler() -> list:
    return shlex.split(os.environ.get("CC") or "cc")


def _cflags(program: Program) -> list:
    return GENERATED_CFLAGS if program.generated else HOST_CFLAGS


def _capacity_defines(program: Program) -> list:
    """The dynamic arrays' capacities.  A rule file's rules are tables: with
    no user C nothing can register, so the arrays shrink to one entry each
    (the least the runtime takes) unless asked; otherwise the runtime's
    defaults or the options."""
    max_actions, max_events = program.max_actions, program.max_events
    if program.generated and not program.user_files:
        max_actions, max_events = max_actions or 1, max_events or 1
    defines = []
    if max_actions:
        defines.append(f"-DMAX_ACTIONS={max_actions}")
    if max_events:
        defines.append(f"-DMAX_EVENTS={max_events}")
    return defines


# ---- host ---------------------------------------------------------------------

def host_build_key(program: Program) -> str:
    """Everything the executable depends on: the program, the user's C, the
    runtime's sources, the compiler and the flags."""
    h = hashlib.sha256()
    rt = runtime_dir()

    def add(label: str, data: bytes):
        h.update(label.encode() + b"\0" + len(data).to_bytes(8, "big") + data)

    add("name", program.name.encode("utf-8"))
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


STALE_AFTER_S = 24 * 3600      # a temporary build folder older than this is abandoned


def _pid_alive(pid: int) -> bool:
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except (PermissionError, OverflowError):
        return True
    except OSError:
        return False
    return True


def sweep_stale(folder: Path) -> None:
    """Remove the temporary folders and files that killed runs left in
    `folder`: those whose process is gone, or older than a day."""
    import time
    try:
        entries = list(os.scandir(folder))
    except OSError:
        return
    now = time.time()
    for entry in entries:
        if not entry.name.startswith(TEMP_PREFIX):
            continue
        pid_text = entry.name[len(TEMP_PREFIX):].split("-", 1)[0]
        try:
            alive = _pid_alive(int(pid_text)) if pid_text.isdigit() else False
            old = now - entry.stat(follow_symlinks=False).st_mtime > STALE_AFTER_S
        except OSError:
            continue
        if alive and not old:
            continue
        try:
            if entry.is_dir(follow_symlinks=False):
                shutil.rmtree(entry.path, ignore_errors=True)
            else:
                os.unlink(entry.path)
        except OSError:
            pass


def _compile_into(folder: Path, program: Program) -> Path:
    """Write the C file into `folder` and compile the executable there."""
    c_file = folder / f"{program.name}.c"
    write_file(c_file, program.c_text)
    exe = folder / program.name
    _run_compiler(host_compile_command(c_file, exe, program), program.name)
    return exe


def _cached_build(program: Program) -> Path:
    """The executable in the cache, built there when missing. Raises
    OSError/OutputError when the cache cannot be used."""
    host = cache_dir() / "host"
    final = host / host_build_key(program)
    exe = final / program.name
    if exe.is_file():
        return exe
    host.mkdir(parents=True, exist_ok=True)
    sweep_stale(host)
    # Built in a folder of its own, then renamed into place in one step: a
    # killed build leaves only a temporary folder, swept by a later run.
    tmp = Path(tempfile.mkdtemp(prefix=f"{TEMP_PREFIX}{os.getpid()}-", dir=host))
    try:
        _compile_into(tmp, program)
        try:
            os.rename(tmp, final)
        except OSError:
            if not exe.is_file():           # neither a parallel build's result
                shutil.rmtree(final, ignore_errors=True)
                os.rename(tmp, final)
    finally:
        if tmp.exists():
            shutil.rmtree(tmp, ignore_errors=True)
    return exe


class host_executable:
    """`with host_executable(program) as exe:` the harness executable, from
    the cache; when the cache cannot be used (missing permissions, a
    read-only or full disk, EPUCKC_CACHE_DIR somewhere impossible), built in
    a temporary folder that is removed afterwards, with one line saying so."""

    def __init__(self, program: Program):
        self.program = program
        self._tmp = None

    def __enter__(self) -> Path:
        try:
            return _cached_build(self.program)
        except (OSError, OutputError) as exc:
            reason = str(exc) if isinstance(exc, OutputError) else \
                describe_os_error(exc, exc.filename or cache_dir(), "use")
        print(f"epuckc: note: building in a temporary folder, the cache is unusable ({reason}); "
              "set EPUCKC_CACHE_DIR to a writable folder", file=sys.stderr)
        system_tmp = tempfile.gettempdir()
        sweep_stale(Path(system_tmp))
        try:
            self._tmp = Path(tempfile.mkdtemp(prefix=f"{TEMP_PREFIX}{os.getpid()}-"))
        except OSError as exc:
            raise BuildError(describe_os_error(exc, system_tmp,
                                               "create a temporary folder in")) from None
        try:
            return _compile_into(self._tmp, self.program)
        except OutputError as exc:
            raise BuildError(str(exc)) from None

    def __exit__(self, *exc_info):
        if self._tmp is not None:
            shutil.rmtree(self._tmp, ignore_errors=True)
        return False


def build_host(program: Program, out_dir: Path) -> Path:
    """The harness executable and its C file, in `out_dir`."""
    out_dir = prepare_directory(out_dir)
    with host_executable(program) as exe:
        data = exe.read_bytes()
    write_file(out_dir / f"{program.name}.c", program.c_text)
    write_file(out_dir / program.name, data, mode=0o755)
    return out_dir / program.name


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
    out_dir = prepare_directory(out_dir)
    write_atomic(out_dir / f"{program.name}.c", program.c_text)
    for rel in ROBOT_FILES:
        write_atomic(out_dir / rel, (rt / rel).read_bytes())
    for rel in program.user_files:
        write_atomic(out_dir / rel, (program.base_dir / rel).read_bytes())
    sources = [f"{program.name}.c", "epuckrt.c", "platform_robot.c"]
    # the robot has no trace: the name labels are not even stored
    defines = [d[2:] for d in _capacity_defines(program)] + ["EPUCKRT_NO_NAMES"]
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
