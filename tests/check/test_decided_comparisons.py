"""Comparisons whose sides always differ by the same number are decided by
the checker (W016), and folded, so that the C never holds one.

`v - 200 <= v` is true whatever `v` is: the dsPIC's and the AVR's gcc fold
it themselves and warn, under -Wall (-Wstrict-overflow), that they assume
no overflow, which -Werror makes an accepted program that does not build
(the fuzz campaign found `v1 + -200 steps/s <= v1` so). For random pairs of
sums of the same parts in other orders and groupings, with other numbers
(and, as a control, with one factor changed, or sums that can leave 32
bits and saturate):

- the checker decides each pair whose difference is a number and no sum
  of which can leave 32 bits (a W016 at its place);
- what it decides is what the running program computes: each comparison is
  also written with `+ random(0, 0)` (the same value, which the checker
  cannot see through), and both, run for many values of the variables
  (their extremes included), take the same branch;
- the C compiles with 16-bit avr-gcc under -Werror (and with gcc, and runs
  clean under the sanitizers: tests/support/hostile.py).
"""
from __future__ import annotations

import random
import re

import pytest

from conftest import require_tool
from tests.support.hostile import Outcome, Program, check_one, runtime_objects
from tests.support.programs import epuckc, run_program

OPS = ["<", "<=", ">", ">=", "==", "!="]
# parts that are not sums: variables, a reading, and operations over them
PARTS = ["a", "b", "ir0", "a / 3", "abs(b)", "min(a, b)", "max(a, 7) % 5"]
BIG = ["a * b"]         # up to 2^30: three of them leave 32 bits


def _sum(rng, terms, number) -> str:
    """sum(k * part) + number, written in a random order and grouping,
    the number split in two at a random place."""
    items = [(k, p) for k, p in terms]
    split = rng.randint(-50, 50)
    items += [(number - split, None), (split, None)]
    rng.shuffle(items)
    text = ""
    for k, part in items:
        if part is None:
            piece, negative = str(abs(k)), k < 0
        else:
            factor, inner = abs(k), f"({part})" if " " in part else part
            piece = inner if factor == 1 else rng.choice([f"{factor} * {inner}",
                                                          f"{inner} * {factor}"])
            negative = k < 0
        if not text:
            text = f"-{piece}" if negative and part is None else (
                f"-({piece})" if negative else piece)
        else:
            text = f"{text} {'-' if negative else '+'} {piece}"
        if rng.random() < 0.3:
            text = f"({text})"
    return text


def _pair(rng) -> tuple:
    """(left, right, decided): two sums of the same parts with other
    numbers; decided when their difference is a number and no sum can leave
    32 bits."""
    big = rng.random() < 0.2
    pool = PARTS + (BIG if big else [])
    terms = [(rng.choice([-3, -2, -1, 1, 2, 3]), part)
             for part in rng.sample(pool, rng.randint(1, 3))]
    if big:
        terms.append((rng.choice([2, 3]), "a * b"))
    other = list(terms)
    rng.shuffle(other)
    changed = rng.random() < 0.2
    if changed:         # the control: one factor differs, nothing is decided by form
        k, part = other[0]
        other[0] = (k + rng.choice([-1, 1]) or 2, part)
    left = _sum(rng, terms, rng.randint(-300, 300))
    right = _sum(rng, other, rng.randint(-300, 300))
    return left, right, not changed and not big


