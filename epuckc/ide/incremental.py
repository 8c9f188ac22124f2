"""Checking a file again and again as it is edited, reusing what did not change.

The language server calls `Analyzer.analyse(text)` after every edit. The
result is exactly what `epuckc check` reports on the same text (the test
suite compares them on random edit sequences), but after a one-rule edit to
a 1,000-rule file only the edited statement is lexed, parsed and checked:

1. **Splitting**: after an edit, only the text between the common
   beginning and the common end of the two versions (found by comparing
   slices, at C speed) is split into statements again, by the lexer and
   `lexer.iter_statements` themselves, starting at the last statement
   start before the edit: statements before it are kept as they were, and
   the split stops where it meets the old one again, at a statement start
   after the edit.
2. **Parsing** one statement at a time, as `epuckc check` does. A statement
   that the edit touched is parsed again unless its text (with its column
   and the keyword after it) is one the edit replaced (an undo).
3. **Positions that do not move.** A parsed statement's AST is built with
   *virtual* line numbers: statement number `id` has its lines at
   `id * VLINE + 1, + 2, ...` (columns are real: a statement that starts
   mid-line is padded with spaces). Inserting a line above a statement
   therefore changes nothing in its AST, nor in what the checker found
   about it; virtual lines are turned into real ones only for what is
   shown (`Analysis.real`, and `Analysis.real_words` for the lines a
   message names). Lines below VLINE are real lines.
4. **Checking** (recheck.py): the declarations (names, the robot block)
   and the whole-program checks (rules that can never fire, unused names,
   capacity) run every time, over all statements: they are cheap loops.
   Resolving each rule, the expensive part, is replayed (its diagnostics
   and the facts the whole-program checks need) when the rule is the same
   object and every name it looked up (`_Watched`) still means the same
   (a guard's narrowing looks up only the variables it names), by blocks
   of about 32 rules whose ends an edit does not move (`_Block`); named
   actions are replayed as a whole when no declaration changed. The
   variables' intervals are solved again only for the components of their
   dependency graph that an edit reaches (check/ranges.py), and W009 keeps
   each rule's facts and its last pairs (check/races.py).
5. **Showing**: a diagnostic is put in real lines once, and again only when
   a statement it names moved; the server keeps its LSP form while it is
   the same object on lines of the same text (lsp.py).

A file with 20 or more runs of bad characters is checked whole, because
the lexer stops at the 20th and that cut depends on the whole file.
"""
from __future__ import annotations

import bisect
import gc
import operator
from dataclasses import dataclass
from pathlib import Path
from typing import Optional

from ..base.source import SourceFile, Span
from ..check.checker import Checker
from ..check.program import CheckedProgram
from ..diagnostics import Collector, Diagnostic
from ..syntax import ast
from ..syntax.lexer import MAX_LEXICAL_ERRORS
from ..syntax.parser import parse
from .pieces import FirstLines, LineCache, Pieces
from .recheck import IncrementalChecker, _Memo
from .showing import Shown, real_words
from .statements import (_CR_ENDS_LINES, _MARGIN, VLINE, Entry, _boundaries, _common_prefix,
                         _common_suffix, _parse_chunk, line_starts, patched_line_starts)

_ID = operator.attrgetter("id")

# ---- the analysis of one version of a document ----------------------------------

