"""The host build (epuckc/build/host.py): translation units compiled at once on
the machine's processors, the runtime's objects kept in a cache of their
own keyed on what they are made of, and a failure anywhere reported as one
clean message with nothing left in the cache."""
from __future__ import annotations

import os
import shutil
import stat
import sys
from pathlib import Path

import pytest

from epuckc.build import host as build_module
from epuckc.build.common import HOST_SOURCES, BuildError
from epuckc.build.parallel import CompileStep, run_compile_steps
from epuckc.base.resources import RUNTIME_CORE
from tests.conftest import require_tool

from tests.support.programs import REPO, epuckc

PROGRAM = "on immediate do start_straight(300, 10 cm)\non stop_motor do exit_main\n"
OTHER = "on immediate do start_straight(200, 5 cm)\non stop_motor do exit_main\n"
SPIN = """#include "ext_externs.h"
static param_start_curve curve;
void spin(void *param)
{
    curve.radius = 0;
    curve.degrees = 360 * ((const param_spin *)param)->turns;
    curve.speed = 500;
    start_curve(&curve);
}
"""
EXTERN = ('extern action spin(turns: int) from "spin.c"\n'
          "on immediate do spin(turns: 1)\non stop_motor do exit_main\n")


def _write(folder: Path, name: str, text: str) -> Path:
    path = folder / name
    path.write_text(text, encoding="utf-8")
    return path


def _entries(folder: Path) -> list:
    """The names in a cache folder, temporary ones included."""
    return sorted(p.name for p in folder.iterdir()) if folder.is_dir() else []


def _logging_cc(tmp_path: Path) -> tuple:
    """A C compiler that logs the source it compiles (or `link`), then runs cc."""
    cc = require_tool("cc")
    log = tmp_path / "cc.log"
    wrapper = tmp_path / "logcc"
    wrapper.write_text(f"""#!/bin/sh
src=link
for a in "$@"; do case "$a" in *.c) src="$a";; esac; done
echo "$src" >> '{log}'
exec '{cc}' "$@"
""")
    wrapper.chmod(wrapper.stat().st_mode | stat.S_IXUSR)
    return wrapper, log


def _compiled(log: Path) -> list:
    """The base names of the sources compiled since the log was last read."""
    lines = log.read_text().splitlines() if log.exists() else []
    log.write_text("")
    return sorted(Path(line).name for line in lines if line != "link")


# ---- the steps themselves ---------------------------------------------------------

def _sh(script: str, size: int = 0, what: str = "") -> CompileStep:
    return CompileStep(["/bin/sh", "-c", script], what or script, "", size)


def test_steps_run_at_once(tmp_path):
    """Two steps that each wait for the other's file finish only if they run
    at the same time."""
    require_tool("sh")
    a, b = tmp_path / "a", tmp_path / "b"
    wait = "i=0; while [ ! -e {0} ] && [ $i -lt 100 ]; do sleep 0.05; i=$((i+1)); done; [ -e {0} ]"
    run_compile_steps([_sh(f"touch {a}; " + wait.format(b)),
                       _sh(f"touch {b}; " + wait.format(a))], jobs=2)


def test_the_first_failing_step_in_order_is_reported_whichever_fails_first(capsys):
    """The later step fails at once and starts first (it is the bigger);
    the earlier one fails after it: the message is still the earlier one's,
    with its output and command; the warnings of a step before it are
    shown, those of steps after it are not."""
    require_tool("sh")
    steps = [_sh("echo 'a warning' >&2", what="first"),
             _sh("sleep 0.3; echo 'second: broken' >&2; exit 1", what="second"),
             _sh("echo 'third: broken' >&2; exit 1", size=10**6, what="third"),
             _sh("echo 'fourth warns' >&2", what="fourth")]
    for jobs in (1, 2, 4):
        with pytest.raises(BuildError) as failed:
            run_compile_steps(steps, jobs=jobs)
        message = str(failed.value)
        assert message.startswith("the C compiler failed to build second:\nsecond: broken\n")
        assert "third" not in message and "command: /bin/sh -c 'sleep 0.3;" in message
        err = capsys.readouterr().err
        assert err == "a warning\n", err


