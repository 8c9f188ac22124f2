"""The incremental analysis' first two steps (see incremental.py): splitting
an edited text into statements again only around the edit, and parsing one
statement at a time with virtual line numbers, so that a statement whose
text did not change keeps its AST and everything found about it."""
from __future__ import annotations

import bisect
import re
from dataclasses import dataclass, replace
from typing import Optional

from ..base.source import SourceFile, Span
from ..diagnostics import Collector, Diagnostic
from ..syntax.lexer import KEYWORDS, STATEMENT_STARTS, iter_statements, iter_tokens
from ..syntax import aseba
from ..syntax.parser import parse_statement

VLINE = 1 << 20          # lines per statement in virtual coordinates


# Where lines end is SourceFile's decision (and the lexer's); positions
# here are offsets into the text as the editor has it, so the same line
# ends are found here, as SourceFile counts them.
_CR_ENDS_LINES = SourceFile("", "\r").line_count == 2


_BREAK_RE = re.compile(r"\r\n?|\n" if _CR_ENDS_LINES else r"\n")


def line_starts(text: str) -> list:
    """The offsets where lines start, as SourceFile numbers lines."""
    return [0] + [m.end() for m in _BREAK_RE.finditer(text)]


def patched_line_starts(old_starts: list, old_length: int, text: str, prefix: int,
                        suffix: int) -> list:
    """line_starts(text), from those of the previous text (`old_starts`, of
    `old_length` characters) that shares `text`'s first `prefix` and last
    `suffix` characters (not overlapping): a line break is one or two
    characters, so the starts before the prefix's end and those more than
    one character into the suffix stay (shifted), and only the rest is
    searched again."""
    new_end = len(text) - suffix                    # where the suffix starts in text
    keep = bisect.bisect_left(old_starts, prefix)
    head = old_starts[:keep] if keep else [0]
    middle = [m.end() for m in _BREAK_RE.finditer(text, max(0, prefix - 1),
                                                   min(len(text), new_end + 3))
              if prefix <= m.end() < new_end + 2]
    delta = len(text) - old_length
    tail = old_starts[bisect.bisect_left(old_starts, old_length - suffix + 2):]
    return head + middle + ([x + delta for x in tail] if delta else tail)


def split_statements(text: str) -> tuple:
    """The offsets where statements start, as `lexer.iter_statements` cuts
    them, and the keyword at each; the first is always 0 (the text before
    the first keyword belongs to the first statement), with keyword None."""
    starts, keywords = [0], [None]
    for at, kw in _boundaries(text):
        starts.append(at)
        keywords.append(kw)
    return starts, keywords


def _boundaries(text: str, start: int = 0, starts: Optional[list] = None):
    """(offset, keyword) of each statement start after the one at `start`
    (0, or the offset of a statement start), found by the lexer itself,
    lazily: only as much of the text is read as the caller takes. At a
    statement start the splitter begins afresh, as it does at the file's
    start, so the cut from there on is the whole file's. `starts`: the
    text's line_starts, which place the tokens when SourceFile changed the
    line ends it lexed."""
    source = SourceFile("", text[start:] if start else text)
    chunks = iter_statements(iter_tokens(source, Collector(source)))
    if next(chunks, None) is None:
        return
    if source.text == (text[start:] if start else text):
        for chunk in chunks:
            yield start + chunk[0].start_pos, chunk[0].value
        return
    # the lexer read `\r\n` as `\n`: place tokens by line and column
    starts = starts if starts is not None else line_starts(text)
    first = bisect.bisect_right(starts, start) - 1
    for chunk in chunks:
        tok = chunk[0]
        if tok.line == 1:
            yield start + tok.column - 1, tok.value
        else:
            yield starts[first + tok.line - 1] + tok.column - 1, tok.value


# A statement start is decided by the tokens before it and its keyword; a
# token's extent depends on a few characters after it. One this far
# before an edit cannot change.
_MARGIN = max(len(k) for k, t in KEYWORDS.items() if t in STATEMENT_STARTS) + 8


def _common_prefix(a: str, b: str) -> int:
    lo, hi = 0, min(len(a), len(b))
    while lo < hi:          # slices compare at C speed
        mid = (lo + hi + 1) // 2
        if a[lo:mid] == b[lo:mid]:
            lo = mid
        else:
            hi = mid - 1
    return lo


def _common_suffix(a: str, b: str, limit: int) -> int:
    lo, hi = 0, limit
    la, lb = len(a), len(b)
    while lo < hi:
        mid = (lo + hi + 1) // 2
        if a[la - mid:la - lo] == b[lb - mid:lb - lo]:
            lo = mid
        else:
            hi = mid - 1
    return lo


@dataclass
class Entry:
    """One statement's text, parsed: its AST (None when it has a syntax
    error or holds no token), its lexical and syntax diagnostics, in the
    virtual lines of `id`."""
    id: int
    statements: list
    diags: list
    bad_runs: int           # runs of unexpected characters (E002)
    lines: int
    once: bool = False      # has diagnostics said once per file (see _ONCE)


def _shift_span(span: Span, by: int) -> Span:
    return Span(span.line + by, span.column, span.end_line + by, span.end_column)


def _shift_diag(d: Diagnostic, by: int) -> Diagnostic:
    return replace(d, span=_shift_span(d.span, by),
                   notes=tuple(replace(n, span=_shift_span(n.span, by)) if n.span else n
                               for n in d.notes),
                   fixes=tuple(replace(f, span=_shift_span(f.span, by)) for f in d.fixes))


def _parse_chunk(name: str, padded: str, following: Optional[str], ident: int) -> Entry:
    base = ident * VLINE
    source = SourceFile(name, padded)
    lexical = Collector(source)
    tokens = list(iter_tokens(source, lexical))
    for tok in tokens:
        tok.line += base
        tok.end_line += base
    syntax = Collector(source)
    statements = []
    groups = list(iter_statements(tokens))
    for i, group in enumerate(groups):
        if i + 1 < len(groups):
            after = groups[i + 1][0]
        elif following is not None:
            after = _Following(following)
        else:
            after = None
        statement = parse_statement(group, after, source, syntax)
        if statement is not None:
            statements.append(statement)
    # (the `.` of Aseba's `call math.dot`: said by its E095, syntax/aseba.py)
    shifted = aseba.uncovered([_shift_diag(d, base) for d in lexical.items], syntax.items)
    diags = shifted + syntax.items
    bad_runs = sum(d.code == "E002" for d in shifted)
    once = any(d.code in _ONCE for d in lexical.items)
    return Entry(ident, statements, diags, bad_runs, source.line_count, once)


# What the lexer says once per file however often it occurs: a name that
# is not ASCII (E008, lexer.iter_tokens). Each statement is lexed on its
# own here, so the statements after the first drop theirs.
_ONCE = frozenset({"E008"})


class _Following:
    """The first token of the next statement, as the parser's messages see
    it: only its text is shown (`found `on`, which starts a new statement`)."""
    def __init__(self, value):
        self.value = value
