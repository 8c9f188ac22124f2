"""LSP positions: lines end at \\n, \\r\\n or \\r; columns count UTF-16 (or
UTF-8, UTF-32) code units; positions outside the text are clamped."""
from __future__ import annotations

from lsprotocol.types import Position

from epuckc.ide.lsp import Lines, line_edits

TEXT = "on é\r\nx😀y\rlast\n"


def test_positions_in_each_encoding():
    for encoding, y_column in (("utf-16", 3), ("utf-8", 5), ("utf-32", 2)):
        lines = Lines(TEXT, encoding)
        y = TEXT.index("y")
        assert lines.position(y) == Position(1, y_column)
        assert lines.offset(Position(1, y_column)) == y
        assert lines.position(TEXT.index("last")) == Position(2, 0)
        assert lines.offset(Position(0, 4 if encoding != "utf-8" else 5)) == TEXT.index("\r")


def test_positions_outside_the_text_are_clamped():
    lines = Lines(TEXT, "utf-16")
    assert lines.offset(Position(0, 99)) == TEXT.index("\r")        # end of the line
    assert lines.offset(Position(99, 0)) == len(TEXT)
    # between \r and \n there is no position: the one before the \r is used
    assert lines.position(TEXT.index("\n")) == Position(0, 4)


def test_line_edits_rebuild_the_new_text():
    old = "a\nb\r\nc\rd\n"
    new = "a\nB\r\nc\rd\ne\n"
    text = old
    for start, end, replacement in reversed(line_edits(old, new)):
        text = text[:start] + replacement + text[end:]
    assert text == new
