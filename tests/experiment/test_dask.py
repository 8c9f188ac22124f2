"""`--engine dask` on a cluster the test starts: `dask scheduler` and two
`dask worker` processes on 127.0.0.1, always stopped at the end. The same
experiment gives the same rows as the local engine."""
from __future__ import annotations

import os
import shutil
import socket
import subprocess
import sys
import time

import pytest

from epuckc.experiment import engines
from tests.experiment.helpers import env, make, needs_enki
from tests.support.cli import run_cli

pytestmark = needs_enki


def _free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def _dask_command() -> list:
    exe = shutil.which("dask")
    return [exe] if exe else [sys.executable, "-m", "dask"]


@pytest.fixture
def cluster(tmp_path):
    if not engines.dask_available():
        if os.environ.get("EPUCKC_REQUIRE_ALL_TOOLS"):
            pytest.fail("Dask is not installed (pip install -e '.[cluster]')")
        pytest.skip("Dask is not installed (pip install -e '.[cluster]')")
    port = _free_port()
    address = f"tcp://127.0.0.1:{port}"
    logs = tmp_path / "dask-logs"
    logs.mkdir()
    procs = []
    # the workers run in another folder: nothing of the experiment's files
    # reaches them but through the tasks
    elsewhere = tmp_path / "worker-home"
    elsewhere.mkdir()
    try:
        procs.append(subprocess.Popen(
            _dask_command() + ["scheduler", "--host", "127.0.0.1", "--port", str(port),
                               "--no-dashboard"],
            env=env(), cwd=elsewhere, stdout=open(logs / "scheduler.log", "w"),
            stderr=subprocess.STDOUT))
        _wait_for_port(port)
        for i in range(2):
            procs.append(subprocess.Popen(
                _dask_command() + ["worker", address, "--host", "127.0.0.1", "--nthreads", "1",
                                   "--nworkers", "1", "--no-dashboard", "--name", f"w{i}"],
                env=env(), cwd=elsewhere, stdout=open(logs / f"worker{i}.log", "w"),
                stderr=subprocess.STDOUT))
        _wait_for_workers(address, 2)
        yield address
    finally:
        for p in reversed(procs):
            p.terminate()
        for p in reversed(procs):
            try:
                p.wait(timeout=20)
            except subprocess.TimeoutExpired:
                p.kill()
                p.wait()


def _wait_for_port(port: int, seconds: float = 60):
    deadline = time.monotonic() + seconds
    while time.monotonic() < deadline:
        try:
            with socket.create_connection(("127.0.0.1", port), timeout=1):
                return
        except OSError:
            time.sleep(0.1)
    raise AssertionError(f"the Dask scheduler did not start on port {port}")


def _wait_for_workers(address: str, n: int, seconds: float = 90):
    from distributed import Client
    with Client(address, timeout="30s") as client:
        client.wait_for_workers(n, timeout=seconds)


def test_same_rows_on_a_dask_cluster(tmp_path, cluster, capsys):
    exp = make(tmp_path / "exp")
    status, out, err = run_cli(["experiment", str(exp), "-o", str(tmp_path / "dask"),
                                "--engine", "dask", "--scheduler", cluster], capsys)
    assert status == 0, err
    status, out, err2 = run_cli(["experiment", str(exp), "-o", str(tmp_path / "local"),
                                 "--workers", "1"], capsys)
    assert status == 0, err2
    dask_rows = (tmp_path / "dask" / "runs.csv").read_text()
    assert dask_rows.count("\n") == 13
    assert dask_rows == (tmp_path / "local" / "runs.csv").read_text()
    assert (tmp_path / "dask" / "summary.csv").read_bytes() == \
        (tmp_path / "local" / "summary.csv").read_bytes()
    # both workers took runs
    from distributed import Client
    with Client(cluster, timeout="30s") as client:
        counts = client.run(lambda: len(__import__(
            "epuckc.experiment.task", fromlist=["_built"])._built))
    assert len(counts) == 2 and all(n >= 1 for n in counts.values()), counts


def test_without_dask_the_engine_says_so(tmp_path, capsys, monkeypatch):
    monkeypatch.setattr(engines, "dask_available", lambda: False)
    exp = make(tmp_path)
    status, out, err = run_cli(["experiment", str(exp), "--engine", "dask"], capsys)
    assert status == 1
    assert "pip install 'epuckc[cluster]'" in err
    assert not (tmp_path / "exp-results").exists()


def test_an_unreachable_scheduler(tmp_path, capsys):
    if not engines.dask_available():
        if os.environ.get("EPUCKC_REQUIRE_ALL_TOOLS"):
            pytest.fail("Dask is not installed (pip install -e '.[cluster]')")
        pytest.skip("Dask is not installed (pip install -e '.[cluster]')")
    exp = make(tmp_path)
    port = _free_port()
    status, out, err = run_cli(["experiment", str(exp), "--engine", "dask", "--scheduler",
                                f"tcp://127.0.0.1:{port}"], capsys)
    assert status == 1 and "cannot reach the Dask scheduler" in err


def test_a_tune_on_a_dask_cluster_has_the_local_history(tmp_path, cluster, capsys):
    """`epuckc tune --engine dask`: the same candidates as on one local
    worker (the rounds do not depend on the engine)."""
    pytest.importorskip("optuna") if not os.environ.get("EPUCKC_REQUIRE_ALL_TOOLS") else None
    from tests.experiment.helpers import REPO
    for name in ("avoider.epk", "clutter.world", "avoider_tune.toml"):
        text = (REPO / "examples" / name).read_text()
        if name.endswith(".toml"):
            text = (text.replace("budget = 96", "budget = 12").replace('"10 s"', '"1 s"')
                    .replace("test_seeds = 20", "test_seeds = 2"))
        (tmp_path / name).write_text(text)
    tune = tmp_path / "avoider_tune.toml"
    status, _, err = run_cli(["tune", str(tune), "-o", str(tmp_path / "dask"), "--engine", "dask",
                              "--scheduler", cluster], capsys)
    assert status == 0, err
    status, _, err = run_cli(["tune", str(tune), "-o", str(tmp_path / "local"), "--workers", "1"],
                             capsys)
    assert status == 0, err
    assert (tmp_path / "dask" / "history.csv").read_bytes() == \
        (tmp_path / "local" / "history.csv").read_bytes()
    assert (tmp_path / "dask" / "history.csv").read_text().count("\n") == 3
