"""The checker's passes over the whole program, following an edit: each
keeps what it found by piece of the document (ide/pieces.py), so that an
edit costs the pieces it touched and a loop over the pieces, not a pass
over every statement (a part of recheck.IncrementalChecker).

- **Declarations** (`_declarations`): every statement that declares
  something (all but rules without a name) and the robot block. While they
  are the same objects (and the extern C files they name say the same),
  what declaring them left in the checker is put back as it was: the same
  tables, the same VarInfo objects, the same diagnostics.
- **Assignments** (`_assignments_by_variable`, for check/ranges.py): each
  piece's assignments by variable; a variable's list is made again only
  when the pieces an edit replaced assigned it differently.
- **Facts** (FactCounts): the names the replayed blocks of rules use and
  assign, counted by block: an edit takes away and adds the blocks it
  changed.
- **Unused names** (`_unused`): said again only when the declarations or
  the names used changed.
- **A warning beside an error** (`_no_warnings_beside_errors`): the
  statement that holds a place is found by its virtual line (the entry's
  id, statements.py), among that entry's statements only.
"""
from __future__ import annotations

import bisect
import itertools
import operator

from ..check.externs import extern_file_problem
from ..check.ranges import statement_assignments
from ..diagnostics import ERROR
from .statements import VLINE

_DECLS, _EXTERNS, _RULES = (operator.attrgetter("decls"), operator.attrgetter("externs"),
                            operator.attrgetter("rules"))
_SEVERITY = operator.attrgetter("severity")
_START = operator.itemgetter(0, 1)     # a Span's (line, column)

class Declared:
    """What declaring came to, kept while the declaring statements are the
    same (`key`): the records it left (check/state.py), its diagnostics,
    whether the program describes the robot."""
    __slots__ = ("key", "decls", "facts", "memories", "diags", "robot_given")

    def __init__(self, key, decls, facts, memories, diags, robot_given):
        self.key, self.decls, self.facts, self.memories = key, decls, facts, memories
        self.diags, self.robot_given = diags, robot_given


class Unused:
    """What `_unused` said (`diags`), and what it read: the declarations
    (a Declared) and the names used (`key`)."""
    __slots__ = ("declared", "key", "diags")

    def __init__(self, declared, key, diags):
        self.declared, self.key, self.diags = declared, key, diags


class PieceAssigns:
    """A piece's assignments (`_assignments_by_variable`): the piece (kept
    alive, so that its id stays its own), its entries by variable, and
    each assigning statement's place in it (by id)."""
    __slots__ = ("piece", "by_name", "order")

    def __init__(self, piece, by_name: dict, order: dict):
        self.piece, self.by_name, self.order = piece, by_name, order


