"""Tokeniser and statement splitter.

Tokens carry their positions, so the LALR driver (lalr.py) can take them
directly. Characters that start no token are reported (one diagnostic
per run of them) and skipped, so the rest of the file is still checked.
"""
from __future__ import annotations

import re

from ..diagnostics import Collector, Fix
from ..base.source import SourceFile, Span

KEYWORDS = {
    "robot": "_ROBOT", "const": "_CONST", "action": "_ACTION",
    "extern": "_EXTERN", "event": "_EVENT", "on": "_ON", "rule": "_RULE",
    "do": "_DO", "then": "_THEN", "repeat": "_REPEAT", "cancel": "_CANCEL",
    "from": "_FROM", "priority": "_PRIORITY", "mode": "_MODE", "initial": "_INITIAL",
    "enter": "_ENTER", "var": "_VAR", "when": "_WHEN", "every": "_EVERY", "after": "_AFTER",
    "if": "_IF", "else": "_ELSE", "and": "_AND", "or": "_OR", "not": "_NOT",
}
PUNCTUATION = {
    "(": "_LPAR", ")": "_RPAR", "{": "_LBRACE", "}": "_RBRACE", ",": "_COMMA",
    ":": "_COLON", "=": "_EQUAL", "/": "_SLASH", "-": "MINUS", ">": "CMP",
    "<": "CMP", "+": "_PLUS", "*": "_STAR", "%": "_PERCENT", "[": "_LBRACK", "]": "_RBRACK",
    # two characters, the second always `=`
    "<=": "CMP", ">=": "CMP", "==": "CMP", "!=": "CMP", "+=": "_PLUSEQ", "-=": "_MINUSEQ",
    # the bitwise operators (16 bits, docs/language.md); a shift is its character twice
    "&": "_AMP", "|": "_PIPE", "^": "_CARET", "~": "_TILDE", "<<": "_SHL", ">>": "_SHR",
}
class Token:
    """One token: its terminal name (`NAME`, `_ON`, ...), its text and where
    it is (lines and columns from 1, end column exclusive)."""
    __slots__ = ("type", "value", "start_pos", "line", "column", "end_line",
                 "end_column", "end_pos", "after_bad")

    def __init__(self, type, value, start_pos, line, column, end_line, end_column, end_pos):
        self.type = type
        self.value = value
        self.start_pos = start_pos
        self.line = line
        self.column = column
        self.end_line = end_line
        self.end_column = end_column
        self.end_pos = end_pos
        self.after_bad = False      # unexpected characters come just before it

    @property
    def span(self) -> Span:
        return Span(self.line, self.column, self.end_line, self.end_column)

    def __str__(self):
        return self.value

    def __repr__(self):
        return f"Token({self.type!r}, {self.value!r}, {self.line}:{self.column})"


# Keywords that begin a statement: the parser restarts at each of them.
STATEMENT_STARTS = {"_ROBOT", "_CONST", "_ACTION", "_EXTERN", "_ON", "_RULE", "_MODE",
                    "_INITIAL", "_VAR", "_WHEN", "_EVERY", "_AFTER"}
# The keywords that start a rule's head: `rule NAME: when ...` is one statement.
TRIGGERS = {"_ON", "_WHEN", "_EVERY", "_AFTER"}
MODE_STARTS = {"_MODE", "_INITIAL"}

# Stop reporting bad characters after this many: the file is likely not a
# rule file at all, and thousands of errors help nobody.
MAX_LEXICAL_ERRORS = 20

# One match per token: the blanks before a token are part of its match (a
# match per blank run cost as much again); a run of blank lines is one
# `space` match, and so is the end of the text.
_TOKEN_RE = re.compile(r"""
    [ \t\r\f\v]*
    (?:
    (?P<space>\n[ \t\r\n\f\v]*|\Z)
  | (?P<comment>\#[^\n]*)
  | (?P<NAME>(?![0-9])\w+)                   # any letters: `café` is one token, one E008
  | (?P<radix>0[xXbB][0-9A-Za-z_]*)          # 0x1F, 0b101 (checked in _radix)
  | (?P<exponent>[0-9]+(?:\.[0-9]+)?[eE][+-]?[0-9]+)
  | (?P<NUMBER>[0-9]+(?:\.[0-9]+)?)
  | (?P<STRING>"(?:[^"\\\n]|\\.)*")
  | (?P<open_string>"(?:[^"\\\n]|\\.)*)
  | (?P<punct>[<>=!+\-]=|<<|>>|[(){}\[\],:=/\-><+*%&|^~])
    )""", re.VERBOSE)
