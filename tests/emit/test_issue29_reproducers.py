"""The reproducers of issue 29's classes of accepted programs that did not
build with -Werror or computed other values than the checker: each one now
builds with gcc and 16-bit avr-gcc under -std=c99 -Wall -Wextra -Werror
-pedantic, and runs as the checker folds it."""
from __future__ import annotations

import subprocess

import pytest

from conftest import REPO, require_tool
from tests.support.programs import epuckc, run_program

RUNTIME = REPO / "runtime_c"
STRICT = ["-std=c99", "-Wall", "-Wextra", "-Werror", "-pedantic"]

PROGRAMS = {
    # read only where a comparison is decided (folded), or never assigned
    "unread_variables": """\
var u = 0
var w = 5
var z = 3
when u > 5 do stop_motor
every 2 s if w * 0 > 1 do led_toggle(body)
every 1 s do set_speed(z * 0 steps/s, 0 steps/s)
after 3 s priority 1 do exit_main
""",
    # a variable never read at all: assigned only (the trace shows it)
    "written_only": """\
var unused = 0
every 1 s do unused = 1
after 3 s do exit_main
""",
    # gcc's tautological-compare
    "self_comparison": """\
var v = 0
every 1 s do v += 1
when v >= v priority 1 do led_on(body)
every 500 ms if v != v do led_toggle(front)
after 3 s priority 2 do exit_main
""",
    # -K with K = -32768: 32767 (saturating), not 32768 (outside 16 bits)
    "negated_minimum": """\
const K = -32768
var a = 0
var b = 0
var v = 0
on immediate do a = -K, v = 5
after 10 ms do b = v - K
after 20 ms priority 1 do exit_main
""",
}


@pytest.mark.parametrize("name", sorted(PROGRAMS))
def test_the_reproducer_builds_for_32_and_16_bits(tmp_path, name):
    path = tmp_path / f"{name}.epk"
    path.write_text(PROGRAMS[name], encoding="utf-8")
    c = tmp_path / f"{name}.c"
    epuckc("compile", path, "-o", c, check=True)
    cc, avr = require_tool("cc"), require_tool("avr-gcc")
    subprocess.run([cc, *STRICT, f"-I{RUNTIME}", "-c", str(c), "-o", str(tmp_path / "a.o")],
                   check=True)
    subprocess.run([avr, "-mmcu=atmega128", *STRICT, "-Os", f"-I{RUNTIME}", "-c", str(c),
                    "-o", str(tmp_path / "b.o")], check=True)


def test_a_negated_minimum_runs_as_the_checker_folds_it(tmp_path):
    path = tmp_path / "neg.epk"
    path.write_text(PROGRAMS["negated_minimum"], encoding="utf-8")
    records, _ = run_program(path, tmp_path)
    final = {r["var"]: r["value"] for r in records if r["kind"] == "set"}
    assert final["a"] == 32767              # -(-32768) saturates
    assert final["b"] == 32767              # 5 - (-32768) saturates too
    c_text = epuckc("compile", path, "-o", "-", check=True).stdout
    assert "32768" not in c_text.replace("-32768", "")
