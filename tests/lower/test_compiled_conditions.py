"""The compiled sensor conditions and the runtime's table walk against a
model of the language's semantics: random sensor rules (one or two
conditions, one-shot or repeating, more than sixteen so that the state
spans several words), timer rules that stop or start the sensors in the
middle of the walk, and random scenarios; the events the harness fires must
be exactly the model's.  Also: every golden program compiles warning-free
with gcc and with 16-bit avr-gcc, with and without the robot's
EPUCKRT_NO_NAMES."""
from __future__ import annotations

import json
import os
import subprocess
from pathlib import Path

from epuckc.base.resources import LIBRARY_SIMULATION, RUNTIME_CORE, RUNTIME_SIMULATED
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from conftest import require_tool
from epuckc.diagnostics import Report
from epuckc.emit.program import emit_c
from epuckc.check.frontend import check_file

from tests.support.programs import REPO

RT = REPO / "runtime_c"
STRICT = ["-std=c99", "-Wall", "-Wextra", "-Werror", "-pedantic"]
SENSORS = 4
END_MS = 40


def _sensor_rule():
    condition = st.tuples(st.sampled_from([">", "<"]), st.integers(0, 1000))
    return st.tuples(st.dictionaries(st.integers(0, SENSORS - 1), condition, min_size=1,
                                     max_size=2),
                     st.booleans())


@st.composite
def programs(draw):
    rules = [("sensor", conds, repeat)
             for conds, repeat in draw(st.lists(_sensor_rule(), min_size=1, max_size=40))]
    for _ in range(draw(st.integers(0, 2))):
        rule = ("timer", draw(st.integers(1, 30)), draw(st.sampled_from(["stop_sensor",
                                                                          "start_sensor"])))
        rules.insert(draw(st.integers(0, len(rules))), rule)
    changes = draw(st.lists(st.tuples(st.integers(0, END_MS - 1), st.integers(0, SENSORS - 1),
                                      st.integers(0, 1000)), max_size=10))
    return rules, sorted(changes, key=lambda c: c[0])


def rule_file(rules) -> str:
    lines = ["on immediate do start_sensor, set_timer"]
    for rule in rules:
        if rule[0] == "timer":
            lines.append(f"on timer({rule[1]} ms) do {rule[2]}")
        else:
            conds = ", ".join(f"ir{n} {op} {value}" for n, (op, value) in sorted(rule[1].items()))
            lines.append(f"on sensor({conds}){' repeat' if rule[2] else ''} do stop_motor")
    return "\n".join(lines) + "\n"


def scenario(changes) -> str:
    return "".join(f"{t} ms ir{n}={v}\n" for t, n, v in changes)


def model(rules, changes) -> list:
    """(event id, t_ms) of every firing, by the semantics of docs/runtime.md:
    polls at 1, 2, ... ms walk the events in order; a sensor event occurs
    when `sensors on and some condition holds` becomes true (false before
    its first poll); start_sensor turns the sensors on from the next poll,
    stop_sensor at once; the timer starts at 1 ms, so `timer(T)` fires at
    T + 1."""
    readings = [0] * SENSORS
    pending = list(changes)
    armed = [True] * (len(rules) + 1)
    latch = [False] * (len(rules) + 1)
    sensors_on = starting = False
    fired = []
    for t in range(1, END_MS):
        while pending and pending[0][0] <= t:
            _, n, v = pending.pop(0)
            readings[n] = v
        if starting:
            sensors_on, starting = True, False
        if armed[0]:
            fired.append((0, t))
            armed[0] = False
            starting = not sensors_on
        for k, rule in enumerate(rules, 1):
            if not armed[k]:
                continue
            if rule[0] == "timer":
                if t - 1 >= rule[1]:
                    fired.append((k, t))
                    armed[k] = False
                    if rule[2] == "start_sensor":
                        starting = not sensors_on
                    else:
                        sensors_on = starting = False
                continue
            cond = sensors_on and any(readings[n] > value if op == ">" else readings[n] < value
                                      for n, (op, value) in rule[1].items())
            if cond and not latch[k]:
                fired.append((k, t))
                if not rule[2]:
                    armed[k] = False
            latch[k] = cond
    return fired


