"""The robot's tracer end to end on simavr: every example that the 16-bit
path runs (those without the e-puck2's devices, as tests/runtime/
test_avr_trace.py) and the language's test programs, built for the AVR
with the tracer of `epuckc build --trace` (runtime_c/rt_trace.c, the
e-puck's UART1 link over the ATmega's USART0 at the Bluetooth link's
speed), run in the robot's time, the UART's bytes decoded by `epuckc
monitor`'s decoder, as `epuckc run PROG --int16 --robot-trace` does:
equal to the host harness's trace of the same program and scenario, record
for record at the same ms (the pose, the monitor's odometry, within half a
millimetre and half a degree); a program that sends more than the link
carries has its records dropped, counted exactly where they are missing.
The readable trace is the host's too, within the same tolerance."""
import json
from pathlib import Path

import pytest

from conftest import REPO
from tests.runtime.test_avr_trace import EXAMPLES, EXTRA
from tests.support.programs import epuckc
from tests.support.robot_trace import (HEADING_DEG, POSE_MM, assert_robot_trace_is_hosts,
                                       link_load, require_simavr)

LIMIT = "5000ms"


def _run(program: Path, tmp: Path, *how) -> tuple:
    trace = tmp / f"{program.stem}{len(how)}.jsonl"
    scenario = program.with_suffix(".scn")
    more = ["--scenario", scenario] if scenario.is_file() else []
    r = epuckc("run", program, *how, *more, "--time-limit", LIMIT, "--trace", trace)
    assert r.returncode in (0, 3), r.stdout + r.stderr
    return [json.loads(line) for line in trace.read_text().splitlines()], r


# Where the host's records would fill the robot's link (link_load) the robot
# drops some; where they take well under it, none. Between (an estimate's
# margin: led_patterns, whose LED calls the robot sends only on a change),
# either may be right and the trace is compared as it comes.
FLOODS, FITS = 1.3, 0.7


@pytest.mark.parametrize("program", EXAMPLES + list(EXTRA), ids=lambda p: getattr(p, "stem", p))
def test_the_robots_trace_is_the_hosts(tmp_path, program):
    require_simavr()
    if isinstance(program, str):
        path = tmp_path / f"{program}.epk"
        path.write_text(EXTRA[program], encoding="utf-8")
        program = path
    host, host_run = _run(program, tmp_path)
    robot, robot_run = _run(program, tmp_path, "--int16", "--robot-trace")
    assert_robot_trace_is_hosts(host, robot)
    assert robot[-1]["kind"] in ("exit", "timeout") and robot[-1]["kind"] == host[-1]["kind"]
    assert robot_run.returncode == host_run.returncode
    load, dropped = link_load(host), any(r["kind"] == "dropped" for r in robot)
    if load >= FLOODS or load <= FITS:
        assert dropped == (load >= FLOODS), f"the host's records take {load:.2f} of the link"
    if not any(r["kind"] == "dropped" for r in robot):
        from epuckc.testing.case import Tolerance
        from epuckc.testing.compare import first_difference
        # the scenario's inputs are the harness's lines: the robot's tracer
        # sends what the program did, not what its sensors read
        a = [line for line in host_run.stdout.splitlines() if " ms] input " not in line]
        b = robot_run.stdout.splitlines()
        assert len(a) == len(b)
        assert first_difference(a, b, Tolerance(pose_mm=POSE_MM, heading_deg=HEADING_DEG)) \
            is None


def test_the_links_load_is_the_records_bytes_against_its_speed():
    """A burst larger than the buffers floods; the same records spread at
    less than the link's speed do not (link_load, tests/support)."""
    def sets(n, every_ms):
        return [{"t_ms": i * every_ms, "kind": "set", "var": "v", "value": 1000}
                for i in range(n)]
    assert link_load(sets(100, 0)) > FLOODS
    assert link_load(sets(100, 2)) < FITS           # 11 bytes every 2 ms: under 23
    assert link_load(sets(1000, 0.5)) > FLOODS      # 11 bytes every 0.5 ms: over 5.8
    assert link_load([{"t_ms": 0, "kind": "pose"}] * 1000) == 0


def test_robot_trace_needs_int16():
    r = epuckc("run", REPO / "examples" / "square.epk", "--robot-trace")
    assert r.returncode == 2 and "give --int16 with it" in r.stderr
