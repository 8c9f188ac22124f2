"""Every file epuckc writes goes through epuckc/base/output.py: standard output
for `-`, links followed, device nodes never replaced, the whole file or
nothing, and messages that name the path. And the host-build cache: an
unusable one means a temporary folder, killed runs leave nothing behind."""
from __future__ import annotations

import errno
import json
import os
import stat
import threading
import time
from pathlib import Path

import pytest

from epuckc.build import host as build_module
from epuckc.base import output
from epuckc.base.output import OutputError, write_file
from tests.conftest import require_tool

from tests.support.programs import epuckc

PROGRAM = "on immediate do start_straight(300, 10 cm)\non stop_motor do exit_main\n"


@pytest.fixture
def prog(tmp_path):
    path = tmp_path / "p.epk"
    path.write_text(PROGRAM, encoding="utf-8")
    return path


# ---- the writer itself --------------------------------------------------------

def test_dash_is_standard_output(prog, tmp_path):
    result = epuckc("compile", prog, "-o", "-", cwd=tmp_path)
    assert result.returncode == 0, result.stderr
    assert result.stdout.startswith("/*") and "register_program(" in result.stdout
    assert not (tmp_path / "-").exists()


def test_a_link_is_followed_and_its_target_replaced(tmp_path):
    target = tmp_path / "real.c"
    target.write_text("old\n")
    target.chmod(0o600)
    link = tmp_path / "link.c"
    link.symlink_to(target.name)
    write_file(link, "new\n")
    assert link.is_symlink() and os.readlink(link) == "real.c"
    assert target.read_text() == "new\n"
    assert stat.S_IMODE(target.stat().st_mode) == 0o600       # its mode is kept
    assert sorted(p.name for p in tmp_path.iterdir()) == ["link.c", "real.c"]


def test_a_dangling_link_gets_its_target(tmp_path):
    link = tmp_path / "link.c"
    link.symlink_to("sub/made.c")
    (tmp_path / "sub").mkdir()
    write_file(link, "x\n")
    assert link.is_symlink() and (tmp_path / "sub" / "made.c").read_text() == "x\n"


def test_a_fifo_is_written_not_replaced(tmp_path):
    fifo = tmp_path / "pipe"
    os.mkfifo(fifo)
    got = []
    reader = threading.Thread(target=lambda: got.append(fifo.read_bytes()))
    reader.start()
    write_file(fifo, "through the pipe\n")
    reader.join(10)
    assert got == [b"through the pipe\n"]
    assert stat.S_ISFIFO(os.lstat(fifo).st_mode)


def test_a_device_node_is_written_not_replaced(tmp_path, prog):
    """`-o /dev/null` as root replaced the node with a regular file. A node
    of our own (a copy of /dev/null) is used, so the test cannot harm the
    machine if the code were wrong."""
    node = tmp_path / "null"
    try:
        os.mknod(node, 0o666 | stat.S_IFCHR, os.makedev(1, 3))
    except PermissionError:
        pytest.skip("making a device node needs root")
    result = epuckc("compile", prog, "-o", node)
    assert result.returncode == 0, result.stderr
    assert stat.S_ISCHR(os.lstat(node).st_mode)


def test_dev_stdout_is_the_open_standard_output(prog, tmp_path):
    before = os.lstat("/dev/stdout")
    result = epuckc("compile", prog, "-o", "/dev/stdout")
    assert result.returncode == 0, result.stderr
    assert "register_program(" in result.stdout
    after = os.lstat("/dev/stdout")
    assert (after.st_mode, after.st_ino) == (before.st_mode, before.st_ino)
    assert not list(Path("/dev").glob(".epuckc-tmp-*"))


def test_dev_stdout_redirected_to_a_file(prog, tmp_path):
    """The shell's open file is written, not a new file put in its place."""
    import subprocess
    import sys
    from tests.support.programs import REPO
    out = tmp_path / "out.c"
    with open(out, "wb") as f:
        subprocess.run([sys.executable, "-m", "epuckc", "compile", prog, "-o", "/dev/stdout"],
                       stdout=f, check=True, env=dict(os.environ, PYTHONPATH=str(REPO)))
    assert "register_program(" in out.read_text()


