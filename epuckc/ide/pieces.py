"""The statements of a document in pieces that an edit leaves alone (the
third step of incremental.py, between parsing and checking).

A piece is a run of consecutive entries (statements as split and parsed,
statements.py) that ends after an entry whose id is a multiple of PIECE:
ids are given in the order entries are parsed, so the ends of the pieces
an edit does not touch stay where they were, and after an edit only the
pieces the edit's window overlaps are cut again (the others are the same
objects). Each piece is placed once (syntax/parser.py's ModePlacer: a mode's
head and `}` become a ModeDef and a ModeEnd, a rule inside a mode gets its
mode) and keeps what it came to: its statements, their diagnostics and
those of placing them, in the order a whole file's parse gives them, the
open modes after it. A piece is placed again only when its entries or the
modes open before it changed.

What the checker's passes need of each piece is kept with it: its rules,
its declarations (every statement but a rule without a name); the passes
keep more by piece (ide/recheck.py, check/ranges.py, check/races.py), so
that what an edit costs is the pieces it touches, plus a loop over the
pieces.
"""
from __future__ import annotations

import bisect
import itertools
import operator
from typing import Optional

from ..diagnostics import Collector
from ..syntax import ast
from ..syntax.parser import ModePlacer
from .statements import _ONCE as _SAID_ONCE

# A piece ends after an entry whose id is a multiple of this.
PIECE = 32

_STATEMENTS, _DIAGS = operator.attrgetter("statements"), operator.attrgetter("diags")
_ONCE = operator.attrgetter("once")


class _Named:
    """What a Collector needs of its source: the name shown."""
    def __init__(self, name):
        self.name = name


class Piece:
    """A run of entries, placed (see the module's doc). `mode_in`: the
    ModeOpens of the modes open before it (innermost last), `mode_out`
    those open after it; `diags`: its entries' diagnostics and those of
    placing its statements, in order; `placed`: ModePlacer's memory of its
    statements."""
    __slots__ = ("entries", "offsets", "kws", "lines", "keys", "index", "mode_in", "mode_out",
                 "statements", "diags", "placed", "once", "rules", "decls", "externs")

    def __init__(self, rows: list, mode_in: tuple, placed: dict, name: str):
        """`rows`: each entry's (start, keyword, first line, entry, key) in
        the text (kept relative to the first one's: a piece after an edit
        moves as a whole, Layout)."""
        base, line = rows[0][0], rows[0][2]
        self.offsets = [r[0] - base for r in rows]
        self.kws = [r[1] for r in rows]
        self.lines = [r[2] - line for r in rows]
        entries = self.entries = [r[3] for r in rows]
        self.keys = [r[4] for r in rows]
        self.index = {e.id: x for x, e in enumerate(entries)}
        self.mode_in = mode_in
        program = ast.Program(name)
        diags = Collector(_Named(name))
        placer = ModePlacer(program, diags, placed)
        placer.modes = list(mode_in)
        items = diags.items
        for entry in entries:
            if entry.statements:
                placer.extend(entry.statements)
            if entry.diags:
                items.extend(entry.diags)
        self.statements, self.diags, self.placed = program.statements, items, placer.placed
        self.mode_out = tuple(placer.modes)
        self.once = any(entry.once for entry in entries)
        rule = ast.Rule
        self.rules = [s for s in self.statements if s.__class__ is rule]
        self.decls = tuple(s for s in self.statements if s.__class__ is not rule or s.name)
        self.externs = tuple(s for s in self.decls if s.__class__ is ast.ExternDef)


class _Program(ast.Program):
    """The program of the pieces' statements, made into one list only when
    something asks for it (hover, a check of the declarations): an edit's
    analysis does not."""
    __slots__ = ("_pieces", "_statements", "_count")

    def __init__(self, name: str, pieces: list):
        self.file, self._pieces, self._statements, self._count = name, pieces, None, None

    @property
    def statements(self) -> list:
        if self._statements is None:
            self._statements = list(itertools.chain.from_iterable(map(_STATEMENTS,
                                                                      self._pieces)))
        return self._statements

    @property
    def count(self) -> int:
        """How many statements (without making their list)."""
        if self._statements is not None:
            return len(self._statements)
        if self._count is None:     # (asked a few times a check: counted once)
            self._count = sum(map(len, map(_STATEMENTS, self._pieces)))
        return self._count


def _same_modes(a: tuple, b: tuple) -> bool:
    return len(a) == len(b) and all(x is y for x, y in zip(a, b))


