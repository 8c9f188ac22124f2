"""An open document of the language server (lsp.py): its text as the
editor has it, its analysis (ide/incremental.py), LSP positions of its text
(Lines), and the LSP form of its diagnostics, kept from one analysis to the
next (Conversions). With lsp.py, the only module that imports lsprotocol.
"""
from __future__ import annotations

import bisect
import itertools
import operator
import re
import sys
from pathlib import Path
from typing import Optional
from urllib.parse import unquote, urlparse

from lsprotocol import types as lsp

from .incremental import Analysis, Analyzer
from .showing import find_sorted
from .statements import _common_prefix, _common_suffix

# ---- positions ------------------------------------------------------------------

_LINE_END_RE = re.compile(r"\r\n?|\n")
_NEWLINE_RE = re.compile(r"\n")


class Lines:
    """LSP positions of a text: lines end at \\n, \\r\\n or \\r (LSP's line
    ends), characters are counted in the negotiated encoding."""

    def __init__(self, text: str, encoding: str, starts: Optional[list] = None):
        """`starts`: the offsets where lines start at \\n, when known."""
        self.text = text
        self.encoding = encoding
        self.has_cr = "\r" in text
        ends = _LINE_END_RE if self.has_cr else _NEWLINE_RE
        self.starts = starts if starts is not None and not self.has_cr else \
            [0] + [m.end() for m in ends.finditer(text)]

    def _line_end(self, line: int) -> int:
        end = self.starts[line + 1] if line + 1 < len(self.starts) else len(self.text)
        while end > self.starts[line] and self.text[end - 1] in "\r\n":
            end -= 1
        return end

    def _units(self, s: str) -> int:
        if self.encoding == "utf-16":
            return len(s) + sum(ord(c) > 0xFFFF for c in s)
        if self.encoding == "utf-8":
            return len(s.encode("utf-8", "surrogatepass"))
        return len(s)

    def text_of(self, first: int, last: int) -> str:
        """The text of lines first..last (from 0), clamped to the text."""
        starts = self.starts
        first = min(max(first, 0), len(starts) - 1)
        last = max(first, min(last, len(starts) - 1))
        return self.text[starts[first]:starts[last + 1] if last + 1 < len(starts) else len(self.text)]

    def position(self, offset: int) -> lsp.Position:
        offset = max(0, min(offset, len(self.text)))
        line = bisect.bisect_right(self.starts, offset) - 1
        start = self.starts[line]
        offset = min(offset, self._line_end(line))
        segment = self.text[start:offset]
        return lsp.Position(line, len(segment) if segment.isascii() else self._units(segment))

    def offset(self, pos: lsp.Position) -> int:
        """The character offset of a position; out-of-range positions are
        clamped, as the specification asks."""
        line = max(0, pos.line)
        if line >= len(self.starts):
            return len(self.text)
        start, end = self.starts[line], self._line_end(line)
        segment = self.text[start:end]
        want = max(0, pos.character)
        if segment.isascii():
            return start + min(want, len(segment))
        units = 0
        for i, c in enumerate(segment):
            if units >= want:
                return start + i
            units += self._units(c)
        return end


