"""`epuckc experiment` with the local engine: rows and summary, the same
rows with any number of workers, resuming after an interrupt, a failing
run as a row with its error."""
from __future__ import annotations

import math
import signal
import statistics
import subprocess
import time

from tests.experiment.helpers import command, env, make, needs_enki, rows
from tests.support.cli import run_cli

pytestmark = needs_enki


def test_two_by_six_gives_twelve_rows_and_a_two_row_summary(tmp_path, capsys):
    exp = make(tmp_path)
    status, out, err = run_cli(["experiment", str(exp), "-o", str(tmp_path / "one"),
                                "--workers", "1"], capsys)
    assert status == 0, err
    runs = rows(tmp_path / "one" / "runs.csv")
    assert len(runs) == 12
    assert [(r["K"], r["seed"]) for r in runs] == [(k, str(s)) for k in ("1 steps/s", "4 steps/s")
                                                  for s in range(1, 7)]
    assert all(r["robot"] == "r1" and r["error"] == "" and r["status"] == "3" for r in runs)
    # the run is 1.5 s long: the robot drives, and no exit_main: exit_s is the limit
    assert all(float(r["distance_mm"]) > 20 and r["exit_s"] == "1.500" for r in runs)
    assert all(int(r["coverage_cells"]) >= 1 for r in runs)
    # seeds differ: the noise gives different paths
    assert len({r["distance_mm"] for r in runs}) > 1
    summary = rows(tmp_path / "one" / "summary.csv")
    assert [s["K"] for s in summary] == ["1 steps/s", "4 steps/s"]
    for s in summary:
        mine = [float(r["distance_mm"]) for r in runs if r["K"] == s["K"]]
        assert s["runs"] == "6" and s["failed"] == "0" and s["distance_mm:n"] == "6"
        mean, sd = statistics.mean(mine), statistics.stdev(mine)
        assert math.isclose(float(s["distance_mm:mean"]), mean, abs_tol=1e-3)
        assert math.isclose(float(s["distance_mm:sd"]), sd, abs_tol=1e-3)
        half = 2.571 * sd / math.sqrt(6)        # t(0.975, 5)
        assert math.isclose(float(s["distance_mm:ci95_low"]), mean - half, abs_tol=2e-3)
    svg = (tmp_path / "one" / "summary.svg").read_text()
    assert svg.startswith("<svg") and "distance_mm" in svg and "K=4 steps/s" in svg
    assert not (tmp_path / "one" / "traces").exists()       # only when asked

    # the same rows, byte for byte, with two workers
    status, out, err = run_cli(["experiment", str(exp), "-o", str(tmp_path / "two"),
                                "--workers", "2"], capsys)
    assert status == 0, err
    assert (tmp_path / "two" / "runs.csv").read_bytes() == \
        (tmp_path / "one" / "runs.csv").read_bytes()
    assert (tmp_path / "two" / "summary.csv").read_bytes() == \
        (tmp_path / "one" / "summary.csv").read_bytes()


def test_the_constants_reach_the_program(tmp_path, capsys):
    """Each grid point's program has its constants: with K = 0 the sensors
    do not steer, and three times the cruise speed drives three times as
    far (the wheels' noise aside)."""
    exp = make(tmp_path, """program = "brait.epk"
world = "arena.world"
duration = "1 s"
seeds = [5]
metrics = ["distance", "pose"]
[params]
CRUISE = ["200 steps/s", "600 steps/s"]
K = "0 steps/s"
""")
    status, out, err = run_cli(["experiment", str(exp), "-o", str(tmp_path / "o")], capsys)
    assert status == 0, err
    slow, fast = rows(tmp_path / "o" / "runs.csv")
    assert slow["K"] == fast["K"] == "0 steps/s"
    # 200 vs 600 steps/s for 1 s: 26 mm and 77 mm (1000 steps a turn of a 41 mm wheel)
    assert 23 < float(slow["distance_mm"]) < 29
    assert 70 < float(fast["distance_mm"]) < 85


def test_a_failing_run_is_a_row_with_its_error(tmp_path, capsys):
    exp = make(tmp_path, """program = "crash.c"
world = "arena.world"
duration = "500 ms"
seeds = 5
metrics = ["distance"]
timeout = "3 s"
""")
    status, out, err = run_cli(["experiment", str(exp), "-o", str(tmp_path / "o"),
                                "--workers", "2"], capsys)
    assert status == 0, err
    runs = rows(tmp_path / "o" / "runs.csv")
    assert [r["seed"] for r in runs] == ["1", "2", "3", "4", "5"]
    assert runs[0]["error"] == "" and runs[2]["error"] == ""
    assert "world runner failed" in runs[1]["error"] and "signal 6" in runs[1]["error"]
    assert runs[1]["distance_mm"] == ""
    assert "more than 3 s of wall-clock time" in runs[3]["error"]
    assert "watchdog" in runs[3]["error"]
    assert runs[4]["error"] == "the program stopped with exit status 2"
    assert runs[4]["status"] == "2"
    (summary,) = rows(tmp_path / "o" / "summary.csv")
    assert summary["runs"] == "5" and summary["failed"] == "3" and summary["distance_mm:n"] == "2"
    assert "3 failed" in err


