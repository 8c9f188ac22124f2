"""Builds: the host harness executable, and the project for the e-puck.

Both start from one C program: generated from a rule file, or hand-written
against the runtime API (the paper's own way of working).
"""
from __future__ import annotations

import hashlib
import os
import re
import shlex
import shutil
import stat
import subprocess
import sys
import tempfile
from dataclasses import dataclass, field
from pathlib import Path
from typing import Optional

from .output import (TEMP_PREFIX, OutputError, describe_os_error, is_stdout, prepare_directory,
                     write_file)
from .resources import cache_dir, runtime_dir

HOST_CFLAGS = ["-std=c99", "-Wall", "-Wextra", "-pedantic", "-O2"]
# The -Werror policy, the same on the host and the robot: the C epuckc
# writes (the generated program, and on the host the runtime) is
# warning-free by design, so a warning there is a bug in epuckc and fails the
# build; the user's own C (extern files, a hand-written program: the paper's
# figure 2 sets variables it never reads) gets its warnings shown, not fatal.
GENERATED_CFLAGS = HOST_CFLAGS + ["-Werror"]
USER_CFLAGS = HOST_CFLAGS
# The runtime's files for each target, relative to runtime_c/.
HOST_SOURCES = ["epuckrt.c", "host/platform_host.c", "host/epuck_stub.c"]
HOST_INCLUDES = [".", "epuck_api", "host"]
ROBOT_SOURCES = ["epuckrt.c", "platform_robot.c"]
ROBOT_HEADERS = ["epuckrt.h", "rt_platform.h", "utility.h"]
ROBOT_FILES = ROBOT_SOURCES + ROBOT_HEADERS
# Folders of the dspic project: the runtime's copies and the user's.
DSPIC_RUNTIME = "runtime"
DSPIC_USER = "user"


EXIT_USAGE = 2             # bad request: e.g. an output that is one of the inputs
EXIT_NO_TOOLCHAIN = 3      # the project is written but XC16, the library or make is missing


class BuildError(Exception):
    """A build step failed; the message says what and how to go on."""

    def __init__(self, message: str, status: int = 1):
        super().__init__(message)
        self.status = status


@dataclass
class Program:
    """A C program ready to build.

    Generated from a rule file: `c_text`, the externs header
    (`header_name`, `header_text`) when there are externs, and the user's C
    files that define them (`user_files`, paths as the user's rule file
    names them, joined to its folder: gcc's messages then name the user's
    own file). Hand-written: `source_path` is compiled where it is.
    `inputs` are every file the command reads: nothing is written over them.
    """
    name: str
    c_text: str
    base_dir: Path
    user_files: list = field(default_factory=list)
    max_actions: Optional[int] = None
    max_events: Optional[int] = None
    generated: bool = True
    header_name: Optional[str] = None
    header_text: Optional[str] = None
    source_path: Optional[Path] = None
    inputs: list = field(default_factory=list)

    def user_sources(self) -> list:
        """The C files of the user's that are compiled on their own."""
        return [self.source_path] if self.source_path is not None else list(self.user_files)


def write_atomic(path: Path, data, mode: int = 0o644, only_if_changed: bool = False):
    """Write the whole file or nothing (see output.py, which every write
    uses). With only_if_changed, an identical file is left alone (its time
    stamp too, so that make rebuilds nothing)."""
    if only_if_changed and not is_stdout(path):
        payload = data.encode("utf-8") if isinstance(data, str) else data
        try:
            if Path(path).is_file() and Path(path).read_bytes() == payload:
                return
        except OSError:
            pass
    write_file(path, data, mode)


def _same_file(a: Path, b: Path) -> bool:
    try:
        if os.path.samefile(a, b):
            return True
    except OSError:
        pass
    return os.path.realpath(a) == os.path.realpath(b)


