"""Syntax errors in words: what the parser wanted, in the user's terms,
with a fix for the likeliest mistake (a `do` missing, `=` for `:`, `and`
between a sensor rule's conditions, ...)."""
from __future__ import annotations

import re

from . import lalr
from ..base.source import SourceFile, Span
from ..diagnostics import Collector, Fix
from .lexer import KEYWORDS, STATEMENT_STARTS

# ---- syntax errors in words -------------------------------------------------

_FRIENDLY = {
    "NAME": "a name", "NUMBER": "a number", "STRING": 'a file name in quotes ("blink.c")',
    "CMP": "`>` or `<`", "MINUS": "`-`", "$END": "the end of the statement",
    "_LPAR": "`(`", "_RPAR": "`)`", "_LBRACK": "`[`", "_RBRACK": "`]`", "_LBRACE": "`{`",
    "_RBRACE": "`}`", "_COMMA": "`,`",
    "_COLON": "`:`", "_EQUAL": "`=`", "_SLASH": "`/`", "_PLUS": "`+`", "_STAR": "`*`",
    "_PERCENT": "`%`", "_PLUSEQ": "`+=`", "_MINUSEQ": "`-=`",
    "_AMP": "`&`", "_PIPE": "`|`", "_CARET": "`^`", "_TILDE": "`~`", "_SHL": "`<<`",
    "_SHR": "`>>`",
}
_OPERATORS = {"_PLUS", "MINUS", "_STAR", "_SLASH", "_PERCENT", "_AMP", "_PIPE", "_CARET",
              "_SHL", "_SHR"}
_STATEMENT_LIST = "a statement (`on`, `rule`, `action`, `const`, `extern`, `robot` or `mode`)"


def _friendly(term: str) -> str:
    if term in _FRIENDLY:
        return _FRIENDLY[term]
    if term.startswith("_"):
        return f"`{term[1:].lower()}`"
    return term


def _describe_found(tok) -> str:
    if tok.type == "$END":
        return "the end of the statement"
    if tok.type in ("NAME", "NUMBER", "STRING"):
        return f"`{tok.value}`"
    return f"`{tok.value}`"


def _describe_expected(prev, expected: set) -> tuple[str, str | None]:
    """What the parser wanted, in the user's words, and a hint."""
    prev_type = prev.type if prev is not None else None
    if prev is None and expected & {"_ON", "_RULE", "_ACTION"}:
        return _STATEMENT_LIST, "every statement starts with one of these keywords"
    if "_CANCEL" in expected:
        return "an action", "name an action, e.g. `stop_motor`, `start_straight(300, 10 cm)` or `cancel RULE`"
    if prev_type == "_ON":
        return "an event", "name an event, e.g. `immediate`, `stop_motor`, `timer(2 s)` or `sensor(ir0 > 300)`"
    if prev_type == "_ACTION":
        return "a name for the action", "write `action NAME = ...`"
    if prev_type == "_CONST":
        return "a name for the constant", "write `const NAME = VALUE`"
    if prev_type == "_RULE":
        return "a name for the rule", "write `rule NAME: on EVENT do ACTION`"
    if expected >= {"NUMBER", "NAME", "MINUS"}:
        wanted = "a value or `)`" if "_RPAR" in expected else "a value"
        return wanted, "a value is a number with an optional unit (`20 cm`) or a constant's name"
    operators = _OPERATORS <= expected
    names = sorted(_friendly(t) for t in expected if not (t == "NAME" and prev_type == "NUMBER")
                   and not (operators and t in _OPERATORS)
                   and not (operators and t == "CMP"))
    if prev_type == "NUMBER" and "NAME" in expected:
        names.append("a unit")
    if operators:
        names.append("an operator")
    if not names:
        return "nothing more", None
    wanted = ", ".join(names[:-1]) + " or " + names[-1] if len(names) > 1 else names[0]
    if "_DO" in expected:
        hint = "a rule reads `on EVENT do ACTION`"
    elif "_RPAR" in expected:
        hint = "is a `)` missing?"
    elif "_RBRACE" in expected:
        hint = "is a `}` missing?"
    else:
        hint = None
    return wanted, hint


