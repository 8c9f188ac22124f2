"""Checking a document again after an edit, reusing what did not change
(the checker's part of ide/incremental.py, which has the whole story).

Resolving each rule, the expensive part, is replayed (its diagnostics and
the facts the whole-program checks need) when the rule is the same object
and every name it looked up (`_Watched`) still means the same; named
actions are replayed as a whole when no declaration changed; the
variables' intervals (check/ranges.py) and W009 (check/races.py) keep
their own memos here (`_Memo`).
"""
from __future__ import annotations

import itertools
from collections.abc import Sequence
from typing import Optional

from ..check import conditions as cond, modes
from ..check.checker import Checker
from ..check.state import Declarations
from ..check.program import CheckedProgram
from ..check.races import RaceMemo
from ..check.rules import may_never_fire
from ..check.ranges import RangeMemo
from ..diagnostics import ERROR, Diagnostic
from ..syntax import ast
from .passes import _SEVERITY, FactCounts, PiecePasses
from .pieces import PIECE
from .watch import _ALL, _MISSING, _Narrowing, _Watched, watched  # noqa: F401
from .statements import VLINE

# ---- checking, reusing results ----------------------------------------------

class _Memo:
    """What the incremental checker keeps between two analyses."""
    def __init__(self):
        self.env = None
        self.actions = None     # ActionsHit: the result of resolving the named actions
        self.rules: dict = {}   # id(rule node) -> RuleHit
        self.ranges = RangeMemo()   # the variables' intervals by component (check/ranges.py)
        self.races = RaceMemo()     # W009's facts of each rule and its last pairs (check/races.py)
        self.blocks: dict = {}  # id(piece) -> _Block of its rules (IncrementalChecker._rules)
        self.declared = None    # (what declaring read, the state it left, its diagnostics, robot given)
        self.counts = FactCounts()  # the facts of the blocks of rules replayed, counted
        self.unused = None      # (what _unused read, what it said)
        self.errors: dict = {}  # id(a list of diagnostics) -> (it, has an error) (passes.py)
        self.beside: dict = {}  # id(a list of diagnostics) -> passes._SegmentIndex of it


class RuleHit:
    """What checking one rule came to, kept by the rule node's id: the
    node (kept alive, so that its id stays its own), the geometry and the
    names it looked up (watch.py: (table, name, what was found)), its
    result, the diagnostics it said that another step may say too (said
    once for the file) and those within its own statement, its facts
    (Facts.items()), the declarations (env) it was last found valid with,
    and the variables it read (None: it looked at all of them)."""
    __slots__ = ("node", "geo", "lookups", "resolved", "said_once", "facts", "env", "own",
                 "variables")

    def __init__(self, node, geo, lookups, resolved, said_once, facts, env, own, variables):
        self.node, self.geo, self.lookups, self.resolved = node, geo, lookups, resolved
        self.said_once, self.facts, self.env, self.own = said_once, facts, env, own
        self.variables = variables


class ActionsHit:
    """What resolving the named actions came to (kept while no declaration
    changed): the out.actions and action_nodes it gave, the checker's
    resolved bodies, its diagnostics and facts, and the actions' depths
    once spliced (Declarations.action_depths)."""
    __slots__ = ("actions", "nodes", "resolved", "diags", "facts", "depths")

    def __init__(self, actions, nodes, resolved, diags, facts, depths):
        self.actions, self.nodes, self.resolved = actions, nodes, resolved
        self.diags, self.facts, self.depths = diags, facts, depths


# A block of rules is a piece's (ide/pieces.py), which ends after an entry
# whose id is a multiple of this.
BLOCK = PIECE


