"""`epuckc cache` and the cache folder under pressure, as whole processes:
--info, --trim and --clear; a read-only and a full cache folder (a real
read-only bind mount and a real 64 KiB tmpfs, in a user and mount namespace
of their own) and a bound of one byte never fail `check` or `run` (nor, with
a read-only folder, a world, an experiment or `run --int16`: every cache's
writer falls back); several processes trimming one cache at once never fail
each other."""
from __future__ import annotations

import os
import subprocess
import sys
import time
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

import pytest

from tests.conftest import require_enki, require_tool
from tests.support.programs import REPO, epuckc

PROGRAMS = {
    "ahead": "on immediate do start_straight(300, 10 cm)\non stop_motor do exit_main\n",
    "turn": "on immediate do start_curve(0 mm, 90 deg, 200)\non stop_motor do exit_main\n",
}


def _programs(folder: Path) -> dict:
    out = {}
    for name, text in PROGRAMS.items():
        (folder / f"{name}.epk").write_text(text, encoding="utf-8")
        out[name] = folder / f"{name}.epk"
    return out


def _last_line(result) -> str:
    assert result.returncode == 0, result.stdout + result.stderr
    return result.stdout.strip().splitlines()[-1]


def _age_everything(folder: Path, seconds: float) -> None:
    then = time.time() - seconds
    for base, dirs, files in os.walk(folder):
        for name in dirs + files:
            os.utime(os.path.join(base, name), (then, then), follow_symlinks=False)


def _info(env) -> dict:
    """area -> entries, from `epuckc cache --info`."""
    result = epuckc("cache", "--info", env=env, check=True)
    rows = {}
    for line in result.stdout.splitlines()[1:-1]:
        name, count = line.split()[:2]
        rows[name] = int(count)
    return rows


def test_info_trim_and_clear(tmp_path):
    cache = tmp_path / "cache"
    env = {"EPUCKC_CACHE_DIR": str(cache)}
    prog = _programs(tmp_path)["ahead"]
    assert epuckc("check", prog, env=env).returncode == 0
    first = _last_line(epuckc("run", prog, env=env))
    rows = _info(env)
    assert rows["check"] == rows["host"] == rows["runtime"] == rows["run"] == 1
    assert rows["enki"] == rows["experiment"] == 0
    text = epuckc("cache", env=env).stdout          # --info is the default
    assert f"cache folder: {cache}\n" in text and "of a bound of 1.0 GiB (the default)" in text
    # a bound of 1 byte: what was used just now stays, the rest goes
    _age_everything(cache, 3600)
    assert epuckc("check", prog, env=env).returncode == 0        # marks its entry used
    result = epuckc("cache", "--trim", env={**env, "EPUCKC_CACHE_MAX": "1"}, check=True)
    assert result.stdout.startswith("evicted 3 entries")
    assert "the bound is 1 B (EPUCKC_CACHE_MAX=1)" in result.stdout
    rows = _info(env)
    assert rows["check"] == 1 and rows["host"] == rows["runtime"] == rows["run"] == 0
    assert _last_line(epuckc("run", prog, env=env)) == first     # built again
    result = epuckc("cache", "--clear", env=env, check=True)
    assert result.stdout.startswith("removed 4 entries")
    assert set(_info(env).values()) == {0}
    bad = epuckc("cache", "--info", env={**env, "EPUCKC_CACHE_MAX": "lots"}, check=True)
    assert "(the default: EPUCKC_CACHE_MAX `lots` is not a size (like 500M or 2G))" in bad.stdout


def _namespace_works() -> bool:
    unshare = require_tool("unshare")
    probe = subprocess.run([unshare, "--user", "--map-root-user", "--mount", "true"],
                           capture_output=True)
    if probe.returncode != 0:
        reason = f"user and mount namespaces are not allowed here: {probe.stderr!r}"
        if os.environ.get("EPUCKC_REQUIRE_ALL_TOOLS"):
            pytest.fail(reason)
        pytest.skip(reason)
    return True