def test_a_missing_compiler_is_one_message():
    steps = [_sh("exit 0"), CompileStep(["/nonexistent/epuckc-cc", "-c", "x.c"], "x.c")]
    with pytest.raises(BuildError) as failed:
        run_compile_steps(steps, jobs=2)
    assert "the C compiler `/nonexistent/epuckc-cc` was not found" in str(failed.value)


# ---- failures leave nothing in the cache -----------------------------------------------

def test_a_failing_extern_file_reports_it_and_caches_nothing(tmp_path):
    """The user's C fails while the runtime compiles beside it: one message
    naming the user's file, and neither an executable nor runtime objects
    (nor a temporary folder) in the cache."""
    require_tool("cc")
    prog = _write(tmp_path, "p.epk", EXTERN)
    _write(tmp_path, "spin.c", '#include "p_externs.h"\nvoid spin(void *p) { nonsense; }\n')
    cache = tmp_path / "cache"
    result = epuckc("run", prog, env={"EPUCKC_CACHE_DIR": str(cache)})
    assert result.returncode == 1, result.stdout + result.stderr
    assert "the C compiler failed to build" in result.stderr and "spin.c" in result.stderr
    assert "nonsense" in result.stderr and "Traceback" not in result.stderr
    assert _entries(cache / "host") == [] and _entries(cache / "runtime") == []


def test_a_failing_runtime_unit_reports_it_and_caches_nothing(tmp_path, monkeypatch):
    """A runtime source that does not compile (here: an edited copy of the
    runtime) is reported as the runtime's, with gcc's message, and leaves
    no executable and no runtime objects."""
    require_tool("cc")
    from epuckc.diagnostics import Report
    from epuckc.cli.driver import load_program
    runtime = tmp_path / "rt"
    shutil.copytree(REPO / "runtime_c", runtime, ignore=shutil.ignore_patterns("build"))
    stub = runtime / "host" / "epuck_stub.c"
    stub.write_text(stub.read_text() + "\nstatic int unused_by_anyone;\n")
    monkeypatch.setattr(build_module, "runtime_dir", lambda: runtime)
    cache = tmp_path / "cache"
    monkeypatch.setenv("EPUCKC_CACHE_DIR", str(cache))
    program = load_program(_write(tmp_path, "p.epk", PROGRAM), Report())
    with pytest.raises(BuildError) as failed:
        with build_module.host_executable(program):
            pass
    message = str(failed.value)
    assert message.startswith("the C compiler failed to build the runtime (host/epuck_stub.c)")
    assert "unused_by_anyone" in message and "-Werror" in message
    assert _entries(cache / "host") == [] and _entries(cache / "runtime") == []


def test_a_missing_compiler_is_reported_and_nothing_cached(tmp_path):
    prog = _write(tmp_path, "p.epk", PROGRAM)
    cache = tmp_path / "cache"
    result = epuckc("run", prog, env={"EPUCKC_CACHE_DIR": str(cache),
                                      "CC": str(tmp_path / "no-such-cc")})
    assert result.returncode == 1, result.stdout + result.stderr
    assert f"the C compiler `{tmp_path / 'no-such-cc'}` was not found" in result.stderr
    assert "Traceback" not in result.stderr
    assert _entries(cache / "host") == [] and _entries(cache / "runtime") == []


# ---- the runtime's objects --------------------------------------------------------------

