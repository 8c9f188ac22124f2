"""What the language server publishes after an edit (documents.Conversions,
issue 31): the LSP form of each diagnostic kept from the last analysis
unless its lines were edited or moved, and the list always the one a
server that never saw the document makes of the same text."""
from __future__ import annotations

import random
from pathlib import Path

from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from epuckc.ide.lsp import Document, EpuckServer

CASES = Path(__file__).resolve().parents[1] / "check" / "cases"
PROGRAMS = [p.read_text(encoding="utf-8") for p in sorted(CASES.glob("W0*.epk"))[:8]]
PIECES = ["é", "😀", " # é\n", "\n", "\r\n", "\r", "stop_motor", "on immediate do x\n",
          "start_straight(300, 2 m)", "v", "  ", "rule r: ", "on timer(1 s) do set_timer\n",
          "on immediate do stop_motr é on timer(1 s) do stop_motr\n", "var v = 1\n",
          "every 10 ms do v = v + 1\n", "\n\n\n"]


def _server(encoding: str) -> EpuckServer:
    return type("Server", (EpuckServer,), {"encoding": encoding})()


def _fresh(server, text: str) -> list:
    doc = Document("file:///x/prog.epk", text, 1, server)
    analysis = doc.analyse()
    return [server.diagnostic(doc, analysis, d) for d in analysis.diagnostics]


@settings(max_examples=60, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(st.sampled_from(("utf-16", "utf-8", "utf-32")), st.integers(0, len(PROGRAMS) - 1),
       st.lists(st.tuples(st.integers(0, 10_000), st.integers(0, 12),
                          st.lists(st.sampled_from(PIECES), max_size=3)),
                min_size=1, max_size=8))
def test_published_after_each_edit_is_what_a_fresh_server_makes(encoding, which, edits):
    server = _server(encoding)
    doc = Document("file:///x/prog.epk", PROGRAMS[which], 1, server)
    assert server.diagnostics(doc, doc.analyse()) == _fresh(server, doc.text)
    for at, length, pieces in edits:
        at %= len(doc.text) + 1
        doc.text = doc.text[:at] + "".join(pieces) + doc.text[at + length:]
        assert server.diagnostics(doc, doc.analyse()) == _fresh(server, doc.text)


def test_an_edit_converts_only_what_it_reaches():
    """An edit of one rule of many keeps the LSP objects of the other
    rules' diagnostics (the same objects), above and below it."""
    server = _server("utf-16")
    text = "".join(f"on timer({i + 1} s) do set_timer, stop_motr\n" for i in range(60))
    doc = Document("file:///x/prog.epk", text, 1, server)
    before = server.diagnostics(doc, doc.analyse())
    at = doc.text.index("timer(30 s)")
    doc.text = doc.text[:at] + "timer(31 s)" + doc.text[at + len("timer(30 s)"):]
    after = server.diagnostics(doc, doc.analyse())
    assert after == _fresh(server, doc.text)
    same = sum(any(a is b for b in before) for a in after)
    assert len(after) - 3 <= same < len(after)
    # a line added above moves every diagnostic below it: those are new
    doc.text = doc.text[:at] + "\n" + doc.text[at:]
    moved = server.diagnostics(doc, doc.analyse())
    assert moved == _fresh(server, doc.text)
    assert sum(any(a is b for b in after) for a in moved) <= len(moved) // 2 + 3


def test_a_kept_diagnostic_is_converted_again_when_its_line_changes():
    """Two statements on one line; the first's bad character becomes one
    of as many characters but not as many code units: the second's
    diagnostic is the same object, its LSP range is not the same."""
    for encoding in ("utf-16", "utf-8"):
        server = _server(encoding)
        doc = Document("file:///x/prog.epk", "on immediate do stop_motor é on timer(1 s) do "
                       "stop_motr\non timer(2 s) do stop_motr\n", 1, server)
        before = server.diagnostics(doc, doc.analyse())
        kept = {id(d) for d in doc.analysis.diagnostics}
        doc.text = doc.text.replace("é", "😀")
        after = server.diagnostics(doc, doc.analyse())
        assert any(id(d) in kept for d in doc.analysis.diagnostics)    # (the case in question)
        assert after == _fresh(server, doc.text) and after != before
        assert after[-1] is before[-1]      # (the next line's is kept)


def test_random_sessions_in_every_encoding():
    rng = random.Random(31)
    for encoding in ("utf-16", "utf-8", "utf-32"):
        server = _server(encoding)
        for program in PROGRAMS[:4]:
            doc = Document("file:///x/prog.epk", program, 1, server)
            for _ in range(15):
                assert server.diagnostics(doc, doc.analyse()) == _fresh(server, doc.text)
                at = rng.randint(0, len(doc.text))
                if rng.random() < 0.3:      # a character of another width in its place
                    doc.text = doc.text[:at] + rng.choice("é😀x") + doc.text[at + 1:]
                    continue
                end = at + rng.choice([0, 0, 1, 3, 20])
                doc.text = doc.text[:at] + rng.choice(PIECES) + doc.text[end:]


@settings(max_examples=60, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(st.sampled_from(("utf-16", "utf-8", "utf-32")), st.integers(0, len(PROGRAMS) - 1),
       st.lists(st.lists(st.tuples(st.integers(0, 10_000), st.integers(0, 12),
                                   st.lists(st.sampled_from(PIECES), max_size=3)),
                         min_size=1, max_size=3),
                min_size=1, max_size=6))
def test_changes_as_the_client_sends_them(encoding, which, notifications):
    """Edits that come as didChange's ranges (several changes in one
    notification, each in the client's view of the text after the one
    before): the document knows from them what stayed the same, and the
    analysis uses that instead of comparing the texts; what is published is
    a fresh server's."""
    from lsprotocol import types as lsp
    from epuckc.ide import incremental
    from epuckc.ide.documents import Lines
    compared = []
    real = incremental._common_prefix

    def counted(a, b):
        compared.append(1)
        return real(a, b)
    incremental._common_prefix = counted
    try:
        server = _server(encoding)
        doc = Document("file:///x/prog.epk", PROGRAMS[which], 1, server)
        server.diagnostics(doc, doc.analyse())
        for changes in notifications:
            for at, length, pieces in changes:
                at %= len(doc.text) + 1
                end = min(len(doc.text), at + length)
                lines = Lines(doc.text, encoding)       # (the client's view, as the server's)
                doc.apply(lsp.TextDocumentContentChangePartial(
                    range=lsp.Range(lines.position(at), lines.position(end)),
                    text="".join(pieces)), encoding)
            assert server.diagnostics(doc, doc.analyse()) == _fresh(server, doc.text)
        assert not compared         # (the changes said where the edits were)
    finally:
        incremental._common_prefix = real