class Document:
    def __init__(self, uri: str, text: str, version: Optional[int], server=None):
        self.uri = uri
        self._same: Optional[list] = None
        self.text = text
        self.version = version
        self.path = _path_of(uri)
        self.analyzer = Analyzer(self.path.name if self.path else uri)
        self.analysis: Optional[Analysis] = None
        self.analysed_text: Optional[str] = None
        self.published = None       # the text whose diagnostics were published
        self.timer = None
        self._lines = None
        self.lsp_diagnostics: dict = {}     # id(Diagnostic) -> (it, its lines' text, LSP's)
        self.conversions = Conversions()    # what publishing converted, kept

    @property
    def text(self) -> str:
        return self._text

    @text.setter
    def text(self, text: str):
        """A new text that no change describes (the client sent it whole,
        or a caller set it)."""
        self._text = text
        self._same = None

    def base_dir(self) -> Optional[Path]:
        """Where extern C files are looked for: the file's folder, as
        `epuckc check` does for a file that exists."""
        if self.path is not None and self.path.exists():
            return self.path.parent
        return None

    def analyse(self) -> Analysis:
        if self.analysis is None or self.analysed_text is not self.text:
            self.analyzer.options["base_dir"] = self.base_dir()
            same = self._same
            self.analysis = self.analyzer.analyse(
                self.text, None if same is None else (self.analysed_text, *same))
            self.analysed_text = self.text
            self._same = [len(self.text), len(self.text)]
        return self.analysis

    def apply(self, change, encoding: str):
        """One change of a didChange notification."""
        if isinstance(change, lsp.TextDocumentContentChangePartial):
            lines = self.lines(encoding)
            start = lines.offset(change.range.start)
            end = max(start, lines.offset(change.range.end))
            same = self._same
            if same is not None:
                same[0] = min(same[0], start)
                same[1] = min(same[1], len(self._text) - end)
            self._text = self._text[:start] + change.text + self._text[end:]
        else:
            self.text = change.text

    def lines(self, encoding: str) -> Lines:
        if self._lines is None or self._lines.text is not self.text \
                or self._lines.encoding != encoding:
            analysis = self.analysis        # (its lines are these when no \r ends one)
            self._lines = Lines(self.text, encoding, analysis.line_starts if analysis is not None
                                and analysis.text is self.text else None)
        return self._lines


def _path_of(uri: str) -> Optional[Path]:
    try:
        parsed = urlparse(uri)
        if parsed.scheme != "file":
            return None
        path = unquote(parsed.path)
        if sys.platform == "win32" and path.startswith("/"):
            path = path[1:]
        return Path(path)
    except (ValueError, TypeError):
        return None




def _primary_line(d) -> int:
    return d.span.line


