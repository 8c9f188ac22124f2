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

# -O1 as on the robot (the dspic Makefile; XC16's free edition stops there)
# and in the sanitizer builds of the tests: the harness runs no slower than
# at -O2 (virtual time, a poll a millisecond), and gcc takes 40% less time.
HOST_CFLAGS = ["-std=c99", "-Wall", "-Wextra", "-pedantic", "-O1"]
# The -Werror policy, the same on the host and the robot: the C epuckc
# writes (the generated program, and on the host the runtime) is
# warning-free by design, so a warning there is a bug in epuckc and fails the
# build; the user's own C (extern files, a hand-written program: the paper's
# figure 2 sets variables it never reads) gets its warnings shown, not fatal.
GENERATED_CFLAGS = HOST_CFLAGS + ["-Werror"]
USER_CFLAGS = HOST_CFLAGS
# How gcc runs, not what it makes: no temporary assembly files.
BUILD_FLAGS = ["-pipe"]
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

def _compiler_identity() -> str:
    """The C compiler as a command and as a file: the same name for another
    compiler (an upgrade, a new alternative) changes the keys."""
    command = c_compiler()
    found = shutil.which(command[0]) if command else None
    if found is None:
        return " ".join(command) + " (not found)"      # the build says so
    real = os.path.realpath(found)
    try:
        st = os.stat(real)
    except OSError:
        return " ".join(command) + " (unreadable)"
    return f"{' '.join(command)} = {real} {st.st_size} {st.st_mtime_ns}"


def _add(h, label: str, data: bytes):
    h.update(label.encode() + b"\0" + len(data).to_bytes(8, "big") + data)


def _add_runtime_sources(h) -> None:
    """Every C source and header of the runtime (what any of its files may
    include), by its path inside runtime_c/."""
    rt = runtime_dir()
    for path in sorted(rt.rglob("*")):
        if path.is_file() and path.suffix in (".c", ".h") and "build" not in path.relative_to(rt).parts:
            _add(h, f"rt:{path.relative_to(rt).as_posix()}", path.read_bytes())


def host_build_key(program: Program) -> str:
    """Everything the executable depends on: the program, its header, the
    user's C, the runtime's sources, the compiler and the flags."""
    h = hashlib.sha256()
    _add(h, "name", program.name.encode("utf-8"))
    _add(h, "program", program.c_text.encode("utf-8") if program.generated else b"")
    _add(h, "header", (program.header_text or "").encode("utf-8"))
    for path in program.user_sources():
        _add(h, f"user:{os.path.realpath(path)}", Path(path).read_bytes())
    for _, header, _ in user_headers(program):
        _add(h, f"user header:{os.path.realpath(header)}", header.read_bytes())
    _add_runtime_sources(h)
    _add(h, "cc", " ".join(c_compiler() + GENERATED_CFLAGS + USER_CFLAGS
                           + _capacity_defines(program)).encode())
    _add(h, "compiler", _compiler_identity().encode())
    return h.hexdigest()[:24]


def _includes(program: Program, generated_dir: Path) -> list:
    rt = runtime_dir()
    return [f"-I{generated_dir}"] + [f"-I{rt / inc}" for inc in HOST_INCLUDES]


def user_compile_command(source: Path, obj: Path, program: Program, generated_dir: Path,
                         extra_flags=()) -> list:
    """The user's own C, compiled where it is (its messages name it; its own
    #includes are found beside it), warnings shown but not fatal."""
    return (c_compiler() + USER_CFLAGS + list(extra_flags) + _capacity_defines(program)
            + _includes(program, generated_dir)
            + BUILD_FLAGS + ["-x", "c", "-c", str(source), "-o", str(obj)])


def program_compile_command(folder: Path, obj: Path, program: Program, extra_flags=()) -> list:
    """The generated program, with -Werror."""
    return (c_compiler() + GENERATED_CFLAGS + list(extra_flags) + _capacity_defines(program)
            + _includes(program, folder)
            + BUILD_FLAGS + ["-c", str(folder / f"{program.name}.c"), "-o", str(obj)])