def test_a_second_program_reuses_the_runtime_objects(tmp_path):
    """After one program, another with the same capacities compiles only
    itself; its trace is the same as when built from nothing."""
    cc, log = _logging_cc(tmp_path)
    cache = tmp_path / "cache"
    env = {"EPUCKC_CACHE_DIR": str(cache), "CC": str(cc)}
    first, second = _write(tmp_path, "first.epk", PROGRAM), _write(tmp_path, "second.epk", OTHER)
    epuckc("run", first, env=env, check=True)
    assert _compiled(log) == sorted([*(Path(s).name for s in HOST_SOURCES), "first.c"])
    [key] = _entries(cache / "runtime")
    objects = {p: p.stat().st_mtime_ns for p in (cache / "runtime" / key).iterdir()}
    assert sorted(p.name for p in objects) == sorted(
        [name.replace("/", "_")[:-len(".c")] + ".o" for name in HOST_SOURCES])
    warm = epuckc("run", second, "--trace", tmp_path / "warm.jsonl", env=env, check=True)
    assert _compiled(log) == ["second.c"]
    assert {p: p.stat().st_mtime_ns for p in objects} == objects
    cold = epuckc("run", second, "--trace", tmp_path / "cold.jsonl",
                  env={"EPUCKC_CACHE_DIR": str(tmp_path / "cold-cache")}, check=True)
    assert warm.stdout == cold.stdout
    assert (tmp_path / "warm.jsonl").read_bytes() == (tmp_path / "cold.jsonl").read_bytes()


def test_the_runtime_objects_follow_capacities_and_user_c(tmp_path):
    """The capacities are compiled into the runtime: other capacities (an
    option, or user C that can register) are other objects."""
    cc, log = _logging_cc(tmp_path)
    cache = tmp_path / "cache"
    env = {"EPUCKC_CACHE_DIR": str(cache), "CC": str(cc)}
    prog = _write(tmp_path, "p.epk", PROGRAM)
    epuckc("run", prog, env=env, check=True)
    epuckc("run", prog, "--max-events", "5", env=env, check=True)
    assert "epuckrt.c" in _compiled(log)
    assert len(_entries(cache / "runtime")) == 2
    ext = _write(tmp_path, "ext.epk", EXTERN)
    _write(tmp_path, "spin.c", SPIN)
    epuckc("run", ext, env=env, check=True)
    assert "epuckrt.c" in _compiled(log)
    assert len(_entries(cache / "runtime")) == 3


def test_the_runtime_objects_follow_the_runtime_sources_and_the_compiler(tmp_path, monkeypatch):
    """Keyed on every runtime source and header (content, not time), the
    compiler as a command and as a file, and the flags."""
    from epuckc.diagnostics import Report
    from epuckc.cli.driver import load_program
    require_tool("cc")
    runtime = tmp_path / "rt"
    shutil.copytree(REPO / "runtime_c", runtime, ignore=shutil.ignore_patterns("build"))
    monkeypatch.setattr(build_module, "runtime_dir", lambda: runtime)
    monkeypatch.setenv("EPUCKC_CACHE_DIR", str(tmp_path / "cache"))
    program = load_program(_write(tmp_path, "p.epk", PROGRAM), Report())
    rt_cache = tmp_path / "cache" / "runtime"

    def build() -> str:
        with build_module.host_executable(program) as exe:
            assert os.access(exe, os.X_OK)
        return _entries(rt_cache)[-1] if _entries(rt_cache) else ""

    def key() -> str:
        objects = build_module.RuntimeObjects(build_module.HOST_SOURCES,
                                              build_module.runtime_flags(program),
                                              tmp_path, rt_cache)
        objects.discard()
        return objects.objects[0].parent.name

    build()
    first = key()
    assert _entries(rt_cache) == [first] and key() == first
    header = runtime / "epuck_api" / "motor_led" / "e_led.h"
    os.utime(header, ns=(header.stat().st_atime_ns, header.stat().st_mtime_ns + 10**9))
    assert key() == first                       # a time stamp alone is no change
    header.write_text(header.read_text() + "\n/* changed */\n")
    assert key() != first
    build()
    assert len(_entries(rt_cache)) == 2
    changed = key()
    # the compiler: another command, or another file behind the same name
    fake = tmp_path / "bin" / "cc"
    fake.parent.mkdir()
    fake.symlink_to(require_tool("cc"))
    monkeypatch.setenv("CC", str(fake))
    at_fake = key()
    assert at_fake != changed
    fake.unlink()
    shutil.copy(sys.executable, fake)           # any other file will do for the key
    assert key() != at_fake
    monkeypatch.delenv("CC")
    monkeypatch.setattr(build_module, "GENERATED_CFLAGS", build_module.GENERATED_CFLAGS + ["-g"])
    assert key() != changed