class Conversions:
    """The LSP form of a document's diagnostics (what is published), kept
    from one analysis to the next: a diagnostic's form is made again only
    when it is another object (the analysis keeps the object while its
    statements start on the same lines, showing.py) or when a line its
    places are on was edited (the edit's lines, between the text's common
    beginning and end, and every line after them when it added or removed
    lines: found by bisection in the sorted list, with the tallest span's
    height, and among the diagnostics with notes). When the analysis's
    list is the last one spliced (`Analysis.delta`: those taken out and put
    in), the published list is spliced the same way; else each diagnostic's
    form is looked up by its object. A text with `\r` (lines counted
    otherwise than the checker counts them) or another encoding converts
    every diagnostic."""

    def __init__(self):
        self.text = None
        self.encoding = None
        self.shown: list = []       # the last analysis's diagnostics (real lines, sorted)
        self.published: list = []   # their LSP forms, in the same order
        self.forms: dict = {}       # id(d) -> (d, its LSP form)
        self.height = 0             # the most lines a primary span covers, less one
        self.noted: dict = {}       # id(d) -> d, of those with notes that have places

    def all(self, analysis: Analysis, lines: "Lines", convert) -> list:
        """The LSP form of each of `analysis.diagnostics`; `convert(d)`
        makes one."""
        diagnostics, text, delta = analysis.diagnostics, analysis.text, analysis.delta
        if lines.has_cr or lines.encoding != self.encoding or self.text is None:
            self.forms, self.noted, self.height = {}, {}, 0
            delta = None
        elif self.text is not text:
            edited = self._edited(self.text, text, analysis if delta is not None
                                  and delta[0] is self.shown else None)
            if delta is not None and delta[0] is self.shown and edited[2]:
                spliced = self._splice(diagnostics, text, delta, edited, convert)
                if spliced is not None:
                    return spliced
            self._forget(*edited)
        elif delta is not None and delta[0] is self.shown:
            spliced = self._splice(diagnostics, text, delta, None, convert)
            if spliced is not None:
                return spliced
        forms = self.forms
        out = list(map(forms.get, map(id, diagnostics)))
        made = list(itertools.compress(range(len(out)), map(operator.is_, out,
                                                             itertools.repeat(None))))
        for i in made:
            out[i] = self._make(diagnostics[i], convert)
        if len(forms) > len(diagnostics) + 16:      # (those gone)
            live = set(map(id, diagnostics))
            for key in forms.keys() - live:
                del forms[key]
                self.noted.pop(key, None)
        self.text, self.encoding, self.shown = text, lines.encoding, diagnostics
        self.published = list(map(operator.itemgetter(1), out))
        return list(self.published)

    def _make(self, d, convert) -> tuple:
        form = self.forms[id(d)] = (d, convert(d))
        height = d.span.end_line - d.span.line
        if height > self.height:
            self.height = height
        if any(n.span is not None for n in d.notes):
            self.noted[id(d)] = d
        return form

    def _splice(self, diagnostics: list, text: str, delta: tuple, edited, convert):
        """The last published list with the analysis's splice done to it
        (and the forms on edited lines made again); None if a diagnostic is
        not where the splice says."""
        before, removed, inserted = delta
        gone = [find_sorted(before, d) for d in removed]
        came = [find_sorted(diagnostics, d) for d in inserted]
        if None in gone or None in came:
            return None
        out = list(self.published)
        for at in sorted(gone, reverse=True):
            del out[at]
        for d in removed:
            self.forms.pop(id(d), None)
            self.noted.pop(id(d), None)
        for at in sorted(came):
            out.insert(at, self._make(diagnostics[at], convert)[1])
        if edited is not None:          # (no line moved: the splice is the checker's)
            first, last, _ = edited
            for at in self._touching(diagnostics, first, last):
                out[at] = self._make(diagnostics[at], convert)[1]
        self.text, self.shown, self.published = text, diagnostics, out
        return list(out)

    @staticmethod
    def _edited(old: str, text: str, analysis=None) -> tuple:
        """(first line, last line, whether no line was added or removed)
        of the edit from `old` to `text`, lines from 1 as spans count them;
        `analysis`: the analysis of `text` right after that of `old` (its
        split knows the edit and the lines)."""
        if analysis is not None and analysis.edit is not None:
            p, s = analysis.edit
            starts = analysis.line_starts
            first = bisect.bisect_right(starts, p)
            last = bisect.bisect_right(starts, len(text) - s)
        else:
            p = _common_prefix(old, text)
            s = _common_suffix(old, text, min(len(old), len(text)) - p)
            first = old.count("\n", 0, p) + 1
            last = text.count("\n", 0, len(text) - s) + 1
        same = old.count("\n", p, len(old) - s) == text.count("\n", p, len(text) - s)
        return first, last if same else float("inf"), same

    def _touching(self, shown: list, first: int, last) -> list:
        """The places in `shown` of the diagnostics with a place on lines
        first..last."""
        lo = bisect.bisect_left(shown, first - self.height, key=_primary_line)
        hi = len(shown) if last == float("inf") else bisect.bisect_right(shown, last,
                                                                           key=_primary_line)
        found = {at for at in range(lo, hi) if shown[at].span.end_line >= first
                 and shown[at].span.line <= last}
        for d in list(self.noted.values()):
            if any(n.span is not None and n.span.end_line >= first and n.span.line <= last
                   for n in d.notes):
                at = find_sorted(shown, d)
                if at is not None:
                    found.add(at)
        return sorted(found)

    def _forget(self, first: int, last, same: bool) -> None:
        """Drop the forms of the last list's diagnostics with a place on
        the edited lines (and after them, when lines moved)."""
        for at in self._touching(self.shown, first, last):
            d = self.shown[at]
            self.forms.pop(id(d), None)
            self.noted.pop(id(d), None)