def runtime_flags(program: Program, includes=HOST_INCLUDES, extra_flags=()) -> list:
    """The runtime's own flags: -Werror, the capacities, its own folders
    (nothing of the program's: its objects serve every program with the
    same capacities)."""
    rt = runtime_dir()
    return (GENERATED_CFLAGS + list(extra_flags) + _capacity_defines(program)
            + [f"-I{rt / inc}" for inc in includes])


def host_link_command(objects: list, output: Path) -> list:
    return c_compiler() + [str(o) for o in objects] + ["-o", str(output), "-lm"]


def _compiler_missing(command: list) -> BuildError:
    return BuildError(f"the C compiler `{command[0]}` was not found; install one "
                      f"(e.g. `apt-get install gcc`) or set CC")


def _run_compiler(command: list, what: str, hint: str = ""):
    try:
        result = subprocess.run(command, capture_output=True, text=True)
    except FileNotFoundError:
        raise _compiler_missing(command) from None
    if result.stderr and result.returncode == 0:
        sys.stderr.write(result.stderr)      # warnings in the user's C
    if result.returncode != 0:
        output = (result.stdout + result.stderr).rstrip()
        raise BuildError(f"the C compiler failed to build {what}:\n{output}\n"
                         f"command: {shlex.join(command)}{hint}")


@dataclass
class CompileStep:
    """One translation unit: its compiler command, what to call it in a
    message, a hint for when it fails, and its source's size (the biggest
    start first, so that the longest compile does not start last)."""
    command: list
    what: str
    hint: str = ""
    size: int = 0


def compile_jobs() -> int:
    """How many compilers run at once: the processors this process may use."""
    try:
        return max(1, len(os.sched_getaffinity(0)))
    except (AttributeError, OSError):
        return max(1, os.cpu_count() or 1)


class _Job:
    """One step given to a pool: its result is (status, stdout, stderr), or
    the OSError that kept the compiler from starting; None if cancelled."""

    def __init__(self, step: CompileStep, done):
        self.step = step
        self.done = done                # a threading.Event
        self.result = None
        self.proc = None
        self.cancelled = False


class CompilerPool:
    """Runs compile steps on `jobs` worker threads, the biggest waiting step
    first; a job can be waited for or cancelled (which kills its compiler).
    The workers are daemon threads, idle when there is nothing to do."""

    def __init__(self, jobs: int):
        import threading
        self._event = threading.Event
        self._cond = threading.Condition()
        self._waiting = []              # a heap of (-size, order, job)
        self._order = 0
        for _ in range(jobs):
            threading.Thread(target=self._work, daemon=True).start()

    def submit(self, step: CompileStep) -> _Job:
        import heapq
        job = _Job(step, self._event())
        with self._cond:
            self._order += 1
            heapq.heappush(self._waiting, (-step.size, self._order, job))
            self._cond.notify()
        return job

    def cancel(self, job: _Job) -> None:
        """A job not started never starts; a running one is killed with the
        processes it started (gcc's cc1 and as: its process group)."""
        import signal
        with self._cond:
            job.cancelled = True
            if job.proc is not None and job.proc.poll() is None:
                try:
                    os.killpg(job.proc.pid, signal.SIGKILL)
                except OSError:
                    job.proc.kill()

    def _work(self):
        import heapq
        while True:
            with self._cond:
                while not self._waiting:
                    self._cond.wait()
                job = heapq.heappop(self._waiting)[2]
                if job.cancelled:
                    job.done.set()
                    continue
                try:
                    # a process group of its own, so that cancel stops all of it
                    job.proc = subprocess.Popen(job.step.command, stdin=subprocess.DEVNULL,
                                                stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                                                text=True, errors="replace",
                                                start_new_session=True)
                except OSError as exc:
                    job.result = exc
                    job.done.set()
                    continue
            try:
                out, err = job.proc.communicate()
                job.result = (job.proc.returncode, out, err)
            except Exception as exc:        # reported to whoever waits for it
                job.result = OSError(str(exc))
            job.done.set()


