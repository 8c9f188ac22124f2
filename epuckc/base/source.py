"""Source files and spans: what a diagnostic points at."""
from __future__ import annotations

import bisect
import itertools
from typing import NamedTuple
from pathlib import Path


class Span(NamedTuple):
    """A range of source text. Lines and columns start at 1; the end column
    is exclusive (it points just past the last character). A named tuple
    (immutable, ordered by position) because a file makes one per token
    and per syntax node, and a frozen dataclass is four times slower to
    build."""
    line: int
    column: int
    end_line: int
    end_column: int

    @staticmethod
    def of(*items) -> "Span":
        """The smallest span covering every item (Spans or nodes with .span)."""
        spans = [i if isinstance(i, Span) else i.span for i in items if i is not None]
        first = min(spans)
        last = max(spans, key=lambda s: (s.end_line, s.end_column))
        return Span(first.line, first.column, last.end_line, last.end_column)


class SourceFile:
    """The text of one rule file and the offsets of its lines."""

    def __init__(self, name: str, text: str):
        self.name = name
        # Every line end is `\n`: `\r\n` (Windows) and a lone `\r` (old Mac
        # OS, some editors) too, so a comment ends at a lone `\r` instead of
        # swallowing the rest of the file. Columns are unchanged.
        if "\r" in text:
            text = text.replace("\r\n", "\n").replace("\r", "\n")
        self.text = text
        self._starts = None         # where lines start: found the first time they are asked

    @property
    def _line_starts(self) -> list:
        if self._starts is None:
            # (at C speed: the lengths of the lines, each with its `\n`, summed)
            lines = self.text.split("\n")
            self._starts = [0] + list(itertools.accumulate(map((1).__add__, map(len, lines[:-1]))))
        return self._starts

    @classmethod
    def from_path(cls, path: Path, shown_name: str | None = None) -> tuple["SourceFile", object]:
        """Read and decode a file. Returns (source, problem) where problem is
        None or (offset, message) for bytes that are not UTF-8 text."""
        return cls.from_bytes(path.read_bytes(),
                              shown_name if shown_name is not None else str(path))

    @classmethod
    def from_bytes(cls, data: bytes, name: str) -> tuple["SourceFile", object]:
        """Decode a file's bytes (or standard input's), as from_path does."""
        if data.startswith(b"\xef\xbb\xbf"):
            data = data[3:]
        nul = data.find(b"\0")
        try:
            text = data.decode("utf-8")
        except UnicodeDecodeError as exc:
            good = cls(name, data[: exc.start].decode("utf-8"))
            at = len(good.text)
            return good, (at, at, "this file is not UTF-8 text: "
                                     f"byte 0x{data[exc.start]:02x} cannot be decoded")
        if nul >= 0:
            # The file is kept to the end of the NUL's line, the NUL in it, so
            # that the diagnostic shows the line and points at the byte.
            kept = cls(name, text)         # line ends made `\n` (offsets move)
            offset = len(cls(name, data[:nul].decode("utf-8")).text)
            line_end = kept.text.find("\n", offset)
            kept = kept if line_end < 0 else cls(name, kept.text[:line_end])
            return kept, (offset, offset + 1, "this file contains a NUL byte (shown "
                                     "`\\0`): it looks like a binary file, not a rule file")
        return cls(name, text), None

    def position(self, offset: int) -> tuple[int, int]:
        """(line, column) of a character offset, both from 1."""
        line = bisect.bisect_right(self._line_starts, offset) - 1
        return line + 1, offset - self._line_starts[line] + 1

    def span(self, start: int, end: int) -> Span:
        line, column = self.position(start)
        end_line, end_column = self.position(end)
        return Span(line, column, end_line, end_column)

    def line_text(self, line: int) -> str:
        if line < 1 or line > len(self._line_starts):
            return ""
        start = self._line_starts[line - 1]
        end = self.text.find("\n", start)
        return self.text[start:] if end < 0 else self.text[start:end]

    @property
    def line_count(self) -> int:
        return len(self._line_starts)