def test_full_device_names_the_path():
    if not os.path.exists("/dev/full"):
        pytest.skip("no /dev/full")
    with pytest.raises(OutputError) as info:
        write_file("/dev/full", "x" * 10000)
    assert "/dev/full" in str(info.value) and "disk is full" in str(info.value)


def test_full_disk_leaves_the_old_file_and_no_temporary(tmp_path, monkeypatch):
    out = tmp_path / "out.c"
    out.write_text("the old program\n")

    def no_space(fd, data):
        raise OSError(errno.ENOSPC, os.strerror(errno.ENOSPC))
    monkeypatch.setattr(output.os, "write", no_space)
    with pytest.raises(OutputError) as info:
        write_file(out, "the new program\n")
    message = str(info.value)
    assert str(out) in message and "No space left on device" in message
    assert "free some space" in message
    assert out.read_text() == "the old program\n"
    assert [p.name for p in tmp_path.iterdir()] == ["out.c"]


def test_compile_onto_a_directory_says_so(prog, tmp_path):
    (tmp_path / "dir.c").mkdir()
    result = epuckc("compile", prog, "-o", tmp_path / "dir.c")
    assert result.returncode == 2
    assert f"cannot write {tmp_path / 'dir.c'}: it is a directory" in result.stderr


def test_compile_into_a_missing_folder_under_a_file(prog, tmp_path):
    (tmp_path / "f").write_text("")
    result = epuckc("compile", prog, "-o", tmp_path / "f" / "x.c")
    assert result.returncode == 2 and "Traceback" not in result.stderr
    assert str(tmp_path / "f") in result.stderr


# ---- build -o -------------------------------------------------------------------

def test_build_onto_an_existing_file_names_it_and_says_what_to_do(prog, tmp_path):
    (tmp_path / "taken").write_text("mine\n")
    result = epuckc("build", prog, "-o", tmp_path / "taken")
    assert result.returncode == 2
    assert f"cannot use {tmp_path / 'taken'} as the output folder: it is a file" in result.stderr
    assert "give another folder with -o DIR" in result.stderr
    assert (tmp_path / "taken").read_text() == "mine\n"


def test_build_to_dash_is_refused(prog, tmp_path):
    result = epuckc("build", prog, "-o", "-", cwd=tmp_path)
    assert result.returncode == 2 and "`-o -` is for `epuckc compile`" in result.stderr
    assert not (tmp_path / "-").exists()


def test_dspic_project_onto_an_existing_file(prog, tmp_path):
    (tmp_path / "taken").write_text("mine\n")
    result = epuckc("build", prog, "--target", "dspic", "-o", tmp_path / "taken")
    assert result.returncode == 2 and "it is a file" in result.stderr


# ---- the cache ------------------------------------------------------------------------

@pytest.mark.parametrize("where", ["/proc/nope", "a-file", "file-parent/cache"])
def test_run_with_an_unusable_cache_builds_in_a_temporary_folder(prog, tmp_path, where):
    require_tool("cc")
    (tmp_path / "a-file").write_text("")
    (tmp_path / "file-parent").write_text("")
    cache = where if where.startswith("/") else str(tmp_path / where)
    result = epuckc("run", prog, env={"EPUCKC_CACHE_DIR": cache})
    assert result.returncode == 0, result.stderr
    notes = [line for line in result.stderr.splitlines() if line]
    assert len(notes) == 1 and "building in a temporary folder" in notes[0], result.stderr
    assert "internal error" not in result.stderr
    assert "exit" in result.stdout


def test_full_cache_falls_back_to_a_temporary_folder(prog, tmp_path, monkeypatch, capsys):
    require_tool("cc")
    from epuckc.diagnostics import Report
    from epuckc.cli.driver import load_program
    monkeypatch.setenv("EPUCKC_CACHE_DIR", str(tmp_path / "cache"))
    real = build_module._compile_into

    def full_in_cache(folder, program, *rest):
        if str(tmp_path / "cache") in str(folder):
            raise OutputError(f"cannot write {folder}/p.c: No space left on device")
        return real(folder, program, *rest)
    monkeypatch.setattr(build_module, "_compile_into", full_in_cache)
    program = load_program(prog, Report())
    with build_module.host_executable(program) as exe:
        assert exe.is_file() and os.access(exe, os.X_OK)
        folder = exe.parent
    assert not folder.exists()                                 # removed afterwards
    assert "No space left on device" in capsys.readouterr().err
    assert not [p for p in (tmp_path / "cache" / "host").iterdir()]   # nothing left in the cache