_POOL = None


def compiler_pool() -> CompilerPool:
    """The process's pool: as many compilers at once as it has processors."""
    global _POOL
    if _POOL is None:
        _POOL = CompilerPool(compile_jobs())
    return _POOL


def wait_jobs(jobs: list, pool: CompilerPool) -> list:
    """The jobs' results, once all are done. An interruption (Ctrl-C,
    SIGTERM) cancels them all, killing the compilers still running,
    before it goes on."""
    try:
        for job in jobs:
            job.done.wait()
    except BaseException:
        cancel_jobs(jobs, pool)
        raise
    return [job.result for job in jobs]


def cancel_jobs(jobs: list, pool: CompilerPool) -> None:
    """Cancel the jobs and wait until none of their compilers runs."""
    for job in jobs:
        pool.cancel(job)
    for job in jobs:
        if job.proc is not None:
            try:
                job.proc.wait(10)
            except subprocess.TimeoutExpired:
                pass


def report_results(steps: list, results: list) -> None:
    """In the steps' order, the warnings of those that succeeded are shown
    and the first that failed raises BuildError: the same message
    whichever compiler finished first."""
    for step, result in zip(steps, results):
        if isinstance(result, FileNotFoundError):
            raise _compiler_missing(step.command)
        if isinstance(result, OSError):
            raise BuildError(f"cannot run the C compiler `{step.command[0]}`: "
                             f"{result.strerror or result}")
        if result is None:
            raise BuildError(f"the C compiler was stopped before it built {step.what}")
        status, out, err = result
        if status == 0:
            if err:
                sys.stderr.write(err)        # warnings in the user's C
            continue
        output = (out + err).rstrip()
        raise BuildError(f"the C compiler failed to build {step.what}:\n{output}\n"
                         f"command: {shlex.join(step.command)}{step.hint}")


def run_compile_steps(steps: list, jobs: Optional[int] = None) -> None:
    """Run the steps, each to its end, on the process's pool (or on a pool
    of `jobs` workers); then report_results."""
    pool = CompilerPool(jobs) if jobs else compiler_pool()
    report_results(steps, wait_jobs([pool.submit(step) for step in steps], pool))


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


def _size(path) -> int:
    try:
        return os.stat(path).st_size
    except OSError:
        return 0


def program_steps(program: Program, folder: Path, extra_flags=()) -> tuple:
    """Write the generated program and its externs header into `folder`;
    (the steps that compile the user's own C, each file on its own, and the
    program, into `folder`, with `extra_flags`, e.g. -fPIC; their objects)."""
    stale = stale_externs_header(program)
    if stale is not None:
        raise BuildError(stale)
    steps, objects = [], []
    for i, source in enumerate(program.user_sources(), 1):
        obj = folder / f"user{i}.o"
        steps.append(CompileStep(user_compile_command(source, obj, program, folder, extra_flags),
                                 str(source), _include_hint(program, source), _size(source)))
        objects.append(obj)
    if program.generated:
        _write_generated(program, folder)
        obj = folder / f"{program.name}.o"
        steps.append(CompileStep(program_compile_command(folder, obj, program, extra_flags),
                                 program.name, "", len(program.c_text)))
        objects.append(obj)
    return steps, objects


def runtime_objects_key(sources: list, flags: list) -> str:
    """Everything the runtime's objects depend on: every runtime source and
    header, which sources, the compiler (as a command and as a file) and
    the flags."""
    h = hashlib.sha256()
    _add(h, "sources", "\n".join(sources).encode())
    _add(h, "flags", "\n".join(c_compiler() + flags + BUILD_FLAGS).encode())
    _add(h, "compiler", _compiler_identity().encode())
    _add_runtime_sources(h)
    return h.hexdigest()[:24]


