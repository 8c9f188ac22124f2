"""Scenario files checked before a run (epuckc/sim/scenario.py) against the
host harness that reads them (runtime_c/platform/platform_host.c): on the same
files, good or broken, both say yes or no alike, and the harness's first
broken line is the first the checker reports. The checker reports every
problem of a file, each with its column and a caret."""
from __future__ import annotations

import os
import subprocess
from pathlib import Path

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from epuckc.sim.scenario import check_scenario
from tests.conftest import require_tool
from tests.support.programs import EXAMPLES, epuckc

GOOD = [
    b"0 ir0=0\n100 ms ir0=900\n0.2 s ir0=0\n0.005 min ir0=900\n",
    b"\xef\xbb\xbf0 ir0=0\r\n100ms IR7=12 amb3=4095\r250 ms mic=7 accx=2048 selector=15\n",
    b"# comment only\n\n10 ms key=mute key=7 mic2=1\n10 ms accz=0  # same time\n",
    b"0 ground0=1000 GROUND2=0\n20 ms ground1=4095\n",
]
BAD = [
    b"0 ir0=0\n100 xs ir0=900\n",
    b"0 ir0=0\n200 ms ir0=1\n150 ms ir0=2\n",
    b"0.5 ms ir0=1\n",
    b"hello\n",
    b"10 ms ir8=1\n",
    b"10 ms ir0=4096\n",
    b"10 ms key=power\n",
    b"10 ms\x00 ir0=1\n",
    b"10 ms ir0=1\x07\n",
    b"1.0001 s ir0=1\n",
    b"9999999999 ms ir0=1\n",
    b"20 min ir0=1\n" + b"2000000 s ir0=1\n",
    b"10 ms " + b"ir0=1 " * 70 + b"\n",
    b"10 ms accw=3 selector=16 mic3=1\n",
    b"10 ms ground3=1\n",
    b"10 ms ground=1\n",
    b"10 ms ground1=4096\n",
]


@pytest.fixture(scope="module")
def harness(tmp_path_factory):
    """A host harness executable (any program: the scenario is read first)."""
    require_tool("cc")
    out = tmp_path_factory.mktemp("harness")
    epuckc("build", EXAMPLES / "paper_fig2.epk", "-o", out, check=True)
    return out / "paper_fig2"


def harness_verdict(exe: Path, path: Path):
    """(accepted, line of the harness's error or None)."""
    env = {k: v for k, v in os.environ.items() if not k.startswith("EPUCK_")}
    env.update(EPUCK_SCENARIO=str(path), EPUCK_TIME_LIMIT_MS="1", EPUCK_QUIET="1",
               EPUCK_TRACE="/dev/null")
    res = subprocess.run([str(exe)], env=env, capture_output=True, text=True, timeout=60)
    if res.returncode != 2:
        return True, None
    head = res.stderr.split(":", 3)
    return False, int(head[2]) if len(head) > 2 and head[2].isdigit() else None


def checker_verdict(path: Path):
    problems = check_scenario(path, "s.scn")
    return not problems, [int(p.split(":", 3)[1]) for p in problems]


@pytest.mark.parametrize("data", GOOD + BAD, ids=range(len(GOOD + BAD)))
def test_the_checker_and_the_harness_agree(harness, tmp_path, data):
    path = tmp_path / "s.scn"
    path.write_bytes(data)
    ok, line = harness_verdict(harness, path)
    fine, lines = checker_verdict(path)
    assert ok == fine == (data in GOOD), (ok, fine, lines)
    if not ok:
        assert lines[0] == line


WORDS = ["0", "10", "10ms", "ms", "s", "1.5", "2.", "min", "ir0=5", "IR3=4095", "ir8=1", "amb7=0",
         "mic=1", "mic2=9", "mic3=1", "accx=1", "accw=1", "selector=15", "selector=16",
         "key=mute", "key=128", "ground0=900", "ground3=1", "ground=5", "#", "x", "=", "\t"]


@settings(max_examples=60, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(st.lists(st.lists(st.sampled_from(WORDS), max_size=5).map(" ".join), max_size=6))
def test_random_scenarios_get_the_same_verdict(harness, tmp_path, lines):
    path = tmp_path / "r.scn"
    path.write_text("\n".join(lines) + "\n")
    ok, line = harness_verdict(harness, path)
    fine, found = checker_verdict(path)
    assert ok == fine, (lines, line, found)
    if not ok:
        assert found[0] == line, (lines, line, found)


def test_every_problem_at_once_with_a_caret(tmp_path):
    path = tmp_path / "s.scn"
    path.write_bytes(b"0 ir0=0\n100 xs ir0=900\n200ms ir9=5\n150 ms ir0=1\n")
    problems = check_scenario(path, "s.scn")
    assert [p.split(" error: ")[0] for p in problems] == ["s.scn:2:5:", "s.scn:3:7:",
                                                          "s.scn:4:1:"]
    assert problems[1].splitlines()[1:3] == [" 3 | 200ms ir9=5", "   |       ^"]
    assert "before the previous line's 200 ms" in problems[2]


def test_run_reports_them_before_building(tmp_path):
    (tmp_path / "bad.scn").write_bytes(b"0 ir0=0\n100 xs ir0=900\n10 ms ir9=1\n")
    result = epuckc("run", EXAMPLES / "paper_fig2.epk", "--scenario", tmp_path / "bad.scn",
                    env={"CC": "/nonexistent-compiler"})
    assert result.returncode == 2
    assert "bad.scn:2:5: error: unknown time unit" in result.stderr
    assert "bad.scn:3:1: error: time 10 ms is before" in result.stderr
    assert "2 errors in the scenario" in result.stderr
    assert "epuck host" not in result.stderr