def test_stale_temporary_folders_are_swept(prog, tmp_path):
    require_tool("cc")
    cache = tmp_path / "cache"
    host = cache / "host"
    host.mkdir(parents=True)
    dead = host / ".epuckc-tmp-999999999-abc"       # no such process
    dead.mkdir()
    (dead / "p.c").write_text("half")
    old = host / f".epuckc-tmp-{os.getpid()}-old"   # alive, but abandoned long ago
    old.mkdir()
    os.utime(old, (time.time() - 3 * 86400,) * 2)
    busy = host / f".epuckc-tmp-{os.getpid()}-busy"  # a build under way
    busy.mkdir()
    result = epuckc("run", prog, env={"EPUCKC_CACHE_DIR": str(cache)})
    assert result.returncode == 0, result.stderr
    assert not dead.exists() and not old.exists() and busy.exists()
    assert [p.name for p in host.iterdir() if not p.name.startswith(".")]   # the new build


def test_killed_run_leaves_no_temporary_folder(prog, tmp_path):
    """SIGTERM during a run unwinds: the temporary build folder (unusable
    cache) is removed."""
    require_tool("cc")
    import signal
    import subprocess
    import sys
    from tests.support.programs import REPO
    forever = tmp_path / "forever.epk"
    forever.write_text("on immediate do set_timer\non timer(1 s) repeat do stop_motor\n")
    tmpdir = tmp_path / "tmp"
    tmpdir.mkdir()
    env = dict(os.environ, PYTHONPATH=str(REPO), EPUCKC_CACHE_DIR="/proc/nope",
               TMPDIR=str(tmpdir))
    proc = subprocess.Popen([sys.executable, "-m", "epuckc", "run", forever,
                             "--time-limit", "1000000s"], env=env,
                            stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
    deadline = time.time() + 60
    while time.time() < deadline:       # wait until the harness runs
        built = list(tmpdir.glob(".epuckc-tmp-*/forever"))
        if built and os.access(built[0], os.X_OK):
            break
        time.sleep(0.05)
    time.sleep(0.5)
    proc.send_signal(signal.SIGTERM)
    proc.wait(30)
    assert list(tmpdir.iterdir()) == []


def test_trace_dash_writes_json_lines_to_standard_output(prog, tmp_path):
    require_tool("cc")
    result = epuckc("run", prog, "--trace", "-", cwd=tmp_path)
    assert result.returncode == 0, result.stderr
    records = [json.loads(line) for line in result.stdout.splitlines()]
    assert records[0]["kind"] == "event" and records[-1]["kind"] == "exit"
    assert not (tmp_path / "-").exists()


def test_fmt_on_a_full_disk_names_the_file_and_keeps_it(tmp_path, monkeypatch, capsys):
    from epuckc.cli import fmt
    path = tmp_path / "messy.epk"
    path.write_text("on immediate do   stop_motor\n")

    def no_space(fd, data):
        raise OSError(errno.ENOSPC, os.strerror(errno.ENOSPC))
    monkeypatch.setattr(output.os, "write", no_space)
    assert fmt.run([str(path)]) == 2
    err = capsys.readouterr().err
    assert f"cannot write {path}: No space left on device" in err and "internal" not in err
    assert path.read_text() == "on immediate do   stop_motor\n"
    assert [p.name for p in tmp_path.iterdir()] == ["messy.epk"]


def test_an_executable_over_a_plain_file_is_executable(tmp_path):
    path = tmp_path / "prog"
    path.write_text("old")
    path.chmod(0o600)
    write_file(path, b"\x7fELF...", mode=0o755)
    assert stat.S_IMODE(path.stat().st_mode) == 0o711
