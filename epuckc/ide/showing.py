"""The last step of incremental.py: the checker's diagnostics (in virtual
lines) in the text's lines, sorted as `epuckc check` sorts them.

A diagnostic is put in real lines once, and again only when a statement
it names (`_idents`: its places, and the lines its words name) starts on
another line; the object made is kept, so that what caches its LSP form
(lsp.py) keeps that too. After an edit that moved no statement to
another line, the sorted list is the last one spliced: the diagnostics
that went are taken out, the new ones put in by bisection, and those
naming a statement the edit replaced looked at again (`_naming` finds
them); any other edit, or a place where two diagnostics would sort alike
(their order is then the checker's), sorts every diagnostic again.
"""
from __future__ import annotations

import bisect
import itertools
import operator
import re
from dataclasses import replace

from ..diagnostics import Diagnostic
from .statements import VLINE

_FIRST, _SECOND = operator.itemgetter(0), operator.itemgetter(1)
_SORT_KEY = Diagnostic.sort_key
# words that name lines in a diagnostic's text, and those of them that are virtual
_LINE_WORDS = re.compile(r"\b(lines?) (\d+(?:, \d+)*)")
_VIRTUAL_LINE = re.compile(r"\blines? (?:\d+, )*?\d{7,}")


def idents(d: Diagnostic) -> tuple:
    """The statements (ids) whose virtual lines `d` has, in its spans or
    in its words (W009 names rules by their lines)."""
    found = {span.line // VLINE for span in (d.span, *(n.span for n in d.notes if n.span),
                                              *(f.span for f in d.fixes))}
    for text in (d.message, d.help or "", *(n.message for n in d.notes)):
        if _VIRTUAL_LINE.search(text):
            for match in _LINE_WORDS.finditer(text):
                found.update(int(n) // VLINE for n in match.group(2).split(", "))
    found.discard(0)
    return tuple(sorted(found))


def real_words(d: Diagnostic, starts: dict) -> Diagnostic:
    """A diagnostic whose words name lines (`(line 12)`, `the rules of
    lines 14, 15`: W009 names rules so) with those lines made real
    (`starts`: statement id -> its first real line)."""
    def lines(match):
        # (in the order of the file, as the checker lists them: virtual
        # lines follow statements' ids, not their places)
        numbers = list(map(int, match.group(2).split(", ")))
        virtual = [n for n in numbers if n >= VLINE]
        found = first_lines(starts, [n // VLINE for n in virtual])
        if None in found:       # (raises KeyError, as it always did)
            found = [starts[n // VLINE] for n in virtual]
        first = dict(zip(virtual, found))
        numbers = sorted([first[n] + n % VLINE - 1 if n >= VLINE else n for n in numbers])
        return f"{match.group(1)} {', '.join(map(str, numbers))}"

    def fix(text):
        return _LINE_WORDS.sub(lines, text) if text else text
    return replace(d, message=fix(d.message), help=fix(d.help),
                   notes=tuple(replace(n, message=fix(n.message)) for n in d.notes))


def first_lines(starts, idents) -> tuple:
    """The first lines of statements `idents` (None where there is none):
    `starts` is a dict or pieces.FirstLines, which finds many at once."""
    many = getattr(starts, "many", None)
    return many(idents) if many is not None else tuple(map(starts.get, idents))


def real_diagnostic(analysis, d: Diagnostic) -> Diagnostic:
    """`d` in the text's lines (its spans, and the lines its words name)."""
    real = analysis.real
    if d.span.line >= VLINE or any(n.span and n.span.line >= VLINE for n in d.notes) \
            or any(f.span.line >= VLINE for f in d.fixes):
        d = replace(d, span=real(d.span),
                    notes=tuple(replace(n, span=real(n.span)) if n.span else n
                                for n in d.notes),
                    fixes=tuple(replace(f, span=real(f.span)) for f in d.fixes))
    if _VIRTUAL_LINE.search(d.message) or any(_VIRTUAL_LINE.search(n.message)
                                              for n in d.notes):
        d = analysis.real_words(d)
    return d


class Shown:
    """What the last analysis showed: each diagnostic in real lines (kept
    by the checker's object), the sorted list, the checker's segments it
    came from, which diagnostics name which statement; and what changed in
    the list since the analysis before (`delta`, for lsp.py)."""

    def __init__(self):
        self.real: dict = {}        # id(d) -> (d, its statements, their lines, (key, real d))
        self.shown = None           # the last sorted list (None: sort again)
        self.segments: list = []    # the checker's runs of diagnostics they came from
        self.dropped: set = set()   # ids of those of the segments the checker dropped
        self.ties = False           # two of them sort alike
        self.naming: dict = {}      # statement id -> {id(d) of the diagnostics naming it}
        # (the list before, the diagnostics taken out, those put in; None: any)
        self.delta = None

    def reset(self):
        self.shown = None

    def show(self, analysis, items: list, changed=None, segments=None, dropped=()) -> list:
        """The diagnostics `items` (the checker's, virtual lines) in real
        lines, sorted. `changed`: the ids of the statements the edit
        replaced or added, when it moved no other statement to another line
        (None: any may have moved); `segments`: `items` as the checker's
        runs (each the last one's object while the same) before it dropped
        those of `dropped` (ids)."""
        before = self.shown
        if changed is not None and segments is not None and before is not None \
                and not self.ties:
            spliced = self._splice(analysis, segments, set(dropped), changed)
            if spliced is not None:
                self.segments, self.dropped = segments, set(dropped)
                return spliced
        cache, kept = self.real, {}
        starts = analysis.statement_lines
        get = starts.get
        shown = []
        for d in items:
            # hit: (d, its statements, their first lines, (sort key, d in real lines))
            hit = cache.get(id(d))
            if hit is None or hit[0] is not d or (
                    get(hit[1][0]) != hit[2][0] if len(hit[1]) == 1
                    else first_lines(starts, hit[1]) != hit[2]):
                hit = self._hit(analysis, d)
            kept[id(d)] = hit
            shown.append(hit[3])
        self.real = kept
        shown.sort(key=_FIRST)
        keys = list(map(_FIRST, shown))
        self.ties = any(map(operator.eq, keys, itertools.islice(keys, 1, None)))
        self.shown = list(map(_SECOND, shown))
        self.segments, self.dropped = segments or [], set(dropped)
        self.delta = None
        naming = self.naming = {}
        for key, hit in kept.items():
            for ident in hit[1]:
                found = naming.get(ident)
                if found is None:
                    naming[ident] = {key}
                else:
                    found.add(key)
        return self.shown

    @staticmethod
    def _hit(analysis, d: Diagnostic) -> tuple:
        found = idents(d)
        real = real_diagnostic(analysis, d) if found else d
        return (d, found, first_lines(analysis.statement_lines, found), (real.sort_key(), real))

    def _splice(self, analysis, segments: list, dropped: set, changed: set):
        """The last sorted list with the diagnostics that went taken out and
        the new ones put in (see the module's doc), or None when the list
        must be sorted again. What went and came is found from the segments
        that are not the last analysis's objects."""
        cache = self.real
        kept_segments = set(map(id, self.segments)) & set(map(id, segments))
        came = [d for seg in segments if id(seg) not in kept_segments for d in seg]
        went = [d for seg in self.segments if id(seg) not in kept_segments for d in seg]
        came_ids = set(map(id, came))
        if len(came_ids) != len(came):
            return None
        went_ids = set(map(id, went))
        gone = {i for i in went_ids - came_ids if i not in self.dropped}
        added_ids = {i for i in came_ids - went_ids if i not in dropped}
        # (a new one the checker drops beside an error, or an old one dropped
        # that went: nothing to do; one of the last analysis's dropped now,
        # or no more: sort again)
        for i in dropped - self.dropped:
            if i in went_ids or i not in came_ids:
                return None
        for i in self.dropped - dropped:
            if i in came_ids or i not in went_ids:
                return None
        present = {id(d): d for d in came}
        hits = []
        for i in added_ids:
            hit = cache.get(i)
            d = present[i]
            if hit is None or hit[0] is not d or first_lines(analysis.statement_lines, hit[1]) \
                    != hit[2]:
                hit = self._hit(analysis, d)
            hits.append(hit)
        # kept ones that name a statement the edit replaced: looked at again
        # (made again if those statements start on other lines)
        again = set()
        for ident in changed:
            again.update(self.naming.get(ident, ()))
        again -= gone
        again.difference_update(dropped, added_ids)
        moved = []
        for i in again:
            hit = cache[i]
            if first_lines(analysis.statement_lines, hit[1]) != hit[2]:
                moved.append(i)
                hits.append(self._hit(analysis, hit[0]))
        out = list(self.shown)
        removed = [cache[i][3][1] for i in itertools.chain(gone, moved) if i in cache]
        for real in removed:
            at = find_sorted(out, real)
            if at is None:
                return None
            del out[at]
        inserted = []
        hits.sort(key=lambda h: h[3][0])
        for hit in hits:
            key, real = hit[3]
            at = bisect.bisect_right(out, key, key=_SORT_KEY)
            if (at and out[at - 1].sort_key() == key) or (at < len(out)
                                                           and out[at].sort_key() == key):
                self._forget(gone & cache.keys())
                self._remember(hits)
                return None     # two sort alike: their order is the checker's
            out.insert(at, real)
            inserted.append(real)
        self._forget(gone & cache.keys())
        self._remember(hits)
        self.delta = (self.shown, removed, inserted)
        self.shown = out
        return out

    def _forget(self, gone) -> None:
        cache, naming = self.real, self.naming
        for key in gone:
            for ident in cache.pop(key)[1]:
                found = naming.get(ident)
                if found is not None:
                    found.discard(key)
                    if not found:
                        del naming[ident]

    def _remember(self, hits: list) -> None:
        cache, naming = self.real, self.naming
        for hit in hits:
            key = id(hit[0])
            cache[key] = hit
            for ident in hit[1]:
                found = naming.get(ident)
                if found is None:
                    naming[ident] = {key}
                else:
                    found.add(key)


def find_sorted(shown: list, d):
    """The place of `d` in a sorted list of diagnostics (by its key, then
    by identity among those that sort alike); None if it is not there."""
    key = d.sort_key()
    at = bisect.bisect_left(shown, key, key=_SORT_KEY)
    while at < len(shown) and shown[at] is not d:
        if shown[at].sort_key() != key:
            return None
        at += 1
    return at if at < len(shown) else None