def test_resume_after_an_interrupt(tmp_path):
    exp = make(tmp_path, EXPERIMENT_SLOW)
    out = tmp_path / "o"
    proc = subprocess.Popen(command(exp, "-o", out, "--workers", "1"), env=env(),
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    deadline = time.monotonic() + 120
    while time.monotonic() < deadline and _saved(out) < 2:
        time.sleep(0.02)
    proc.send_signal(signal.SIGINT)
    _, err = proc.communicate(timeout=60)
    assert proc.returncode == 130, err
    assert "interrupted" in err and "Traceback" not in err
    saved = _saved(out)
    assert 2 <= saved < 8
    assert not (out / "runs.csv").exists()
    again = subprocess.run(command(exp, "-o", out, "--workers", "2"), env=env(),
                           capture_output=True, text=True, timeout=300)
    assert again.returncode == 0, again.stderr
    assert f"resuming: {saved} of 8 runs" in again.stderr
    # only the runs not saved were run: one progress line each
    assert again.stderr.count("): ok") == 8 - saved
    fresh = subprocess.run(command(exp, "-o", tmp_path / "fresh", "--workers", "2"), env=env(),
                           capture_output=True, text=True, timeout=300)
    assert fresh.returncode == 0
    assert (out / "runs.csv").read_bytes() == (tmp_path / "fresh" / "runs.csv").read_bytes()


def _saved(out) -> int:
    """Runs saved: each batch's file has one a line."""
    return sum(len(p.read_text().splitlines()) for p in (out / "runs").glob("*.jsonl"))


EXPERIMENT_SLOW = """program = "brait.epk"
world = "arena.world"
duration = "4 s"
seeds = 4
metrics = ["distance", "coverage"]
[params]
K = ["1 steps/s", "2 steps/s"]
"""


def test_swarm_rows(tmp_path, capsys):
    exp = make(tmp_path, """program = "brait.epk"
world = "three.world"
duration = "1 s"
seeds = 2
metrics = ["contacts", "distance", "coverage", "exit"]
traces = true
""")
    (tmp_path / "three.world").write_text("arena 60 cm x 40 cm\nrobot a at 10 cm, 10 cm\n"
                                          "robot b at 30 cm, 10 cm\n"
                                          "robot c at 50 cm, 30 cm heading 180 deg\n")
    status, out, err = run_cli(["experiment", str(exp), "-o", str(tmp_path / "o")], capsys)
    assert status == 0, err
    runs = rows(tmp_path / "o" / "runs.csv")
    assert [r["robot"] for r in runs] == ["a", "b", "c", "swarm"] * 2
    for seed in ("1", "2"):
        mine = [r for r in runs if r["seed"] == seed]
        robots, swarm = mine[:3], mine[3]
        total = sum(float(r["distance_mm"]) for r in robots)
        assert math.isclose(float(swarm["distance_mm"]), total, abs_tol=0.01)
        assert int(swarm["coverage_cells"]) <= sum(int(r["coverage_cells"]) for r in robots)
        assert int(swarm["coverage_cells"]) >= max(int(r["coverage_cells"]) for r in robots)
    # the traces, asked for: each run's merged trace, as `epuckc run --trace` writes it
    import json
    records = [json.loads(line) for line in
               (tmp_path / "o" / "traces" / "p0-s2.jsonl").read_text().splitlines()]
    assert records[0]["kind"] == "world" and records[0]["seed"] == 2
    assert {r["robot"] for r in records[1:]} == {"a", "b", "c"}
    assert [r["kind"] for r in records[-3:]] == ["contacts"] * 3
    summary = rows(tmp_path / "o" / "summary.csv")
    swarm_distances = [float(r["distance_mm"]) for r in runs if r["robot"] == "swarm"]
    assert math.isclose(float(summary[0]["distance_mm:mean"]),
                        statistics.mean(swarm_distances), abs_tol=1e-3)



def test_the_pool_forks_only_a_process_of_one_thread_and_the_rows_are_the_same(
        tmp_path, capsys, monkeypatch):
    """`epuckc experiment` forks its workers (a process of one thread); with
    another thread alive (a test runner, a tool embedding epuckc) they come
    from a fork server instead, which no lock of that thread can reach; the
    rows are the same either way."""
    import threading

    from epuckc.experiment import engines
    with monkeypatch.context() as m:
        m.setattr(threading, "active_count", lambda: 1)
        assert engines._pool_context().get_start_method() == "fork"
        m.setattr(threading, "active_count", lambda: 2)
        assert engines._pool_context().get_start_method() == "forkserver"
    exp = make(tmp_path)
    # the command as users run it: a process of one thread, whose workers fork
    forked = subprocess.run(command(exp, "-o", tmp_path / "forked", "--workers", "2"), env=env(),
                            capture_output=True, text=True, timeout=300)
    assert forked.returncode == 0, forked.stderr
    # in this process, with one more thread for sure: a fork server's workers
    stop = threading.Event()
    other = threading.Thread(target=stop.wait)
    other.start()
    try:
        assert engines._pool_context().get_start_method() == "forkserver"
        status, out, err = run_cli(["experiment", str(exp), "-o", str(tmp_path / "served"),
                                    "--workers", "2"], capsys)
    finally:
        stop.set()
        other.join()
    assert status == 0, err
    assert (tmp_path / "served" / "runs.csv").read_bytes() == \
        (tmp_path / "forked" / "runs.csv").read_bytes()