class _Block:
    """The rules of a piece of the document (ide/pieces.py) replayed at
    once: the piece (kept alive, so that its id stays its own, and with it
    its rules), the declarations (env) they were valid with, and what they
    came to together: their results in order, their own diagnostics in
    order (and whether one is an error), the union of their facts, what
    the whole-program checks read of them (the rules that may never fire
    by event, those in modes, the modes they enter). Only rules whose
    diagnostics are all their own (no diagnostic said once for the file)
    make a block, so replaying it is what replaying each would do."""
    __slots__ = ("piece", "env", "geo", "hits", "_deps", "read", "resolved", "maybe", "own",
                 "error", "facts", "in_modes", "entered")

    def __init__(self, piece, env, geo, hits):
        self.piece, self.env, self.geo, self.hits, self._deps = piece, env, geo, hits, None
        # the variables its rules looked up (None: one looked at all of them)
        read = [h.variables for h in hits]
        self.read = None if None in read else frozenset().union(*read)
        self.resolved = [h.resolved for h in hits if h.resolved is not None]
        self.maybe = by_event(self.resolved)        # (see _never_fire)
        self.in_modes = [r for r in self.resolved if r.mode is not None]
        self.entered = None     # (the named actions, the modes entered), when there are modes
        self.own = [d for h in hits for d in h.own]
        self.error = ERROR in map(_SEVERITY, self.own)
        facts: dict = {}
        for h in hits:
            for f, values in h.facts:
                facts.setdefault(f, set()).update(values)
        self.facts = tuple(facts.items())


    @property
    def deps(self) -> list:
        """Every name its rules looked up, once (what makes it valid again
        when a declaration changed, see _Watched), found when first asked."""
        if self._deps is None:
            self._deps = list({(attr, name, id(found)): (attr, name, found)
                               for h in self.hits for attr, name, found in h.lookups}.values())
        return self._deps


class _Joined(Sequence):
    """The resolved rules of every piece, in order (CheckedProgram.rules
    of an edit's check): the pieces' own lists, joined into one only when
    something asks for a rule by its place. Putting 4,000 rules into a new
    list touched each of them at every keystroke, which the whole-program
    checks do not need: they read the rules by piece."""
    __slots__ = ("_runs", "_all", "_len")

    def __init__(self, runs: list):
        self._runs, self._all, self._len = runs, None, None

    def __len__(self) -> int:
        if self._len is None:
            self._len = sum(map(len, self._runs))
        return self._len

    def __iter__(self):
        return itertools.chain.from_iterable(self._runs)

    def __getitem__(self, at):
        if self._all is None:
            self._all = list(itertools.chain.from_iterable(self._runs))
        return self._all[at]

    def __eq__(self, other):
        if not isinstance(other, (list, _Joined)):
            return NotImplemented
        return list(self) == list(other)

    __hash__ = None

    def __repr__(self) -> str:
        return repr(list(self))


def by_event(resolved: list) -> dict:
    """The rules that may never fire, by event (_never_fire asks for those
    of the events it can warn about)."""
    out: dict = {}
    for r in resolved:
        if may_never_fire(r):
            out.setdefault(r.event.name, []).append(r)
    return out


