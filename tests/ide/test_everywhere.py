"""The editor answers at every position of every file of the corpus (the
examples, the golden cases and programs, and generated programs of the
whole language), without an error: hover, completion, definition,
references, rename; on the generated programs, each answer checked against
what it must be (tests/support/ide_walk.py)."""
from __future__ import annotations

from pathlib import Path

import pytest
from hypothesis import HealthCheck, given, settings

from tests.support.ide_walk import answer_everywhere
from tests.support.language import language_programs

REPO = Path(__file__).resolve().parents[2]
CORPUS = sorted([*(REPO / "examples").glob("*.epk"), *(REPO / "tests" / "golden").glob("*.epk"),
                 *(REPO / "tests" / "check" / "cases").glob("*.epk")])


@pytest.mark.parametrize("path", CORPUS, ids=lambda p: f"{p.parent.name}/{p.name}")
def test_every_request_answers_at_every_position_of_the_corpus(path):
    text = path.read_text(encoding="utf-8", errors="replace")
    assert answer_everywhere(text, path.name) >= len(text.splitlines())


@settings(max_examples=25, deadline=None, suppress_health_check=list(HealthCheck))
@given(language_programs())
def test_every_request_answers_rightly_across_generated_programs(program):
    """At every other position (and each line's end), with the answers
    checked: hovers and names under the cursor, definitions and references
    agreeing, renames that keep the program's meaning and undo exactly."""
    answer_everywhere(program.text, step=2, check=True)
