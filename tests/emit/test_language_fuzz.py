"""The project's fuzzing of the whole language (tests/support/language.py),
with a fixed seed and a new one each run (printed at the end of the run;
EPUCKC_FUZZ_SEED=N runs it again):

- no input makes `check`, `compile` or the language server fail, and the
  language server reports what `check` reports;
- every program the checker accepts compiles with gcc and 16-bit avr-gcc
  under -std=c99 -Wall -Wextra -Werror -pedantic and runs clean under
  ASan/UBSan on the host harness;
- for a sample, the 16-bit build on simavr gives the host's trace.

bench/fuzz_campaign.py --language runs the same checks on many more."""
from __future__ import annotations

import os
from pathlib import Path

import pytest
from hypothesis import HealthCheck, given, seed, settings

from conftest import FUZZ_FIXED_SEED, FUZZ_SEED
from epuckc.check.frontend import check_file
from epuckc.diagnostics import Report
from epuckc.emit.program import emit_program
from epuckc.ide.incremental import Analyzer

from tests.support.hostile import Outcome, build_outcomes
from tests.support.language import language_programs

SEEDS = [FUZZ_FIXED_SEED, FUZZ_SEED]
CHECKED = int(os.environ.get("EPUCKC_FUZZ_CHECKED", "150"))
BUILT = int(os.environ.get("EPUCKC_FUZZ_BUILT", "15"))


def front_end(text: str):
    """check, compile (in process) and the language server's analysis of
    one text; an exception here is an internal error."""
    report = Report()
    result = check_file(Path("fuzz.epk"), report, shown_name="fuzz.epk", text=text)
    if result.checked is not None:
        emit_program(result.checked, result.source.text, "fuzz")
    analysis = Analyzer("fuzz.epk").analyse(text)
    return report, result, analysis


def _key(d):
    return d.code, d.span.line, d.span.column, d.message


@pytest.mark.parametrize("fuzz_seed", SEEDS, ids=["fixed", "new"])
def test_no_internal_error_and_the_editor_agrees(fuzz_seed):
    counts = {"accepted": 0, "rejected": 0}

    @seed(fuzz_seed)
    @settings(max_examples=CHECKED, deadline=None, database=None,
              suppress_health_check=list(HealthCheck))
    @given(language_programs())
    def prop(program):
        report, result, analysis = front_end(program.text)
        counts["accepted" if result.checked is not None else "rejected"] += 1
        assert sorted(map(_key, analysis.diagnostics)) == sorted(map(_key, report.diagnostics))

    prop()
    # the generator must reach both sides of the checker
    assert counts["accepted"] > CHECKED // 5 and counts["rejected"] > 0, counts


@pytest.mark.parametrize("fuzz_seed", SEEDS, ids=["fixed", "new"])
def test_accepted_programs_build_for_16_and_32_bits_and_run_clean(tmp_path_factory, fuzz_seed):
    outcomes = build_outcomes(tmp_path_factory, language_programs(), BUILT, "language",
                              fuzz_seed)
    assert outcomes.count(Outcome.BUILT) > 0, outcomes
