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


class _Server:
    """An EpuckServer with a fixed position encoding (no client to negotiate it)."""
    def __new__(cls, encoding):
        from epuckc.ide.lsp import EpuckServer
        return type("Server", (EpuckServer,), {"encoding": encoding})()


def test_kept_lsp_diagnostics_are_those_a_fresh_server_makes():
    """The server keeps each diagnostic's LSP form between edits (issue 31):
    edit after edit, in every encoding, what it publishes is what a server
    that never saw the document before makes of the same text."""
    import random
    from pathlib import Path

    from epuckc.ide.lsp import Document
    cases = Path(__file__).resolve().parents[1] / "check" / "cases"
    programs = sorted(cases.glob("W0*.epk"))[:6]
    pieces = ["é", "😀", " # é\n", "\n", "stop_motor", "on immediate do x\n",
              "start_straight(300, 2 m)", "v", "  ", "rule r: ", "on timer(1 s) do set_timer\n"]
    rng = random.Random(31)
    for encoding in ("utf-16", "utf-8", "utf-32"):
        server = _Server(encoding)
        for path in programs:
            doc = Document("file:///x/prog.epk", path.read_text(encoding="utf-8"), 1, server)
            for _ in range(12):
                analysis = doc.analyse()
                kept = [server.diagnostic(doc, analysis, d) for d in analysis.diagnostics]
                fresh_doc = Document("file:///x/prog.epk", doc.text, 1, server)
                fresh = fresh_doc.analyse()
                assert kept == [server.diagnostic(fresh_doc, fresh, d) for d in fresh.diagnostics]
                at = rng.randint(0, len(doc.text))
                end = at + rng.choice([0, 0, 1, 3])
                doc.text = doc.text[:at] + rng.choice(pieces) + doc.text[end:]


def test_a_kept_diagnostic_moves_with_the_code_units_before_it_on_its_line():
    """Two statements on one line; a bad character of the first becomes
    one of as many characters but not as many UTF-16 units: the second
    statement is the same (same column), and so is its diagnostic object,
    but its LSP range is not."""
    from epuckc.ide.lsp import Document
    server = _Server("utf-16")
    doc = Document("file:///x/prog.epk",
                   "on immediate do stop_motor é on timer(1 s) do stop_motr\n", 1, server)
    analysis = doc.analyse()
    before = [server.diagnostic(doc, analysis, d) for d in analysis.diagnostics]
    kept = {id(d) for d in analysis.diagnostics}
    doc.text = doc.text.replace("é", "😀")
    analysis = doc.analyse()
    assert any(id(d) in kept for d in analysis.diagnostics)     # (the case in question)
    after = [server.diagnostic(doc, analysis, d) for d in analysis.diagnostics]
    fresh_doc = Document("file:///x/prog.epk", doc.text, 1, server)
    fresh = fresh_doc.analyse()
    assert after == [server.diagnostic(fresh_doc, fresh, d) for d in fresh.diagnostics]
    moved = [(b.range, a.range) for b in before for a in after
             if "stop_motr" in a.message and "stop_motr" in b.message]
    assert moved and all(a.start.character == b.start.character + 1 for b, a in moved)
