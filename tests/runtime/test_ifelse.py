"""`if/else` actions run (issue 25, point 4): checked, compiled, built with
gcc under -Werror and UBSan, run on the host harness with a scenario whose
trace shows which branch each poll took; a condition reads the values the
calls before it in the step assigned; a motion started in a branch drives
the wheels; the same program built for a 16-bit int (avr-gcc) runs on
simavr to the host's trace (tests/runtime/test_avr_trace.py, "if_else")."""
import json
import subprocess

from conftest import require_tool
from tests.runtime.test_language import HOST, INCLUDES, STRICT, UBSAN
from tests.support.programs import epuckc

# zone: 3 touching, 2 near, 1 clear after the first half second, 0 before
IF_ELSE = """\
var zone = -1
var ticks = 0
var seen = 0
on immediate do start_sensor
every 10 ms do ticks = clamp(ticks + 1, 0, 1000),
    if ir0 > 2000 { zone = 3, stop_motor }
    else if ir0 > 500 { zone = 2, set_speed(100, 100) }
    else if ticks > 50 { zone = 1 }
    else { zone = 0 }
every 10 ms priority 1 do seen = 0, if seen == 0 { seen = ticks } else { seen = -1 }
after 1 s priority 2 do exit_main
"""

SCENARIO = """\
0 ms ir0=0
300 ms ir0=900
500 ms ir0=3000
700 ms ir0=0
"""


def _sets(records, var):
    return [(r["t_ms"], r["value"]) for r in records if r["kind"] == "set" and r["var"] == var]


def test_the_branch_taken_follows_the_readings(tmp_path):
    prog = tmp_path / "zones.epk"
    prog.write_text(IF_ELSE, encoding="utf-8")
    assert epuckc("check", prog).returncode == 0
    c = tmp_path / "zones.c"
    epuckc("compile", prog, "-o", c, check=True)
    c_text = c.read_text()
    assert "} else if (" in c_text and "} else {" in c_text     # plain, readable C
    exe = tmp_path / "zones"
    subprocess.run([require_tool("cc"), *STRICT, *UBSAN, *INCLUDES, str(c), *map(str, HOST),
                    "-o", str(exe)], check=True)
    scn = tmp_path / "zones.scn"
    scn.write_text(SCENARIO, encoding="utf-8")
    trace = tmp_path / "zones.jsonl"
    result = subprocess.run([str(exe)], capture_output=True, text=True,
                            env={"EPUCK_TRACE": str(trace), "EPUCK_SCENARIO": str(scn),
                                 "EPUCK_QUIET": "1", "EPUCK_TIME_LIMIT_MS": "5000"})
    assert result.returncode == 0, result.stderr
    assert "runtime error" not in result.stderr and "Sanitizer" not in result.stderr
    records = [json.loads(line) for line in trace.read_text().splitlines()]
    zones = _sets(records, "zone")
    values = [v for _, v in zones]
    # each change of branch, in order: the else, then near, touching, clear
    assert values == [0, 2, 3, 1], zones
    times = dict((v, t) for t, v in zones)
    assert 300 <= times[2] < 320 and 500 <= times[3] < 520 and 700 <= times[1] < 720
    # `seen = 0, if seen == 0 {...}`: the condition reads the value assigned
    # just before it in the step, so the `else` never runs
    assert -1 not in [v for _, v in _sets(records, "seen")]
    assert len(_sets(records, "seen")) > 10
    # the motion of the `near` branch drove the wheels between 300 and 500 ms,
    # and the `touching` branch stopped them
    events = [r for r in records if r["kind"] == "event"]
    at = lambda t: max((r for r in events if r["t_ms"] <= t), key=lambda r: r["t_ms"])
    assert at(490)["left_steps"] > at(320)["left_steps"]
    assert at(690)["left_steps"] == at(530)["left_steps"]


def test_the_16_bit_build_compiles(tmp_path):
    avr = require_tool("avr-gcc")
    prog = tmp_path / "zones.epk"
    prog.write_text(IF_ELSE, encoding="utf-8")
    c = tmp_path / "zones.c"
    epuckc("compile", prog, "-o", c, check=True)
    subprocess.run([avr, "-mmcu=atmega128", *STRICT, "-Os", *INCLUDES, "-c", str(c),
                    "-o", str(tmp_path / "x.o")], check=True)


def test_a_wait_in_a_branch_delays_the_next_step_only_when_taken(tmp_path):
    from tests.support.programs import run_program
    program = ("var n = INIT\nevery 10 s do n = 1 - INIT\n"
               "on immediate do if n > 0 { wait(300 ms) } then led_on(body), n = 5\n"
               "after 1 s priority 1 do exit_main\n")
    for init, when in (("1", 301), ("0", 1)):
        path = tmp_path / f"wait{init}.epk"
        path.write_text(program.replace("INIT", init), encoding="utf-8")
        records, _ = run_program(path, tmp_path)
        assert _sets(records, "n") == [(when, 5)]
