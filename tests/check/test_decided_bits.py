"""Comparisons the C compiler decides from facts the checker has are
decided by the checker first (W016, check/decided.py), so that an
accepted program always builds under -Werror (issue 42's campaign):

- by the bits: gcc's -Wtautological-compare refuses `(x & M) == C` where
  C has a bit M has not, and `(x | M) == C` where M has a bit C has not
  (`(-message) & (-32767) == 0xFFFF`, seed 42205); the checker knows the
  bits that the constants of `&`, `|`, `^`, `~` and shifts fix;
- by what a branch that cannot run does not assign: gcc drops
  `if (0) { v1 = ... }`, then knows that `v1` keeps its initial value and
  folds `v1 + v2 >= v2` with -Wstrict-overflow (seed 42208); the checker's
  intervals leave out assignments where the conditions cannot hold.

Each decision is also checked against the running program: the same
comparison with its constant in a variable the checker cannot see
through takes the same branch, for many values.
"""
from __future__ import annotations

import random
import re
from pathlib import Path

import pytest

from conftest import require_tool
from tests.support.hostile import Outcome, Program, check_one, runtime_objects
from tests.support.programs import epuckc, run_program

PROGRAMS = Path(__file__).resolve().parents[1] / "runtime" / "programs"
SIDES = ["a", "b", "-a", "a + b", "a * 3", "ir0", "message", "~b", "a ^ b"]


def _number(rng, v: int) -> str:
    return rng.choice([str(v), f"0x{v & 0xFFFF:X}"])


def _case(rng) -> tuple:
    """(text with the mask written `{M}`, mask, constant, op, must): must
    when gcc's rule decides it (a bit of the constant outside an `&`'s
    mask, or of an `|`'s mask outside the constant)."""
    side = rng.choice(SIDES)
    side = f"({side})" if " " in side or side.startswith("~") else side
    mask = rng.choice([rng.randint(-32768, 32767), rng.choice([1, 6, 0xF0, 0x7FFF, -32767, -2])])
    const = rng.choice([rng.randint(-32768, 32767), -1, 0, 1, 3, 0x10, mask])
    op = rng.choice(["==", "!="])
    shape = rng.choice(["&", "|", "&|", "<<", ">>"])
    if shape == "&":
        text, must = f"({side} & {{M}}) {op} {{C}}", const & ~mask & 0xFFFF != 0
    elif shape == "|":
        text, must = f"({side} | {{M}}) {op} {{C}}", mask & ~const & 0xFFFF != 0
    elif shape == "&|":
        text, must = f"(({side} & {{M}}) | 1) {op} {{C}}", (const & ~(mask | 1) & 0xFFFF) != 0 \
            or const & 1 == 0
    else:
        n = rng.randint(0, 15)
        text, must = f"(({side} & {{M}}) {shape} {n}) {op} {{C}}", False
    return text, mask, const, op, must


