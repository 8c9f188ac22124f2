"""`--engine slurm` against a local stand-in of sbatch and squeue
(tests/experiment/fake_slurm.py on PATH), which runs the job array's
tasks here as slurmd would: the same rows as the local engine, a task
whose node fails gives rows with the error and the next command submits
only those runs, and a command that finds its job still running waits for
it instead of submitting again."""
from __future__ import annotations

import json
import os
import subprocess

import pytest

from tests.experiment import fake_slurm
from tests.experiment.helpers import command, env, make, needs_enki, rows
from tests.support.cli import run_cli

pytestmark = needs_enki


@pytest.fixture
def slurm(tmp_path, monkeypatch):
    """The stand-in on PATH; its state folder."""
    bin_dir = fake_slurm.install(tmp_path / "bin")
    state = tmp_path / "slurm-state"
    monkeypatch.setenv("PATH", f"{bin_dir}{os.pathsep}{os.environ['PATH']}")
    monkeypatch.setenv("FAKE_SLURM_DIR", str(state))
    monkeypatch.setenv("EPUCKC_SLURM_POLL_S", "0.1")
    monkeypatch.setenv("PYTHONPATH", env()["PYTHONPATH"])
    return state


def _local(tmp_path, exp, capsys) -> str:
    status, out, err = run_cli(["experiment", str(exp), "-o", str(tmp_path / "local"),
                                "--workers", "1"], capsys)
    assert status == 0, err
    return (tmp_path / "local" / "runs.csv").read_text()


def test_a_grid_on_a_job_array_gives_the_local_rows(tmp_path, slurm, capsys):
    exp = make(tmp_path / "exp")
    out = tmp_path / "slurm"
    status, _, err = run_cli(["experiment", str(exp), "-o", str(out), "--engine", "slurm",
                              "--batch", "3", "--workers", "3",
                              "--sbatch-options", "--partition=short --time=00:10:00"], capsys)
    assert status == 0, err
    assert "submitted the job array 1000; waiting for its 4 batches" in err
    assert (out / "runs.csv").read_text() == _local(tmp_path, exp, capsys)
    script = (out / "jobs" / "array.sh").read_text()
    assert "#SBATCH --array=0-3%3" in script and "--worker" in script
    submitted = json.loads((slurm / "1000.json").read_text())
    assert submitted["settings"]["--partition"] == "short"
    assert submitted["settings"]["--time"] == "00:10:00"
    # each array task ran one batch of three runs, and said so in its log
    logs = sorted((out / "jobs" / "logs").glob("1000_*.out"))
    assert len(logs) == 4 and all("3 runs saved" in p.read_text() for p in logs)
    assert len(list((out / "runs").glob("*.jsonl"))) == 4
    # the collect step again, from the saved runs only
    status, _, err = run_cli(["experiment", str(exp), "-o", str(out), "--report-only"], capsys)
    assert status == 0 and "report of 12 of 12 runs" in err
    assert not (slurm / "1001.json").exists()


def test_a_task_lost_with_its_node_runs_again_next_time(tmp_path, slurm, capsys, monkeypatch):
    exp = make(tmp_path / "exp")
    out = tmp_path / "slurm"
    monkeypatch.setenv("FAKE_SLURM_FAIL", "1")
    status, _, err = run_cli(["experiment", str(exp), "-o", str(out), "--engine", "slurm",
                              "--batch", "3"], capsys)
    assert status == 0, err
    lost = [r for r in rows(out / "runs.csv") if r["error"]]
    assert len(lost) == 3 and all("ended without saving its runs" in r["error"] for r in lost)
    monkeypatch.delenv("FAKE_SLURM_FAIL")
    status, _, err = run_cli(["experiment", str(exp), "-o", str(out), "--engine", "slurm",
                              "--batch", "3"], capsys)
    assert status == 0, err
    assert "resuming: 9 of 12 runs" in err
    assert "submitted the job array 1001; waiting for its 1 batches" in err
    assert (out / "runs.csv").read_text() == _local(tmp_path, exp, capsys)


def test_detached_then_collected_without_a_second_submission(tmp_path, slurm, capsys,
                                                              monkeypatch):
    exp = make(tmp_path / "exp")
    out = tmp_path / "slurm"
    go = tmp_path / "go"
    monkeypatch.setenv("FAKE_SLURM_HOLD", str(go))
    status, _, err = run_cli(["experiment", str(exp), "-o", str(out), "--engine", "slurm",
                              "--detach"], capsys)
    assert status == 0, err
    assert "submitted the job array 1000" in err and not (out / "runs.csv").exists()
    # the job is queued: the same command waits for it, and submits nothing
    waiting = subprocess.Popen(command(exp, "-o", out, "--engine", "slurm"), env=dict(os.environ),
                               stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    first = waiting.stderr.readline()       # the command's first line, then it waits
    assert first.startswith("waiting for the job array 1000 submitted before"), first
    assert waiting.poll() is None
    go.write_text("")
    _, err = waiting.communicate(timeout=300)
    assert waiting.returncode == 0, err
    assert "12 runs (0 failed)" in err
    assert not (slurm / "1001.json").exists()
    assert (out / "runs.csv").read_text() == _local(tmp_path, exp, capsys)


def test_without_sbatch_the_engine_says_so(tmp_path, capsys, monkeypatch):
    monkeypatch.setenv("PATH", str(tmp_path))
    exp = make(tmp_path / "exp")
    status, _, err = run_cli(["experiment", str(exp), "--engine", "slurm"], capsys)
    assert status == 1 and "needs SLURM's sbatch and squeue" in err
