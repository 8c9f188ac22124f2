"""Tolerances on a readable trace's numbers (pose, heading, times), so that
a golden survives small changes of physics, and property checks in
NAME.toml for cases that are not goldens."""
from __future__ import annotations

import re

import pytest

from epuckc.testing.case import Tolerance
from epuckc.testing.compare import lines_match
from tests.support.programs import epuckc
from tests.testing.test_epuckc_test import make_case


def _shift(text: str, dx: float = 0.0, dheading: float = 0.0, dt: int = 0) -> str:
    """The trace with every pose moved by dx mm, every heading turned and
    every time of an event after the start moved by dt ms (as a new
    version of the physics might)."""
    def pose(m):
        x, y, h = float(m.group(1)), float(m.group(2)), float(m.group(3))
        return f"pose ({x + dx:.1f}, {y:.1f}) {h + dheading:.1f} deg"

    def time(m):
        t = int(m.group(1))
        return f"[{t + dt if t > 1 else t:6d} ms]"
    text = re.sub(r"pose \((-?[\d.]+), (-?[\d.]+)\) (-?[\d.]+) deg", pose, text)
    text = re.sub(r"\[\s*(\d+) ms\]", time, text)
    return re.sub(r"(exit|timeout) at (\d+) ms", lambda m: f"{m.group(1)} at "
                  f"{int(m.group(2)) + dt} ms", text)


@pytest.fixture
def blessed(tmp_path):
    make_case(tmp_path)
    assert epuckc("test", "--bless", tmp_path).returncode == 0
    return tmp_path


def _with_tolerance(folder, text, name="avoid"):
    (folder / f"{name}.toml").write_text(text)
    return epuckc("test", folder)


def test_numbers_within_the_tolerances_pass(blessed):
    trace = blessed / "avoid.trace"
    original = trace.read_text()
    trace.write_text(_shift(original, dx=0.4, dheading=0.6, dt=3))
    r = epuckc("test", blessed)
    assert r.returncode == 1, "without tolerances any difference fails"
    r = _with_tolerance(blessed, "[tolerance]\npose_mm = 0.5\nheading_deg = 1\ntime_ms = 5\n")
    assert (r.returncode, r.stdout) == (0, "1 passed, 0 failed\n"), r.stdout + r.stderr
    # each tolerance on its own is needed
    for tight in ("pose_mm = 0.3\nheading_deg = 1\ntime_ms = 5",
                  "pose_mm = 0.5\nheading_deg = 0.5\ntime_ms = 5",
                  "pose_mm = 0.5\nheading_deg = 1\ntime_ms = 2"):
        r = _with_tolerance(blessed, "[tolerance]\n" + tight + "\n")
        assert r.returncode == 1, tight
        assert "the readable trace differs from avoid.trace" in r.stdout


def test_tolerances_never_excuse_a_different_event(blessed):
    trace = blessed / "avoid.trace"
    trace.write_text(trace.read_text().replace("rule cruise:", "rule roam:"))
    r = _with_tolerance(blessed, "[tolerance]\npose_mm = 1000\nheading_deg = 180\n"
                                 "time_ms = 100000\n")
    assert r.returncode == 1
    assert "rule `roam` fired in the expected trace, rule `cruise` fired in this one" in r.stdout


def test_a_heading_tolerance_wraps_round():
    line = "[   5 ms] event  #1 a.epk:1 on immediate pose (0.0, 0.0) {} deg"
    loose = Tolerance(heading_deg=0.5)
    assert lines_match(line.format("179.9"), line.format("-179.8"), loose)
    assert not lines_match(line.format("179.9"), line.format("-179.0"), loose)
    assert not lines_match(line.format("179.9"), line.format("-179.8"), Tolerance())


def test_property_checks_replace_the_golden(tmp_path):
    make_case(tmp_path, toml='expect = ["exit within 5 s", "x > 40 mm at exit", '
                             '"y > 60 mm at exit", "rule avoid fires within 1.5 s", '
                             '"rule cruise fires", "heading >= 85 deg at end"]\n')
    r = epuckc("test", "--bless", tmp_path)
    assert (r.returncode, r.stdout) == (0, "1 passed, 0 failed\n"), r.stdout + r.stderr
    assert not (tmp_path / "avoid.trace").exists()
    assert epuckc("test", tmp_path).returncode == 0


def test_failing_property_checks_say_what_happened(tmp_path):
    make_case(tmp_path, toml='expect = ["exit within 3 s", "x > 100 mm at exit", '
                             '"rule avoid fires within 1 s", "rule cruise never fires", '
                             '"timeout", "no contact", "exit"]\n')
    r = epuckc("test", tmp_path)
    assert r.returncode == 1
    out = r.stdout
    assert "expect `exit within 3 s`: the program exited at 4001 ms, after 3000 ms" in out
    assert "expect `x > 100 mm at exit`: x is 46.5 at exit (4001 ms)" in out
    assert "expect `rule avoid fires within 1 s`: rule `avoid` first fired at 1200 ms, " \
           "after 1000 ms" in out
    assert "expect `rule cruise never fires`: rule `cruise` fired at 2275 ms" in out
    assert "expect `timeout`: the program exited at 4001 ms, before the time limit" in out
    assert "expect `no contact`: `no contact` needs a world" in out
    assert "expect `exit`:" not in out


