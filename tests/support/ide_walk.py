"""Every request of the editor at every position of a text: hover,
completion, definition, references and rename (prepare and do). The
language server answers each from these functions; none may raise (a
RenameError is an answer: the message the editor shows)."""
from __future__ import annotations

from epuckc.ide import completion, hover, navigate
from epuckc.ide.incremental import Analyzer


def positions(text: str, step: int = 1):
    """(line, column) of every `step`-th character and of each line's end,
    1-based."""
    for ln, line in enumerate(text.split("\n"), 1):
        for col in sorted({*range(1, len(line) + 2, step), len(line) + 1}):
            yield ln, col


def answer_everywhere(text: str, name: str = "walk.epk", step: int = 1) -> int:
    """Ask everything everywhere; returns how many answers were given, and
    raises AssertionError naming the request, position and error."""
    analysis = Analyzer(name).analyse(text)
    navigate.symbols(analysis)
    answers = 0
    for ln, col in positions(text, step):
        where = f"{name}:{ln}:{col}"
        try:
            hover.hover(analysis, ln, col)
            completion.completions(analysis, ln, col)
            occ = navigate.occurrence_at(analysis, ln, col)
            if occ is not None:
                target = navigate.resolve(analysis, occ)
                if target is not None and target.statement is not None:
                    navigate.references(analysis, target)
                try:
                    target = navigate.renameable(analysis, occ)
                    navigate.rename_edits(analysis, target, "renamed_name")
                except navigate.RenameError:
                    pass
        except Exception as exc:  # noqa: BLE001 - the point is to catch any
            raise AssertionError(f"{where}: {type(exc).__name__}: {exc}\n--- text ---\n"
                                 f"{text}") from exc
        answers += 1
    return answers