@dataclass
class Analysis:
    """One version of a document: where its statements are (`layout`: each
    one's offset, first line and parse, pieces.Layout), the AST (virtual
    lines), the checker and its diagnostics (real lines)."""
    name: str
    text: str
    layout: object
    program: ast.Program
    checker: Checker
    checked: CheckedProgram
    diagnostics: list = None      # Diagnostic, real positions, sorted
    # (the last analysis's diagnostics, those taken out, those put in: showing.py)
    delta: tuple = None
    edit: tuple = None          # (the text's common beginning and end with the last one's)

    @property
    def starts(self) -> list:
        """Where each statement starts (a list made when asked)."""
        return [self.layout.start(i) for i in range(self.layout.count)]

    def start_of(self, i: int) -> int:
        return self.layout.start(i)

    @property
    def source(self) -> SourceFile:
        if self._source is None:
            self._source = SourceFile(self.name, self.text)
        return self._source

    # positions

    def real_line(self, line: int) -> int:
        ident = line // VLINE
        if ident == 0:
            return line
        return self.statement_lines[ident] + line % VLINE - 1

    def real_words(self, d: Diagnostic) -> Diagnostic:
        """A diagnostic whose words name lines (`(line 12)`, `the rules of
        lines 14, 15`: W009 names rules so) with those lines made real."""
        return real_words(d, self.statement_lines)

    def real(self, span: Span) -> Span:
        """A span of the AST (virtual lines) in the text's lines."""
        if span.line < VLINE:
            return span
        return Span(self.real_line(span.line), span.column,
                    self.real_line(span.end_line), span.end_column)

    def statements_on(self, vline: int) -> list:
        """The statements that may hold a (virtual) line: those of its
        statement (entry), found by their piece (pieces.py) without a walk
        over the program; every statement for real lines."""
        if vline >= VLINE and self._pieces is not None:
            piece = self._piece_of(vline // VLINE)
            if piece is not None and piece in self._pieces:
                return [s for s in piece.statements if s.span.line // VLINE == vline // VLINE]
        return self.program.statements

    def index_at(self, offset: int) -> int:
        """The statement that holds a character offset."""
        return max(0, self.layout.bisect_right(offset) - 1)

    def virtual(self, line: int, column: int) -> tuple:
        """(virtual line, column) of a real position, for comparing with
        the AST's spans."""
        _, _, first, entry, _ = self.layout.row(self.index_at(self.offset(line, column)))
        if entry.id == 0:
            return line, column
        return entry.id * VLINE + line - first + 1, column

    @property
    def line_starts(self) -> list:
        if self._line_starts is None:
            self._line_starts = line_starts(self.text)
        return self._line_starts

    def offset(self, line: int, column: int) -> int:
        """Character offset of a real (line, column), both from 1; clamped
        to the text, and to the end of the line."""
        starts = self.line_starts
        line = min(max(line, 1), len(starts))
        start = starts[line - 1]
        end = starts[line] if line < len(starts) else len(self.text)
        while end > start and self.text[end - 1] in "\r\n" and (
                self.text[end - 1] == "\n" or _CR_ENDS_LINES):
            end -= 1
        return min(start + max(column, 1) - 1, end)

    def position(self, offset: int) -> tuple:
        """(line, column) of a character offset, both from 1."""
        starts = self.line_starts
        offset = max(0, min(offset, len(self.text)))
        line = bisect.bisect_right(starts, offset) - 1
        return line + 1, offset - starts[line] + 1

    def __post_init__(self):
        self._source = None
        self.statement_lines = None         # statement id -> its first line (pieces.FirstLines)
        self._line_starts = None
        self._pieces = None         # (the analyser's pieces and their index, statements_on)
        self._piece_of = None


class Analyzer:
    """Analyses successive versions of one document (see the module's doc)."""

    def __init__(self, name: str, base_dir: Optional[Path] = None):
        self.name = name
        self.options = dict(base_dir=base_dir)
        # the last version's text and statements (see _chunks)
        self._prev: Optional[tuple] = None
        self._next_id = 1
        self._memo = _Memo()
        self._pieces = Pieces(name)     # the statements in pieces, placed (pieces.py)
        self._window = None         # (k, j, the rows of k..j, by, lines): see Pieces.place
        self._line_starts = None    # of the last text split (_chunks)
        self._changed = None        # the ids of the statements an edit replaced (_chunks)
        self._edit = None           # (common prefix, common suffix) with the last text (_chunks)
        self._same = None           # what the caller knows of them (analyse)
        self._lines = LineCache()   # statements' first lines found (pieces.py)
        self._shown = Shown()       # the diagnostics in real lines (showing.py)

    def analyse(self, text: str, same: Optional[tuple] = None) -> Analysis:
        """The analysis of `text`. `same`: (a text, n, m) when `text` has
        that text's first n and last m characters (an editor's changes say
        so: Document.apply); when it is the last text analysed, the edit is
        known without comparing the two."""
        collecting = gc.isenabled()
        gc.disable()            # the ASTs have no cycles (see frontend.py)
        first_id = self._next_id
        self._same = same
        try:
            return self._analyse(text)
        finally:
            if collecting:
                gc.enable()
                if self._next_id - first_id >= 100:
                    # Many new objects: the collection they will cause is
                    # done now, with the big parse, not at the next keystroke.
                    gc.collect()

    def _analyse(self, text: str) -> Analysis:
        if not self._chunks(text):
            return self._whole(text)
        program, diags, marks = self._pieces.place(*self._window)
        items = diags.items
        checker = IncrementalChecker(program, diags, self._memo, pieces=self._pieces.pieces,
                                     piece_of=self._pieces.of.get, marks=marks, **self.options)
        checked = checker.check()
        memo = self._memo.rules
        if len(memo) > 2 * program.count + 100:
            live = {id(s) for s in program.statements}
            self._memo.rules = {k: v for k, v in memo.items() if k in live}
        layout = self._pieces.layout
        analysis = self._finish(text, layout, FirstLines(layout, self._pieces.of.get,
                                                         self._lines), program,
                                checker, checked, items, self._changed, checker.segments,
                                checker.dropped)
        analysis._line_starts = self._line_starts     # (the split's: the same text's)
        analysis._pieces, analysis._piece_of = self._pieces.pieces, self._pieces.of.get
        analysis.edit = self._edit
        return analysis

    def _chunks(self, text: str) -> bool:
        """Split `text` into statements, again only where it differs from
        the previous version: from the last statement start the edit cannot
        move to a statement start after it that was one before; statements
        before are kept as they were, statements after it are moved as
        pieces (their entries, in virtual lines, do not change). What
        replaces what is left in `_window` for Pieces.place; False when the
        text has too many bad characters to be split so."""
        prev, layout = self._prev, self._pieces.layout
        n = layout.count
        if prev is None:
            old, bad = "", 0
            p = s = 0
        else:
            old, bad = prev
            same = self._same
            if same is not None and same[0] is old:
                # (the editor's changes bound the edit: what is outside is
                # the same, what is inside is split again whether or not)
                p = min(same[1], len(old), len(text))
                s = max(0, min(same[2], min(len(old), len(text)) - p))
            else:
                p = _common_prefix(old, text)
                s = _common_suffix(old, text, min(len(old), len(text)) - p)
        # the last statement start that the edit cannot move
        k = max(0, layout.bisect_right(p - _MARGIN) - 1) if n else 0
        delta = len(text) - len(old)
        suffix_from = len(text) - s
        # split again from there, until a statement start in the unchanged
        # end of the text that was a statement start before
        first = layout.row(k) if k > 0 else (0, None)
        middle, middle_kws = [first[0]], [first[1]]
        j = n                   # the first old statement kept after the edit
        starts_of_lines = line_starts(text) if prev is None or self._line_starts is None \
            else patched_line_starts(self._line_starts, len(old), text, p, s)
        for at, kw in _boundaries(text, middle[0], starts_of_lines):
            line_start = starts_of_lines[bisect.bisect_right(starts_of_lines, at) - 1]
            if at >= suffix_from and n and line_start > suffix_from:
                i = layout.bisect_left(at - delta)
                if i < n and layout.start(i) == at - delta:
                    j = i
                    break
            middle.append(at)
            middle_kws.append(kw)
        # the old statements that the middle replaces: their parses may serve again
        available: dict = {}
        replaced = set()
        for _, _, line, entry, key in layout.rows(k, j):
            available.setdefault(key, []).append((entry, line))
            bad -= entry.bad_runs
            replaced.add(entry.id)
        relocated = False       # (an old statement in the middle, on another line)
        after = layout.row(j) if j < n else None
        ends = middle[1:] + [after[0] + delta if after else len(text)]
        followings = middle_kws[1:] + [after[1] if after else None]
        rows = []
        for start, kw, end, following in zip(middle, middle_kws, ends, followings):
            line = bisect.bisect_right(starts_of_lines, start)
            column = start - starts_of_lines[line - 1] + 1
            key = (text[start:end], column, following)
            pool = available.get(key)
            if pool:
                entry, was = pool.pop()
                relocated = relocated or was != line
            else:
                entry = _parse_chunk(self.name, " " * (column - 1) + key[0], following,
                                     self._next_id)
                self._next_id += 1
            bad += entry.bad_runs
            if entry.lines >= VLINE:
                bad = MAX_LEXICAL_ERRORS
            rows.append((start, kw, line, entry, key))
        # as many lines more (or fewer) as the edit added
        shift = bisect.bisect_right(starts_of_lines, after[0] + delta) - after[2] if after else 0
        if bad >= MAX_LEXICAL_ERRORS:
            self._prev = None
            self._pieces.reset()
            return False
        self._window = (k, j, rows, delta, shift)
        self._edit = (p, s) if prev is not None else None
        # the statements the edit replaced or added, when no other moved to
        # another line (showing.py looks at what names them again)
        self._changed = None if prev is None or shift or relocated else \
            replaced.union(r[3].id for r in rows)
        if self._changed is None:       # (lines moved: the first lines found again)
            self._lines = LineCache()
        else:
            self._lines.generation += 1
            for ident in replaced:
                self._lines.lines.pop(ident, None)
        self._prev = (text, bad)
        self._line_starts = starts_of_lines
        return True

    def _whole(self, text: str) -> Analysis:
        """The whole file at once, in real lines (no reuse)."""
        source = SourceFile(self.name, text)
        diags = Collector(source)
        program = parse(source, diags)
        checker = Checker(program, diags, **self.options)
        checked = checker.check()
        entry = Entry(0, program.statements, [], 0, source.line_count)
        self._shown.reset()
        return self._finish(text, _Whole(entry), {0: 1}, program, checker, checked, diags.items)

    def _finish(self, text, layout, first_lines, program, checker, checked, items,
                changed=None, segments=None, dropped=()) -> Analysis:
        analysis = Analysis(self.name, text, layout, program, checker, checked)
        analysis.statement_lines = first_lines
        analysis.diagnostics = self._shown.show(analysis, items, changed, segments, dropped)
        analysis.delta = self._shown.delta
        return analysis


class _Whole:
    """The layout of a file analysed whole: one entry, in real lines."""
    count = 1

    def __init__(self, entry):
        self.entry = entry

    def start(self, i: int) -> int:
        return 0

    def row(self, i: int) -> tuple:
        return 0, None, 1, self.entry, None

    def bisect_right(self, offset: int) -> int:
        return 1 if offset >= 0 else 0