class Layout:
    """Where each entry (statement) of one version of the text is, kept by
    piece: each piece's entries' offsets and lines relative to its first
    one, and each piece's first entry's index, offset and line. An edit
    makes new pieces where it is, and moves the pieces after it as wholes:
    what a version keeps is a few lists as long as the pieces, not as the
    statements."""
    __slots__ = ("pieces", "firsts", "bases", "lines", "count", "_where")

    def __init__(self, pieces: list, firsts: list, bases: list, lines: list):
        self.pieces, self.firsts, self.bases, self.lines = pieces, firsts, bases, lines
        self.count = firsts[-1] + len(pieces[-1].entries) if pieces else 0
        self._where = None

    def locate(self, i: int) -> tuple:
        """(the place of the piece of entry `i`, the entry's place in it)."""
        p = bisect.bisect_right(self.firsts, i) - 1
        return p, i - self.firsts[p]

    def start(self, i: int) -> int:
        p, x = self.locate(i)
        return self.bases[p] + self.pieces[p].offsets[x]

    def line(self, i: int) -> int:
        p, x = self.locate(i)
        return self.lines[p] + self.pieces[p].lines[x]

    def row(self, i: int) -> tuple:
        """(start, keyword, first line, entry, key) of entry `i`."""
        p, x = self.locate(i)
        piece = self.pieces[p]
        return (self.bases[p] + piece.offsets[x], piece.kws[x], self.lines[p] + piece.lines[x],
                piece.entries[x], piece.keys[x])

    def rows(self, i: int, j: int, by: int = 0, shift: int = 0):
        """The rows of entries i..j, their starts moved by `by` characters
        and their lines by `shift`."""
        while i < j:
            p, x = self.locate(i)
            piece, base, line = self.pieces[p], self.bases[p] + by, self.lines[p] + shift
            for x in range(x, min(len(piece.entries), x + j - i)):
                yield (base + piece.offsets[x], piece.kws[x], line + piece.lines[x],
                       piece.entries[x], piece.keys[x])
                i += 1

    def bisect_right(self, offset: int) -> int:
        """bisect.bisect_right over the entries' starts."""
        p = bisect.bisect_right(self.bases, offset) - 1
        if p < 0:
            return 0
        return self.firsts[p] + bisect.bisect_right(self.pieces[p].offsets, offset - self.bases[p])

    def bisect_left(self, offset: int) -> int:
        """bisect.bisect_left over the entries' starts."""
        p = bisect.bisect_right(self.bases, offset) - 1
        if p < 0:
            return 0
        return self.firsts[p] + bisect.bisect_left(self.pieces[p].offsets, offset - self.bases[p])

    def line_of(self, ident: int, of) -> Optional[int]:
        """The first line of the entry of id `ident` (`of`: id -> a piece
        made of it, Pieces.of), or None."""
        piece = of(ident)
        if self._where is None:
            self._where = {id(p): at for at, p in enumerate(self.pieces)}
        at = self._where.get(id(piece)) if piece is not None else None
        if at is None:          # (a version before the last one: look for it)
            for at, piece in enumerate(self.pieces):
                if ident in piece.index:
                    break
            else:
                return None
        x = piece.index.get(ident)
        return None if x is None else self.lines[at] + piece.lines[x]


class LineCache:
    """The first lines found (statement id -> line), shared by the versions
    an edit moved no line of: an edit of one line pops the statements it
    replaced and counts one generation more (a version of an older
    generation looks its lines up in its own layout); one that moves lines
    starts a new cache."""
    __slots__ = ("lines", "generation")

    def __init__(self):
        self.lines: dict = {}
        self.generation = 0


class FirstLines:
    """statement id -> its first line, of one version (the mapping showing.py
    and Analysis read), found by piece and kept in the LineCache."""
    __slots__ = ("layout", "of", "cache", "generation")

    def __init__(self, layout: Layout, of, cache: LineCache):
        self.layout, self.of, self.cache, self.generation = layout, of, cache, cache.generation

    def get(self, ident, default=None):
        cache = self.cache
        if cache.generation == self.generation:
            found = cache.lines.get(ident)
            if found is None:
                found = self.layout.line_of(ident, self.of)
                if found is not None:
                    cache.lines[ident] = found
        else:
            found = self.layout.line_of(ident, self.of)
        return default if found is None else found

    def __getitem__(self, ident):
        found = self.get(ident)
        if found is None:
            raise KeyError(ident)
        return found

    def many(self, idents) -> tuple:
        """The first lines of `idents` (None where there is none), those in
        the cache looked up at C speed (a W009 warning names every rule)."""
        cache = self.cache
        if cache.generation != self.generation:
            return tuple(map(self.get, idents))
        found = list(map(cache.lines.get, idents))
        if None in found:
            for i, ident in enumerate(idents):
                if found[i] is None:
                    found[i] = self.get(ident)
        return tuple(found)


