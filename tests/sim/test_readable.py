"""The readable trace from JSON records (epuckc/sim/readable.py), which
`epuckc monitor` prints for a robot's trace and `epuckc test` compares for
a recorded one: for every example, run on the host harness, the lines made
from its JSON trace (the steps' texts from the program's trace table) are
exactly what the harness printed."""
import json

import pytest

from conftest import REPO
from epuckc.build.trace_table import trace_table
from epuckc.sim.readable import readable_line, readable_trace
from tests.support.programs import epuckc
from tests.support.robot_trace import program_of

# examples that between them trace every kind of record the harness prints
# (events, actions, steps, set, suppressed, mode, led, sound, input, send,
# exit, timeout), and the language's every-feature program
EXAMPLES = [REPO / "examples" / f"{name}.epk" for name in (
    "explorer", "selector_menu", "go_to_goal", "histogram", "leader", "paper_fig2",
    "two_phase", "extern_spin")] + ["every_feature"]


@pytest.mark.parametrize("example", EXAMPLES, ids=lambda p: getattr(p, "stem", p))
def test_the_readable_trace_of_the_records_is_the_harnesss(tmp_path, example):
    if example == "every_feature":
        from tests.runtime.test_language import EVERY_FEATURE
        example = tmp_path / "every_feature.epk"
        example.write_text(EVERY_FEATURE, encoding="utf-8")
    scenario = example.with_suffix(".scn")
    trace = tmp_path / "t.jsonl"
    more = ["--scenario", scenario] if scenario.is_file() else []
    r = epuckc("run", example, *more, "--time-limit", "8s", "--trace", trace)
    assert r.returncode in (0, 3), r.stderr
    records = [json.loads(line) for line in trace.read_text().splitlines()]
    steps = trace_table(program_of(example))["steps"]
    assert readable_trace(records, lambda a: steps.get(str(a), [])) == r.stdout


def test_a_worlds_readable_trace_is_the_runners_robot_by_robot(tmp_path, enki):
    """In a world, messages arrive (their lines come from the world runner's
    harness): each robot's lines from its records are what the run printed
    for it, in order, `robot: ` before each."""
    trace = tmp_path / "t.jsonl"
    r = epuckc("run", "--world", REPO / "examples" / "follow.world", "--time-limit", "2s",
               "--trace", trace)
    assert r.returncode in (0, 3), r.stderr
    records = [json.loads(line) for line in trace.read_text().splitlines()]
    assert {"send", "message"} <= {rec["kind"] for rec in records}
    for robot in ("leader", "follower"):
        own = [rec for rec in records if rec.get("robot") == robot]
        printed = [line for line in r.stdout.splitlines() if line.startswith(f"{robot}: [")]
        lines = [line for line in map(readable_line, own) if line is not None]
        assert lines == [line.removeprefix(f"{robot}: ") for line in printed]


def test_a_robots_message_has_the_line_of_what_it_knows():
    """A robot's trace (link/stream.py) has no sender's name nor sensor."""
    record = {"t_ms": 120, "kind": "message", "name": "message", "id": -1, "value": 7,
              "bearing_deg": -17.0, "range_mm": 137.0}
    assert readable_line(record) == \
        "[   120 ms] message   7, bearing -17.0 deg, range 137.0 mm"
