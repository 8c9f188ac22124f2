"""The rule language's state and continuous control, through the whole
pipeline: variables, expressions, `when`, guards, `every`/`after`/`wait`,
`set_speed`, `random` and odometry, checked, compiled, built and run on the
host harness with a trace; the 16-bit arithmetic of the runtime against the
checker's (stdlib/arith.py) under UBSan; the generated C of a program using
every feature under strict flags, UBSan and avr-gcc (16-bit int)."""
import json
import random
import subprocess

import pytest

from conftest import REPO, require_tool
from epuckc.base.resources import LIBRARY_SIMULATION, RUNTIME_CORE, RUNTIME_SIMULATED
from epuckc.stdlib import arith
from tests.support.programs import epuckc, run_program

RUNTIME = REPO / "runtime_c"
HOST = [*(RUNTIME / n for n in (*RUNTIME_CORE, *RUNTIME_SIMULATED)),
        RUNTIME / "platform" / "platform_host.c",
        RUNTIME / "host" / "scenario.c", *(RUNTIME / n for n in LIBRARY_SIMULATION)]
INCLUDES = [f"-I{RUNTIME}", f"-I{RUNTIME / 'epuck_api'}", f"-I{RUNTIME / 'host'}",
            f"-I{RUNTIME / 'epuck_api_unsimulated'}"]
STRICT = ["-std=c99", "-Wall", "-Wextra", "-Werror", "-pedantic"]
UBSAN = ["-g", "-fsanitize=address,undefined", "-fno-sanitize-recover=all"]

# Every feature of the language at once (the issue's own example, completed).
EVERY_FEATURE = """\
var bumps = 0
var cruise = 300 steps/s
var turned = 0 deg
const K = 1 steps/s

on immediate do start_sensor, start_straight(cruise, 10 cm) then wait(100 ms)
    then set_speed(left: cruise, right: cruise)
rule bump: on sensor(ir0 > 500) repeat priority 1 if bumps < 3
    do bumps += 1, start_straight(-cruise, 5 cm)
rule three: when bumps >= 3 priority 3 do stop_motor, led_on(body)
when ir0 > 500 and ir7 > 500 or not (selector == 0) repeat priority 2 do stop_motor
every 20 ms if bumps < 3 do set_speed(left: clamp(cruise - (ir0 + ir1) * K / 3, -1000, 1000),
    right: clamp(cruise - (ir6 + ir7) * K / 3, -1000, 1000))
every 500 ms do cruise = random(200, 400) * 1 steps/s, turned = heading
after 3 s priority 4 do stop_motor, exit_main
when abs(heading) >= 90 deg or x > 1 m or y < -50 cm or mic0 > 4000 or acc_z % 7 == 8
    do led_toggle(front)
on timer(1 s) do bumps -= max(min(ambient3 / 100, 2), 0) - 30000 * 2
"""

SCENARIO = """\
0 ms ir0=0 ir7=0
700 ms ir0=900 ir7=900
800 ms ir0=0 ir7=0
1500 ms ir0=900
1600 ms ir0=0
"""


def _write(tmp_path, name, text):
    path = tmp_path / name
    path.write_text(text, encoding="utf-8")
    return path


# ---- the arithmetic: runtime == checker ---------------------------------------------

ARITH_HARNESS = r"""
#include <stdio.h>
#include "epuckrt.h"
int main(void)
{
    long a, b, c;
    while (scanf("%ld %ld %ld", &a, &b, &c) == 3)
        printf("%ld %ld %ld %ld %ld %ld %ld %ld %ld %ld %d\n", rt_add(a, b), rt_sub(a, b),
               rt_mul(a, b), rt_div(a, b), rt_mod(a, b), rt_neg(a), rt_abs(a), rt_min(a, b),
               rt_max(a, b), rt_clamp(a, b, c), rt_sat16(a));
    return 0;
}
"""


