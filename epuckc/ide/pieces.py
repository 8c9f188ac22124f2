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
    __slots__ = ("entries", "mode_in", "mode_out", "statements", "diags", "placed", "once",
                 "rules", "decls", "externs")

    def __init__(self, entries: list, mode_in: tuple, placed: dict, name: str):
        self.entries, self.mode_in = entries, mode_in
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


def _same_modes(a: tuple, b: tuple) -> bool:
    return len(a) == len(b) and all(x is y for x, y in zip(a, b))


class Pieces:
    """A document's pieces (see the module's doc), from one analysis to the
    next."""

    def __init__(self, name: str):
        self.name = name
        self.pieces: list = []
        self.starts: list = []      # the index of each piece's first entry
        self.of: dict = {}          # entry id -> the last piece made of it

    def reset(self):
        self.pieces, self.starts, self.of = [], [], {}

    def place(self, entries: list, k: int, n_new: int, n_old: int) -> tuple:
        """The pieces of `entries`, whose entries k .. k + n_new replaced the
        n_old entries from k of the last analysis; then the program (its
        statements) and a Collector of the statements' diagnostics, in the
        order a whole file's parse gives them."""
        old, starts = self.pieces, self.starts
        shift = n_new - n_old
        a = max(0, bisect.bisect_right(starts, k) - 1) if old else 0
        pieces, new_starts = old[:a], starts[:a]
        # the pieces the window touches, cut again (an old one whose entries
        # are the same objects is kept: an undo); a new run is a list
        i, n, end, t = (starts[a] if old else 0), len(entries), k + n_new, len(old)
        first = {id(p.entries[0]): p for p in old[a:a + 3]}
        while i < n:
            j = i
            while j < n - 1 and entries[j].id % PIECE:
                j += 1
            j += 1
            run = entries[i:j]
            piece = first.get(id(run[0]))
            if piece is not None and len(piece.entries) == len(run) \
                    and all(x is y for x, y in zip(piece.entries, run)):
                run = piece
            pieces.append(run)
            new_starts.append(i)
            i = j
            if i >= end:        # where an old piece starts after the window: the rest is kept
                t = bisect.bisect_left(starts, i - shift)
                if t < len(starts) and starts[t] == i - shift and i - shift >= k + n_old:
                    pieces += old[t:]
                    new_starts += [s + shift for s in starts[t:]] if shift else starts[t:]
                    break
                t = len(old)
        # placed in order: a new run, or a piece after modes that changed
        modes: tuple = ()
        memory = None
        for at, piece in enumerate(pieces):
            if piece.__class__ is list or not _same_modes(piece.mode_in, modes):
                if piece.__class__ is list:
                    if memory is None:      # (what the statements came to last time)
                        memory = {}
                        for gone in old[a:t]:
                            memory.update(gone.placed)
                    piece = Piece(piece, modes, memory, self.name)
                else:
                    piece = Piece(piece.entries, modes, piece.placed, self.name)
                pieces[at] = piece
                for entry in piece.entries:
                    self.of[entry.id] = piece
            modes = piece.mode_out
        self.pieces, self.starts = pieces, new_starts
        if len(self.of) > 2 * len(entries) + 100:
            self.of = {entry.id: piece for piece in pieces for entry in piece.entries}
        return self._program(pieces)

    def _program(self, pieces: list) -> tuple:
        """(the program, a Collector of the statements' diagnostics, where
        each piece's start in them: (place, the piece's list) for the
        checker's segments)."""
        program = ast.Program(self.name)
        program.statements = list(itertools.chain.from_iterable(map(_STATEMENTS, pieces)))
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