class RuntimeObjects:
    """The runtime's objects for one set of sources and flags.

    With a cache folder they are kept there under runtime_objects_key: a
    later build with the same runtime and capacities links them without
    compiling. Missing, they are compiled (`start`, on the process's pool)
    into a temporary folder beside their place, which `commit` renames into
    it in one step once every compiler succeeded; `discard` stops the
    compilers and removes it. Without a cache folder they are compiled into
    `folder` and not kept.
    """

    def __init__(self, sources: list, flags: list, folder: Optional[Path],
                 cache: Optional[Path]):
        rt = runtime_dir()
        names = [src.replace("/", "_")[:-len(".c")] + ".o" for src in sources]
        self._tmp = None
        self._jobs = None
        self._pool = None
        self.final = None
        if cache is not None:
            self.final = cache / runtime_objects_key(sources, flags)
            self.objects = [self.final / n for n in names]
            if all(o.is_file() for o in self.objects):
                self.steps = []
                return
            cache.mkdir(parents=True, exist_ok=True)
            sweep_stale(cache)
            self._tmp = Path(tempfile.mkdtemp(prefix=f"{TEMP_PREFIX}{os.getpid()}-", dir=cache))
            folder = self._tmp
        built = [folder / n for n in names]
        self.steps = [CompileStep(c_compiler() + flags + BUILD_FLAGS
                                  + ["-c", str(rt / src), "-o", str(obj)],
                                  f"the runtime ({src})", "", _size(rt / src))
                      for src, obj in zip(sources, built)]
        if self._tmp is None:
            self.objects = built

    def start(self) -> None:
        """The compilers start (once), in the background."""
        if self._jobs is None:
            self._pool = compiler_pool()
            self._jobs = [self._pool.submit(step) for step in self.steps]

    def wait(self) -> list:
        self.start()
        return wait_jobs(self._jobs, self._pool)

    def commit(self) -> None:
        """Every step succeeded: the objects take their place in the cache
        (or a parallel build's, identical, stay there)."""
        if self._tmp is None:
            return
        try:
            os.rename(self._tmp, self.final)
        except OSError:
            if not all(o.is_file() for o in self.objects):     # nor a parallel build's
                shutil.rmtree(self.final, ignore_errors=True)
                os.rename(self._tmp, self.final)
        finally:
            self.discard()

    def discard(self) -> None:
        """Stop the compilers still running; remove the temporary folder."""
        if self._jobs is not None:
            cancel_jobs(self._jobs, self._pool)
        if self._tmp is not None:
            shutil.rmtree(self._tmp, ignore_errors=True)
            self._tmp = None


# Runtime objects whose compilers were started before the program was known
# (start_host_runtime), by their place in the cache.
_STARTED = {}


def start_host_runtime(generated: bool, max_actions: Optional[int],
                       max_events: Optional[int]) -> None:
    """Start compiling the host runtime in the background for a program
    without user C (a rule file with no `extern`, or hand-written C), while
    the front end checks and lowers it; the build that follows takes these
    objects when its flags are the same. A cache that cannot be used, or
    objects already there, start nothing; stop_started_runtime ends what
    no build took."""
    guess = Program("", "", Path("."), [], max_actions, max_events, generated=generated)
    try:
        runtime = RuntimeObjects(HOST_SOURCES, runtime_flags(guess), None, runtime_cache_dir())
    except (OSError, OutputError):
        return
    if runtime.steps and runtime.final not in _STARTED:
        runtime.start()
        _STARTED[runtime.final] = runtime
    else:
        runtime.discard()


def stop_started_runtime() -> None:
    """Stop the compilers that start_host_runtime started and no build took,
    and remove their folder."""
    while _STARTED:
        _STARTED.popitem()[1].discard()


