"""Aseba's constructs, which a program ported from Aseba brings and epuckc
has not: each is found in a statement that does not parse and reported with
its own code, naming the construct and the epuckc way [E090-E096]:

| Aseba | code | epuckc |
|---|---|---|
| `while COND do ... end`, `for I in A:B do ... end` | E090 | rules run again by themselves (`every 50 ms if COND do ...`); over an array: `sum(a)`, `dot(a, b)`, `argmax(a)`, `min(a)` |
| `x++`, `x--` | E091 | `x += 1`, `x -= 1` |
| `sub NAME`, `callsub NAME` | E092 | a named action: `action NAME = ACTIONS`, then `NAME` |
| `onevent NAME` | E093 | a rule: `on EVENT do ACTION` (`on sensor(...)`, `every 100 ms`, `on message`) |
| `emit NAME` | E094 | `send(VALUE)` to the robots in range, heard by `on message` |
| `call math.NAME(...)` | E095 | the function itself: `dot(a, b)`, `sqrt(x)`, `min(a)`, ... |
| `sort(a)` | E096 | `argmax(a)`, `argmin(a)` (where the largest, the smallest is), `max(a)`, `min(a)` |

The checker reports `sort` (an unknown action or function, E096) through
`sort_diagnostic`; the parser (parser.py) asks `report` about a statement
that does not parse, before its syntax error in words (errors.py): the first
construct found is said instead, and what comes before it on earlier lines is
parsed on its own (Aseba's blocks carry no keyword epuckc starts a statement
with, so `var s = 0` and the `while` on the next line reach the parser as one
statement)."""
from __future__ import annotations

from typing import Optional

from ..base.source import Span
from ..diagnostics import Fix

_LOOP_HELP = ("a rule runs again by itself: write what the loop does at each turn as a rule "
              "(`every 50 ms if i < 10 do i += 1, ...`); for the elements of an array, "
              "`sum(a)`, `dot(a, b)`, `argmax(a)`, `argmin(a)`, `min(a)`, `max(a)` go over it "
              "whole")
_SORT_HELP = ("arrays are never rearranged in place: `argmax(a)` and "
              "`argmin(a)` are where the largest and the smallest element are, `max(a)` and "
              "`min(a)` their values")
# Aseba's math natives and what epuckc writes instead.
_MATH = {
    "dot": "`dot(a, b)` (the sum of the products, exact to 32 bits; for Aseba's shift n "
           "divide it by 2 to the n: `dot(a, b) / 16` for 4)",
    "stat": "`min(a)`, `max(a)` and `sum(a) / N` (the mean)",
    "argbounds": "`argmin(a)` and `argmax(a)`",
    "sort": "`argmax(a)` and `argmin(a)`, or `max(a)` and `min(a)`: epuckc has no sort",
    "sqrt": "`sqrt(x)`", "atan2": "`atan2(y, x)` (in degrees)",
    "sin": "`sin(a)` (a in degrees, 1000 times the sine)",
    "cos": "`cos(a)` (a in degrees, 1000 times the cosine)",
    "min": "`min(a, b)`", "max": "`max(a, b)`", "clamp": "`clamp(x, lo, hi)`",
    "rand": "`random(lo, hi)`", "muldiv": "`a * b / c` (exact to 32 bits inside an expression)",
}
_NATIVES = ", ".join(f"`{n}`" for n in ("sum", "dot", "argmax", "argmin", "min", "max",
                                         "sqrt", "atan2", "sin", "cos", "clamp", "random"))


def _at_start(chunk: list, i: int) -> bool:
    """Whether chunk[i] starts an action or a line: the first token of the
    statement, after `do`, `,`, `{` or `then`, or first on its line."""
    if i == 0:
        return True
    prev = chunk[i - 1]
    return prev.type in ("_DO", "_COMMA", "_LBRACE", "_THEN") or prev.end_line < chunk[i].line


def _next(chunk: list, i: int):
    return chunk[i + 1] if i + 1 < len(chunk) else None


def _span(first, last=None) -> Span:
    last = last or first
    return Span(first.line, first.column, last.end_line, last.end_column)


def _twin(chunk: list, i: int):
    """chunk[i] and chunk[i + 1] are `++` or `--` written together."""
    tok, nxt = chunk[i], _next(chunk, i)
    return tok.type in ("_PLUS", "MINUS") and nxt is not None and nxt.type == tok.type \
        and nxt.line == tok.line and nxt.column == tok.end_column