class PiecePasses:
    """The whole-program passes by pieces (see the module's doc)."""

    pieces = None
    piece_of = None         # entry id -> its piece (ide/pieces.py), when known

    def _declarations(self) -> bool:
        if self.pieces is None:
            return super()._declarations()
        decls = tuple(itertools.chain.from_iterable(map(_DECLS, self.pieces)))
        externs = ()
        if self.base_dir is not None:
            externs = tuple(extern_file_problem(self.base_dir / s.file) for s in
                            itertools.chain.from_iterable(map(_EXTERNS, self.pieces)))
        key = (decls, self.base_dir, self.target, externs)
        memo = self.memo
        hit = memo.declared
        if hit is not None and hit.key == key:
            self.decls, self.facts = hit.decls.copy(), hit.facts.copy()
            self.memories = hit.memories.copy()
            self._mark(hit.diags)
            self.diags.items.extend(hit.diags)
            self._declared_same = True
            return hit.robot_given
        self._mark()
        start = len(self.diags.items)
        robot_given = super()._declarations()
        # (what declaring leaves: its records, check/state.py)
        memo.declared = Declared(key, self.decls.copy(), self.facts.copy(),
                                 self.memories.copy(), self.diags.items[start:], robot_given)
        return robot_given

    def _assignments_by_variable(self, memo, same_names: bool) -> tuple:
        if self.pieces is None:
            return super()._assignments_by_variable(memo, same_names)
        old = memo.pieces           # id(piece) -> PieceAssigns
        known, where = memo.statements, memo.where
        pieces, last = self.pieces, memo.piece_list if old else []
        # (the old pieces are kept alive by `old`: an id in both is the same piece)
        now = set(map(id, pieces))
        fresh_at = list(itertools.compress(range(len(pieces)), map(
            operator.not_, map(old.__contains__, map(id, pieces)))))
        gone_at = list(itertools.compress(range(len(last)), map(
            operator.not_, map(now.__contains__, map(id, last)))))
        new = dict(old) if len(gone_at) < len(old) else {}
        gone = []
        for at in gone_at:
            gone.append(new.pop(id(last[at]), None) or old[id(last[at])])
        fresh = []
        for at in fresh_at:
            piece = pieces[at]
            by_name, order = {}, {}
            for i, stmt in enumerate(piece.statements):
                found = statement_assignments(self, known, stmt).entries
                if found:
                    order[id(stmt)] = i
                    where[id(stmt)] = piece
                    for name, entry in found:
                        by_name.setdefault(name, []).append(entry)
            hit = new[id(piece)] = PieceAssigns(piece, by_name, order)
            fresh.append(hit)
        first_fresh = fresh_at[0] if fresh_at else None
        first_gone = gone_at[0] if gone_at else None
        memo.pieces, memo.piece_list = new, self.pieces
        if len(known) > 2 * self.program.count + 100:
            live = {id(s) for s in self.program.statements}
            memo.statements = {k: v for k, v in known.items() if k in live}
            memo.where = {k: v for k, v in where.items() if k in live}
        if not same_names or not old or len(fresh) > 8:
            assigns = {name: [] for name in self.vars}
            for piece in self.pieces:
                for name, entries in new[id(piece)].by_name.items():
                    found = assigns.get(name)
                    if found is not None:
                        found.extend(entries)
            return assigns, None, self._place_of(new)
        # the variables the replaced pieces assign: made again where the
        # new pieces assign them differently (the same entries in the same
        # order, in the same place of the file, leave the list as it was)
        in_place = first_gone == first_fresh and len(gone) == len(fresh) and (
            not fresh_at or fresh_at[-1] - fresh_at[0] == len(fresh_at) - 1) and (
            not gone_at or gone_at[-1] - gone_at[0] == len(gone_at) - 1)
        touched = set().union(*(h.by_name.keys() for h in gone),
                              *(h.by_name.keys() for h in fresh))
        changed, spliced = set(), {}
        for name in touched:
            before = [e for h in gone for e in h.by_name.get(name, ())]
            after = [e for h in fresh for e in h.by_name.get(name, ())]
            if name in memo.assigns and (not in_place or len(before) != len(after) or any(
                    x is not y for x, y in zip(before, after))):
                changed.add(name)
                if in_place and before:
                    spliced[name] = (before, after)
        assigns = memo.assigns
        if changed:
            assigns = dict(assigns)
            for name in changed:
                # (where the replaced pieces assigned it: their entries, together
                # in its list, replaced; else made again from every piece)
                found = spliced.get(name)
                found = _spliced(assigns[name], *found) if found is not None else None
                assigns[name] = found if found is not None else [
                    e for piece in self.pieces for e in new[id(piece)].by_name.get(name, ())]
        return assigns, changed, self._place_of(new)

    def _unused(self):
        if self.pieces is None:
            return super()._unused()
        # (what _unused reads: the declarations, the names used, whether
        # there are rules)
        declared = self.memo.declared
        key = (self.used_actions, self.const_used, self.vars_used, self.vars_assigned,
               any(map(_RULES, self.pieces)))
        said = self.memo.unused
        # (sets compare with the frozen copies kept; the big ones are
        # FactCounts' frozensets, the same objects while no name came or
        # went, and compare by identity)
        if said is None or said.declared is not declared or said.key != key:
            self._mark()
            start = len(self.diags.items)
            super()._unused()
            diags = self.diags.items[start:]
        else:
            diags = said.diags
            self._mark(diags)
            self.diags.items.extend(diags)
        self.memo.unused = Unused(declared, tuple(frozenset(k) if k.__class__ is set else k
                                                  for k in key), diags)

    # ---- the diagnostics in segments (for showing.py) ----

    def _mark(self, source=None) -> None:
        """A step's diagnostics start here; `source`: the list it puts there
        whole (the same object as last time while the step is replayed).
        (A block of rules replayed marks itself, and says whether it has an
        error, recheck.IncrementalChecker._rules.)"""
        self._unknown.append(len(self._marks))
        self._marks.append((len(self.diags.items), source))

    def _segments(self) -> list:
        """The diagnostics so far as the steps' runs: the list a step put
        whole, else a new list of what it said."""
        items, marks, out = self.diags.items, self._marks, []
        ends = [m[0] for m in marks[1:]] + [len(items)]
        for (start, source), end in zip(marks, ends):
            if end > start:
                out.append(source if source is not None and len(source) == end - start
                           else items[start:end])
        return out

    def _has_errors(self) -> bool:
        if self.pieces is None:
            return super()._has_errors()
        # (by the steps' runs since the last time asked, but for the blocks
        # of rules replayed, which said whether they have one; a list a step
        # put whole says what it said last time: memo.errors)
        items, marks, unknown = self.diags.items, self._marks, self._unknown
        flags, kept = self.memo.errors, self._error_flags
        at, last = self._errors_upto, len(marks) - 1
        if last >= 0 and (not unknown or unknown[-1] != last):
            unknown.append(last)    # (its run may have grown: a look, as at any other)
        for u in range(at, len(unknown)):
            i = unknown[u]
            start, source = marks[i]
            end = marks[i + 1][0] if i < last else len(items)
            if end <= start:
                continue
            if source is not None and len(source) == end - start:
                flag = flags.get(id(source))
                if flag is None or flag[0] is not source:
                    flag = (source, ERROR in map(_SEVERITY, source))
                kept[id(source)] = flag
                found = flag[1]
            else:
                found = ERROR in map(_SEVERITY, items[start:end])
            if found and i < last:
                self._errors_found = True
            elif found:
                return True         # (in the run still under way: asked again next time)
        self._errors_upto = max(at, len(unknown) - 1)
        return self._errors_found

    def _never_fire(self, out, complete: bool):
        if self.pieces is not None:
            self._mark()
        return super()._never_fire(out, complete)

    def _races(self, out):
        if self.pieces is not None:
            self._mark()
        return super()._races(out)

    def _no_warnings_beside_errors(self):
        """Checker._no_warnings_beside_errors's answer, by the segments: the
        errors and the diagnostics that may be beside one (those with a
        place in a broken statement's entry, or with notes) are found by
        each segment's index (_SegmentIndex, kept while the segment is the
        same list), so that an edit costs the segments it made and the
        diagnostics it reaches, not a look at every diagnostic."""
        if self.pieces is None:
            return super()._no_warnings_beside_errors()
        segments = self.segments = self._segments()
        self.dropped = ()
        self.memo.errors = self._error_flags
        if not self._has_errors():
            return
        old, indexes = self.memo.beside, {}
        at, found = 0, []           # (where each segment starts in the list, its index)
        for seg in segments:
            index = old.get(id(seg))
            if index is None or index.segment is not seg:
                index = _SegmentIndex(seg)
            indexes[id(seg)] = index
            found.append((at, index))
            at += len(seg)
        self.memo.beside = indexes
        holders = {}            # entry id -> its statements' spans, in order

        def holder(span):
            """Checker._no_warnings_beside_errors's: the statement whose start
            is the last at or before the span's, if it holds the span; in
            virtual lines, one of the statements of the span's entry."""
            ident = span.line // VLINE
            spans = holders.get(ident)
            if spans is None:
                piece = self._piece_of(ident)
                spans = holders[ident] = [] if piece is None else [
                    s.span for s in piece.statements
                    if getattr(s, "span", None) is not None and s.span.line // VLINE == ident]
            i = bisect.bisect_right(spans, (span.line, span.column), key=_START) - 1
            if i >= 0 and (span.end_line, span.end_column) <= (spans[i].end_line,
                                                                spans[i].end_column):
                return spans[i]
            return None

        broken = {holder(index.segment[i].span) for _, index in found
                  for i in index.errors} - {None}
        if not broken:
            return
        entries = {span.line // VLINE for span in broken}
        # (only a diagnostic with a place in a broken statement's entry, or
        # with notes, can be beside one)
        items = self.diags.items
        drop = set()
        for start, index in found:
            seg, by_entry = index.segment, index.by_entry
            maybe = set(index.noted)
            for entry in entries:
                maybe.update(by_entry.get(entry, ()))
            for i in maybe:
                d = seg[i]
                if d.severity != ERROR and (holder(d.span) in broken or any(
                        n.span is not None and holder(n.span) in broken for n in d.notes)):
                    drop.add(start + i)
        if drop:
            self.dropped = {id(items[i]) for i in drop}
            # (in place: callers hold the list)
            items[:] = [d for i, d in enumerate(items) if i not in drop]

    def _piece_of(self, ident: int):
        """The piece whose entries include the one of id `ident`."""
        found = self.piece_of(ident) if self.piece_of is not None else None
        if found is not None:
            return found
        for piece in self.pieces:
            if any(e.id == ident for e in piece.entries):
                return piece
        return None

    def _place_of(self, kept: dict):
        """The key that puts entries in file order: by piece, then by
        statement in the piece, then in the statement."""
        where, index = self.range_memo.where, {}

        def place(entry):
            if not index:
                index.update((id(p), i) for i, p in enumerate(self.pieces))
            piece = where[entry.statement]
            return index[id(piece)], kept[id(piece)].order[entry.statement], entry.place
        return place


def _spliced(entries: list, before: list, after: list):
    """`entries` with the run `before` (the same objects, one after the
    other) replaced by `after`; None when `before` is not in it so."""
    first = before[0]
    for at, entry in enumerate(entries):
        if entry is first:
            end = at + len(before)
            if all(map(operator.is_, entries[at:end], before)) and end <= len(entries):
                return entries[:at] + after + entries[end:]
            return None
    return None


class _SegmentIndex:
    """What _no_warnings_beside_errors reads of one segment of diagnostics
    (a list kept while a step is replayed): the places of its errors, of
    those with notes, and of each by the entry its own place is in."""
    __slots__ = ("segment", "errors", "noted", "by_entry")

    def __init__(self, segment: list):
        self.segment = segment
        self.errors = [i for i, d in enumerate(segment) if d.severity == ERROR]
        self.noted = [i for i, d in enumerate(segment) if d.notes]
        by_entry: dict = {}
        for i, d in enumerate(segment):
            by_entry.setdefault(d.span.line // VLINE, []).append(i)
        self.by_entry = by_entry


class FactCounts:
    """The facts of the blocks of rules replayed (recheck.IncrementalChecker._rules),
    counted: for each fact, how many of the blocks have each name, so that
    an edit takes away the blocks it changed and adds the new ones instead
    of uniting every block's; and each fact's names as a frozenset, made
    again only when a name came or went. After the rules, the checker's
    set of a fact is that frozenset (with what other steps found, if any
    is not in it): nothing adds to it after the rules are checked, and
    what would gets an error rather than a memory changed behind it."""

    def __init__(self):
        self.blocks: dict = {}      # id(block) -> block, the ones counted
        self.counts: dict = {}      # fact -> {name: how many blocks have it}
        self.names: dict = {}       # fact -> the set of its counted names, when made
        self.merged: dict = {}      # fact -> (its names, the other steps' more, the union)

    def add(self, checker, replayed: list) -> None:
        """Count `replayed` (and no other block), and add their facts to
        the checker's."""
        now = {id(b): b for b in replayed}
        old = self.blocks
        # (the new blocks first: a name that an edit's new block has as the
        # old one had never goes to none, so its fact's set is kept)
        for new in now.keys() - old.keys():
            self._count(now[new], 1)
        for gone in old.keys() - now.keys():
            self._count(old[gone], -1)
        self.blocks = now
        names = self.names
        for fact, counted in self.counts.items():
            if counted:
                found = names.get(fact)
                if found is None:
                    found = names[fact] = frozenset(counted)
                current = getattr(checker.facts, fact)
                # (the same frozenset as long as no name came or went and what
                # the other steps found is in it, or is what they found last
                # time: no copy, and the unused names' key compares it by
                # identity, _unused)
                if current <= found:
                    setattr(checker.facts, fact, found)
                    continue
                extra = current - found
                last = self.merged.get(fact)
                if last is None or last[0] is not found or last[1] != extra:
                    last = self.merged[fact] = (found, extra, found | extra)
                setattr(checker.facts, fact, last[2])

    def _count(self, block, by: int) -> None:
        for fact, values in block.facts:
            counted = self.counts.setdefault(fact, {})
            for value in values:
                n = counted.get(value, 0) + by
                if n:
                    if n == 1 and by > 0:
                        self.names.pop(fact, None)      # (a name came)
                    counted[value] = n
                else:
                    del counted[value]
                    self.names.pop(fact, None)          # (a name went)