def test_a_build_in_a_temporary_folder_keeps_no_runtime_objects(tmp_path):
    """An unusable cache: everything is compiled in the temporary folder,
    which goes afterwards."""
    prog = _write(tmp_path, "p.epk", PROGRAM)
    require_tool("cc")
    (tmp_path / "a-file").write_text("")
    tmpdir = tmp_path / "tmp"
    tmpdir.mkdir()
    result = epuckc("run", prog, env={"EPUCKC_CACHE_DIR": str(tmp_path / "a-file" / "cache"),
                                      "TMPDIR": str(tmpdir)})
    assert result.returncode == 0, result.stderr
    assert "building in a temporary folder" in result.stderr
    assert list(tmpdir.iterdir()) == []


# ---- the runtime started before the program is known -------------------------------------

def _slow_cc(tmp_path: Path) -> tuple:
    """A C compiler that waits 30 s in a process of its own (as gcc runs cc1),
    then runs cc; both process ids are recorded."""
    cc = require_tool("cc")
    pids = tmp_path / "pids"
    wrapper = tmp_path / "slowcc"
    wrapper.write_text(f"#!/bin/sh\necho $$ >> '{pids}'\nsleep 30 &\necho $! >> '{pids}'\n"
                       f"wait $!\nexec '{cc}' \"$@\"\n")
    wrapper.chmod(wrapper.stat().st_mode | stat.S_IXUSR)
    return wrapper, pids


def _alive(pid: int) -> bool:
    try:
        with open(f"/proc/{pid}/stat") as f:
            return f.read().rsplit(")", 1)[1].split()[0] not in ("Z", "X")
    except OSError:
        return False


def _all_gone(pids: Path) -> bool:
    import time
    numbers = [int(n) for n in pids.read_text().split()] if pids.exists() else []
    deadline = time.time() + 5
    while time.time() < deadline and any(_alive(n) for n in numbers):
        time.sleep(0.05)
    return not any(_alive(n) for n in numbers)


def test_a_rule_file_with_errors_stops_the_runtime_started_for_it(tmp_path):
    """The runtime starts compiling while the file is checked; an error
    stops those compilers at once and keeps nothing of theirs."""
    cc, pids = _slow_cc(tmp_path)
    bad = _write(tmp_path, "bad.epk", "on immediate do nothing_such\n")
    cache = tmp_path / "cache"
    result = epuckc("run", bad, env={"EPUCKC_CACHE_DIR": str(cache), "CC": str(cc)})
    assert result.returncode == 1 and "E011" in result.stderr, result.stderr
    assert _all_gone(pids)
    assert _entries(cache / "runtime") == []


def test_started_runtime_compilers_run_until_stopped(tmp_path, monkeypatch):
    import time
    cc, pids = _slow_cc(tmp_path)
    cache = tmp_path / "cache"
    monkeypatch.setenv("EPUCKC_CACHE_DIR", str(cache))
    monkeypatch.setenv("CC", str(cc))
    build_module.start_host_runtime(True, None, None)
    try:
        [started] = build_module._STARTED.values()
        assert started.final.parent == cache / "runtime"
        deadline = time.time() + 20
        while time.time() < deadline and not (pids.exists() and pids.read_text().strip()):
            time.sleep(0.05)
        assert pids.exists(), "no compiler started"
        assert len(_entries(cache / "runtime")) == 1       # its temporary folder
    finally:
        build_module.stop_started_runtime()
    assert build_module._STARTED == {}
    assert _all_gone(pids)
    assert _entries(cache / "runtime") == []


def test_the_runtime_started_is_the_one_the_build_takes(tmp_path):
    """A rule file without `extern`, and hand-written C: each runtime source
    is compiled once, whether started early or not."""
    cc, log = _logging_cc(tmp_path)
    env = {"CC": str(cc)}
    prog = _write(tmp_path, "p.epk", PROGRAM)
    epuckc("run", prog, env={**env, "EPUCKC_CACHE_DIR": str(tmp_path / "a")}, check=True)
    assert _compiled(log) == sorted([*(Path(s).name for s in HOST_SOURCES), "p.c"])
    fig2 = tmp_path / "fig2.c"
    fig2.write_text((REPO / "tests" / "runtime" / "paper_fig2.c").read_text())
    epuckc("run", fig2, env={**env, "EPUCKC_CACHE_DIR": str(tmp_path / "b")}, check=True)
    assert _compiled(log) == sorted([*(Path(s).name for s in HOST_SOURCES), "fig2.c"])


