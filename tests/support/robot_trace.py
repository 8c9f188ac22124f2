"""The robot's trace for tests: a rule program built for the 16-bit AVR
with the robot's tracer and run on simavr (epuckc/sim/int16.py), its
UART's bytes and its table; and the comparison of a decoded robot trace
with the host harness's trace of the same program and scenario."""
from __future__ import annotations

import math
from pathlib import Path

from conftest import require_tool

# what the robot's trace has of the host's (not `input`, the scenario's;
# not `pose`, which each side gives at its own moments)
POSE = ("x_mm", "y_mm", "heading_deg")
POSE_MM, HEADING_DEG = 0.5, 0.5     # the monitor's odometry of the steps against the harness's


def require_simavr():
    for tool in ("cc", "avr-gcc", "simavr"):
        require_tool(tool)
    if not Path("/usr/include/simavr/sim_avr.h").exists():
        require_tool("libsimavr-dev (the simavr headers)")


def program_of(path: Path, text: str = None):
    """A rule file (written first when `text` is given) as a Program."""
    from epuckc.cli.driver import load_program
    from epuckc.diagnostics import Report
    if text is not None:
        path.write_text(text, encoding="utf-8")
    program = load_program(path, Report())
    assert program is not None, path
    return program


def robot_run(program, scenario=None, time_limit_ms=5000, tracer=True):
    """The 16-bit build with the tracer on simavr: sim.int16.RobotRun."""
    from epuckc.sim.int16 import run_int16_robot
    return run_int16_robot(program, str(scenario) if scenario else None, time_limit_ms, tracer)


def decode(table, data: bytes) -> list:
    from epuckc.link.stream import TraceDecoder
    decoder = TraceDecoder(table)
    return decoder.feed(data) + decoder.close()


def _without_pose(r: dict) -> dict:
    return {k: v for k, v in r.items() if k not in POSE}


def assert_robot_trace_is_hosts(host: list, robot: list):
    """Record for record, at the same ms, every field but the pose equal
    (the pose within POSE_MM and HEADING_DEG: the monitor's odometry of
    the wheels' steps, the harness's own of the same steps); records the
    robot dropped are missing exactly where its `dropped` records say, as
    many as they count. No record is lost on the simulated link."""
    host = [r for r in host if r["kind"] not in ("input", "pose")]
    robot = [r for r in robot if r["kind"] != "pose"]
    assert not [r for r in robot if r["kind"] == "lost"], "frames lost on a faultless link"
    at, pending = 0, 0
    for r in robot:
        if r["kind"] == "dropped":
            pending += r["count"]
            continue
        at += pending
        pending = 0
        assert at < len(host), f"the robot has more than the host: {r}"
        h = host[at]
        assert _without_pose(r) == _without_pose(h), f"record {at}: host {h}\n robot {r}"
        if "x_mm" in h:
            assert math.hypot(r["x_mm"] - h["x_mm"], r["y_mm"] - h["y_mm"]) <= POSE_MM, (h, r)
            d = abs((r["heading_deg"] - h["heading_deg"] + 180.0) % 360.0 - 180.0)
            assert d <= HEADING_DEG, (h, r)
        at += 1
    assert at + pending == len(host), f"host records after the robot's last: {host[at:][:3]}"


# ---- how much of the robot's link a host trace would take --------------------------
# runtime_c/rt_trace.c: a payload is its kind, a sequence byte and 16 bits of
# the clock, then its fields (ids and counts unsigned LEB128, values zigzag,
# the wheels' two 16-bit counters); on the wire COBS(payload, CRC-16) and a 0;
# records wait in a ring of 256 bytes and a piece of 96 being sent; the link is
# 115200 baud 8N1: 11.52 bytes a millisecond.
LINK_BYTES_PER_MS = 115200 / 10 / 1000
LINK_BUFFER = 256 + 96
_WHEELS = 4


def _uvar(v: int) -> int:
    n = 1
    while v >= 0x80:
        v >>= 7
        n += 1
    return n


def _svar(v: int) -> int:
    return _uvar(((-(v + 1)) << 1) | 1 if v < 0 else v << 1)


def _fields(r: dict):
    """The bytes of a record's fields on the robot's link, or None for a
    record the robot's tracer does not send (poses, inputs, the world's)."""
    kind = r["kind"]
    if kind == "event":
        return _uvar(max(r["id"], 0)) + _WHEELS
    if kind == "action":
        step = _uvar(r["step"]) + _uvar(r["steps"]) if "step" in r else 0
        return _uvar(max(r["id"], 0)) + _WHEELS + step
    if kind == "set":
        value = r["value"]
        return 1 + (_svar(int(value)) if isinstance(value, (int, float)) else 3)
    if kind == "suppressed":
        return 4 + _WHEELS
    if kind in ("mode", "sound", "send", "motors", "led"):
        return 2 + _WHEELS
    if kind == "message":
        return 6 + _WHEELS
    if kind in ("exit", "timeout"):
        return _WHEELS
    return None


def link_load(records: list) -> float:
    """The largest backlog the host trace's records would make on the
    robot's link (a leaky bucket draining at the link's speed), as a share
    of the tracer's buffers: above 1 the robot must drop records, well
    below it must not. An estimate (the tracer sends an LED only when it
    changes, and frames at the link's pace), good away from 1."""
    backlog, before, worst = 0.0, 0, 0.0
    for r in records:
        fields = _fields(r)
        if fields is None:
            continue
        backlog = max(0.0, backlog - (r["t_ms"] - before) * LINK_BYTES_PER_MS)
        before = r["t_ms"]
        backlog += 4 + fields + 2 + 2       # kind, sequence, clock; CRC; COBS's code, the 0
        worst = max(worst, backlog)
    return worst / LINK_BUFFER
