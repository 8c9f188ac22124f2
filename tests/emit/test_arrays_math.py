"""Issue 25 through the whole pipeline: arrays, their functions, the math
functions and exact 32-bit intermediates, checked, lowered, built for 32
and 16 bits under -Werror, and run; every value the running program
computes is what the checker folds and what a Python model of the
language computes from the same readings."""
from __future__ import annotations

import math
import random
import subprocess

import pytest

from conftest import REPO, require_tool
from epuckc.stdlib import arith, imath
from tests.support.programs import epuckc, run_program

RUNTIME = REPO / "runtime_c"
STRICT = ["-std=c99", "-Wall", "-Wextra", "-Werror", "-pedantic"]


def _final(records) -> dict:
    return {r["var"]: r["value"] for r in records if r["kind"] == "set"}


def _sets(records, var) -> list:
    return [r["value"] for r in records if r["kind"] == "set" and r["var"] == var]


def _build_both(tmp_path, path):
    """The generated C builds with gcc and with avr-gcc (16-bit int)."""
    c = tmp_path / "prog.c"
    epuckc("compile", path, "-o", c, check=True)
    cc, avr = require_tool("cc"), require_tool("avr-gcc")
    subprocess.run([cc, *STRICT, f"-I{RUNTIME}", "-c", str(c), "-o", str(tmp_path / "a.o")],
                   check=True)
    subprocess.run([avr, "-mmcu=atmega128", *STRICT, "-Os", f"-I{RUNTIME}", "-c", str(c),
                    "-o", str(tmp_path / "b.o")], check=True)
    return c.read_text()


W_LEFT = [8, 4, 2, 0, 0, -4, -8, -16]
W_RIGHT = [-16, -8, -4, 0, 0, 2, 4, 8]


def test_weighted_sums_are_exact_where_the_robot_s_long_sum_is(tmp_path):
    """`(16 * ir7 + 16 * ir0) / 4` with both readings at 4000 is 32000, and
    GCtronic's weight matrix as `dot` gives its `long` sum divided once, for
    random readings over the whole range, on 32 and 16 bits."""
    rng = random.Random(25)
    readings = [[4000] * 8] + [[rng.randint(0, 4095) for _ in range(8)] for _ in range(40)]
    scenario = "\n".join(f"{10 * (k + 1)} ms " + " ".join(f"ir{i}={v}" for i, v in enumerate(r))
                         for k, r in enumerate(readings)) + "\n"
    (tmp_path / "r.scn").write_text(scenario)
    program = tmp_path / "w.epk"
    program.write_text(
        f"const L = {W_LEFT}\nconst R = {W_RIGHT}\n"
        "var pair = 0\nvar left = 0\nvar right = 0\n"
        "every 10 ms do pair = (16 * ir7 + 16 * ir0) / 4, left = dot(L, ir) / 4 + 550,\n"
        "    right = dot(R, ir) / 4 + 550\n"
        f"after {10 * len(readings) + 5} ms priority 1 do exit_main\n")
    c_text = _build_both(tmp_path, program)
    assert "rt_sat16" not in c_text             # proven inside 16 bits where stored
    records, _ = run_program(program, tmp_path, "--scenario", tmp_path / "r.scn")
    # each poll of the `every` rule reads the readings of its time; the trace
    # has a value each time it changes
    left = _sets(records, "left")
    assert _sets(records, "pair")[0] == 32000
    want = []
    for r in readings:
        exact = sum(w * v for w, v in zip(W_LEFT, r))
        value = arith.div(exact, 4) + 550
        if not want or want[-1] != value:
            want.append(value)
    assert left == want, (left[:5], want[:5])


def test_arrays_run_as_the_checker_folds_them(tmp_path):
    """Each function of arrays and each math function, once on constant
    arrays (the checker folds it: the C holds the number) and once on
    variable arrays given the same values while the program runs: both
    values equal the Python model."""
    rng = random.Random(7)
    cases = []
    for _ in range(12):
        size = rng.choice([1, 3, 8])
        a = [rng.choice([-32768, -1, 0, 1, 4095, 32767, rng.randint(-32768, 32767)])
             for _ in range(size)]
        b = [rng.randint(-300, 300) for _ in range(size)]
        cases.append((a, b))
    lines, rules, expected = [], [], {}
    for n, (a, b) in enumerate(cases):
        lines += [f"const A{n} = {a}", f"const B{n} = {b}",
                  f"var a{n} = {[0] * len(a)}", f"var b{n} = {[0] * len(b)}"]
        rules.append(", ".join([f"a{n}[{k}] = {v}" for k, v in enumerate(a)]
                               + [f"b{n}[{k}] = {v}" for k, v in enumerate(b)]))
        model = {
            "sum": arith.sat(sum(a)), "min": min(a), "max": max(a),
            "argmin": a.index(min(a)), "argmax": a.index(max(a)),
            "dot": arith.sat(sum(x * y for x, y in zip(a, b))),
            "last": a[-1],      # an index past the end is taken as the last element
            "hyp": arith.sat(imath.hypot(a[0], b[0])),
            "ang": imath.atan2(b[-1], a[0]),
            "root": arith.sat(imath.sqrt(abs(a[0]))),
            "sine": imath.sin(b[0]),
        }
        for what, value in model.items():
            expected[f"f{n}_{what}"] = expected[f"g{n}_{what}"] = value
            lines += [f"var f{n}_{what} = 0", f"var g{n}_{what} = 0"]

        def forms(arr, brr):
            return {"sum": f"sum({arr})", "min": f"min({arr})", "max": f"max({arr})",
                    "argmin": f"argmin({arr})", "argmax": f"argmax({arr})",
                    "dot": f"dot({arr}, {brr})", "last": f"{arr}[{len(a) + 5}]",
                    "hyp": f"hypot({arr}[0], {brr}[0])",
                    "ang": f"atan2({brr}[{len(b) - 1}], {arr}[0]) / 1 deg",
                    "root": f"sqrt(abs({arr}[0]))", "sine": f"sin({brr}[0] * 1 deg)"}
        for what, text in forms(f"A{n}", f"B{n}").items():
            if what == "last":
                text = f"A{n}[{len(a) - 1}]"        # a fixed index past the end is E061
            rules.append(f"f{n}_{what} = {text}")
        for what, text in forms(f"a{n}", f"b{n}").items():
            if what == "last":
                text = f"a{n}[g{n}_last + {len(a) + 5}]"
            rules.append(f"g{n}_{what} = {text}")
    program = tmp_path / "arrays.epk"
    # one rule each, in order: a case's values are set before they are used
    program.write_text("\n".join(lines) + "\n"
                       + "".join(f"after {10 * (k + 1)} ms do {rule}\n"
                                 for k, rule in enumerate(rules))
                       + f"after {10 * (len(rules) + 1)} ms priority 1 do exit_main\n")
    _build_both(tmp_path, program)
    records, _ = run_program(program, tmp_path, "--time-limit", "10s")
    final = _final(records)
    for name, value in expected.items():
        assert final.get(name, 0) == value, (name, final.get(name, 0), value)