def _runtime_objects(sources: list, flags: list, folder: Path,
                     cache: Optional[Path]) -> RuntimeObjects:
    """Those already started for these flags, else new ones."""
    if cache is not None and _STARTED:
        started = _STARTED.pop(cache / runtime_objects_key(sources, flags), None)
        if started is not None:
            return started
    return RuntimeObjects(sources, flags, folder, cache)


def compile_objects(program: Program, folder: Path, runtime_sources: list, runtime_flags: list,
                    runtime_cache: Optional[Path], extra_flags=()) -> tuple:
    """Compile the program, the user's C (each file on its own, with
    `extra_flags`, e.g. -fPIC) and, unless `runtime_cache` has them, the
    runtime's sources, all at once on the machine's processors; (the
    program's and the user's objects, in `folder`; the runtime's). Nothing
    of a failed build is kept."""
    steps, objects = program_steps(program, folder, extra_flags)
    runtime = _runtime_objects(runtime_sources, runtime_flags, folder, runtime_cache)
    try:
        runtime.start()
        pool = compiler_pool()
        own = wait_jobs([pool.submit(step) for step in steps], pool)
        report_results(steps + runtime.steps, own + runtime.wait())
        runtime.commit()
    finally:
        runtime.discard()
    return objects, runtime.objects


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


def runtime_cache_dir() -> Path:
    """Where the runtime's objects are kept (see RuntimeObjects)."""
    return cache_dir() / "runtime"


def _compile_into(folder: Path, program: Program, runtime_cache: Optional[Path] = None) -> Path:
    """Write the generated C into `folder`, compile it (see
    compile_objects) and link the executable there."""
    objects, runtime = compile_objects(program, folder, HOST_SOURCES, runtime_flags(program),
                                       runtime_cache)
    exe = folder / program.name
    _run_compiler(host_link_command(objects + runtime, exe), program.name)
    for obj in objects:             # linked: the executable is what the cache keeps
        obj.unlink()
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
        _compile_into(tmp, program, runtime_cache_dir())
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
            return self._build()
        finally:
            stop_started_runtime()      # no build takes them now

    def _build(self) -> Path:
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
        except BaseException as exc:
            # __exit__ is not called when __enter__ fails
            shutil.rmtree(self._tmp, ignore_errors=True)
            if isinstance(exc, OutputError):
                raise BuildError(str(exc)) from None
            raise

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


_QUOTED_INCLUDE = re.compile(rb'^[ \t]*#[ \t]*include[ \t]*"([^"\n]+)"', re.MULTILINE)


def user_headers(program: Program) -> list:
    """(header, its path relative to the folder of the user's C file that
    includes it, first or through other headers) for every header the
    user's C includes with quotes that is found where the compiler looks
    first, beside the including file; followed through the headers it
    includes. A quoted include found nowhere there (the program's own
    externs header, the runtime's, the e-puck library's) is left to the
    include paths. The builds depend on these headers as on the C."""
    found = []
    for source in program.user_sources():
        source = Path(source)
        home = os.path.dirname(os.path.abspath(source))
        queue, seen = [source], set()
        while queue:
            including = queue.pop(0)
            try:
                data = including.read_bytes()
            except OSError:
                continue            # the compiler says why
            for match in _QUOTED_INCLUDE.finditer(data):
                name = match.group(1).decode("utf-8", "surrogateescape")
                header = Path(os.path.normpath(os.path.join(including.parent, name)))
                if name == program.header_name:
                    continue        # generated (a file beside it: stale_externs_header)
                if header in seen or not header.is_file():
                    continue
                seen.add(header)
                found.append((source, header,
                              Path(os.path.relpath(os.path.abspath(header), home)).as_posix()))
                queue.append(header)
    return found