def check_outputs(outputs, inputs, inside: Optional[Path] = None):
    """Refuse, before anything is written, to write over one of the
    command's inputs, or (with `inside`) anywhere outside that folder, e.g.
    through a link."""
    for out in outputs:
        for given in inputs:
            if _same_file(out, given):
                raise BuildError(f"refusing to write {out}: it is {given}, one of the files "
                                 f"this command reads; choose another output with -o",
                                 status=EXIT_USAGE)
        if inside is not None:
            root = os.path.realpath(inside)
            real = os.path.realpath(out)
            if os.path.commonpath([root, real]) != root:
                raise BuildError(f"refusing to write {out}: it leads outside {inside} "
                                 f"(to {real})", status=EXIT_USAGE)


def c_compiler() -> list:
    return shlex.split(os.environ.get("CC") or "cc")


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
    """Everything the executable depends on: the program, its header, the
    user's C, the runtime's sources, the compiler and the flags."""
    h = hashlib.sha256()
    rt = runtime_dir()

    def add(label: str, data: bytes):
        h.update(label.encode() + b"\0" + len(data).to_bytes(8, "big") + data)

    add("name", program.name.encode("utf-8"))
    add("program", program.c_text.encode("utf-8") if program.generated else b"")
    add("header", (program.header_text or "").encode("utf-8"))
    for path in program.user_sources():
        add(f"user:{os.path.realpath(path)}", Path(path).read_bytes())
    for path in sorted(rt.rglob("*")):
        if path.is_file() and path.suffix in (".c", ".h") and "build" not in path.relative_to(rt).parts:
            add(f"rt:{path.relative_to(rt).as_posix()}", path.read_bytes())
    add("cc", " ".join(c_compiler() + GENERATED_CFLAGS + USER_CFLAGS
                       + _capacity_defines(program)).encode())
    return h.hexdigest()[:24]


def _includes(program: Program, generated_dir: Path) -> list:
    rt = runtime_dir()
    return [f"-I{generated_dir}"] + [f"-I{rt / inc}" for inc in HOST_INCLUDES]


def user_compile_command(source: Path, obj: Path, program: Program, generated_dir: Path,
                         extra_flags=()) -> list:
    """The user's own C, compiled where it is (its messages name it; its own
    #includes are found beside it), warnings shown but not fatal."""
    return (c_compiler() + USER_CFLAGS + list(extra_flags) + _capacity_defines(program)
            + _includes(program, generated_dir) + ["-x", "c", "-c", str(source), "-o", str(obj)])


def host_link_command(generated_dir: Path, objects: list, output: Path, program: Program) -> list:
    """The generated program and the runtime with -Werror, then the user's
    objects."""
    rt = runtime_dir()
    program_c = [str(generated_dir / f"{program.name}.c")] if program.generated else []
    return (c_compiler() + GENERATED_CFLAGS + _capacity_defines(program)
            + _includes(program, generated_dir) + program_c
            + [str(rt / src) for src in HOST_SOURCES]
            + [str(o) for o in objects] + ["-o", str(output), "-lm"])


def _run_compiler(command: list, what: str, hint: str = ""):
    try:
        result = subprocess.run(command, capture_output=True, text=True)
    except FileNotFoundError:
        raise BuildError(f"the C compiler `{command[0]}` was not found; install one "
                         f"(e.g. `apt-get install gcc`) or set CC") from None
    if result.stderr and result.returncode == 0:
        sys.stderr.write(result.stderr)      # warnings in the user's C
    if result.returncode != 0:
        output = (result.stdout + result.stderr).rstrip()
        raise BuildError(f"the C compiler failed to build {what}:\n{output}\n"
                         f"command: {shlex.join(command)}{hint}")


def _include_hint(program: Program, source: Path) -> str:
    """A user's extern file that does not include the externs header does
    not know the parameter structs: say so when it fails to compile."""
    if not program.header_name:
        return ""
    try:
        if program.header_name in Path(source).read_text(encoding="utf-8", errors="replace"):
            return ""
    except OSError:
        return ""
    return (f"\nhint: {source} does not include \"{program.header_name}\", the header epuckc "
            f"writes with the parameter structs and prototypes of the externs; add\n"
            f"    #include \"{program.header_name}\"")