class Pieces:
    """A document's pieces (see the module's doc), from one analysis to the
    next, and their Layout."""

    def __init__(self, name: str):
        self.name = name
        self.reset()

    def reset(self):
        self.pieces, self.of = [], {}   # (of: entry id -> the last piece made of it)
        self.layout = Layout([], [], [], [])

    def place(self, k: int, j: int, middle: list, by: int, shift: int) -> tuple:
        """The pieces after an edit whose rows `middle` (see Piece) replaced
        the last version's entries k..j, the entries after them moved by
        `by` characters and `shift` lines; then the program (its
        statements), a Collector of the statements' diagnostics, in the
        order a whole file's parse gives them, and where each piece's are."""
        layout = self.layout
        old, firsts = layout.pieces, layout.firsts
        count = layout.count - (j - k) + len(middle)
        d = len(middle) - (j - k)
        a = max(0, bisect.bisect_right(firsts, k) - 1) if old else 0
        pieces, new_firsts = old[:a], firsts[:a]
        bases, lines = layout.bases[:a], layout.lines[:a]
        # the rows from the first piece the window touches, in order
        i = firsts[a] if old else 0
        rows = itertools.chain(layout.rows(i, k), middle, layout.rows(j, layout.count, by, shift))
        end, t = k + len(middle), len(old)
        first = {id(p.entries[0]): p for p in old[a:a + 3]}
        run = []
        for row in rows:
            run.append(row)
            if row[3].id % PIECE and i + len(run) < count:
                continue
            # a run ends: a new piece, or an old one whose entries are
            # the same objects (an undo)
            piece = first.get(id(run[0][3]))
            if piece is None or len(piece.entries) != len(run) \
                    or any(x is not r[3] for x, r in zip(piece.entries, run)):
                piece = run
            pieces.append(piece)
            new_firsts.append(i)
            bases.append(run[0][0])
            lines.append(run[0][2])
            i += len(run)
            run = []
            if i >= end:        # where an old piece starts after the window: the rest is kept
                t = bisect.bisect_left(firsts, i - d)
                if t < len(firsts) and firsts[t] == i - d and i - d >= j:
                    pieces += old[t:]
                    new_firsts += [x + d for x in firsts[t:]] if d else firsts[t:]
                    bases += [x + by for x in layout.bases[t:]] if by else layout.bases[t:]
                    lines += [x + shift for x in layout.lines[t:]] if shift \
                        else layout.lines[t:]
                    break
                t = len(old)
        # placed in order: a new run, or a piece after modes that changed
        modes: tuple = ()
        memory = None
        for at, piece in enumerate(pieces):
            if piece.__class__ is list or (piece.mode_in is not modes
                                           and not _same_modes(piece.mode_in, modes)):
                if piece.__class__ is list:
                    if memory is None:      # (what the statements came to last time)
                        memory = {}
                        for gone in old[a:t]:
                            memory.update(gone.placed)
                    piece = Piece(piece, modes, memory, self.name)
                else:
                    piece = Piece(list(zip([bases[at] + o for o in piece.offsets], piece.kws,
                                           [lines[at] + x for x in piece.lines],
                                           piece.entries, piece.keys)),
                                  modes, piece.placed, self.name)
                pieces[at] = piece
                for entry in piece.entries:
                    self.of[entry.id] = piece
            modes = piece.mode_out
        self.pieces = pieces
        self.layout = Layout(pieces, new_firsts, bases, lines)
        if len(self.of) > 2 * count + 100:
            self.of = {entry.id: piece for piece in pieces for entry in piece.entries}
        return self._program(pieces)

    def _program(self, pieces: list) -> tuple:
        """(the program, a Collector of the statements' diagnostics, where
        each piece's start in them: (place, the piece's list) for the
        checker's segments)."""
        program = _Program(self.name, pieces)
        diags = Collector(_Named(self.name))
        items = diags.items = list(itertools.chain.from_iterable(map(_DIAGS, pieces)))
        marks, at = [], 0
        for piece in pieces:
            if piece.diags:
                marks.append((at, piece.diags))
                at += len(piece.diags)
        if any(map(_ONCE, pieces)):
            marks = [(0, None)]
            # a name that is not ASCII (E008) is said once per file
            said, kept = set(), []
            for d in items:
                if d.code in _SAID_ONCE:
                    if (d.code, d.message) in said:
                        continue
                    said.add((d.code, d.message))
                kept.append(d)
            items[:] = kept
        if pieces and pieces[-1].mode_out:      # modes not closed at the end of the file
            marks.append((len(items), None))
            placer = ModePlacer(program, diags)
            placer.modes = list(pieces[-1].mode_out)
            placer.finish()
        return program, diags, marks