def build_and_run(text: str, scn: str, tmp_path: Path) -> list:
    epk = tmp_path / "rules.epk"
    epk.write_text(text)
    report = Report()
    result = check_file(epk, report)
    assert result.checked is not None, [d.message for d in report.diagnostics]
    c_file = tmp_path / "rules.c"
    c_file.write_text(emit_c(result.checked, text))
    exe = tmp_path / "rules"
    subprocess.run([require_tool("cc"), *STRICT, "-O1", "-DMAX_ACTIONS=1", "-DMAX_EVENTS=1",
                    f"-I{RT}", f"-I{RT / 'epuck_api'}", f"-I{RT / 'host'}",
                    f"-I{RT / 'epuck_api_unsimulated'}", str(c_file),
                    *(str(RT / name) for name in (*RUNTIME_CORE, *RUNTIME_SIMULATED)),
                    str(RT / "platform" / "platform_host.c"), str(RT / "host" / "scenario.c"),
                    *(str(RT / name) for name in LIBRARY_SIMULATION), "-o", str(exe), "-lm"],
                   check=True)
    (tmp_path / "rules.scn").write_text(scn)
    env = {k: v for k, v in os.environ.items() if not k.startswith("EPUCK_")}
    env.update(EPUCK_SCENARIO=str(tmp_path / "rules.scn"), EPUCK_TRACE=str(tmp_path / "t.jsonl"),
               EPUCK_TIME_LIMIT_MS=str(END_MS - 1), EPUCK_QUIET="1")
    res = subprocess.run([str(exe)], env=env, capture_output=True, text=True)
    assert res.returncode == 3, res.stderr       # the time limit ends the run
    records = [json.loads(line) for line in (tmp_path / "t.jsonl").read_text().splitlines()]
    return [(r["id"], r["t_ms"]) for r in records if r["kind"] == "event"]


@settings(max_examples=25, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(programs())
def test_compiled_conditions_follow_the_semantics(tmp_path, program):
    rules, changes = program
    assert build_and_run(rule_file(rules), scenario(changes), tmp_path) == model(rules, changes)


def test_model_sees_edges_and_mid_walk_stops(tmp_path):
    """A fixed case, so that the model itself is checked: the sensors
    started at 1 ms are read from 2 ms; rule 3 is after the timer that stops
    the sensors at 6 ms, rule 1 before it."""
    rules = [("sensor", {0: (">", 500)}, True), ("timer", 5, "stop_sensor"),
             ("sensor", {0: (">", 500)}, True), ("sensor", {1: ("<", 10)}, False)]
    changes = [(0, 0, 900), (3, 0, 0), (4, 0, 900), (4, 1, 50)]
    expected = [(0, 1), (1, 2), (3, 2), (4, 2), (1, 4), (3, 4), (2, 6)]
    assert model(rules, changes) == expected
    assert build_and_run(rule_file(rules), scenario(changes), tmp_path) == expected


GOLDEN_C = sorted((REPO / "tests" / "golden" / "expected").glob("*.c"))


@pytest.mark.parametrize("c_file", GOLDEN_C, ids=[p.stem for p in GOLDEN_C])
@pytest.mark.parametrize("compiler", ["cc", "avr-gcc"])
def test_generated_c_is_strict_on_gcc_and_16_bit_avr_gcc(c_file, compiler, tmp_path):
    tool = require_tool(compiler)
    target = ["-mmcu=atmega128", "-Os"] if compiler == "avr-gcc" else ["-O2"]
    for names in ([], ["-DEPUCKRT_NO_NAMES"]):
        res = subprocess.run([tool, *STRICT, *target, *names, f"-I{RT}", f"-I{RT / 'epuck_api'}",
                              f"-I{REPO / 'tests' / 'golden'}", "-c", str(c_file),
                              "-o", str(tmp_path / "x.o")], capture_output=True, text=True)
        assert res.returncode == 0, res.stderr


@pytest.mark.parametrize("compiler", ["cc", "avr-gcc"])
def test_a_program_without_rules_still_builds(compiler, tmp_path):
    """W006 is only a warning: the C of a rule-less program (no tables) must
    compile strictly too."""
    tool = require_tool(compiler)
    text = "const x = 3 cm\n"
    epk = tmp_path / "empty.epk"
    epk.write_text(text)
    result = check_file(epk, Report())
    assert result.checked is not None
    c_file = tmp_path / "empty.c"
    c_file.write_text(emit_c(result.checked, text))
    assert "register_program(&" not in c_file.read_text()
    target = ["-mmcu=atmega128", "-Os"] if compiler == "avr-gcc" else ["-O2"]
    res = subprocess.run([tool, *STRICT, *target, f"-I{RT}", f"-I{RT / 'epuck_api'}", "-c",
                          str(c_file), "-o", str(tmp_path / "x.o")], capture_output=True, text=True)
    assert res.returncode == 0, res.stderr
