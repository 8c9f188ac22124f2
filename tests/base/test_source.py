"""Decoding a rule file (base/source.py): a NUL byte or a byte that is not
UTF-8 is E004, and its diagnostic points at the byte, on the line as the
user's editor shows it (any line ends: \\n, \\r\\n, a lone \\r)."""
import re

from hypothesis import given, settings
from hypothesis import strategies as st

from epuckc.base.source import SourceFile
from epuckc.diagnostics import Collector, Report
from epuckc.diagnostics.render import render_report

LINE_ENDS = re.compile(r"\r\n|\r|\n")


def _where(text: str, offset: int) -> tuple:
    """(line, column) of a character offset, counted as editors count them."""
    before = LINE_ENDS.split(text[:offset])
    return len(before), len(before[-1]) + 1


def _e004(data: bytes):
    source, problem = SourceFile.from_bytes(data, "f.epk")
    assert problem is not None
    start, end, message = problem
    diags = Collector(source)
    diags.error("E004", source.span(start, end), message, help="h")
    report = Report()
    report.sources["f.epk"] = source
    report.extend(diags.items)
    return diags.items[0], render_report(report, "human")


text_with_line_ends = st.lists(
    st.one_of(st.text(st.characters(blacklist_categories=("Cs", "Cc")), max_size=8),
              st.sampled_from(["\n", "\r\n", "\r", "\t"])), max_size=12).map("".join)


@settings(max_examples=300, deadline=None)
@given(text_with_line_ends, text_with_line_ends)
def test_a_nul_byte_is_pointed_at_and_shown(before, after):
    data = before.encode() + b"\0" + after.encode()
    diag, shown = _e004(data)
    line, column = _where(before, len(before))
    assert (diag.span.line, diag.span.column) == (line, column)
    assert diag.span.end_column == column + 1
    # the excerpt shows the byte as \0 and the caret stands under it
    excerpt, caret = [row.split("|", 1)[1] for row in shown.splitlines()[1:3]]
    start = caret.index("^")
    assert excerpt[start:start + 2] == "\\0" and caret[start:].rstrip() == "^^"


@settings(max_examples=200, deadline=None)
@given(text_with_line_ends)
def test_a_byte_that_is_not_utf8_is_pointed_at(before):
    diag, _ = _e004(before.encode() + b"\xff rest")
    assert (diag.span.line, diag.span.column) == _where(before, len(before))
