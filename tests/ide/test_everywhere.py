"""The editor answers at every position of every file of the corpus (the
examples, the golden cases and programs, and generated programs of the
whole language), without an error: hover, completion, definition,
references, rename."""
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


@settings(max_examples=40, deadline=None, suppress_health_check=list(HealthCheck))
@given(language_programs())
def test_every_request_answers_at_every_position_of_generated_programs(program):
    answer_everywhere(program.text)