def stale_externs_header(program: Program) -> Optional[str]:
    """A file named like the program's externs header beside the user's C
    that is not that header (written by an earlier `epuckc compile`,
    before the externs changed): the compiler would read it instead of the
    current one, since a quoted include looks beside the including file
    first. The message that says so, or None."""
    if not program.header_name:
        return None
    for source in program.user_sources():
        beside = Path(source).parent / program.header_name
        try:
            if beside.is_file() and beside.read_text(encoding="utf-8") != program.header_text:
                return (f"{beside} is not the externs header of this program (an earlier "
                        f"`epuckc compile` wrote it, before the externs changed), and "
                        f"{Path(source).name} would include it instead of the current one: "
                        f"delete it, or run `epuckc compile` again to rewrite it")
        except (OSError, UnicodeDecodeError):
            continue
    return None


def dspic_user_headers(program: Program) -> list:
    """(a header, its copy's path inside the project) for each of
    user_headers: the C is copied into user/, so its headers go there at
    the same place relative to it. One that climbs out of the C's folder,
    or two different headers that would land on the same copy, cannot be
    laid out so: BuildError."""
    copies: dict = {}               # path in the project -> (header, its bytes)
    for source, header, rel in user_headers(program):
        if rel.startswith("../") or rel == ".." or os.path.isabs(rel):
            raise BuildError(
                f"{source} includes {header}, a header outside its folder; the dspic project "
                f"copies your C into {DSPIC_USER}/ with the headers beside it or below it "
                f"only: move {header.name} next to {source.name}", status=EXIT_USAGE)
        target = f"{DSPIC_USER}/{rel}"
        content = header.read_bytes()
        if target in copies and copies[target][1] != content:
            raise BuildError(
                f"two different headers would both be {target} in the dspic project: "
                f"{copies[target][0]} and {header}; give them different names",
                status=EXIT_USAGE)
        copies[target] = (header, content)
    return [(header, target) for target, (header, _) in sorted(copies.items())]


def write_dspic_project(program: Program, out_dir: Path, template_render) -> None:
    """A self-contained project inside out_dir: the program (and its
    externs header) at the top, the runtime files the robot needs in
    runtime/, copies of the user's C in user/, and a Makefile for XC16.
    Files whose contents did not change are not rewritten, so `make`
    rebuilds only what changed."""
    rt = runtime_dir()
    copies = dspic_user_copies(program)
    headers = dspic_user_headers(program)
    generated = [f"{program.name}.c"] if program.generated else []
    if program.generated and program.header_name:
        generated.append(program.header_name)
    runtime_files = [f"{DSPIC_RUNTIME}/{rel}" for rel in ROBOT_FILES]
    targets = (generated + runtime_files + [copy for _, copy in copies + headers]
               + ["Makefile"])
    check_outputs([out_dir / t for t in targets],
                  program.inputs + [header for header, _ in headers], inside=out_dir)
    out_dir = prepare_directory(out_dir)
    if program.generated:
        _write_generated(program, out_dir, only_if_changed=True)
    for rel in ROBOT_FILES:
        write_atomic(out_dir / DSPIC_RUNTIME / rel, (rt / rel).read_bytes(), only_if_changed=True)
    for source, copy in copies + headers:
        (out_dir / copy).parent.mkdir(parents=True, exist_ok=True)
        write_atomic(out_dir / copy, source.read_bytes(),
                     mode=stat.S_IMODE(source.stat().st_mode), only_if_changed=True)
    # the robot has no trace: the name labels are not even stored
    defines = [d[2:] for d in _capacity_defines(program)] + ["EPUCKRT_NO_NAMES"]
    write_atomic(out_dir / "Makefile", template_render(
        "dspic.mk.j2", name=program.name, generated=program.generated,
        header=program.header_name if program.generated else None,
        runtime=DSPIC_RUNTIME, runtime_sources=[f"{DSPIC_RUNTIME}/{r}" for r in ROBOT_SOURCES],
        runtime_headers=[f"{DSPIC_RUNTIME}/{r}" for r in ROBOT_HEADERS],
        user_sources=[copy for _, copy in copies], user_headers=[copy for _, copy in headers],
        defines=defines), only_if_changed=True)


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