class IncrementalChecker(PiecePasses, Checker):
    """The checker, with named actions and rules replayed from `memo` when
    nothing they can see has changed."""

    def __init__(self, program, diags, memo: _Memo, pieces=None, piece_of=None, marks=(),
                 **options):
        super().__init__(program, diags, **options)
        self.memo = memo
        self.pieces = pieces        # the document's pieces (ide/pieces.py), in order
        self.piece_of = piece_of    # entry id -> its piece
        # where each step's diagnostics start, and the list it replayed whole
        # (None: made now); the parse's are the pieces' (passes.segments)
        self._marks = list(marks)
        self._unknown = list(range(len(self._marks)))  # (the marks _has_errors looks at)
        self.segments = self.dropped = None
        # (passes._has_errors: the runs looked at, and whether one has an error)
        self._error_flags, self._errors_upto, self._errors_found = {}, 0, False
        self.range_memo = memo.ranges
        self.race_memo = memo.races
        self._known: Optional[set] = None
        self._env_now = None
        self._maybe: list = []      # the rules _never_fire looks at (_rules)
        self._compared: dict = {}   # (table, name, id(found)) -> (found, still the same)
        self._env_before = None     # the last analysis's declarations
        self._moved = None          # the variables whose intervals alone changed since, if so

    def _env(self):
        """Everything a rule or a named action can depend on besides itself:
        the geometry and every name table a rule reads (Declarations.TABLES;
        the variables last; AST nodes compare by identity first, so this is
        cheap when nothing changed)."""
        d = self.decls
        return (d.geo, *(_ENV.get(t, _items)(getattr(d, t)) for t in Declarations.TABLES))

    def _replay(self, diags, facts, own=()):
        """Put a step's diagnostics and facts back. `own`: diagnostics
        within the step's own statement, which no other step can say too
        (their spans are its virtual lines); the others are said once."""
        if own:
            self.diags.items.extend(own)
        if diags:
            known = self._known
            if known is None:
                known = self._known = set(self.diags.items)
            for d in diags:
                # a constant's bad value is reported once, at its first use
                if d not in known:
                    known.add(d)
                    self.diags.items.append(d)
        self.facts.update(facts)

    def _resolve_actions(self, out: CheckedProgram):
        self._mark()
        env = self._env()
        memo = self.memo
        self._env_before = memo.env
        if memo.env != env:
            # (the declarations of the last analysis, some variables' intervals
            # moved: those, ranges.py says which; else any may have changed)
            if not (self._declared_same and self.range_memo.moved is not None
                    and memo.env is not None and env[:-1] == memo.env[:-1]):
                self._moved = None
            else:
                self._moved = self.range_memo.moved
            memo.env, memo.actions = env, None
        self._env_now = memo.env    # the same object as long as nothing changes
        if memo.actions is None:
            with self.apart() as step:
                super()._resolve_actions(out)
            memo.actions = ActionsHit(dict(out.actions), dict(out.action_nodes),
                                      dict(self._resolved_actions), step.diags, step.facts,
                                      dict(self.action_depths))
        hit = memo.actions
        out.actions.update(hit.actions)
        out.action_nodes.update(hit.nodes)
        self._resolved_actions.update(hit.resolved)
        self.action_depths.update(hit.depths)
        self._replay(hit.diags, hit.facts)

    def _still_valid(self, geo, deps) -> bool:
        """Does everything a rule looked up still say the same?"""
        if geo is not self.geo and geo != self.geo:
            return False
        compared = self._compared
        for attr, name, found in deps:
            table = getattr(self.decls, attr)
            if name is _ALL:
                if tuple(table.items()) != found:
                    return False
            else:
                # (rules read the same names: each name against each object
                # it was found as is compared once a check; the object is
                # kept with the answer, so its id cannot be another's)
                key = (attr, name, id(found))
                known = compared.get(key)
                if known is None or known[0] is not found:
                    now = table.get(name, _MISSING)
                    known = compared[key] = (found, now is found or now == found)
                if not known[1]:
                    return False
        return True

    def _guarded_body(self, body, guard):
        table = self.vars
        if guard is None or not body.steps or not isinstance(table, _Watched):
            return super()._guarded_body(body, guard)
        self.vars = _Narrowing(table, cond.names_of(cond.formula(guard)))
        try:
            return super()._guarded_body(body, guard)
        finally:
            self.vars = table

    def _rules(self, out: CheckedProgram):
        """Every rule, a piece of the document at a time (_Block): the rules
        of a piece that is the same object, all valid with the same
        declarations, are replayed with one extend (their facts are
        counted by block, passes.FactCounts); any other piece's are checked
        rule by rule (_rule) and, if they can, kept as a block."""
        if self.pieces is None:
            return super()._rules(out)
        memo = self.memo
        old, blocks = memo.blocks, {}
        env, before, moved = self._env_now, self._env_before, self._moved
        items = self.diags.items
        runs = []               # (the resolved rules, by piece: out.rules, _Joined)
        maybe = self._maybe = []            # (dicts of by_event, none empty)
        in_modes = self._in_modes = []      # (lists of rules, none empty)
        groups = self.rule_groups = []      # (W009's, check/races.py)
        replayed, loose = [], []
        for piece in self.pieces:
            run = piece.rules
            if not run:
                continue
            block = old.get(id(piece))
            same = block is not None and block.piece is piece
            if same and block.env is not env and (
                    (moved is not None and block.env is before and block.read is not None
                     and block.read.isdisjoint(moved))       # (only intervals it does not read moved)
                    or self._still_valid(block.geo, block.deps)):
                block.env = env             # (its rules' own, when they are checked again: _rule)
            if not same or block.env is not env:
                self._mark()
                checked = []
                for rule in run:
                    r = self._rule(rule)
                    if r is not None:
                        checked.append(r)
                block = self._block(piece, env)
                if block is None:
                    runs.append(checked)
                    loose += checked
                    found = by_event(checked)
                    if found:
                        maybe.append(found)
                    found = [r for r in checked if r.mode is not None]
                    if found:
                        in_modes.append(found)
                    groups.append((None, checked))
                    continue
            else:
                self._marks.append((len(items), block.own))     # (see PiecePasses._mark)
                if block.error:
                    self._errors_found = True
                items.extend(block.own)
                replayed.append(block)
            runs.append(block.resolved)
            if block.maybe:         # (those of the blocks that have some, in order)
                maybe.append(block.maybe)
            if block.in_modes:
                in_modes.append(block.in_modes)
            groups.append((block, block.resolved))
            blocks[id(piece)] = block
        memo.blocks = blocks
        out.rules = _Joined(runs)
        self._loose = loose
        memo.counts.add(self, replayed)

    def _may_never_fire(self, out: CheckedProgram, events: set):
        if self.pieces is None:
            return super()._may_never_fire(out, events)
        return [r for by in self._maybe for event in events for r in by.get(event, ())]

    def _modes_program(self, out: CheckedProgram, complete: bool):
        if self.pieces is None:
            return super()._modes_program(out, complete)
        self._mark()

        def entered():          # (by block, kept: its rules' bodies are the same)
            found, actions = set(), self.memo.actions
            for block in self.memo.blocks.values():
                if block.entered is None or block.entered[0] is not actions:
                    block.entered = (actions, modes.entered_by(self, [r.body for r in
                                                                      block.resolved]))
                found |= block.entered[1]
            return found | modes.entered_by(self, [r.body for r in self._loose])
        modes.check_program(self, out, complete,
                            list(itertools.chain.from_iterable(self._in_modes)), entered)

    def _block(self, piece, env) -> Optional[_Block]:
        """The rules of `piece`, just checked or replayed, as a block, if each
        can be replayed with the rest (see _Block)."""
        run = piece.rules
        hits = [self.memo.rules.get(id(rule)) for rule in run]
        geo, same_geo = self.geo, set()
        for rule, hit in zip(run, hits):
            if hit is None or hit.node is not rule or hit.env is not env or hit.said_once:
                return None
            if hit.geo is not geo and id(hit.geo) not in same_geo:
                if hit.geo != geo:      # (each check has its own Geometry object)
                    return None
                same_geo.add(id(hit.geo))
        return _Block(piece, env, geo, hits)

    def _rule(self, rule: ast.Rule):
        hit = self.memo.rules.get(id(rule))
        env = self._env_now
        if hit is not None and hit.node is rule and hit.env is env and not hit.said_once:
            if hit.own:         # (the common case, inline: most rules are replayed)
                self.diags.items.extend(hit.own)
            self.facts.update(hit.facts)
            return hit.resolved
        if hit is None or hit.node is not rule:
            hit = None
        elif hit.env is not env:
            moved = self._moved
            if moved is not None and hit.env is self._env_before and hit.variables is not None \
                    and hit.variables.isdisjoint(moved):
                hit.env = env       # (only intervals it does not read moved)
            elif self._still_valid(hit.geo, hit.lookups):
                hit.env = env
            else:
                hit = None
        if hit is None:
            deps = []
            with self.apart(watched(self.decls, deps)) as step:
                resolved = super()._rule(rule)
            ident = rule.span.line // VLINE
            own = [d for d in step.diags if ident and _within(d, ident)]
            shared = [d for d in step.diags if not (ident and _within(d, ident))]
            hit = RuleHit(rule, self.geo, deps, resolved, shared, step.facts, env, own,
                          _variables_read(deps))
            self.memo.rules[id(rule)] = hit
        self._replay(hit.said_once, hit.facts, hit.own)
        return hit.resolved


def _items(table) -> tuple:
    return tuple(table.items())


# what of a table the environment compares, where it is not every entry
_ENV = {"externs": lambda t: tuple((n, e.kind, e.params, e.node) for n, e in t.items()),
        "rule_names": tuple}


def _variables_read(deps) -> Optional[frozenset]:
    """The variables a rule looked up (None: it looked at all of them)."""
    names = set()
    for attr, name, _ in deps:
        if attr == "vars":
            if name is _ALL:
                return None
            names.add(name)
    return frozenset(names)


def _within(d: Diagnostic, ident: int) -> bool:
    """Whether every place `d` names is in statement `ident` (virtual lines)."""
    return all(span.line // VLINE == ident and span.end_line // VLINE == ident
               for span in (d.span, *(n.span for n in d.notes if n.span),
                            *(f.span for f in d.fixes)))