def syntax_error(exc: lalr.ParseError, chunk: list, following, source: SourceFile,
                  diags: Collector):
    tok = exc.token
    if getattr(tok, "after_bad", False) and chunk and tok is not chunk[0]:
        # the unexpected character just before it, in this statement, is
        # already reported (E002). One before the statement's first token
        # belongs to the statement before: the language server, which lexes
        # each statement on its own, could not see it, and must say the same.
        return
    if tok.type == "$END":
        # Point at the last token read: that is where something is missing.
        prev = chunk[-1]
        span = Span(prev.line, prev.column, prev.end_line, prev.end_column)
        if following is not None:
            found = f"`{following.value}`, which starts a new statement"
        else:
            found = "the end of the file"
    else:
        index = next(i for i, t in enumerate(chunk) if t is tok)
        prev = chunk[index - 1] if index > 0 else None
        found = _describe_found(tok)
        span = Span(tok.line, tok.column, tok.end_line, tok.end_column)
    expected = set(exc.before)
    wanted, hint = _describe_expected(prev, expected)
    after = f" after `{prev.value}`" if prev is not None else ""
    if tok.type == "_EQUAL" and "_COLON" in expected and prev is not None:
        # `start_straight(speed = 300, ...)`: arguments are named with `:`
        diags.error("E001", span, f"expected `:` after `{prev.value}`, found `=`",
                    help=_fix(tok, prev, expected,
                              f"arguments are named with `:`: write `{prev.value}: ...`"))
        return
    if _if_error(chunk, tok, prev, expected, span, found, diags):
        return
    joint = _joining_word(chunk, tok, prev, expected)
    if joint is not None:
        # `sensor(ir0 > 300 and ir7 > 300)`: `and` (read as a unit after a
        # number, or found after a constant) joins two conditions
        word, before = joint.value, chunk[chunk.index(joint) - 1]
        where = Span(joint.line, joint.column, joint.end_line, joint.end_column)
        if word == "or":
            help = Fix(Span(before.end_line, before.end_column, joint.end_line, joint.end_column),
                       ",", "conditions are separated by `,`, which means or: "
                            "write `,` for `or`")
        else:
            help = _when_fix(chunk, source) or (
                "conditions are separated by `,`, which means *or*: the rule occurs when "
                "any of them becomes true; to wait for two at once, write a `when` rule: "
                "`when ir0 > 300 and ir7 > 300 do ...`")
        diags.error("E001", where, f"`{word}` cannot join the conditions of an event", help=help)
        return
    if tok.type == "_REPEAT" and "_DO" in expected and index >= 2 \
            and chunk[index - 2].type == "_PRIORITY":
        # `on ... priority 1 repeat do`: the words go the other way round
        first = chunk[index - 2]
        order = f"repeat priority {prev.value}"
        diags.error("E001", span, f"expected {wanted}{after}, found `repeat`",
                    help=Fix(Span(first.line, first.column, tok.end_line, tok.end_column), order,
                             f"`repeat` comes before `priority`: write `{order}`"))
        return
    keyword = KEYWORDS.get(tok.value.lower()) if tok.type == "NAME" else None
    if keyword is not None and (keyword in expected
                                or (prev is None and keyword in STATEMENT_STARTS)):
        diags.error("E001", span, f"expected {wanted}{after}, found `{tok.value}`",
                    help=Fix(span, tok.value.lower(),
                             f"keywords are lower case: write `{tok.value.lower()}`, "
                             f"not `{tok.value}`"))
        return
    diags.error("E001", span, f"expected {wanted}{after}, found {found}",
                help=_fix(tok, prev, expected, hint))


def _open_if_brace(chunk: list, upto: int):
    """The `{` of an `if` (or `else`) in chunk[:upto] that is not closed, or None."""
    opened = []
    for i, t in enumerate(chunk[:upto]):
        if t.type == "_LBRACE":
            opened.append(i)
        elif t.type == "_RBRACE" and opened:
            opened.pop()
    for i in reversed(opened):
        if i > 0 and any(t.type in ("_IF", "_ELSE") for t in chunk[max(0, i - 64):i]):
            return chunk[i]
    return None