def test_at_exit_needs_an_exit(tmp_path):
    make_case(tmp_path, toml='time_limit = "2s"\nexpect = ["x > 0 mm at exit", "timeout"]\n')
    r = epuckc("test", tmp_path)
    assert r.returncode == 1
    assert "the program did not exit (time limit at 2000 ms)" in r.stdout
    assert "write `at end`" in r.stdout and "expect `timeout`" not in r.stdout


def test_properties_and_golden_together(tmp_path):
    make_case(tmp_path, toml='trace = true\nexpect = ["exit within 5 s"]\n')
    r = epuckc("test", tmp_path)
    assert r.returncode == 1 and "avoid.trace is missing" in r.stdout
    assert "expect `exit" not in r.stdout


def test_property_checks_in_a_world(tmp_path):
    from epuckc.sim.enki import enki_available
    if not enki_available():
        pytest.skip("Enki is not installed (libenki-dev)")
    world = "arena 60 cm x 40 cm\nrobot r1 at 10 cm, 20 cm heading 0 deg\n" \
            "robot r2 at 50 cm, 10 cm heading 90 deg\n"
    program = "on immediate do start_straight(500 steps/s, 1 m)\non stop_motor do exit_main\n"
    make_case(tmp_path, name="crash", program=program, scenario=None,
              toml='time_limit = "6s"\nexpect = ["no contact", "r2: timeout", '
                   '"r1: x > 400 mm at end", "r3: exit"]\n')
    (tmp_path / "crash.world").write_text(world)
    r = epuckc("test", tmp_path)
    assert r.returncode == 1, r.stdout + r.stderr
    out = r.stdout
    # r1 drives along the arena; r2 runs into its far wall
    assert re.search(r"expect `no contact`: r2: collisions in \d+ physics steps, the first at "
                     r"\d+ ms", out), out
    assert "expect `r3: exit`: there is no robot `r3` in this run (robots: r1, r2)" in out
    assert "r2: timeout" not in out and "r1: x" not in out


def test_a_world_golden_within_tolerances(tmp_path):
    """As after a change of Enki: every robot's poses and times moved a
    little; its lines carry the robot's name."""
    from epuckc.sim.enki import enki_available
    if not enki_available():
        pytest.skip("Enki is not installed (libenki-dev)")
    program = ("on immediate do start_sensor, start_straight(500 steps/s, 20 cm)\n"
               "rule near: on sensor(ir0 > 300, ir7 > 300) repeat priority 1 do stop_motor\n"
               "on stop_motor do exit_main\n")
    make_case(tmp_path, name="walls", program=program, scenario=None)
    (tmp_path / "walls.world").write_text("arena 40 cm x 40 cm\nrobot at 10 cm, 20 cm\n"
                                          "robot at 30 cm, 20 cm heading 180 deg\n")
    assert epuckc("test", "--bless", tmp_path).returncode == 0
    trace = tmp_path / "walls.trace"
    assert trace.read_text().startswith("r1: [")
    trace.write_text(_shift(trace.read_text(), dx=-0.8, dt=4))
    r = epuckc("test", tmp_path)
    assert r.returncode == 1
    # the same event at the same time, somewhere else: the poses are named
    assert "at 1 ms robot r1: the rule at walls.epk:1 (`on immediate`) fired in both traces, " \
           "at pose (99.2, 200.0) 0.0 deg in the expected one, (100.0, 200.0) 0.0 deg in this " \
           "one" in r.stdout, r.stdout
    r = _with_tolerance(tmp_path, "[tolerance]\npose_mm = 1\ntime_ms = 5\n", name="walls")
    assert (r.returncode, r.stdout) == (0, "1 passed, 0 failed\n"), r.stdout + r.stderr


def test_long_diffs_are_cut_and_say_so():
    from epuckc.testing.compare import MAX_DIFF_LINES, trimmed_diff
    expected = "".join(f"line {i}\n" for i in range(200))
    actual = "".join(f"line {i}{' changed' if i >= 100 else ''}\n" for i in range(200))
    diff = trimmed_diff(expected, actual, "a (expected)", "b (this run)", 100)
    lines = diff.splitlines()
    assert len(lines) == MAX_DIFF_LINES + 1
    assert lines[-1].startswith("... (") and lines[-1].endswith("more diff lines)")
    # it starts at the first difference, with its context, not at the top
    assert lines[2].startswith("@@ -98,") and lines[3] == " line 97"