@pytest.mark.parametrize("seed", [1, 2])
def test_comparisons_decided_by_their_bits_build_and_run_alike(tmp_path, seed):
    cc, avr = require_tool("cc"), require_tool("avr-gcc")
    rng = random.Random(seed)
    cases = [_case(rng) for _ in range(40)]
    values = [-32768, 32767, 0, 1, -1, 0xF0, -2] + [rng.randint(-32768, 32767) for _ in range(7)]
    lines = ["var a = 0", "var b = 0"]
    lines += [f"var {v}{i} = 0" for i in range(len(cases)) for v in "rsm"]
    # (m_i is the mask at run time; the checker sees every int16 in it)
    lines.append("after 1 ms do " + ", ".join(f"m{i} = {m}" for i, (_, m, _, _, _) in
                                              enumerate(cases)))
    lines.append("after 100000 ms do " + ", ".join(f"m{i} = -32768, m{i} = 32767"
                                                   for i in range(len(cases))))
    tests = ", ".join(
        f"if {text.format(M=_number(rng, m), C=_number(rng, c))} {{ r{i} = 1 }} "
        f"else {{ r{i} = 0 }}, "
        f"if {text.format(M=f'm{i}', C=str(c))} {{ s{i} = 1 }} else {{ s{i} = 0 }}"
        for i, (text, m, c, _, _) in enumerate(cases))
    times = []
    for n, (va, vb) in enumerate(zip(values, reversed(values))):
        times.append(10 * (n + 1))
        lines.append(f"after {times[-1]} ms do a = {va}, b = {vb}, {tests}")
    lines.append(f"after {10 * (len(values) + 1)} ms do exit_main")
    text = "\n".join(lines) + "\n"
    path = tmp_path / "bits.epk"
    path.write_text(text, encoding="utf-8")

    # decided where gcc's rule decides it: a W016 on the comparison
    check = epuckc("check", path, "--format", "short")
    said = check.stdout + check.stderr
    decided = {int(col) for line, col in re.findall(r"bits\.epk:(\d+):(\d+): warning\[W016\]",
                                                    said) if int(line) == len(lines) - 1}
    first_test = lines[-2]
    at = 0
    for i, (_, _, _, _, must) in enumerate(cases):
        at = first_test.index("if ", at) + 3
        if must:
            assert at + 1 in decided, (cases[i], said)
        at = first_test.index("if ", at) + 3      # (its twin, with the mask in m_i)

    # what it decides is what running computes, for every value
    records, _ = run_program(path, tmp_path, "--time-limit", "2s")
    now: dict = {}
    for r in records:
        if r["kind"] == "set":
            now[r["var"]] = r["value"]
            if r["var"].startswith("s"):
                i = r["var"][1:]
                assert now.get(f"r{i}", 0) == r["value"], (cases[int(i)], r)

    # and it builds: avr-gcc (16-bit int) and gcc with -Werror, under the sanitizers
    outcome = check_one(Program("bits", text), tmp_path / "build", cc, avr,
                        runtime_objects(tmp_path, cc))
    assert outcome == Outcome.BUILT


DEAD = ["if not (v1 <= v1) {{ {a} }}", "if v1 != v1 {{ {a} }} else {{ w = 1 }}",
        "if heading == heading {{ w = 2 }} else {{ {a} }}",
        "if ir0 > 5000 {{ {a} }}", "if (w & 2) == 1 {{ {a} }}"]


@pytest.mark.parametrize("dead", DEAD)
def test_a_branch_that_cannot_run_assigns_nothing(tmp_path, dead):
    """A variable assigned only in a branch whose conditions cannot hold
    keeps its initial value for the checker, as for gcc (which drops the
    branch): `v1 + v2 >= v2` is decided and the program builds with
    avr-gcc under -Werror. A branch that can run still counts."""
    cc, avr = require_tool("cc"), require_tool("avr-gcc")
    for live in (False, True):
        condition = "if ir0 > 100 {{ {a} }}" if live else dead
        text = ("var v1 = 300 steps/s\nvar v2 = 300 steps/s\nvar w = 0\n"
                "every 20 ms do v2 = clamp(v2 - 10 steps/s, -900 steps/s, 900 steps/s)\n"
                f"every 10 ms do {condition.format(a='v1 -= v2')}\n"
                "when not (v1 + v2 >= v2) do w = 3\n"
                "after 200 ms do exit_main\n")
        path = tmp_path / "dead.epk"
        path.write_text(text, encoding="utf-8")
        said = epuckc("check", path, "--format", "short")
        out = said.stdout + said.stderr
        c = epuckc("compile", path, "-o", "-").stdout
        shown = re.search(r"var v1: (\S+) \*/", c).group(1)
        if live:
            assert shown != "300..300", shown
            assert "dead.epk:6:11: warning[W016]" not in out
        else:
            assert shown == "300..300", (dead, shown)
            assert "dead.epk:6:11: warning[W016]" in out, (dead, out)
            outcome = check_one(Program("dead", text), tmp_path / "build", cc, avr, [],
                                run=False)
            assert outcome == Outcome.COMPILED, dead


@pytest.mark.parametrize("name,seed", [("bits_always_differ", 42205),
                                       ("sum_known_difference", 42208)])