def test_runtime_arithmetic_is_the_checkers(tmp_path):
    """Saturation at 32 bits, truncating division, division by 0, and the
    16-bit saturation of a stored value: the C runtime and stdlib/arith.py
    (which the checker folds and bounds with) agree on the corners of 16 and
    32 bits and on random operands, with UBSan watching the C."""
    cc = require_tool("cc")
    src = _write(tmp_path, "arith.c", ARITH_HARNESS)
    exe = tmp_path / "arith"
    subprocess.run([cc, *STRICT, *UBSAN, *INCLUDES, str(src), *map(str, HOST), "-o", str(exe), "-lm"],
                   check=True)
    corners = [-2**31, -2**31 + 1, -46341, -32769, -32768, -32767, -30000, -256, -3, -1, 0, 1,
               2, 3, 181, 182, 255, 30000, 32767, 32768, 46340, 46341, 2**31 - 1]
    rng = random.Random(16)
    cases = [(a, b, c) for a in corners for b in corners for c in corners[::4]]
    cases += [tuple(rng.randint(-32768, 32767) for _ in range(3)) for _ in range(3000)]
    cases += [tuple(rng.randint(-2**31, 2**31 - 1) for _ in range(3)) for _ in range(3000)]
    result = subprocess.run([str(exe)], input="".join(f"{a} {b} {c}\n" for a, b, c in cases),
                            capture_output=True, text=True, check=True)
    assert "runtime error" not in result.stderr
    for (a, b, c), line in zip(cases, result.stdout.splitlines()):
        expected = [arith.add(a, b), arith.sub(a, b), arith.mul(a, b), arith.div(a, b),
                    arith.mod(a, b), arith.neg(a), arith.absolute(a), min(a, b), max(a, b),
                    arith.clamp(a, b, c), arith.sat(a)]
        assert list(map(int, line.split())) == expected, (a, b, c)


def test_intervals_hold_every_value():
    """The checker's intervals (arith.interval) contain every result of
    their operation over operands drawn from the operands' intervals."""
    rng = random.Random(7)
    ends = [-2**31, -32768, -1000, -1, 0, 1, 3, 4095, 32767, 2**31 - 1]
    for op in ("+", "-", "*", "/", "%", "min", "max", "neg", "abs", "clamp"):
        for _ in range(400):
            ivs = [tuple(sorted((rng.choice(ends + [rng.randint(-99, 99)]),
                                 rng.choice(ends + [rng.randint(-99, 99)])))) for _ in range(3)]
            lo, hi = arith.interval(op, *ivs)
            f = {"neg": lambda a, b, c: arith.neg(a), "abs": lambda a, b, c: arith.absolute(a),
                 "clamp": arith.clamp}.get(op) or (lambda a, b, c: arith.BINARY[op](a, b))
            for _ in range(30):
                values = [rng.randint(*iv) for iv in ivs]
                assert lo <= f(*values) <= hi, (op, ivs, values)


# ---- host runs --------------------------------------------------------------------------

def _sets(records, var):
    return [(r["t_ms"], r["value"]) for r in records if r["kind"] == "set" and r["var"] == var]


def test_counting_with_a_variable_a_guard_and_a_when_rule(tmp_path):
    records, out = run_program(REPO / "examples" / "bump_counter.epk", tmp_path, "--scenario",
                               REPO / "examples" / "bumps.scn", "--time-limit", "10s")
    assert _sets(records, "bumps") == [(1000, 1), (3000, 2), (5000, 3)]
    done = [r for r in records if r["kind"] == "event" and "rule done" in r["name"]]
    assert [r["t_ms"] for r in done] == [5001]       # the poll after the third bump
    assert [r["t_ms"] for r in records if r["kind"] == "exit"] == [5501]   # wait(500 ms)
    assert "set       bumps = 3" in epuckc("run", REPO / "examples" / "bump_counter.epk",
                                          "--scenario", REPO / "examples" / "bumps.scn").stdout


def test_every_after_and_wait_keep_their_own_times(tmp_path):
    prog = _write(tmp_path, "times.epk", """\
var n = 0
var m = 0
every 100 ms do n += 1
after 250 ms do m = 7
every 40 ms do m -= 1
on immediate do led_on(body) then wait(320 ms) then led_off(body) then wait(100 ms)
    then exit_main
""")
    records, _ = run_program(prog, tmp_path)
    assert [t for t, _ in _sets(records, "n")] == [101, 201, 301, 401]
    assert (251, 7) in _sets(records, "m")
    assert [t for t, _ in _sets(records, "m")][:3] == [41, 81, 121]
    leds = [r["t_ms"] for r in records if r["kind"] == "led"]
    assert leds == [1, 321]
    assert [r["t_ms"] for r in records if r["kind"] == "exit"] == [421]


