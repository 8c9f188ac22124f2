"""A robot's recorded trace as a case's run (`recorded = "run.jsonl"` in
NAME.toml, docs/testing.md): `epuckc test` checks it as it checks a
simulated run, with the same golden file, tolerances and property
checks. The recording here is the robot's tracer on simavr (`epuckc run
--int16 --robot-trace --trace`, what `epuckc monitor --trace` writes for
a real robot); its golden is the host harness's readable trace."""
import json
import shutil

from conftest import REPO
from tests.support.programs import epuckc
from tests.support.robot_trace import require_simavr

EXAMPLES = REPO / "examples"


def _case(tmp_path):
    folder = tmp_path / "lab"
    folder.mkdir()
    shutil.copy(EXAMPLES / "bump_counter.epk", folder / "bump_counter.epk")
    r = epuckc("run", folder / "bump_counter.epk", "--int16", "--robot-trace", "--scenario",
               EXAMPLES / "bumps.scn", "--trace", folder / "robot.jsonl")
    assert r.returncode == 0, r.stderr
    host = epuckc("run", folder / "bump_counter.epk", "--scenario", EXAMPLES / "bumps.scn",
                  cwd=folder)
    (folder / "bump_counter.trace").write_text(host.stdout)
    (folder / "bump_counter.toml").write_text(
        'recorded = "robot.jsonl"\ntrace = true\n'
        'expect = ["exit within 6 s", "rule bump fires", "x < 10 mm at exit"]\n'
        '[tolerance]\npose_mm = 0.5\nheading_deg = 0.5\n')
    return folder


def test_a_recorded_robot_trace_passes_the_simulations_golden_and_checks(tmp_path):
    require_simavr()
    folder = _case(tmp_path)
    r = epuckc("test", folder, "-v")
    assert r.returncode == 0, r.stdout + r.stderr
    assert "ok   " in r.stdout and "1 passed, 0 failed" in r.stdout


def test_a_recording_that_differs_fails_with_its_diff(tmp_path):
    """A record missing (a bump not counted) and the drops it came with:
    the diff shows both, and the property that no longer holds fails."""
    require_simavr()
    folder = _case(tmp_path)
    records = [json.loads(line) for line in (folder / "robot.jsonl").read_text().splitlines()]
    at = next(i for i, r in enumerate(records) if r["kind"] == "set" and r["value"] == 3)
    records[at] = {"t_ms": records[at]["t_ms"], "kind": "dropped", "name": "dropped", "id": -1,
                   "count": 1, "total": 1}
    (folder / "robot.jsonl").write_text("".join(json.dumps(r) + "\n" for r in records))
    (folder / "bump_counter.toml").write_text(
        'recorded = "robot.jsonl"\ntrace = true\nexpect = ["exit within 5 s"]\n'
        '[tolerance]\npose_mm = 0.5\n')
    r = epuckc("test", folder)
    assert r.returncode == 1
    assert "-[  5000 ms] set       bumps = 3" in r.stdout
    assert "+[  5000 ms] dropped   1 record: the robot's link was full (1 so far)" in r.stdout
    assert "expect `exit within 5 s`" in r.stdout


def test_a_recorded_trace_that_is_not_there_is_a_located_error(tmp_path):
    folder = tmp_path / "lab"
    folder.mkdir()
    shutil.copy(EXAMPLES / "square.epk", folder / "square.epk")
    (folder / "square.toml").write_text('recorded = "gone.jsonl"\n')
    r = epuckc("test", folder)
    assert r.returncode == 2
    assert "square.toml:1:12: error: the recorded trace gone.jsonl does not exist" in r.stderr


def test_a_recorded_trace_replays_as_a_page_and_draws(tmp_path):
    require_simavr()
    folder = _case(tmp_path)
    for out in ("replay.html", "path.svg"):
        r = epuckc("plot", folder / "robot.jsonl", "-o", tmp_path / out)
        assert r.returncode == 0, r.stderr
    page = (tmp_path / "replay.html").read_text()
    assert "<svg" in page and '"firings"' in page and "bump_counter.epk:13" in page


def test_a_goldens_input_lines_are_the_simulations_not_the_recordings(tmp_path):
    """A golden made by the host harness has the scenario's inputs
    (`input selector=1`); the robot's recording has none (its tracer sends
    what the program did): they are left out of the comparison, and
    everything else must match."""
    require_simavr()
    folder = tmp_path / "menu"
    folder.mkdir()
    shutil.copy(EXAMPLES / "selector_menu.epk", folder / "selector_menu.epk")
    args = ("--scenario", EXAMPLES / "selector_menu.scn", "--time-limit", "5s")
    r = epuckc("run", folder / "selector_menu.epk", "--int16", "--robot-trace", *args,
               "--trace", folder / "robot.jsonl")
    assert r.returncode == 3, r.stderr
    golden = epuckc("run", folder / "selector_menu.epk", *args, cwd=folder).stdout
    assert "[     0 ms] input     selector=1" in golden
    (folder / "selector_menu.trace").write_text(golden)
    (folder / "selector_menu.toml").write_text('recorded = "robot.jsonl"\ntrace = true\n'
                                               '[tolerance]\npose_mm = 0.5\n')
    assert epuckc("test", folder).returncode == 0
    # a line of the program's own that differs still fails
    (folder / "selector_menu.trace").write_text(golden.replace("mode      idle", "mode      dance"))
    r = epuckc("test", folder)
    assert r.returncode == 1 and "mode      dance" in r.stdout
