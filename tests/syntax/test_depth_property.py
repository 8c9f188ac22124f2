"""The depth limit as a property (syntax/limits.py): a statement of any
mixture of nestings (expressions in expressions, conditions, `if`s in
`if`s, from one kind to another, a named action spliced in; drawn by
tests/support/nesting.py) at exactly MAX_DEPTH goes through every stage
with a stack already 150 frames deep: the checker, lowering to C, the
formatter (twice, the same), the language server's analysis, and hover and
completion at its deepest point; one level more is one E056, from either
front end, and no stage fails. tests/syntax/test_limits.py has each
nesting alone, built with gcc and avr-gcc."""
from __future__ import annotations

from pathlib import Path

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from epuckc.base.source import SourceFile
from epuckc.check.frontend import check_file
from epuckc.diagnostics import Collector, Report
from epuckc.emit.program import emit_program
from epuckc.ide import completion, hover
from epuckc.ide.fmt import FormatError, format_text
from epuckc.ide.incremental import Analyzer
from epuckc.syntax import accel
from epuckc.syntax.limits import MAX_DEPTH, SLACK, children, measure
from epuckc.syntax.parser import _c_driver, parse_c, parse_python

from tests.support.language import _Drawn
from tests.support.nesting import HEAD, STATEMENTS, exactly, plan

FRAMES = 150


def with_stack_used(frames: int, f, *args):
    if frames == 0:
        return f(*args)
    return with_stack_used(frames - 1, f, *args)


@st.composite
def nested_statements(draw):
    """(the statement at MAX_DEPTH, the same one level deeper)."""
    r = _Drawn(draw)
    statement = STATEMENTS[r.integers(0, len(STATEMENTS) - 1)]
    layers = plan(r, statement, MAX_DEPTH)
    return (exactly(statement[0], layers, MAX_DEPTH),
            exactly(statement[0], layers, MAX_DEPTH + 1))


def deepest(text: str) -> tuple:
    """(line, column) of the deepest node of the last statement of `text`."""
    source = SourceFile("d.epk", text)
    statement = parse_python(source, Collector(source)).statements[-1]
    best, todo = (0, statement), [(statement, 1)]
    while todo:
        node, depth = todo.pop()
        if depth > best[0]:
            best = (depth, node)
        todo.extend((child, depth + 1) for child in children(node))
    span = best[1].span
    return span.line, span.column


def _check(text):
    report = Report()
    result = check_file(Path("d.epk"), report, shown_name="d.epk", text=text)
    return report, result


def _errors(report) -> list:
    return [d.code for d in report.diagnostics if d.severity == "error"]


@settings(max_examples=20, deadline=None, database=None,
          suppress_health_check=list(HealthCheck))
@given(nested_statements())
def test_any_nesting_at_the_limit_passes_every_stage_and_one_more_is_e056(pair):
    at, past = HEAD + pair[0] + "\n", HEAD + pair[1] + "\n"
    report, result = with_stack_used(FRAMES, _check, at)
    assert _errors(report) == [], [d.message for d in report.diagnostics]
    with_stack_used(FRAMES, emit_program, result.checked, at, "d")
    formatted = with_stack_used(FRAMES, format_text, at)
    assert with_stack_used(FRAMES, format_text, formatted) == formatted
    analysis = with_stack_used(FRAMES, Analyzer("d.epk").analyse, at)
    assert "E056" not in [d.code for d in analysis.diagnostics]
    line, column = deepest(at)
    with_stack_used(FRAMES, hover.hover, analysis, line, column)
    with_stack_used(FRAMES, completion.completions, analysis, line, column)

    report, _ = with_stack_used(FRAMES, _check, past)
    assert _errors(report).count("E056") == 1
    analysis = with_stack_used(FRAMES, Analyzer("d.epk").analyse, past)
    assert [d.code for d in analysis.diagnostics].count("E056") == 1
    with pytest.raises(FormatError) as refused:     # (as for a syntax error)
        with_stack_used(FRAMES, format_text, past)
    assert "E056" in [d.code for d in refused.value.diagnostics]

    source = SourceFile("d.epk", past)
    by_python = Collector(source)
    python = parse_python(source, by_python)
    if accel.front() is not None:
        by_c = Collector(source)
        assert parse_c(_c_driver(), source, by_c).statements == python.statements
        assert [(d.code, d.span) for d in by_c.items] == [(d.code, d.span) for d in by_python.items]
    for statement in python.statements:     # limits.narrow's bound holds
        span = statement.span
        if span.line == span.end_line:
            assert measure(statement, None)[0] <= span.end_column - span.column + SLACK