def test_values_saturate_at_16_bits(tmp_path):
    prog = _write(tmp_path, "sat.epk", """\
var v = 30000
var w = -30000
var q = 7
on immediate do v += 30000, w -= 30000 * 2, q = -32768 / -1 + q % ir0 then exit_main
""")
    records, _ = run_program(prog, tmp_path)
    assert _sets(records, "v") == [(1, 32767)]
    assert _sets(records, "w") == [(1, -32768)]
    assert _sets(records, "q") == [(1, 32767)]      # -32768 / -1 saturates; % 0 gives 0
    # (`% ir0` can be 0: a warning that says so, not an error)
    assert "W014" in epuckc("check", prog).stderr


def test_when_fires_on_rising_edges_of_a_conjunction(tmp_path):
    prog = _write(tmp_path, "both.epk", """\
var both = 0
var either = 0
when ir0 > 500 and ir7 > 500 repeat do both += 1
when ir0 > 500 or ir7 > 500 repeat do either += 1
after 1 s do exit_main
""")
    scn = _write(tmp_path, "both.scn", """\
0 ms ir0=0 ir7=0
100 ms ir0=900
200 ms ir7=900
300 ms ir0=0
400 ms ir0=900
500 ms ir0=0 ir7=0
600 ms ir0=600 ir7=600
""")
    records, _ = run_program(prog, tmp_path, "--scenario", scn)
    assert [t for t, _ in _sets(records, "both")] == [200, 400, 600]
    assert [t for t, _ in _sets(records, "either")] == [100, 600]


def test_random_is_reproducible_and_follows_the_seed(tmp_path):
    prog = _write(tmp_path, "dice.epk", """\
var d = 0
every 10 ms do d = random(1, 6)
after 300 ms do exit_main
""")

    def throws(*seed):
        records, _ = run_program(prog, tmp_path, *seed)
        return [v for _, v in _sets(records, "d")]
    first, again, other = throws(), throws("--seed", "1"), throws("--seed", "2")
    assert first == again and first != other
    assert set(first) <= set(range(1, 7)) and len(set(first)) >= 4


def test_odometry_follows_the_wheels(tmp_path):
    prog = _write(tmp_path, "odo.epk", """\
var fx = 0 mm
var fy = 0 mm
var h = 0 deg
on immediate do start_straight(300, 100 mm) then start_curve(radius: 0 mm, degrees: 90 deg,
    speed: 300) then start_straight(300, 50 mm)
when heading >= 45 deg do h = heading
when x >= 60 mm do fx = x
on stop_motor do fx = x, fy = y
after 6 s do exit_main
""")
    records, _ = run_program(prog, tmp_path)
    xs, ys = _sets(records, "fx"), _sets(records, "fy")
    assert xs[0][1] == 60                         # the poll it passed 60 mm
    assert 99 <= xs[-1][1] <= 101                 # 100 mm forward, a quarter turn on the spot,
    assert 49 <= ys[-1][1] <= 51                  # then 50 mm to the left
    assert 45 <= _sets(records, "h")[0][1] <= 47
    pose = [r for r in records if r["kind"] == "exit"][0]
    assert abs(pose["x_mm"] - xs[-1][1]) <= 1.5 and abs(pose["y_mm"] - ys[-1][1]) <= 1.5


def test_set_speed_is_a_motor_command_under_priorities(tmp_path):
    prog = _write(tmp_path, "prio.epk", """\
on immediate priority 2 do start_straight(200, 1 cm)
every 10 ms do set_speed(left: 500, right: -500)
after 600 ms do exit_main
""")
    records, _ = run_program(prog, tmp_path)
    suppressed = [r for r in records if r["kind"] == "suppressed"]
    assert suppressed and all(r["command"] == "set_speed" for r in suppressed)
    # the straight of higher priority drives its 1 cm undisturbed; then set_speed spins
    last = [r for r in records if r["kind"] == "exit"][0]
    assert 9.5 <= last["x_mm"] <= 10.5 and last["heading_deg"] < -20