def _if_error(chunk, tok, prev, expected, span, found, diags) -> bool:
    """The likeliest mistakes in an `if` action, in words: a `}` missing, the
    braces left out, an empty branch, `elif`. Whether it was one."""
    if prev is None or not any(t.type in ("_IF", "_ELSE") for t in chunk):
        return False
    at = len(chunk) if tok.type == "$END" else next(i for i, t in enumerate(chunk) if t is tok)
    brace = _open_if_brace(chunk, at)
    if "_RBRACE" in expected and brace is not None and tok.type != "_RBRACE" \
            and "_RPAR" not in expected:
        diags.error("E001", span, f"the `{{` on line {brace.line} (column {brace.column}) is "
                                  f"never closed: expected `}}` after `{prev.value}`, found {found}",
                    help=Fix(Span(prev.end_line, prev.end_column, prev.end_line, prev.end_column),
                             " }", "close the branch with `}` after its last action"))
        return True
    if tok.type == "_RBRACE" and prev.type == "_LBRACE":
        diags.error("E001", Span(prev.line, prev.column, tok.end_line, tok.end_column),
                    "a branch of an `if` needs at least one action",
                    help="to act only when the condition is false, negate it: "
                         "`if not (COND) { ... }`, or remove the empty branch")
        return True
    if "_LBRACE" in expected and "_IF" not in expected \
            and any(t.type == "_IF" for t in chunk[:at]) and prev.type != "_ELSE":
        diags.error("E001", span, f"expected `{{` after `{prev.value}`, found {found}",
                    help="an `if`'s actions go in braces: `if COND { ACTIONS } else { ACTIONS }`")
        return True
    if prev.type == "_ELSE" and tok.type != "$END":
        diags.error("E001", span, f"expected `if` or `{{` after `else`, found {found}",
                    help=Fix(Span(tok.line, tok.column, tok.line, tok.column), "{ ",
                             "the `else` branch's actions go in braces: `else { ACTIONS }`"))
        return True
    if tok.type == "NAME" and tok.value in ("elif", "elsif", "elseif") and "_ELSE" in expected:
        diags.error("E001", span, f"expected `else` after `}}`, found `{tok.value}`",
                    help=Fix(span, "else if", f"write `else if`, not `{tok.value}`"))
        return True
    return False


def _when_fix(chunk: list, source: SourceFile):
    """`on sensor(ir0 > 300 and ir7 > 300)` as the `when` rule it means:
    `when ir0 > 300 and ir7 > 300` (for `ambient`, on the ambient readings)."""
    types = [t.type for t in chunk]
    if "_ON" not in types:
        return None
    at = types.index("_ON")
    if at + 2 >= len(chunk) or chunk[at + 1].value not in ("sensor", "ambient") \
            or types[at + 2] != "_LPAR":
        return None
    depth, close = 0, None
    for i in range(at + 2, len(chunk)):
        depth += {"_LPAR": 1, "_RPAR": -1}.get(types[i], 0)
        if depth == 0:
            close = i
            break
    if close is None:
        return None
    inside = [t for t in chunk[at + 3:close]]
    if any(t.type in ("_COMMA", "_OR") for t in inside):
        return None         # `,` is already an or: mixing them needs a person
    text = " ".join(t.value for t in inside)
    if chunk[at + 1].value == "ambient":
        text = re.sub(r"\bir([0-7])\b", r"ambient\1", text)
    start, end = chunk[at], chunk[close]
    return Fix(Span(start.line, start.column, end.end_line, end.end_column), f"when {text}",
               f"a sensor rule's conditions are or-ed; to wait for both, write a `when` "
               f"rule: `when {text}`")


def _joining_word(chunk: list, tok, prev, expected: set):
    """The `and` or `or` token that joins two conditions of an event's
    arguments, or None."""
    if tok.type == "$END":
        return None
    for word in (prev, tok):
        if word is not None and word.type in ("_AND", "_OR") \
                and ("_RPAR" in expected or "_COMMA" in expected) and chunk.index(word) > 0:
            return word
    return None


_CLOSERS = {"is a `)` missing?": ")", "is a `}` missing?": "}"}

# One punctuation mark mistaken for the other: `speed = 300`, `const X: 5`.
_SWAPS = {("_EQUAL", "_COLON"): ":", ("_COLON", "_EQUAL"): "="}


def _fix(tok, prev, expected: set, hint: str):
    """A machine-applicable fix for the likeliest mistake, with `hint` as
    its sentence; or the hint alone."""
    span = Span(tok.line, tok.column, tok.end_line, tok.end_column)
    for (found, wanted), mark in _SWAPS.items():
        if tok.type == found and wanted in expected:
            # in the usual layout: `speed: 300`, `const X = 5`
            text = mark
            if prev is not None and prev.end_line == tok.line:
                if mark == ":":
                    span = Span(prev.end_line, prev.end_column, tok.end_line, tok.end_column)
                elif prev.end_column == tok.column:
                    text = " ="
            return Fix(span, text, hint or f"write `{mark}` here, not `{tok.value}`")
    if hint in _CLOSERS and prev is not None:
        # `start_straight(300, 2 m do ...`: close it after the last token
        return Fix(Span(prev.end_line, prev.end_column, prev.end_line, prev.end_column),
                   _CLOSERS[hint], hint)
    if tok.type == "$END":
        return hint
    if "_DO" in expected and tok.type in ("NAME", "_CANCEL"):
        # `on immediate start_sensor`: the `do` is missing before the action
        return Fix(Span(tok.line, tok.column, tok.line, tok.column), "do ", hint)
    return hint