@pytest.mark.parametrize("goal", [(400, 300), (-300, 200), (0, -500), (-400, -10)])
def test_go_to_goal_stops_within_a_centimetre(tmp_path, goal):
    """examples/go_to_goal.epk steers with atan2 and hypot to its goal, in
    every quadrant (behind the robot too), and stops within 1 cm of it."""
    gx, gy = goal
    records, _ = run_program(REPO / "examples" / "go_to_goal.epk", tmp_path, "--time-limit",
                             "40s", "-D", f"GX={gx}mm", "-D", f"GY={gy}mm")
    end = [r for r in records if r["kind"] == "exit"]
    assert end, "the robot never reached its goal"
    assert math.hypot(end[0]["x_mm"] - gx, end[0]["y_mm"] - gy) < 10.0, end[0]
    # it drove towards the goal, not along the axes: never much farther off
    # the straight line from the start than its own width
    poses = [(r["x_mm"], r["y_mm"]) for r in records if "x_mm" in r]
    length = math.hypot(gx, gy)
    off = max(abs(x * gy - y * gx) / length for x, y in poses)
    assert off < 60.0, off


def test_the_examples_build_for_16_and_32_bits(tmp_path):
    for name in ("go_to_goal", "weights", "histogram"):
        _build_both(tmp_path, REPO / "examples" / f"{name}.epk")


def test_the_ring_and_the_rgb_leds_show_numbers(tmp_path):
    """led_ring(n) lights LEDs 0..n-1 (n clamped to 0..8), led_bits(b) the
    bits of b, led_rgb sets an e-puck2 RGB LED's colour, each change traced;
    the e-puck (dspic) has no RGB LEDs: E070 naming it."""
    program = tmp_path / "leds.epk"
    program.write_text("var n = -2\n"
                       "every 100 ms do n += 3, led_ring(n), led_rgb(led5, n * 10, 0, 100 - n)\n"
                       "after 450 ms do led_bits(165)\n"
                       "after 500 ms priority 1 do exit_main\n")
    records, _ = run_program(program, tmp_path)
    rings = [r["ring"] for r in records if r["kind"] == "led"]
    for n, ring in ((1, "10000000"), (4, "11110000"), (7, "11111110"), (10, "11111111")):
        assert ring in rings, (n, ring, rings)
    assert rings[-1] == "10100101"              # 165: bits 0, 2, 5, 7
    colours = [(r["led"], r["red"], r["blue"]) for r in records if r["kind"] == "rgb"]
    # 10 * n saturates the percent at 100 from n = 10 on; 100 - n goes on
    assert colours == [("led5", 10, 99), ("led5", 40, 96), ("led5", 70, 93), ("led5", 100, 90)]
    result = epuckc("check", "--target", "dspic", program)
    assert result.returncode == 1 and "error[E070]" in result.stderr
    assert "`led_rgb`" in result.stderr and "the e-puck (dspic) does not have" in result.stderr


def test_c_never_divides_the_smallest_int_by_minus_one(tmp_path):
    """`%` and `/` of a value that can be -32768 by one that can be -1 are
    undefined in C where int is 16 bits: the C widens the division (`/`:
    32768 needs a long) or calls the runtime (`%`), and divides with C's
    own operator only where the intervals rule the pair out."""
    program = tmp_path / "div.epk"
    # b is -5..-1: never 0, so only the -32768 by -1 pair stands in the way
    program.write_text("var a = 1\nvar b = -1\nvar m = 5\nvar q = 5\nvar s = 5\n"
                       "every 3 ms do a = -32768, b = clamp(b - 1, -5, -1), m = a % b, q = a / b\n"
                       "every 5 ms do s = a % 7 + clamp(a, -32767, 0) % b\n")
    c_text = _build_both(tmp_path, program)
    assert "rt_mod(epk_v_a, epk_v_b)" in c_text
    assert " epk_v_a % epk_v_b" not in c_text
    assert " epk_v_a / epk_v_b" not in c_text    # an int's division: widened, or a call
    assert "(long)epk_v_a / epk_v_b" in c_text or "rt_div(epk_v_a, epk_v_b)" in c_text
    assert "epk_v_a % 7" in c_text              # the pair is ruled out: C's own `%`
    assert "rt_clamp(epk_v_a, -32767, 0) % epk_v_b" in c_text
