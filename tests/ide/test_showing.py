"""After an edit that moves no statement to another line, the analysis's
sorted diagnostics are the last ones spliced by the checker's segments
(ide/showing.py), and what the server publishes the last list spliced the
same way (documents.Conversions): both must be what a from-scratch check
and a fresh server give, errors put in and out (warnings beside an error
dropped and back), intervals moved, W009 said again."""
from __future__ import annotations

import random
from pathlib import Path

from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from epuckc.check.frontend import check_file
from epuckc.diagnostics import Report
from epuckc.ide import documents, showing
from epuckc.ide.lsp import Document, EpuckServer

REPO = Path(__file__).resolve().parents[2]
CASES = REPO / "tests" / "check" / "cases"


def _programs() -> list:
    import sys
    sys.path.insert(0, str(REPO / "bench"))
    from lsp_bench import expression_program
    from tests.support.language import RandomChoices, language_program
    out = [expression_program(40, seed=s) for s in range(3)]
    out += [language_program(RandomChoices(random.Random(s))).text for s in range(6)]
    out += [p.read_text(encoding="utf-8") for p in sorted(CASES.glob("W0*.epk"))[:6]]
    return out


PROGRAMS = _programs()
# pieces without a line break: errors in and out, numbers, names, a rule's end
PIECES = ["x", "stop_motr", "stop_motor", "7", "99999", " + 1", " - 7", "v0", "v1", "(", ")",
          " if v0 > 3", ", stop_motor", "set_speed(300 steps/s, 300 steps/s)", "iff", " kg",
          " priority 2", "=", "+=", "é", "@", " do ", "#", '"']


def full_check(text: str) -> list:
    report = Report()
    check_file(Path("/nonexistent/prog.epk"), report, shown_name="prog.epk", text=text)
    return report.sorted()


def _server() -> EpuckServer:
    return type("Server", (EpuckServer,), {"encoding": "utf-16"})()


def _fresh(server, text: str) -> list:
    doc = Document("file:///x/prog.epk", text, 1, server)
    analysis = doc.analyse()
    return [server.diagnostic(doc, analysis, d) for d in analysis.diagnostics]


@settings(max_examples=100, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(st.integers(0, len(PROGRAMS) - 1),
       st.lists(st.tuples(st.integers(0, 10_000), st.integers(0, 6),
                          st.lists(st.sampled_from(PIECES), max_size=2)),
                min_size=1, max_size=8))
def test_edits_on_one_line_spliced_equal_a_full_check(which, edits):
    server = _server()
    doc = Document("file:///x/prog.epk", PROGRAMS[which], 1, server)
    server.diagnostics(doc, doc.analyse())
    for at, length, pieces in edits:
        at %= len(doc.text) + 1
        if "\n" in doc.text[at:at + length]:
            continue            # (moving lines: another path)
        doc.text = doc.text[:at] + "".join(pieces) + doc.text[at + length:]
        analysis = doc.analyse()
        assert analysis.diagnostics == full_check(doc.text)
        assert server.diagnostics(doc, analysis) == _fresh(server, doc.text)


def test_an_editing_session_is_spliced(monkeypatch):
    """(The property above is about the splices: a session of one-line
    edits takes them, warnings dropped beside an error and back too.)"""
    spliced = []
    for owner in (showing.Shown, documents.Conversions):
        real = owner._splice

        def counting(self, *a, _real=real, _owner=owner):
            found = _real(self, *a)
            spliced.append((_owner, found is not None))
            return found
        monkeypatch.setattr(owner, "_splice", counting)
    server = _server()
    text = PROGRAMS[0]
    doc = Document("file:///x/prog.epk", text, 1, server)
    server.diagnostics(doc, doc.analyse())
    rng = random.Random(31)
    for _ in range(30):
        at = rng.choice([i for i in range(len(doc.text)) if doc.text.startswith("v", i)])
        doc.text = doc.text[:at] + rng.choice(["x", "v", "(", "9"]) + doc.text[at + 1:]
        analysis = doc.analyse()
        assert analysis.diagnostics == full_check(doc.text)
        assert server.diagnostics(doc, analysis) == _fresh(server, doc.text)
    assert sum(ok for owner, ok in spliced if owner is showing.Shown) >= 20
    assert sum(ok for owner, ok in spliced if owner is documents.Conversions) >= 20