# ---- the generated C of every feature ----------------------------------------------

def _compiled(tmp_path):
    prog = _write(tmp_path, "every.epk", EVERY_FEATURE)
    result = epuckc("check", prog)
    assert result.returncode == 0, result.stderr
    c = tmp_path / "every.c"
    epuckc("compile", prog, "-o", c, check=True)
    return prog, c


def test_every_feature_runs_clean_under_ubsan(tmp_path):
    cc = require_tool("cc")
    prog, c = _compiled(tmp_path)
    exe = tmp_path / "every"
    subprocess.run([cc, *STRICT, *UBSAN, *INCLUDES, str(c), *map(str, HOST), "-o", str(exe), "-lm"],
                   check=True)
    scn = _write(tmp_path, "every.scn", SCENARIO)
    trace = tmp_path / "every.jsonl"
    result = subprocess.run([str(exe)], capture_output=True, text=True,
                            env={"EPUCK_TRACE": str(trace), "EPUCK_SCENARIO": str(scn),
                                 "EPUCK_QUIET": "1", "EPUCK_TIME_LIMIT_MS": "5000"})
    assert result.returncode == 0, result.stderr
    assert "runtime error" not in result.stderr and "Sanitizer" not in result.stderr
    records = [json.loads(line) for line in trace.read_text().splitlines()]
    assert [v for _, v in _sets(records, "bumps")][:2] == [1, 2]
    assert [r["t_ms"] for r in records if r["kind"] == "exit"] == [3001]


def test_every_feature_builds_for_a_16_bit_int(tmp_path):
    """avr-gcc: int is 16 bits there, as on the dsPIC."""
    avr = require_tool("avr-gcc")
    _, c = _compiled(tmp_path)
    for source in [c, *(RUNTIME / n for n in RUNTIME_CORE), RUNTIME / "platform" / "platform_robot.c"]:
        subprocess.run([avr, "-mmcu=atmega128", *STRICT, "-Os", *INCLUDES, "-c", str(source),
                        "-o", str(tmp_path / "x.o")], check=True)


@pytest.mark.parametrize("example", ["braitenberg.epk", "wall_follower.epk",
                                     "bump_counter.epk", "random_walk.epk"])
def test_course_examples_check_clean(example):
    result = epuckc("check", REPO / "examples" / example)
    assert result.returncode == 0 and result.stderr == "", result.stderr


def test_a_modes_own_timers_count_from_its_entry(tmp_path):
    prog = _write(tmp_path, "modes.epk", """\
var n = 0
initial mode a {
    after 100 ms do n += 1, enter b
}
mode b {
    after 50 ms do enter a
}
after 500 ms do exit_main
""")
    records, _ = run_program(prog, tmp_path)
    # each entry re-arms the mode's `after`: 100 ms in a, 50 ms in b (+1 ms: the
    # mode's rules are polled from the poll after the entry)
    assert [t for t, _ in _sets(records, "n")] == [101, 253, 405]


def test_when_needs_no_start_sensor_and_sensor_rules_still_do(tmp_path):
    """Both are compiled conditions of one function; the sensor rule's is
    false while the sensors are off, the `when` rule's is not."""
    prog = _write(tmp_path, "gates.epk", """\
var n = 0
var m = 0
when ir0 > 500 repeat do n += 1
on sensor(ir0 > 500) repeat do m += 1
after 300 ms do start_sensor
after 600 ms do exit_main
""")
    scn = _write(tmp_path, "gates.scn", "0 ms ir0=0\n100 ms ir0=900\n200 ms ir0=0\n"
                                        "400 ms ir0=900\n500 ms ir0=0\n")
    records, _ = run_program(prog, tmp_path, "--scenario", scn)
    assert [t for t, _ in _sets(records, "n")] == [100, 400]
    assert [t for t, _ in _sets(records, "m")] == [400]
    assert "RT_CONDITIONS_ALWAYS" in epuckc("compile", prog, "-o", "-").stdout