def _in_namespace(mount: str, folder: Path, *args, env):
    """`epuckc ARGS` with `folder` mounted as `mount` says, seen by it alone."""
    _namespace_works()
    setup = {"read-only": 'mount --bind "$1" "$1" && mount -o remount,bind,ro "$1"',
             "full": 'mount -t tmpfs -o size=64k tmpfs "$1"'}[mount]
    full_env = dict(os.environ, PYTHONPATH=str(REPO), **env)
    return subprocess.run(["unshare", "--user", "--map-root-user", "--mount", "sh", "-c",
                           f'{setup} && shift && exec "$@"', "sh", str(folder),
                           sys.executable, "-m", "epuckc", *map(str, args)],
                          env=full_env, capture_output=True, text=True, timeout=600)


@pytest.mark.parametrize("filled", [True, False], ids=["filled", "empty"])
def test_a_read_only_cache_folder_fails_no_command(tmp_path, filled):
    cache = tmp_path / "cache"
    cache.mkdir()
    env = {"EPUCKC_CACHE_DIR": str(cache)}
    prog = _programs(tmp_path)["ahead"]
    expected = _last_line(epuckc("run", prog, env={"EPUCKC_CACHE_DIR": str(tmp_path / "other")}))
    if filled:
        assert epuckc("check", prog, env=env).returncode == 0
        _last_line(epuckc("run", prog, env=env))
    before = sorted(str(p.relative_to(cache)) for p in cache.rglob("*"))
    check = _in_namespace("read-only", cache, "check", prog, env=env)
    assert check.returncode == 0 and check.stderr == "", check.stderr
    run = _in_namespace("read-only", cache, "run", prog, env=env)
    assert _last_line(run) == expected
    if filled:
        assert run.stderr == ""                         # the cached run, as it was
    else:
        assert "building in a temporary folder, the cache is unusable" in run.stderr
        assert "Read-only file system" in run.stderr
    info = _in_namespace("read-only", cache, "cache", "--info", env=env)
    assert info.returncode == 0 and "(read-only: not kept)" in info.stdout
    clear = _in_namespace("read-only", cache, "cache", "--clear", env=env)
    if filled:
        assert clear.returncode == 1
        assert clear.stderr.startswith(f"epuckc: error: cannot remove {cache}/")
        assert "the file system is read-only" in clear.stderr
    else:
        assert clear.returncode == 0 and clear.stdout.startswith("removed 0 entries")
    assert sorted(str(p.relative_to(cache)) for p in cache.rglob("*")) == before


def test_a_world_runs_with_a_read_only_cache_folder(tmp_path):
    """The world runner and the robots are built in a temporary folder."""
    require_enki()
    cache = tmp_path / "cache"
    cache.mkdir()
    prog = _programs(tmp_path)["ahead"]
    world = tmp_path / "one.world"
    world.write_text("arena 100 cm x 100 cm\nrobot at 20 cm, 50 cm heading 0 deg\n")
    run = _in_namespace("read-only", cache, "run", prog, "--world", world, "--time-limit", "5s",
                        env={"EPUCKC_CACHE_DIR": str(cache)})
    assert run.returncode == 0, run.stderr
    assert "r1: no collision" in run.stdout + run.stderr
    assert run.stderr.count("building in a temporary folder, the cache is unusable") == 1
    assert list(cache.iterdir()) == []


EXPERIMENT = """program = "ahead.epk"
world = "one.world"
duration = "1500 ms"
seeds = 2
metrics = ["distance", "exit"]
"""


def _runs(folder: Path) -> list:
    """runs.csv's rows: what was measured (times.csv has the times)."""
    return (folder / "runs.csv").read_text(encoding="utf-8").splitlines()


