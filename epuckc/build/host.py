"""The host build: the harness executable of a program (generated from a rule
file, or hand-written against the runtime API, the paper's own way of
working), its cache keyed on every input, and the runtime's objects compiled
once and reused."""
from __future__ import annotations

import hashlib
import os
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path
from typing import Optional

from ..base.output import TEMP_PREFIX, OutputError, describe_os_error, prepare_directory, write_file
from ..base import cache as _cache
from ..base.resources import cache_dir, runtime_dir
from .common import (BUILD_FLAGS, GENERATED_CFLAGS, HOST_INCLUDES, HOST_SOURCES, HOST_USER_FLAGS,
                     USER_CFLAGS,
                     BuildError, Program, _capacity_defines, _run_compiler, _write_generated,
                     c_compiler, check_outputs, stale_externs_header, user_headers)
from . import dspic_asm
from .parallel import CompileStep, cancel_jobs, compiler_pool, report_results, wait_jobs

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
    _add(h, "cc", " ".join(c_compiler() + GENERATED_CFLAGS + USER_CFLAGS + HOST_USER_FLAGS
                           + _capacity_defines(program)).encode())
    _add(h, "compiler", _compiler_identity().encode())
    _add(h, "asm", str(dspic_asm.FORMAT).encode())
    return h.hexdigest()[:24]


def _includes(program: Program, generated_dir: Path) -> list:
    """The generated folder and the runtime's; for a C program of several
    files, also each file's folder (main.c includes the header beside the
    demo it calls, as one project of the library's)."""
    rt = runtime_dir()
    folders = []
    if program.source_path is not None and program.user_files:
        for source in program.user_sources():
            folder = f"-I{os.path.dirname(os.path.abspath(source))}"
            if folder not in folders:
                folders.append(folder)
    return [f"-I{generated_dir}"] + folders + [f"-I{rt / inc}" for inc in HOST_INCLUDES]


def _assembly(obj: Path) -> Path:
    return obj.with_name(obj.name + ".s")


def user_compile_command(source: Path, obj: Path, program: Program, generated_dir: Path,
                         extra_flags=()) -> list:
    """The user's own C, compiled where it is (its messages name it; its own
    #includes are found beside it), warnings shown but not fatal; to
    assembly, which `assemble_user` makes `obj` of."""
    return (c_compiler() + USER_CFLAGS + HOST_USER_FLAGS + list(extra_flags)
            + _capacity_defines(program)
            + _includes(program, generated_dir)
            + BUILD_FLAGS + ["-x", "c", "-S", str(source), "-o", str(_assembly(obj))])


def assemble_user(source: Path, obj: Path):
    """What follows user_compile_command, on the compiler's worker: its
    inline dsPIC instructions carried out by the simulation and its globals
    where a reset restores them (build/dspic_asm.py), then assembled into
    `obj`. (status, stdout, stderr) as a compiler's."""
    def post(out: str, err: str) -> tuple:
        assembly = _assembly(obj)
        try:
            text = assembly.read_text(encoding="utf-8", errors="surrogateescape")
            assembly.write_text(dspic_asm.rewrite(text, str(source)), encoding="utf-8",
                                errors="surrogateescape")
        except dspic_asm.AsmError as exc:
            return 1, out, err + f"{exc}\n"
        try:
            done = subprocess.run(c_compiler() + ["-c", str(assembly), "-o", str(obj)],
                                  stdin=subprocess.DEVNULL, capture_output=True, text=True,
                                  errors="replace")
        finally:
            assembly.unlink(missing_ok=True)
        return done.returncode, out + done.stdout, err + done.stderr
    return post


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
    """--wrap=main: main starts from runtime_c/host/cmain.c's __wrap_main,
    where a reset starts it again."""
    return (c_compiler() + [str(o) for o in objects]
            + ["-Wl,--wrap=main", "-o", str(output), "-lm"])


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
                                 str(source), _include_hint(program, source), _size(source),
                                 post=assemble_user(source, obj)))
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
            if self._complete(self.final):
                self.steps = []
                return
            cache.mkdir(parents=True, exist_ok=True)
            sweep_stale(cache)
            self._tmp = _cache.temporary_folder(cache)
            folder = self._tmp
        built = [folder / n for n in names]
        self.steps = [CompileStep(c_compiler() + flags + BUILD_FLAGS
                                  + ["-c", str(rt / src), "-o", str(obj)],
                                  f"the runtime ({src})", "", _size(rt / src))
                      for src, obj in zip(sources, built)]
        if self._tmp is None:
            self.objects = built

    def _complete(self, final: Path) -> bool:
        """The entry is there, whole (and marked used)."""
        return _cache.used(final) and all((final / o.name).is_file() for o in self.objects)

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
            _cache.commit_folder(self._tmp, self.final, self._complete)
        finally:
            self._tmp = None
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
    return _cache.area("runtime")


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
    host = _cache.area("host")
    final = host / host_build_key(program)
    exe = final / program.name

    def complete(folder: Path) -> bool:
        return _cache.used(folder) and (folder / program.name).is_file()
    if complete(final):
        return exe
    reason = _cache.problem(host)
    if reason is not None:
        raise OutputError(reason)       # (a full disk too: the compiler would fail)
    sweep_stale(host)
    # Built in a folder of its own, then renamed into place in one step: a
    # killed build leaves only a temporary folder, swept by a later run.
    tmp = _cache.temporary_folder(host)
    try:
        _compile_into(tmp, program, runtime_cache_dir())
        _cache.commit_folder(tmp, final, complete)
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


