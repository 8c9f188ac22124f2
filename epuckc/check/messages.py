"""Wording shared by the checker's concerns: names in backquotes, suggestions,
examples of a kind's values, counts."""
from __future__ import annotations

from typing import Optional

from ..diagnostics import Fix
from ..stdlib.table import Param
from ..stdlib.units import ANGLE, DISTANCE, DURATION, INT, SPEED
from ..syntax import ast
from .program import BOOL

KIND_WORDS = {INT: "a plain number", DISTANCE: "a distance (mm)", SPEED: "a speed (steps/s)",
              ANGLE: "an angle (deg)", DURATION: "a duration (ms)", BOOL: "a condition"}


def _kind_word(kind: str) -> str:
    return KIND_WORDS.get(kind, kind)


def did_you_mean(ident: ast.Ident, candidates) -> Optional[Fix]:
    """The closest of `candidates` to a misspelt name, as a fix that
    replaces the name (its help reads "did you mean `start_straight`?")."""
    import difflib  # only for a misspelt name: `check` starts faster without it
    close = difflib.get_close_matches(ident.name, sorted(candidates), n=1, cutoff=0.6)
    return Fix(ident.span, close[0], f"did you mean `{close[0]}`?") if close else None


def _code(text: str) -> str:
    return f"`{text}`"


def _shown(value) -> str:
    """A value or expression as the formatter would write it."""
    cls = value.__class__
    if cls is ast.Number:
        return value.text + (f" {value.unit}" if value.unit else "")
    if cls is ast.ConstRef:
        return ("-" if value.negative else "") + value.name.name
    if cls is ast.BinOp:
        return f"{_shown(value.left)} {value.op} {_shown(value.right)}"
    if cls is ast.UnaryOp:
        return f"not {_shown(value.operand)}" if value.op == "not" \
            else f"{value.op}{_shown(value.operand)}"
    if cls is ast.Paren:
        return f"({_shown(value.expr)})"
    if cls is ast.FuncCall:
        return f"{value.name.name}({', '.join(_shown(a.value) for a in value.args or ())})"
    if cls is ast.Ident:
        return value.name
    if cls is ast.Index:
        return f"{value.name.name}[{_shown(value.index)}]"
    if cls is ast.Slice:
        return (f"{value.name.name}[{'' if value.lo is None else _shown(value.lo)}:"
                f"{'' if value.hi is None else _shown(value.hi)}]")
    if cls is ast.ArrayLit:
        return f"[{', '.join(_shown(item) for item in value.items)}]"
    if cls is ast.Assign:
        return f"{_target(value)} {value.op} {_shown(value.value)}"
    return "..."


def _target(assign) -> str:
    """What an assignment assigns: `n`, or `a[i]`."""
    name = assign.target.name
    return name if assign.index is None else f"{name}[{_shown(assign.index)}]"


def _clip(text: str, limit: int = 24) -> str:
    return text if len(text) <= limit else text[:limit] + "..."


def _article(word: str) -> str:
    return "an" if word[:1] in "aeiouAEIOU" or word == "LED" else "a"


def _then(fix: Optional[Fix], more: str):
    """A fix followed by more help, or the help alone."""
    return fix.then(more) if fix is not None else more


def _either(names) -> str:
    names = [_code(n) for n in names]
    return names[0] if len(names) == 1 else ", ".join(names[:-1]) + " or " + names[-1]


def _count(n: int) -> str:
    return {0: "no arguments", 1: "1 argument"}.get(n, f"{n} arguments")


def _signature_help(name: str, params) -> str:
    if not params:
        return f"write `{name}` with no arguments"
    return f"write `{name}({', '.join(f'{p.name}: {_example_of(p)}' for p in params)})`"


def _example_of(p: Param) -> str:
    return p.choices.values[0].name if p.choices is not None else _example(p.kind)


def _example(kind: str) -> str:
    return {DISTANCE: "10 cm", SPEED: "300 steps/s", ANGLE: "90 deg",
            DURATION: "2 s", INT: "3"}[kind]
