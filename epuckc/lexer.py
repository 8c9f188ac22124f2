"""Tokeniser and statement splitter.

Tokens are lark.Token objects with positions, so the LALR parser can take
them directly. Characters that start no token are reported (one diagnostic
per run of them) and skipped, so the rest of the file is still checked.
"""
from __future__ import annotations

import re

from lark import Token

from .diagnostics import Collector
from .source import SourceFile

KEYWORDS = {
    "robot": "_ROBOT", "const": "_CONST", "action": "_ACTION",
    "extern": "_EXTERN", "event": "_EVENT", "on": "_ON", "rule": "_RULE",
    "do": "_DO", "then": "_THEN", "repeat": "_REPEAT", "cancel": "_CANCEL",
    "from": "_FROM",
}
PUNCTUATION = {
    "(": "_LPAR", ")": "_RPAR", "{": "_LBRACE", "}": "_RBRACE", ",": "_COMMA",
    ":": "_COLON", "=": "_EQUAL", "/": "_SLASH", "-": "MINUS", ">": "CMP",
    "<": "CMP",
}
# Keywords that begin a statement: the parser restarts at each of them.
STATEMENT_STARTS = {"_ROBOT", "_CONST", "_ACTION", "_EXTERN", "_ON", "_RULE"}

# Stop reporting bad characters after this many: the file is likely not a
# rule file at all, and thousands of errors help nobody.
MAX_LEXICAL_ERRORS = 20

_TOKEN_RE = re.compile(r"""
    (?P<space>[ \t\r\n\f\v]+)
  | (?P<comment>\#[^\n]*)
  | (?P<NAME>[A-Za-z_][A-Za-z0-9_]*)
  | (?P<NUMBER>[0-9]+(?:\.[0-9]+)?)
  | (?P<STRING>"(?:[^"\\\n]|\\.)*")
  | (?P<open_string>"(?:[^"\\\n]|\\.)*)
  | (?P<punct>[(){},:=/\-><])
""", re.VERBOSE)


def tokenize(source: SourceFile, diags: Collector) -> list:
    text = source.text
    tokens = []
    pos = 0
    errors = 0
    n = len(text)
    match = _TOKEN_RE.match
    while pos < n:
        m = match(text, pos)
        if m is None:
            start = pos
            while pos < n and match(text, pos) is None:
                pos += 1
            errors += 1
            bad = text[start:pos]
            shown = bad if len(bad) <= 10 else bad[:10] + "..."
            diags.error("E002", source.span(start, pos),
                        f"unexpected character{'s' if len(bad) > 1 else ''} {shown!r}",
                        help="rule files use names, numbers, units and `( ) { } , : = / - > <`; "
                             "comments start with `#`")
            if errors >= MAX_LEXICAL_ERRORS:
                diags.error("E002", source.span(pos, pos),
                            "too many unexpected characters: the rest of the file is not checked",
                            help="is this a rule file? epuckc reads UTF-8 text files (.epk)")
                break
            continue
        kind = m.lastgroup
        end = m.end()
        if kind in ("space", "comment"):
            pos = end
            continue
        value = m.group()
        if kind == "open_string":
            diags.error("E003", source.span(pos, end), "this string has no closing `\"`",
                        help="close the string on the same line")
            kind = "STRING"
            value += '"'
        elif kind == "NAME":
            kind = KEYWORDS.get(value, "NAME")
        elif kind == "punct":
            kind = PUNCTUATION[value]
        line, column = source.position(pos)
        end_line, end_column = source.position(end)
        tokens.append(Token(kind, value, pos, line, column, end_line, end_column, end))
        pos = end
    return tokens


def split_statements(tokens: list) -> list:
    """Cut the token stream before every keyword that starts a statement.
    `action` after `extern`, and the `on` of `rule NAME: on ...`, belong to
    the statement already under way."""
    chunks = []
    current: list = []
    seen_on = False
    for tok in tokens:
        starts = tok.type in STATEMENT_STARTS and current
        if starts and tok.type == "_ACTION" and current[-1].type == "_EXTERN":
            starts = False
        if starts and tok.type == "_ON" and current[0].type == "_RULE" and not seen_on:
            starts = False
        if starts:
            chunks.append(current)
            current = []
            seen_on = False
        seen_on = seen_on or tok.type == "_ON"
        current.append(tok)
    if current:
        chunks.append(current)
    return chunks