def test_the_campaigns_inputs_build(tmp_path, name, seed):
    """The two inputs of issue 42's campaign (seeds 42205 and 42208) that
    the checker accepted and gcc or avr-gcc refused under -Werror."""
    cc, avr = require_tool("cc"), require_tool("avr-gcc")
    text = (PROGRAMS / f"{name}.epk").read_text()
    outcome = check_one(Program(name, text), tmp_path / name, cc, avr, [], run=False)
    assert outcome == Outcome.COMPILED, seed


FIRST = ["v - {a} != -v", "2 * v != {b}", "v + {a} == {b} - v", "3 * v - {a} >= {b}",
         "not (v - {a} == v * 2 - {b})", "v * -2 < {a}"]
LATER = ["v > -v", "v + 1 > v - {a}", "v - {a} <= v + v", "-v >= {b} - v * 3", "v * 2 != {b}"]


@pytest.mark.parametrize("seed", [1, 2])
def test_a_later_condition_is_checked_where_the_ones_before_it_failed(tmp_path, seed):
    """`if v - 1000 != -v { } else if v > -v`: where the first fails, v is
    500, and gcc, which knows it, folds the second with -Wstrict-overflow
    (seed 42223). Each later condition of a chain is checked with the
    intervals the failed ones leave (a comparison whose sides differ by
    `k * v + c` bounds v); decided, it is always what the run computes
    (the same chain with the first condition hidden from the checker by
    `+ random(0, 0)` takes the same branch), and the C builds."""
    cc, avr = require_tool("cc"), require_tool("avr-gcc")
    rng = random.Random(seed)
    chains = []
    for _ in range(30):
        a, b = rng.randint(-600, 600), rng.randint(-1200, 1200)
        first = rng.choice(FIRST).format(a=a, b=b)
        later = rng.choice(LATER).format(a=rng.randint(-60, 60), b=rng.choice([b, 2 * a, 7]))
        chains.append((first, later))
    lines = ["var v = 0"] + [f"var {w}{i} = 0" for i in range(len(chains)) for w in "rs"]
    tests = ", ".join(
        f"if {first} {{ r{i} = 1 }} else if {later} {{ r{i} = 2 }} else {{ r{i} = 3 }}, "
        f"if ({first}) and random(0, 0) == 0 {{ s{i} = 1 }} else if {later} {{ s{i} = 2 }} "
        f"else {{ s{i} = 3 }}"
        for i, (first, later) in enumerate(chains))
    values = sorted({rng.randint(-900, 900) for _ in range(12)} | {0, 1, -1, 500, 300, -300})
    values += [x for x in range(-600, 601, 100) if x not in values]
    for n, value in enumerate(values):
        lines.append(f"after {10 * (n + 1)} ms do v = {value}, {tests}")
    lines.append(f"after {10 * (len(values) + 1)} ms do exit_main")
    text = "\n".join(lines) + "\n"
    path = tmp_path / "chain.epk"
    path.write_text(text, encoding="utf-8")
    records, _ = run_program(path, tmp_path, "--time-limit", "2s")
    now: dict = {}
    for r in records:
        if r["kind"] == "set":
            now[r["var"]] = r["value"]
            if r["var"].startswith("s"):
                i = r["var"][1:]
                assert now.get(f"r{i}") == r["value"], (chains[int(i)], now.get("v"), r)
    outcome = check_one(Program("chain", text), tmp_path / "build", cc, avr,
                        runtime_objects(tmp_path, cc))
    assert outcome == Outcome.BUILT


def test_the_campaigns_equality_before_an_else_if_builds(tmp_path):
    """Issue 42's campaign, seed 42223, input 289: `... else if v0 > -v0`
    after `if v0 - 1000 steps/s != -v0` failed; avr-gcc refused it under
    -Werror. Now the checker says it is always true there, and folds it."""
    cc, avr = require_tool("cc"), require_tool("avr-gcc")
    text = (PROGRAMS / "equal_before.epk").read_text()
    assert "if v0 - 1000 steps/s != -v0" in text
    outcome = check_one(Program("equal", text), tmp_path / "equal", cc, avr, [], run=False)
    assert outcome == Outcome.COMPILED
    path = tmp_path / "equal_before.epk"
    path.write_text(text, encoding="utf-8")
    said = epuckc("check", path, "--format", "short")
    assert re.search(r"warning\[W016\]: `v0 > -v0` is always true", said.stdout + said.stderr)