_BLANKS_RE = re.compile(r"[ \t\r\f\v]*")

# A run of characters that start no token (every other character starts one).
_BAD_RE = re.compile(r"""(?:!(?!=)|[^\w \t\r\n\f\v#"(){}\[\],:=/\-><+*%!&|^~])+""")


# Symbols that stand for a unit, and the unit's name in rule files.
_UNIT_SYMBOLS = {"\u00b0": "deg", "\u00ba": "deg"}      # 90° (and the ordinal sign that looks like it)


def _bad_help(source: SourceFile, text: str, start: int, end: int):
    """The help of E002: the fix for a unit written as a symbol (`90°`),
    else what rule files are made of."""
    unit = _UNIT_SYMBOLS.get(text[start])
    if unit is not None and end == start + 1:
        before = text[start - 1] if start > 0 else ""
        spaced = f" {unit}" if before.isdigit() else unit
        number = re.search(r"[0-9.]*$", text[:start].rstrip(" \t")).group(0) or "90"
        return Fix(source.span(start, end), spaced,
                   f"units are written as words: `{number} {unit}`")
    return ("rule files use names, numbers, units and "
            "`( ) { } [ ] , : = + - * / % > < != & | ^ ~ << >>`; "
            "comments start with `#`")


def iter_tokens(source: SourceFile, diags: Collector):
    """The tokens of a file, one at a time (a 10 MB file has millions)."""
    text = source.text
    pos = 0
    errors = 0
    n = len(text)
    match = _TOKEN_RE.match
    line, line_start = 1, 0         # where `pos` is, kept up to date by hand
    keywords, punctuation = KEYWORDS, PUNCTUATION
    new = object.__new__
    after_bad = False
    not_ascii: set = set()
    while pos < n:
        m = match(text, pos)
        if m is None:
            # no token starts with a newline: the bad run is on this line
            start = pos = _BLANKS_RE.match(text, pos).end()
            pos = _BAD_RE.match(text, pos).end()
            errors += 1
            after_bad = True
            bad = text[start:pos]
            shown = bad if len(bad) <= 10 else bad[:10] + "..."
            diags.error("E002", source.span(start, pos),
                        f"unexpected character{'s' if len(bad) > 1 else ''} {shown!r}",
                        help=_bad_help(source, text, start, pos))
            if errors >= MAX_LEXICAL_ERRORS:
                diags.error("E002", source.span(pos, pos),
                            "too many unexpected characters: the rest of the file is not checked",
                            help="is this a rule file? epuckc reads UTF-8 text files (.epk)")
                break
            continue
        kind = m.lastgroup
        end = m.end()
        value = m.group(kind)
        start = end - len(value)
        if kind == "NAME":
            kind = keywords.get(value, "NAME")
            # (an ASCII \w+ that starts with no digit is a valid name)
            if kind == "NAME" and not value.isascii() and value not in not_ascii:
                not_ascii.add(value)        # said once per name
                _not_ascii(source, diags, start, end, value)
        elif kind == "radix":
            value = _radix(source, diags, start, end, value)
            kind = "NUMBER"
        elif kind == "exponent":
            value = _exponent(source, diags, start, end, value)
            kind = "NUMBER"
        elif kind == "punct":
            kind = punctuation[value]
        elif kind == "space":
            newlines = value.count("\n")
            if newlines:
                line += newlines
                line_start = start + value.rindex("\n") + 1
            pos = end
            continue
        elif kind == "comment":
            pos = end
            continue
        elif kind == "open_string":
            diags.error("E003", source.span(start, end),
                        "this string has no closing `\"`",
                        help="close the string on the same line")
            kind = "STRING"
            value += '"'
        # A token never spans a newline, so it ends on the line it starts on;
        # it is made field by field, cheaper than a call to Token().
        column = start - line_start + 1
        token = new(Token)
        token.type = kind
        token.value = value
        token.start_pos = start
        token.line = token.end_line = line
        token.column = column
        token.end_column = column + (end - start)
        token.end_pos = end
        token.after_bad = after_bad
        after_bad = False
        yield token
        pos = end


