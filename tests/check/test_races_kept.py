"""W009 from the runs of rules (check/races.py, issue 31): the pairs of big
groups compared by timing alone are found from each run's kinds
(`_by_timing`) without a look at each motor rule; the warnings must be
those the pairs found rule by rule (`_pairs`) give, whatever the runs,
priorities, modes, shapes and conditions."""
from __future__ import annotations

import random
import sys
from pathlib import Path

from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from epuckc.base.source import SourceFile
from epuckc.check import races
from epuckc.check.checker import Checker
from epuckc.diagnostics import Collector
from epuckc.ide.incremental import Analyzer
from epuckc.syntax.parser import parse

REPO = Path(__file__).resolve().parents[2]

SHAPES = [
    "every {t} ms do set_speed(300 steps/s, 300 steps/s)",
    "every {t} ms if ir{k} > {n} do stop_motor",
    "after {t} ms do start_curve(0 mm, 90 deg, 300)",
    "on sensor(ir{k} > {n}) repeat do start_straight(300, 2 cm)",
    "when ir{k} > {n} do stop_motor",
    "when ir{k} > {n} and ir{j} < {m} do set_speed(100 steps/s, 0 steps/s)",
    "on timer({s} s) repeat do set_timer, stop_motor",
    "every {t} ms if v < {n} do v = v + 1, set_speed(200 steps/s, 200 steps/s)",
    "on immediate repeat do led_toggle(led1)",
]


def program(rng: random.Random, rules: int) -> str:
    """Rules of every timing shape, with and without conditions; a second
    priority for none, one, a few or about half of them (so that there are
    big groups of two priorities, or a small group beside a big one)."""
    lines = ["var v = 0", "on immediate do start_sensor, set_timer"]
    second = rng.choice([0.0, 0.0, 0.02, 0.1, 0.5])
    for i in range(rules):
        shape = rng.choice(SHAPES).format(t=rng.choice([10, 20, 50, 100]), k=rng.randrange(8),
                                          j=rng.randrange(8), n=100 + i, m=3000 - i,
                                          s=rng.choice([1, 2, 4]))
        if rng.random() < second:
            shape = shape.replace(" do ", " priority 2 do ", 1)
        lines.append(shape)
    return "\n".join(lines) + "\n"


def _w009(text: str, cut: list, fast: bool) -> tuple:
    """The W009 warnings of a check whose rules come as runs cut at the
    places `cut` (as the language server's blocks), with the pairs found
    from the runs' kinds or not; and whether they were."""
    taken = []
    real = races._by_timing

    def by_timing(*a):
        found = real(*a) if fast else None
        taken.append(found is not None)
        return found

    class Runs(Checker):
        def _races(self, out):
            bounds = [0] + sorted(c % (len(out.rules) + 1) for c in cut) + [len(out.rules)]
            self.rule_groups = [(object(), out.rules[a:b])
                                for a, b in zip(bounds, bounds[1:]) if b > a]
            return super()._races(out)
    source = SourceFile("p.epk", text)
    diags = Collector(source)
    races._by_timing = by_timing
    try:
        Runs(parse(source, diags), diags).check()
    finally:
        races._by_timing = real
    return [d for d in diags.items if d.code == "W009"], any(taken)


@settings(max_examples=60, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(seed=st.integers(0, 10_000), rules=st.integers(41, 320),
       cut=st.lists(st.integers(0, 500), max_size=6))
def test_pairs_from_the_runs_kinds_say_what_pairs_rule_by_rule_say(seed, rules, cut):
    text = program(random.Random(seed), rules)
    fast, _ = _w009(text, cut, True)
    slow, _ = _w009(text, cut, False)
    assert fast == slow


def test_the_property_takes_the_fast_path_and_the_full_one():
    """(The property above compares something: its programs come both
    ways, by the runs' kinds and rule by rule.)"""
    taken = [_w009(program(random.Random(seed), rules), [7, 90], True)[1]
             for seed, rules in ((1, 300), (2, 320), (3, 80), (4, 250), (5, 310), (6, 60))]
    assert 2 <= sum(taken) <= 5


def test_the_language_server_s_w009_by_the_runs_kinds_edit_after_edit():
    """In the language server (its runs are the document's pieces, its
    warnings kept while the runs' motor rules are the same objects), over
    edits that take a motor rule out and put it back, change a rule that
    commands no motor, or a guard: W009 is what a check that finds every
    pair rule by rule says."""
    sys.path.insert(0, str(REPO / "bench"))
    from lsp_bench import error_edits, expression_program

    def rule_by_rule(text: str) -> list:
        real = races._by_timing
        races._by_timing = lambda *a: None
        try:
            source = SourceFile("p.epk", text)
            diags = Collector(source)
            Checker(parse(source, diags), diags).check()
        finally:
            races._by_timing = real
        return [_shown_lines(d) for d in diags.items if d.code == "W009"]

    taken = []
    real = races._by_timing

    def by_timing(*a):
        found = real(*a)
        taken.append(found is not None)
        return found
    rng = random.Random(31)
    text = expression_program(480)          # (120 motor rules of one priority)
    analyzer = Analyzer("p.epk")
    races._by_timing = by_timing
    try:
        for step in range(16):
            if step:
                start, end, new = error_edits(text, rng, 1)[0]
                if step % 4 == 3:           # (a guard: the first number after the edit)
                    at = text.index(" < ", start) + 3
                    start, end, new = at, at + 1, str(rng.randint(1, 9))
                text = text[:start] + new + text[end:]
            shown = [_shown_lines(d) for d in analyzer.analyse(text).diagnostics
                     if d.code == "W009"]
            assert sorted(shown) == sorted(rule_by_rule(text)), step
    finally:
        races._by_timing = real
    assert any(taken)


def _shown_lines(d) -> tuple:
    """What a W009 warning says, and where (lines real in both)."""
    return (d.span.line, d.message, d.help)


def test_a_big_group_by_timing_is_found_from_the_runs():
    """(The property above compares something: big groups of conditions
    that make too many kinds are found from the runs' kinds.)"""
    text = "\n".join(["on immediate do start_sensor"] + [
        f"when ir{i % 8} > {100 + i} do stop_motor" for i in range(120)]) + "\n"
    fast, taken = _w009(text, [10, 50, 90], True)
    assert taken and fast
    assert fast == _w009(text, [10, 50, 90], False)[0]