@pytest.mark.parametrize("seed", [1, 2])
def test_comparisons_of_sums_that_differ_by_a_number_are_decided_and_run_alike(tmp_path, seed):
    cc = require_tool("cc")
    avr = require_tool("avr-gcc")
    rng = random.Random(seed)
    pairs = [(*_pair(rng), rng.choice(OPS)) for _ in range(30)]
    values = [-32768, 32767, 0, 1, -1] + [rng.randint(-32768, 32767) for _ in range(7)]
    lines = ["var a = 0", "var b = 0"]
    lines += [f"var {v}{i} = 0" for i in range(len(pairs)) for v in "rs"]
    tests = ", ".join(
        f"if {left} {op} {right} {{ r{i} = 1 }} else {{ r{i} = 0 }}, "
        f"if {left} + random(0, 0) {op} {right} {{ s{i} = 1 }} else {{ s{i} = 0 }}"
        for i, (left, right, _, op) in enumerate(pairs))
    times = []
    for n, (va, vb) in enumerate(zip(values, reversed(values))):
        times.append(10 * (n + 1))
        lines.append(f"after {times[-1]} ms do a = {va}, b = {vb}, {tests}")
    lines.append(f"after {10 * (len(values) + 1)} ms do exit_main")
    text = "\n".join(lines) + "\n"
    path = tmp_path / "decided.epk"
    path.write_text(text, encoding="utf-8")

    # decided where the form decides it: a W016 at the comparison's line and column
    check = epuckc("check", path, "--format", "short")
    decided = {(int(line), int(col)) for line, col in
               re.findall(r"decided\.epk:(\d+):(\d+): warning\[W016\]", check.stdout + check.stderr)}
    first = next(n for n, line in enumerate(lines) if line.startswith("after"))
    for i, (left, right, must, op) in enumerate(pairs):
        column = lines[first].index(f"if {left} {op} {right} {{ r{i} =") + len("if ") + 1
        if must:
            assert (first + 1, column) in decided, (left, op, right, check.stdout + check.stderr)

    # what it decides is what running computes, for every value
    records, _ = run_program(path, tmp_path, "--time-limit", "2s")
    now: dict = {}
    at: dict = {}
    for r in records:
        if r["kind"] == "set":
            now[r["var"]] = r["value"]
            at[r["t_ms"]] = dict(now)
    seen = {}
    for t in sorted(at):
        seen.update(at[t])
        if t in times:
            for i, (left, right, _, op) in enumerate(pairs):
                assert seen.get(f"r{i}", 0) == seen.get(f"s{i}", 0), (t, left, op, right)

    # and it builds: avr-gcc (16-bit int) and gcc with -Werror, run with the sanitizers
    work = tmp_path / "build"
    outcome = check_one(Program("decided", text), work, cc, avr, runtime_objects(tmp_path, cc))
    assert outcome == Outcome.BUILT


def test_the_warning_says_by_how_much(tmp_path):
    path = tmp_path / "by.epk"
    path.write_text("var v = 0 steps/s\n"
                    "every 10 ms do v = clamp(v + 10 steps/s, -500 steps/s, 500 steps/s)\n"
                    "every 20 ms do if v + -200 steps/s <= v { stop_motor }\n", encoding="utf-8")
    result = epuckc("check", path)
    assert ("`v + -200 steps/s <= v` is always true: `v + -200 steps/s` is always 200 steps/s "
            "less than `v`") in result.stderr + result.stdout
    c = epuckc("compile", path, "-o", "-").stdout
    code = re.sub(r'"(?:[^"\\]|\\.)*"', '""', re.sub(r"/\*.*?\*/", "", c, flags=re.S))
    assert "epk_v_v" in code and "<=" not in code       # (the C of the comparison: 1)


def test_a_sum_that_can_leave_32_bits_is_not_decided_by_its_form(tmp_path):
    """`a * b * 4 + 1 > a * b * 4` is false where the product saturates
    (32767 * 32767 * 4 is past 2^31 - 1; plus 1 saturates too): not always
    true, and the checker does not say it is."""
    path = tmp_path / "big.epk"
    path.write_text("var a = 0\nvar b = 0\nvar r = 0\n"
                    "after 10 ms do a = 32767, b = 32767\n"
                    "every 20 ms do if a * b * 4 + 1 > a * b * 4 { r = 1 } else { r = 2 }\n"
                    "after 50 ms do exit_main\n", encoding="utf-8")
    result = epuckc("check", path)
    assert "W016" not in result.stdout + result.stderr
    records, _ = run_program(path, tmp_path, "--time-limit", "1s")
    assert [r["value"] for r in records if r["kind"] == "set" and r["var"] == "r"] == [2]
