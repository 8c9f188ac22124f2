"""Every request of the editor at every position of a text: hover,
completion, definition, references and rename (prepare and do). The
language server answers each from these functions; none may raise (a
RenameError is an answer: the message the editor shows). With `check`,
the answers are also checked against what they must be:

- a hover and a name found under the cursor cover the cursor;
- a name that resolves to a definition in the file is among the
  references of what it resolves to, and the definition resolves to the
  same (go to definition and find references agree);
- each rename, applied to the text, gives a program with the same
  diagnostics (codes and places) in which the new name resolves where
  the old one did, and renaming it back gives the text byte for byte.
"""
from __future__ import annotations

from epuckc.ide import completion, hover, navigate
from epuckc.ide.incremental import Analyzer


def positions(text: str, step: int = 1):
    """(line, column) of every `step`-th character and of each line's end,
    1-based."""
    for ln, line in enumerate(text.split("\n"), 1):
        for col in sorted({*range(1, len(line) + 2, step), len(line) + 1}):
            yield ln, col


def _covers(span, line: int, column: int) -> bool:
    """The position is in the span (or just past its end: the cursor after
    a word is on it)."""
    return (span.line, span.column) <= (line, column) <= (span.end_line, span.end_column)


def _apply(text: str, edits: list) -> str:
    starts = [0]
    for line in text.split("\n"):
        starts.append(starts[-1] + len(line) + 1)
    for span, new in sorted(edits, key=lambda e: (e[0].line, e[0].column), reverse=True):
        a = starts[span.line - 1] + span.column - 1
        b = starts[span.end_line - 1] + span.end_column - 1
        text = text[:a] + new + text[b:]
    return text


def _diagnostics(analysis) -> list:
    return sorted((d.code, d.span.line) for d in analysis.diagnostics)


def _check_rename(analysis, name: str, target, edits: list) -> None:
    """Renamed, the program means the same; renamed back, it is the text."""
    old = target.name
    renamed = _apply(analysis.text, edits)
    again = Analyzer(name).analyse(renamed)
    assert _diagnostics(again) == _diagnostics(analysis), "a rename changed the diagnostics"
    first = min(span for span, _ in edits)
    occ = navigate.occurrence_at(again, first.line, first.column)
    assert occ is not None and occ.ident.name == "renamed_name", "the new name is not found"
    back = navigate.rename_edits(again, navigate.renameable(again, occ), old)
    assert _apply(renamed, back) == analysis.text, "renaming back does not give the text"


def _check_names(analysis, ln: int, col: int, occ) -> None:
    assert _covers(analysis.real(occ.ident.span), ln, col), "the name found is elsewhere"
    target = navigate.resolve(analysis, occ)
    if target is None or target.statement is None or target.ident is None:
        return
    refs = navigate.references(analysis, target)
    if not occ.definition or occ.ident is target.ident:
        assert any(r.ident is occ.ident for r in refs), "a use is not among the references"
    span = analysis.real(target.ident.span)
    at_definition = navigate.occurrence_at(analysis, span.line, span.column)
    assert at_definition is not None and navigate.resolve(analysis, at_definition) == target, \
        "the definition does not resolve to itself"


def answer_everywhere(text: str, name: str = "walk.epk", step: int = 1,
                      check: bool = False) -> int:
    """Ask everything everywhere; returns how many answers were given, and
    raises AssertionError naming the request, position and error. With
    `check`, the answers are checked too (see the module's doc)."""
    analysis = Analyzer(name).analyse(text)
    navigate.symbols(analysis)
    answers = 0
    renamed = set()
    for ln, col in positions(text, step):
        where = f"{name}:{ln}:{col}"
        try:
            shown = hover.hover(analysis, ln, col)
            if check and shown is not None:
                assert _covers(shown[1], ln, col), f"the hover is about {shown[1]}"
            completion.completions(analysis, ln, col)
            occ = navigate.occurrence_at(analysis, ln, col)
            if occ is not None:
                if check:
                    _check_names(analysis, ln, col, occ)
                target = navigate.resolve(analysis, occ)
                if target is not None and target.statement is not None:
                    navigate.references(analysis, target)
                try:
                    target = navigate.renameable(analysis, occ)
                    edits = navigate.rename_edits(analysis, target, "renamed_name")
                    if check and (target.namespace, target.name) not in renamed:
                        renamed.add((target.namespace, target.name))
                        _check_rename(analysis, name, target, edits)
                except navigate.RenameError:
                    pass
        except Exception as exc:  # noqa: BLE001 - the point is to catch any
            raise AssertionError(f"{where}: {type(exc).__name__}: {exc}\n--- text ---\n"
                                 f"{text}") from exc
        answers += 1
    return answers