def find(chunk: list) -> Optional[tuple]:
    """The first Aseba construct of a statement's tokens: (code, index of
    its first token, message, help), or None."""
    for i, tok in enumerate(chunk):
        word = tok.value if tok.type == "NAME" else None
        nxt = _next(chunk, i)
        named = nxt is not None and nxt.type == "NAME"
        if word in ("while", "for") and _at_start(chunk, i) and nxt is not None \
                and nxt.type not in ("_EQUAL", "_PLUSEQ", "_MINUSEQ", "_LBRACK", "_COLON"):
            return ("E090", i, f"epuckc has no `{word}` loop", _LOOP_HELP)
        if _twin(chunk, i):
            op = tok.value * 2
            before = chunk[i - 1] if i > 0 else None
            after = chunk[i + 2] if i + 2 < len(chunk) else None
            target = before if before is not None and before.type == "NAME" \
                and not _at_start(chunk, i) else after if after is not None \
                and after.type == "NAME" and _at_start(chunk, i) else None
            if target is None:
                continue        # `a - -b`, `--b` inside an expression: epuckc's own
            sign = "+=" if op == "++" else "-="
            first, last = (target, chunk[i + 1]) if target is before else (tok, target)
            return ("E091", i, f"epuckc has no `{op}`",
                    Fix(_span(first, last), f"{target.value} {sign} 1",
                        f"write `{target.value} {sign} 1`"))
        if word in ("sub", "callsub") and named and _at_start(chunk, i):
            name = nxt.value
            how = (f"define it as a named action, `action {name} = ACTIONS` (its actions "
                   f"joined by `,`), and write `{name}` where it is done")
            return ("E092", i, f"epuckc has no `{word}`: subroutines are named actions", how)
        if word == "onevent" and named and _at_start(chunk, i):
            return ("E093", i, "epuckc has no `onevent`: a rule says when it acts",
                    f"write a rule, `on EVENT do ACTION`: Aseba's `onevent {nxt.value}` is "
                    f"e.g. `on sensor(ir0 > 300) do ...`, `every 100 ms do ...` (a timer), "
                    f"`on message do ...` (an event from another robot)")
        if word == "emit" and named and _at_start(chunk, i):
            return ("E094", i, "epuckc has no `emit`: robots talk with IR messages",
                    "`send(VALUE)` sends a number (0..255) to the robots in range, whose "
                    "`on message do ...` rules hear it (`message` is its value)")
        if word == "call" and named and _at_start(chunk, i):
            native = _native(chunk, i)
            instead = _MATH.get(native) if native else None
            shown = f"call {nxt.value}.{native}" if native else f"call {nxt.value}"
            return ("E095", i, f"epuckc has no `call`: `{shown}` is a function here",
                    (f"write {instead} inside an expression" if instead else
                     f"the natives are functions of expressions: {_NATIVES}"))
    return None


def _native(chunk: list, i: int) -> Optional[str]:
    """`dot` of `call math.dot(...)`: the name after the one after `call`
    (its `.` is a character no token starts with)."""
    if i + 2 < len(chunk) and chunk[i + 2].type == "NAME" and chunk[i + 2].after_bad:
        return chunk[i + 2].value
    return None


def report(chunk: list, diags) -> Optional[int]:
    """Reports the first Aseba construct of a statement that does not
    parse; returns the index of its first token (None: none). A `.` of
    `call math.dot` was reported as a character no token starts with
    (E002): the construct says it all, and that report goes."""
    found = find(chunk)
    if found is None:
        return None
    code, i, message, help = found
    tok = chunk[i]
    end = chunk[i + 2] if code == "E095" and _native(chunk, i) else \
        chunk[i + 1] if code in ("E091", "E092", "E093", "E094", "E095") else tok
    diags.error(code, _span(tok, end), message, help=help)
    if code == "E095":
        diags.items[:] = uncovered(diags.items, diags.items[-1:])
    return i


def uncovered(items: list, reports: list) -> list:
    """`items` but the E002 of a `.` inside a `call math.NAME` of `reports`
    (the language server lexes apart from parsing, and filters its own)."""
    calls = [d.span for d in reports if d.code == "E095"]
    return [d for d in items if d.code != "E002" or not any(
        d.span.line == s.line and s.column <= d.span.column < s.end_column for s in calls)]


def sort_diagnostic(diags, span) -> None:
    """`sort(a)`, as an action or a function [E096]."""
    diags.error("E096", span, "epuckc has no `sort`", help=_SORT_HELP)