def _not_ascii(source, diags, start, end, name):
    import unicodedata
    others = sorted({c for c in name if not (c.isascii() and (c.isalnum() or c == "_"))},
                    key=name.index)
    plain = unicodedata.normalize("NFKD", name).encode("ascii", "ignore").decode()
    plain = re.sub(r"\W", "", plain)
    if not plain or plain[0].isdigit():
        plain = "n_" + plain
    diags.error("E008", source.span(start, end),
                f"names are ASCII: `{name}` has {', '.join(f'`{c}`' for c in others)}",
                help=f"write it with ASCII letters, digits and `_`, e.g. `{plain}`")


_RADIX_DIGITS = {"x": ("hexadecimal", "0123456789abcdefABCDEF", "0x1F"),
                 "b": ("binary", "01", "0b101")}


def _radix(source, diags, start, end, text) -> str:
    """A hexadecimal or binary number (`0x1F`, `0b101`) as it is; one with
    a digit its base has not (or none) is reported [E009] and read as 0,
    so that the rest of the file is checked."""
    name, digits, example = _RADIX_DIGITS[text[1].lower()]
    body = text[2:]
    if body and all(c in digits for c in body):
        return text
    bad = next((c for c in body if c not in digits), None)
    if bad is None:
        message = f"`{text}` has no digits"
    else:
        message = f"`{text}` has `{bad}`, which is not a {name} digit"
    if name == "binary" and body and not body[0].isdigit():
        more = f"; for zero of a unit, leave a space: `0 {body}`"
    else:
        more = ""
    diags.error("E009", source.span(start, end), message,
                help=f"{name} numbers are written `{example}` with the digits "
                     f"{'0-9 and a-f' if name == 'hexadecimal' else '0 and 1'}{more}")
    return "0"


def _exponent(source, diags, start, end, text) -> str:
    """Report a number written with an exponent (E007); return it written
    out, so that the rest of the file is checked with the meant value."""
    from decimal import Decimal, InvalidOperation
    mantissa, _, power = text.lower().partition("e")
    try:
        exact = Decimal(text)
        plain = format(exact, "f") if abs(int(power)) <= 12 else None
    except (InvalidOperation, ValueError):
        plain = None
    if plain is not None and "." in plain:
        plain = plain.rstrip("0").rstrip(".")
    diags.error("E007", source.span(start, end),
                f"numbers have no exponent: `{text}`",
                help=f"write `{plain}`" if plain is not None else
                "write the number out in full, or use a larger unit")
    return plain if plain is not None else mantissa


def iter_statements(tokens):
    """Cut the token stream before every keyword that starts a statement.
    `action` after `extern`, `mode` after `initial`, and the `on` of
    `rule NAME: on ...`, belong to the statement already under way.

    A mode block `[initial] mode NAME { rules }` holds statements: its head
    up to `{` is a statement of its own, and so is a `}` that closes no `{`
    of the statement under way (the parser pairs it with a mode, or says
    it closes none). Both are decided from the statement under way alone,
    so that any part of a file splits as the whole does (the language
    server splits again only what an edit touched). Yields each
    statement's token list."""
    current: list = []
    seen_on = False
    depth = 0               # `{` of the statement under way not yet closed
    for tok in tokens:
        if tok.type == "_RBRACE" and depth == 0:
            if current:
                yield current
            yield [tok]
            current, seen_on = [], False
            continue
        starts = tok.type in STATEMENT_STARTS and current
        if starts and tok.type == "_ACTION" and current[-1].type == "_EXTERN":
            starts = False
        if starts and tok.type == "_MODE" and current[-1].type == "_INITIAL" and len(current) == 1:
            starts = False
        if starts and tok.type in TRIGGERS and current[0].type == "_RULE" and not seen_on:
            starts = False
        if starts:
            yield current
            current = []
            seen_on = False
            depth = 0
        seen_on = seen_on or tok.type in TRIGGERS
        current.append(tok)
        if tok.type == "_LBRACE":
            if current[0].type in MODE_STARTS:
                yield current
                current, seen_on, depth = [], False, 0
            else:
                depth += 1
        elif tok.type == "_RBRACE" and depth:
            depth -= 1
    if current:
        yield current
