"""check/reeval.py: an assignment's value computed again from the plan of
its first evaluation is the value the checker gives, for every interval
the fixpoint asks it with, and a plan is made only where it computes what
the checker does."""
from __future__ import annotations

import random
import sys
from pathlib import Path

import pytest
from hypothesis import HealthCheck, given, settings

from epuckc.check import ranges, reeval
from epuckc.check.frontend import check_file
from epuckc.diagnostics import Report
from tests.support.language import RandomChoices, language_program, language_programs

REPO = Path(__file__).resolve().parents[2]


def _check(text: str):
    report = Report()
    result = check_file(Path("prog.epk"), report, text=text)
    return result, report


@pytest.fixture
def verified(monkeypatch):
    """Every value a plan gives is compared with the checker's
    (ranges._verify_plan, which asserts them equal); the count of them."""
    count = []
    real = ranges._verify_plan

    def verify(checker, call, info, value):
        count.append(call)
        return real(checker, call, info, value)
    monkeypatch.setattr(ranges, "_VERIFY_PLANS", True)
    monkeypatch.setattr(ranges, "_verify_plan", verify)
    return count


@settings(max_examples=60, deadline=None, suppress_health_check=[HealthCheck.too_slow,
                                                                  HealthCheck.function_scoped_fixture])
@given(language_programs())
def test_a_plans_value_is_the_checkers_in_generated_programs(verified, program):
    _check(program.text)


def test_the_plans_answer_in_programs_whose_variables_read_each_other(verified):
    """In the language server's bench programs (small groups and one
    component of all the variables) nearly every value after the first of
    each assignment comes from its plan, and each is the checker's."""
    sys.path.insert(0, str(REPO / "bench"))
    from lsp_bench import expression_program
    for coupled in (False, True):
        before = len(verified)
        _check(expression_program(200, coupled=coupled))
        assert len(verified) - before > 200
    mixed = [language_program(RandomChoices(random.Random(s))).text for s in range(20)]
    before = len(verified)
    for text in mixed:
        _check(text)
    assert len(verified) > before


def test_the_same_diagnostics_and_intervals_with_and_without_plans(monkeypatch):
    """A program checked with its plans gives what it gives when every
    value is the checker's (plans never made)."""
    sys.path.insert(0, str(REPO / "bench"))
    from lsp_bench import expression_program
    texts = [expression_program(120, seed=3, coupled=True), expression_program(120, seed=4)]
    texts += [language_program(RandomChoices(random.Random(s))).text for s in range(30, 40)]

    def outcome(text):
        result, report = _check(text)
        checked = result.checked
        variables = {} if checked is None else {
            n: (v.lo, v.hi) for n, v in checked.variables.items()}
        return [str(d) for d in report.diagnostics], variables
    with_plans = [outcome(t) for t in texts]
    monkeypatch.setattr(reeval, "plan_of", lambda *a: None)
    assert [outcome(t) for t in texts] == with_plans


def _found(text: str, target: str):
    """(the plan, the checker's Expr) of the first assignment to `target`."""
    made = []
    real = reeval.plan_of

    def plan_of(value, info, compound):
        plan = real(value, info, compound)
        if info.name == target:
            made.append((plan, value))
        return plan
    mp = pytest.MonkeyPatch()
    mp.setattr(reeval, "plan_of", plan_of)
    try:
        _check(text)
    finally:
        mp.undo()
    return made


@pytest.mark.parametrize("value, planned", [
    ("clamp(v + ir3 / 64 - w / 2, -500, 500)", True),
    ("abs(v - w) % 100", True),
    ("max(w - 1, 0) * 3", True),
    ("-v + 7", True),
    ("v & 255", False),             # bitwise: bits.py's intervals
    ("random(0, v)", False),
    ("v << 2", False),
    ("sqrt(v)", False),
])
def test_a_plan_is_made_only_for_what_it_computes_as_the_checker(value, planned):
    text = ("var v = 3\nvar w = 1\nvar t = 0\non immediate do start_sensor\n"
            f"every 10 ms do v = min(v + 1, 90), w = max(w - 1, -40), t = {value}\n")
    made = _found(text, "t")
    assert made, "the assignment was evaluated"
    assert all((plan is not None) == planned for plan, _ in made)


def test_a_divisor_that_the_intervals_make_always_0_is_the_checkers_error():
    """E049's case: a plan answers None (no value) where the divisor's
    interval is [0, 0], as the checker reports the division and gives none."""
    text = ("var d = 5\nvar t = 0\non immediate do start_sensor\n"
            "every 10 ms do d = d + 1, t = 100 / d\n")
    made = _found(text, "t")
    plan = next(p for p, _ in made if p is not None)

    class Info:
        def __init__(self, name, kind, lo, hi):
            self.name, self.kind, self.lo, self.hi, self.size = name, kind, lo, hi, 0
    t = Info("t", plan.target, 0, 0)
    assert reeval.evaluate(plan, {"d": Info("d", plan.target, 0, 0)}, {}, t) is None
    kind, lo, hi = reeval.evaluate(plan, {"d": Info("d", plan.target, 1, 4)}, {}, t)
    assert (lo, hi) == (25, 100)
    # a variable of another kind than the plan was made for: the checker's turn
    assert reeval.evaluate(plan, {"d": Info("d", "distance", 1, 4)}, {}, t) is reeval.MISMATCH
