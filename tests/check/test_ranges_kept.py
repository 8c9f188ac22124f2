"""The variables' intervals (check/ranges.py) with what each assignment
gave kept by what it read (`Ranges._assigned_where`, issue 31): every
interval, and every diagnostic, is the one found evaluating each
assignment afresh, in a full check and edit after edit in the language
server's analysis, where the kept values outlive one check."""
from __future__ import annotations

import random
import sys
from pathlib import Path

from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from epuckc.base.source import SourceFile
from epuckc.check.checker import Checker
from epuckc.check.ranges import Ranges
from epuckc.diagnostics import Collector
from epuckc.ide.incremental import Analyzer
from epuckc.syntax.parser import parse

REPO = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(REPO / "bench"))

from lsp_bench import expression_program  # noqa: E402
from tests.support.language import RandomChoices, language_program  # noqa: E402

PROGRAMS = [expression_program(40, seed=s) for s in range(3)] + [
    language_program(RandomChoices(random.Random(s))).text for s in range(12)]
PIECES = ["v0", "v1", " + 1", " - 7", " * 3", " / 2", "max(", "clamp(", ", 5)", "7", "=",
          "+=", "(", ")", "\n", "abs(", "ir0", " if v0 > 3", "v1 += 1, ", "var v9 = 4\n",
          "every 10 ms do v0 = v0 + 1\n", "every 10 ms if v0 < 50 do v0 += 5\n"]


def _afresh(text: str) -> tuple:
    """The intervals and diagnostics of a check that evaluates every
    assignment afresh."""
    class Afresh(Checker):
        def _assigned_where(self, call, info):
            return self._evaluated_where(call, info)
    source = SourceFile("prog.epk", text)
    diags = Collector(source)
    checker = Afresh(parse(source, diags), diags)
    checker.check()
    return _intervals(checker), diags.items


def _intervals(checker) -> dict:
    return {name: (info.lo, info.hi) for name, info in checker.vars.items()}


def _kept(text: str) -> tuple:
    source = SourceFile("prog.epk", text)
    diags = Collector(source)
    checker = Checker(parse(source, diags), diags)
    checker.check()
    return _intervals(checker), diags.items


def test_the_values_are_kept_and_used():
    """(The property below compares something: assignments are asked again
    with what they read unchanged, and answered from what was kept.)"""
    asked = []
    real = Ranges._evaluated_where

    class Counting(Checker):
        def _evaluated_where(self, call, info):
            asked.append(call)
            return real(self, call, info)
    text = PROGRAMS[0]
    source = SourceFile("prog.epk", text)
    diags = Collector(source)
    Counting(parse(source, diags), diags).check()
    evaluated = len(asked)
    asked.clear()

    class Afresh(Counting):
        def _assigned_where(self, call, info):
            return self._evaluated_where(call, info)
    source = SourceFile("prog.epk", text)
    diags = Collector(source)
    Afresh(parse(source, diags), diags).check()
    assert evaluated < len(asked)


@settings(max_examples=80, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(st.integers(0, len(PROGRAMS) - 1),
       st.lists(st.tuples(st.integers(0, 10_000), st.integers(0, 12),
                          st.lists(st.sampled_from(PIECES), max_size=3)),
                min_size=1, max_size=6))
def test_kept_values_give_what_evaluating_afresh_gives(which, edits):
    text = PROGRAMS[which]
    analyzer = Analyzer("prog.epk")
    for at, length, pieces in [(0, 0, [])] + edits:
        at %= len(text) + 1
        text = text[:at] + "".join(pieces) + text[at + length:]
        intervals, diagnostics = _afresh(text)
        assert _kept(text) == (intervals, diagnostics)
        analysis = analyzer.analyse(text)
        assert _intervals(analysis.checker) == intervals


def test_an_edit_that_resizes_an_array_reaches_its_fills():
    """`fill(a, v)` assigns as many elements as `a` has (check/arrays.py):
    an edit of the declaration alone changes what the unchanged rule's
    `fill` assigns, in the language server's analysis as afresh."""
    before = "var a = [1, 2, 3]\nevery 10 ms do if ir0 > 5 { fill(a, 30000) } else { a[0] = 7 }\n"
    # (an item the checker refuses is 0: E009, and the array has two)
    after = before.replace("[1, 2, 3]", "[0x0x1, 2]")
    analyzer = Analyzer("prog.epk")
    for text in (before, after):
        intervals, _ = _afresh(text)
        assert intervals["a"] == ((0 if text == after else 1), 30000)
        assert _intervals(analyzer.analyse(text).checker) == intervals