def test_an_experiment_and_the_16_bit_path_run_with_a_read_only_cache_folder(tmp_path):
    """The last two caches' writers (experiment/task.py on a worker, the
    simavr runner of sim/int16.py) fall back on a temporary folder of their
    process, removed when it ends: the results are those of a usable cache
    (the session's), and nothing is left in the cache or in TMPDIR."""
    require_enki()
    require_tool("avr-gcc")
    require_tool("simavr")
    if not Path("/usr/include/simavr/sim_avr.h").exists():
        require_tool("libsimavr-dev (the simavr headers)")
    cache, scratch = tmp_path / "cache", tmp_path / "tmp"
    cache.mkdir()
    scratch.mkdir()
    prog = _programs(tmp_path)["ahead"]
    (tmp_path / "one.world").write_text("arena 100 cm x 100 cm\nrobot at 20 cm, 50 cm heading 0 deg\n")
    (tmp_path / "exp.toml").write_text(EXPERIMENT)
    env = {"EPUCKC_CACHE_DIR": str(cache), "TMPDIR": str(scratch)}
    exp = _in_namespace("read-only", cache, "experiment", tmp_path / "exp.toml",
                        "-o", tmp_path / "ro", "--workers", "1", env=env)
    assert exp.returncode == 0, exp.stderr
    assert "2 runs (0 failed)" in exp.stderr
    assert exp.stderr.count("building in a temporary folder, the cache is unusable") == 2
    reference = epuckc("experiment", tmp_path / "exp.toml", "-o", tmp_path / "rw", "--workers", "1")
    assert reference.returncode == 0, reference.stderr
    assert _runs(tmp_path / "ro") == _runs(tmp_path / "rw") and len(_runs(tmp_path / "rw")) == 3
    int16 = _in_namespace("read-only", cache, "run", prog, "--int16", env=env)
    assert int16.returncode == 0, int16.stderr
    assert "building in a temporary folder, the cache is unusable" in int16.stderr
    assert int16.stdout == epuckc("run", prog, "--int16", check=True).stdout
    assert list(cache.iterdir()) == [] and list(scratch.iterdir()) == []


def test_a_full_cache_folder_fails_no_command(tmp_path):
    cache = tmp_path / "cache"
    cache.mkdir()
    prog = _programs(tmp_path)["ahead"]
    env = {"EPUCKC_CACHE_DIR": str(cache)}
    expected = _last_line(epuckc("run", prog, env={"EPUCKC_CACHE_DIR": str(tmp_path / "other")}))
    # (64 KiB: the check's entry fits, the runtime's objects do not)
    check = _in_namespace("full", cache, "check", prog, env=env)
    assert check.returncode == 0 and check.stderr == "", check.stderr
    run = _in_namespace("full", cache, "run", prog, env=env)
    assert _last_line(run) == expected
    assert "the cache is unusable" in run.stderr and "the disk is full" in run.stderr


def test_a_bound_of_one_byte_fails_no_command(tmp_path):
    env = {"EPUCKC_CACHE_DIR": str(tmp_path / "cache"), "EPUCKC_CACHE_MAX": "1",
           "EPUCKC_CACHE_GRACE": "0", "EPUCKC_CACHE_TRIM_EVERY": "0"}
    progs = _programs(tmp_path)
    for _ in range(2):
        for prog in progs.values():
            assert epuckc("check", prog, env=env).returncode == 0
            result = epuckc("run", prog, env=env)
            assert result.returncode == 0 and result.stderr == "", result.stderr
    # each write trimmed all but what the writing process itself uses: the
    # last run's executable, runtime objects and entry are left
    rows = _info(env)
    assert (rows.pop("host"), rows.pop("runtime"), rows.pop("run")) == (1, 1, 1)
    assert set(rows.values()) == {0}


def test_processes_trimming_one_cache_do_not_fail_each_other(tmp_path):
    """Every write trims the cache to one byte, sparing only the entries
    used in the last 20 seconds: entries go while the other process runs,
    but never one that it has looked up and is about to use."""
    env = {"EPUCKC_CACHE_DIR": str(tmp_path / "cache"), "EPUCKC_CACHE_MAX": "1",
           "EPUCKC_CACHE_GRACE": "20", "EPUCKC_CACHE_TRIM_EVERY": "0"}
    progs = _programs(tmp_path)
    expected = {name: _last_line(epuckc("run", prog, env={
        "EPUCKC_CACHE_DIR": str(tmp_path / "reference")})) for name, prog in progs.items()}

    def worker(order):
        got = []
        for name in order:
            result = epuckc("run", progs[name], env=env)
            got.append((name, result.returncode, result.stderr,
                        result.stdout.strip().splitlines()[-1:]))
        return got

    orders = [["ahead", "turn", "ahead"], ["turn", "ahead", "turn"]]
    with ThreadPoolExecutor(len(orders)) as pool:
        results = [r for rs in pool.map(worker, orders) for r in rs]
    for name, status, err, last in results:
        assert (status, err, last) == (0, "", [expected[name]])
    _age_everything(tmp_path / "cache", 60)
    epuckc("cache", "--trim", env=env, check=True)
    assert sum(_info(env).values()) == 0