def test_a_build_found_in_the_cache_stops_the_runtime_started(tmp_path):
    """The input cache misses (here: emptied) but the executable is in the
    build cache: the runtime started early is stopped before the program
    runs, and not kept."""
    prog = _write(tmp_path, "p.epk", PROGRAM)
    cache = tmp_path / "cache"
    env = {"EPUCKC_CACHE_DIR": str(cache)}
    first = epuckc("run", prog, env=env, check=True)
    for folder in ("run", "runtime"):
        shutil.rmtree(cache / folder)
    again = epuckc("run", prog, env=env, check=True)
    assert again.stdout == first.stdout
    assert _entries(cache / "runtime") == []


def test_sigterm_while_compiling_kills_the_compilers_and_keeps_nothing(tmp_path):
    """SIGTERM during the build: every compiler (with the processes it
    started) is killed, and no temporary folder stays in the cache."""
    import signal
    import subprocess
    import time
    cc, pids = _slow_cc(tmp_path)
    prog = _write(tmp_path, "p.epk", PROGRAM)
    cache = tmp_path / "cache"
    env = dict(os.environ, PYTHONPATH=str(REPO), EPUCKC_CACHE_DIR=str(cache), CC=str(cc))
    proc = subprocess.Popen([sys.executable, "-m", "epuckc", "run", str(prog)], env=env,
                            stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    deadline = time.time() + 60
    while time.time() < deadline and not (pids.exists() and pids.read_text().strip()):
        time.sleep(0.05)
    time.sleep(0.3)
    proc.send_signal(signal.SIGTERM)
    _, err = proc.communicate(timeout=20)
    assert proc.returncode != 0 and "Traceback" not in err, err
    assert _all_gone(pids)
    for folder in ("host", "runtime"):
        assert _entries(cache / folder) == [], folder


def test_build_for_the_host_starts_the_runtime_early_too(tmp_path):
    """`epuckc build`: each runtime source compiled once; an output that is
    refused stops what was started."""
    cc, log = _logging_cc(tmp_path)
    cache = tmp_path / "cache"
    env = {"CC": str(cc), "EPUCKC_CACHE_DIR": str(cache)}
    prog = _write(tmp_path, "p.epk", PROGRAM)
    epuckc("build", prog, "-o", tmp_path / "out", env=env, check=True)
    assert _compiled(log) == sorted([*(Path(s).name for s in HOST_SOURCES), "p.c"])
    assert os.access(tmp_path / "out" / "p", os.X_OK)
    shutil.rmtree(cache / "runtime")
    (tmp_path / "a-file").write_text("")
    refused = epuckc("build", prog, "-o", tmp_path / "a-file", env=env)
    assert refused.returncode == 2 and "a-file" in refused.stderr, refused.stderr
    assert _entries(cache / "runtime") == []


def test_an_incomplete_runtime_entry_is_rebuilt(tmp_path):
    """Objects missing from a runtime entry (removed by hand): compiled
    again and the entry replaced, not an unusable cache."""
    prog = _write(tmp_path, "p.epk", PROGRAM)
    cache = tmp_path / "cache"
    env = {"EPUCKC_CACHE_DIR": str(cache)}
    epuckc("run", prog, env=env, check=True)
    [key] = _entries(cache / "runtime")
    (cache / "runtime" / key / "epuckrt.o").unlink()
    shutil.rmtree(cache / "host")
    shutil.rmtree(cache / "run")
    result = epuckc("run", prog, env=env, check=True)
    assert "temporary folder" not in result.stderr
    assert _entries(cache / "runtime") == [key]
    assert (cache / "runtime" / key / "epuckrt.o").is_file()