def _write_generated(program: Program, folder: Path, only_if_changed: bool = False):
    write_atomic(folder / f"{program.name}.c", program.c_text, only_if_changed=only_if_changed)
    if program.header_name:
        write_atomic(folder / program.header_name, program.header_text,
                     only_if_changed=only_if_changed)


def prepare_sources(program: Program, folder: Path, extra_flags=()) -> list:
    """Write the generated program and its externs header into `folder`
    and compile the user's own C there, each file on its own (with
    `extra_flags`, e.g. -fPIC); returns the user's objects, to be linked
    with the program and the runtime."""
    if program.generated:
        _write_generated(program, folder)
    objects = []
    for i, source in enumerate(program.user_sources(), 1):
        obj = folder / f"user{i}.o"
        command = user_compile_command(source, obj, program, folder, extra_flags)
        _run_compiler(command, str(source), _include_hint(program, source))
        objects.append(obj)
    return objects


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
    """Write the generated C into `folder`, compile the user's C there on
    its own, and link the executable there."""
    objects = prepare_sources(program, folder)
    exe = folder / program.name
    _run_compiler(host_link_command(folder, objects, exe, program), program.name)
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
    """The harness executable in `out_dir`, with the generated C (program
    and externs header) it was built from; never over one of the inputs."""
    outputs = [out_dir / program.name]
    if program.generated:
        outputs.append(out_dir / f"{program.name}.c")
        if program.header_name:
            outputs.append(out_dir / program.header_name)
    check_outputs(outputs, program.inputs)
    out_dir = prepare_directory(out_dir)
    with host_executable(program) as exe:
        data = exe.read_bytes()
    if program.generated:
        _write_generated(program, out_dir)
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


def dspic_user_copies(program: Program) -> list:
    """(the user's file, its copy's path inside the project): numbered in
    the `user/` folder, so no two copies and nothing else share a name."""
    copies = []
    for i, source in enumerate(program.user_sources(), 1):
        stem = re.sub(r"[^A-Za-z0-9_-]", "_", Path(source).stem) or "file"
        copies.append((Path(source), f"{DSPIC_USER}/{i}_{stem}.c"))
    return copies


def write_dspic_project(program: Program, out_dir: Path, template_render) -> None:
    """A self-contained project inside out_dir: the program (and its
    externs header) at the top, the runtime files the robot needs in
    runtime/, copies of the user's C in user/, and a Makefile for XC16.
    Files whose contents did not change are not rewritten, so `make`
    rebuilds only what changed."""
    rt = runtime_dir()
    copies = dspic_user_copies(program)
    generated = [f"{program.name}.c"] if program.generated else []
    if program.generated and program.header_name:
        generated.append(program.header_name)
    runtime_files = [f"{DSPIC_RUNTIME}/{rel}" for rel in ROBOT_FILES]
    targets = generated + runtime_files + [copy for _, copy in copies] + ["Makefile"]
    check_outputs([out_dir / t for t in targets], program.inputs, inside=out_dir)
    out_dir = prepare_directory(out_dir)
    if program.generated:
        _write_generated(program, out_dir, only_if_changed=True)
    for rel in ROBOT_FILES:
        write_atomic(out_dir / DSPIC_RUNTIME / rel, (rt / rel).read_bytes(), only_if_changed=True)
    for source, copy in copies:
        write_atomic(out_dir / copy, source.read_bytes(),
                     mode=stat.S_IMODE(source.stat().st_mode), only_if_changed=True)
    # the robot has no trace: the name labels are not even stored
    defines = [d[2:] for d in _capacity_defines(program)] + ["EPUCKRT_NO_NAMES"]
    write_atomic(out_dir / "Makefile", template_render(
        "dspic.mk.j2", name=program.name, generated=program.generated,
        header=program.header_name if program.generated else None,
        runtime=DSPIC_RUNTIME, runtime_sources=[f"{DSPIC_RUNTIME}/{r}" for r in ROBOT_SOURCES],
        runtime_headers=[f"{DSPIC_RUNTIME}/{r}" for r in ROBOT_HEADERS],
        user_sources=[copy for _, copy in copies], defines=defines), only_if_changed=True)


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
