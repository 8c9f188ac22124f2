"""Diagnostics: what is wrong, where, and how to fix it.

Every diagnostic has a stable code (E### for errors, W### for warnings, see
codes.py, with an explanation each in explanations/), a primary span, a
message, and optional help, notes and fixes. Every stage reports through a
Collector; render.py and sarif.py turn a Report into text. This package
imports only base/.
"""
from __future__ import annotations

import operator
from typing import Iterable, Optional

from ..base.records import field, record
from ..base.source import SourceFile, Span

ERROR = "error"
WARNING = "warning"
_SEVERITY = operator.attrgetter("severity")


@record(frozen=True)
class Note:
    message: str
    span: Optional[Span] = None     # shown as file:line:col when given


@record(frozen=True)
class Fix:
    """A suggestion a tool can apply: replace the text at `span` with `text`
    (an empty span inserts, an empty text deletes). `help` is the sentence
    that proposes it ("did you mean `start_straight`?"); the help line of
    the diagnostic is made from it, so that what the command line says and
    what an editor's quick fix does cannot disagree."""
    span: Span
    text: str
    help: str

    def then(self, more: str) -> "Fix":
        """The same edit, with more help after the suggestion."""
        return Fix(self.span, self.text, f"{self.help} {more}")


@record(frozen=True)
class Diagnostic:
    code: str
    severity: str
    message: str
    file: str
    span: Span
    help: Optional[str] = None
    notes: tuple = ()
    fixes: tuple = ()       # Fix, machine-applicable suggestions

    def sort_key(self):
        return (self.file, self.span.line, self.span.column, self.code)


@record
class Report:
    """The diagnostics of one run, and the sources they point into."""
    diagnostics: list = field(default_factory=list)
    sources: dict = field(default_factory=dict)     # file name -> SourceFile

    def extend(self, diags: Iterable[Diagnostic]):
        self.diagnostics.extend(diags)

    def sorted(self) -> list:
        return sorted(self.diagnostics, key=Diagnostic.sort_key)

    @property
    def error_count(self) -> int:
        return sum(d.severity == ERROR for d in self.diagnostics)

    @property
    def warning_count(self) -> int:
        return sum(d.severity == WARNING for d in self.diagnostics)


class Collector:
    """Collects the diagnostics found in one source file."""

    def __init__(self, source: SourceFile):
        self.source = source
        self.items: list = []

    def error(self, code, span, message, help=None, notes=()):
        """`help` is a sentence, or a Fix whose help sentence is shown."""
        self._add(code, ERROR, span, message, help, notes)

    def warning(self, code, span, message, help=None, notes=()):
        self._add(code, WARNING, span, message, help, notes)

    def _add(self, code, severity, span, message, help, notes):
        fixes = ()
        if isinstance(help, Fix):
            help, fixes = help.help, (help,)
        self.items.append(Diagnostic(code, severity, message, self.source.name,
                                     span, help, tuple(notes), fixes))

    @property
    def has_errors(self) -> bool:
        return ERROR in map(_SEVERITY, self.items)       # (at C speed)

    def capture(self) -> "_Captured":
        """`with sink.capture() as said:` what is reported to this collector
        meanwhile goes to the list `said` instead (a step whose diagnostics
        are looked at, kept or dropped before any is said); the collector
        stays the one object its holders were given."""
        return _Captured(self)


class _Captured:
    __slots__ = ("_sink", "_outer")

    def __init__(self, sink: Collector):
        self._sink = sink

    def __enter__(self) -> list:
        self._outer = self._sink.items
        said = self._sink.items = []
        return said

    def __exit__(self, *exc):
        self._sink.items = self._outer
        return False


# ---- renderings -------------------------------------------------------------
