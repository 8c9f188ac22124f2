"""W009's report: the pairs of rules of one priority that can command the
motors in the same poll (found by arbitration.py), each named, with the
fix that fits it; in a big program, by kinds of rules, every rule listed."""
from __future__ import annotations

import itertools

from ..diagnostics import Note
from .arbitration import (describe, head_text, _is_enter, _code, _Rules, _racing_pairs, EXPAND_RULES,
                          PAIR_BUDGET, _events_that_never_occur, _early, RuleFacts,
                          timing_allows)
from . import conditions as cond
from .messages import _shown

MAX_REPORTS = 10


class RaceMemo:
    """W009 kept between two analyses of one document (the language
    server's, ide/incremental.py): each rule's facts (while the named
    actions are the same), what each group of rules (a piece of the
    document, ide/pieces.py) gives the pair analysis, and the last pair
    analysis with what it was computed from: the motor rules' facts' keys
    in order, the intervals their conditions read, which events never
    occur, whether an entry stops, and, if the pairs asked in what order
    rules write variables, the order of the rules that write and those
    that command the motors. An edit that leaves those the same (a rule
    that commands no motor, a changed number in an action, a rule taken
    out that writes nothing a motor rule reads) reuses the pairs; any
    other computes them again. Where every group of one priority with two
    rules or more is so big that it is compared by timing alone, the
    pairs come from each run's kinds instead (_by_timing, which looks at
    each run, not at each rule), and the warnings are the last ones while
    the runs' motor rules are the same objects."""
    def __init__(self):
        self.env = None
        self.named: dict = {}       # named action -> whether it commands the motors
        self.rules: dict = {}       # id(ResolvedRule) -> (rule, RuleFacts)
        self.groups: dict = {}      # id(group's owner) -> _Group
        self.read = None            # (the motor rules' keys, the names their conditions read)
        self.pairs = None           # (key, walked, order, pairs, blocks, by_timing_only)
        self.said = ()              # (what the last warnings were made from, them, the rules)
        self.kinds: dict = {}       # id(first rule of a kind) -> (it, key, its warning, rules)


class _Group:
    """What W009 reads of a run of consecutive rules, computed once while
    the run is the same (its `owner` kept alive): each rule's facts, what
    tells whether an entry stops the motors, and, by the events that never
    occur, its motor rules (their keys, the names their conditions read,
    their kinds by priority, their ids) and the order of its rules that
    write or command the motors."""
    __slots__ = ("owner", "rules", "facts", "id_facts", "moves_outside", "enters",
                 "entry_moves", "stops", "by_never")

    def __init__(self, owner, rules, checker, memo: RaceMemo):
        known, named = memo.rules, memo.named
        facts = []
        for r in rules:
            hit = known.get(id(r))
            if hit is None or hit[0] is not r:
                hit = known[id(r)] = (r, RuleFacts(checker, r, named))
            facts.append(hit[1])
        self.owner, self.rules, self.facts = owner, rules, facts
        self.id_facts = [(id(r), f) for r, f in zip(rules, facts)]
        self.moves_outside = any(f.moves_outside for f in facts)
        self.enters = any(f.enters for f in facts)
        self.entry_moves = {r.mode for r, f in zip(rules, facts) if f.entry_moves}
        # (its rules that stop: whether one is not an `on enter`, and the others)
        stops = [r for r, f in zip(rules, facts) if f.stops]
        self.stops = (any(not _is_enter(r) for r in stops), [r for r in stops if _is_enter(r)])
        self.by_never: dict = {}

    def motor(self, never: frozenset) -> tuple:
        """(the motor rules but those whose event never occurs, their keys,
        the names their conditions read, (is motor, key) of each rule that
        writes or commands the motors, their ids, the motor rules' _Kinds
        by priority, their ids)."""
        found = self.by_never.get(never)
        if found is None:
            rules, keys, names, order, ids = [], [], set(), [], []
            kinds: dict = {}        # priority -> _Kinds of its motor rules here
            for r, f in zip(self.rules, self.facts):
                motor = f.motor and not (r.event.kind == "standard" and r.event.name in never)
                if motor:
                    rules.append(r)
                    keys.append(f.key)
                    names.update(f.names)
                    at = kinds.get(r.priority)
                    if at is None:
                        at = kinds[r.priority] = _Kinds()
                    at.add(r, f)
                if motor or f.writes:
                    order.append((motor, f.key))
                    ids.append(id(r))
            found = self.by_never[never] = (rules, tuple(keys), frozenset(names), tuple(order),
                                            tuple(ids), kinds, tuple(map(id, rules)))
        return found


class _Kinds:
    """What the pairs of a big group of one priority (arbitration's
    _racing_blocks) read of some of its motor rules, in file order, when
    it compares them by timing alone: the rules by timing shape; and how
    many kinds they surely make when compared by condition (a rule whose
    condition has clauses is a kind of its own; the others, at least one a
    shape), which decides that it does."""
    __slots__ = ("rules", "by_shape", "own", "shapes")

    def __init__(self):
        self.rules: list = []
        self.by_shape: dict = {}    # timing shape -> its rules, in order
        self.own = 0                # rules that are surely kinds of their own
        self.shapes: dict = {}      # (whether true, shape) of the others

    def add(self, rule, facts) -> None:
        self.rules.append(rule)
        found = self.by_shape.get(facts.shape)
        if found is None:
            self.by_shape[facts.shape] = [rule]
        else:
            found.append(rule)
        true = facts.condition is cond.TRUE
        if not true and cond._clauses(facts.condition) is not None:
            self.own += 1
        else:
            self.shapes[(true, facts.shape)] = None

    def join(self, other: "_Kinds") -> None:
        self.rules += other.rules
        for shape, rules in other.by_shape.items():
            found = self.by_shape.get(shape)
            if found is None:
                self.by_shape[shape] = list(rules)
            else:
                found += rules
        self.own += other.own
        self.shapes.update(other.shapes)


def _groups(checker, rules, groups, memo: RaceMemo) -> list:
    """The _Group of each (owner, rules) of `groups` (None: all the rules,
    one group), from `memo` where the owner is the same."""
    env = tuple(checker._resolved_actions.items())
    if memo.env != env:
        memo.env, memo.named, memo.rules, memo.groups = env, {}, {}, {}
    old, out, kept = memo.groups, [], {}
    for owner, run in groups if groups is not None else ((None, rules),):
        group = old.get(id(owner)) if owner is not None else None
        if group is None or group.owner is not owner:
            group = _Group(owner, run, checker, memo)
        if owner is not None:
            kept[id(owner)] = group
        out.append(group)
    memo.groups = kept
    if len(memo.rules) > 2 * len(rules) + 100:
        live = {i for g in out for i, _ in g.id_facts}
        memo.rules = {k: v for k, v in memo.rules.items() if k in live}
    return out


def _entry_stops(checker, groups: list) -> bool:
    """arbitration.entry_stops, from the groups' parts."""
    if any(e.kind == "action" for e in checker.externs.values()):
        return False
    if any(g.moves_outside for g in groups):
        return False
    if not any(g.enters for g in groups):
        return True
    if any(g.stops[0] for g in groups):
        return False
    entry_moves = set().union(*(g.entry_moves for g in groups))
    return not any(r.mode in entry_moves for g in groups for r in g.stops[1])


def check_program(checker, out, groups=None) -> None:
    """W009 over `out.rules`; `groups`: them as (owner, rules) runs, in
    order, each the same while its owner is (the language server's)."""
    memo = getattr(checker, "race_memo", None) or RaceMemo()
    never = frozenset(_events_that_never_occur(checker))
    rules = out.rules
    found_groups = _groups(checker, rules, groups, memo)
    motors = [g.motor(never) for g in found_groups]
    if sum(len(m[0]) for m in motors) < 2:
        return
    stops = _entry_stops(checker, found_groups)
    # big groups compared by timing alone: their pairs from the runs' kinds,
    # and the warnings the last ones while the runs' motor rules are the
    # same objects (their ids, by run: memo.said keeps them alive)
    said_from = ("by timing", stops, tuple(m[6] for m in motors))
    if memo.said and memo.said[0] == said_from:
        checker.diags.items.extend(memo.said[1])
        return
    motor_rules = list(itertools.chain.from_iterable(m[0] for m in motors))
    fast = _by_timing(motors, stops)
    if fast is not None:
        blocks, by_timing_only = fast
        return _said(checker, memo, said_from, [], blocks, None, by_timing_only, motor_rules,
                     rules)
    motor_keys = tuple(itertools.chain.from_iterable(m[1] for m in motors))
    if memo.read is None or memo.read[0] != motor_keys:
        memo.read = (motor_keys, sorted(frozenset().union(*(m[2] for m in motors))))
    key = (never, stops, motor_keys, tuple(map(checker.vars.get, memo.read[1])))
    found = None

    def every_rule():
        return _Rules(checker, motor_rules, rules,
                      dict(itertools.chain.from_iterable(g.id_facts for g in found_groups)),
                      stops=stops)
    last = memo.pairs
    if last is None or last[0] != key or (last[1] and last[2] != tuple(
            itertools.chain.from_iterable(m[3] for m in motors))):
        found = every_rule()
        pairs, blocks = _pairs(motor_rules, found)
        at = {id(r): i for i, r in enumerate(motor_rules)}
        walked = found._walk is not None        # (the pairs read the order of the writes)
        order = tuple(itertools.chain.from_iterable(m[3] for m in motors)) if walked else None
        last = memo.pairs = (key, walked, order, [(at[id(a)], at[id(b)]) for a, b in pairs],
                             [_block(at, *block) for block in blocks], found.by_timing_only)
    by_timing_only = last[5]
    # what the warnings say depends on the rules they name (and, for the
    # pairs' help, on the rules that write): the same pairs of the same
    # objects say the same (by their ids: memo.said keeps the rules alive)
    said_from = (last, tuple(map(id, motor_rules)),
                 tuple(itertools.chain.from_iterable(m[4] for m in motors)) if last[3] else ())
    if memo.said and memo.said[0][0] is last and memo.said[0][1:] == said_from[1:]:
        checker.diags.items.extend(memo.said[1])
        return
    if found is None:
        pairs = [(motor_rules[a], motor_rules[b]) for a, b in last[3]]
        blocks = [_block(motor_rules, *block) for block in last[4]]
    _said(checker, memo, said_from, pairs, blocks, found if found is not None else every_rule
          if pairs else None, by_timing_only, motor_rules, rules)


def _said(checker, memo: RaceMemo, said_from: tuple, pairs, blocks, found, by_timing_only,
          motor_rules, rules) -> None:
    """The warnings of the pairs and blocks: the last ones when they were
    made from the same (`said_from`), else made (`found`: the _Rules, or
    what makes them; None: only the motor rules' order is read)."""
    diags = checker.diags
    if memo.said and memo.said[0] == said_from:
        diags.items.extend(memo.said[1])
        return
    if callable(found):
        found = found()
    if found is None:
        found = _MotorOrder(motor_rules)
    found.by_timing_only = by_timing_only
    first = len(diags.items)
    _report(checker, pairs, blocks, found, memo)
    said = diags.items[first:]
    if memo.said and said == list(memo.said[1]):
        diags.items[first:] = memo.said[1]  # the same objects: what caches them keeps them
    memo.said = (said_from, tuple(diags.items[first:]), rules, motor_rules)


def _by_timing(motors: list, stops: bool):
    """(blocks, whether a group was compared by timing alone) as _pairs
    finds them (with no pairs), from the runs' kinds (_Kinds)
    without a look at each motor rule, when every group of one priority
    with two rules or more is big and surely compared by timing alone (a
    small group's pairs are found one by one and kept: the full path);
    None otherwise."""
    by_priority: dict = {}
    for m in motors:
        for priority, kinds in m[5].items():
            found = by_priority.get(priority)
            if found is None:
                found = by_priority[priority] = _Kinds()
            found.join(kinds)
    blocks, by_timing = [], False
    for kinds in by_priority.values():
        if len(kinds.rules) <= EXPAND_RULES:
            if len(kinds.rules) > 1:
                return None     # (its pairs one by one: kept by the full path's memo)
            continue
        # at least as many kinds as _racing_blocks would make (a rule whose
        # condition has clauses has boxes of its own), and when their pairs
        # are surely more than the budget, it compares by timing alone
        n = kinds.own + len(kinds.shapes)
        if n * (n + 1) // 2 <= PAIR_BUDGET:
            return None
        found = _timing_blocks(kinds, stops)
        if found is None:
            return None
        blocks += found
        by_timing = True
    return blocks, by_timing


def _timing_blocks(kinds: _Kinds, stops: bool):
    """_racing_blocks of a big group compared by timing alone: a kind a
    timing shape (in the order they come), its first rule standing for its
    pairs; None where the order decides (pair by pair: the full path)."""
    order = list(kinds.by_shape.items())
    timing: dict = {}
    blocks = []
    for x, (sx, xs) in enumerate(order):
        for sy, ys in order[x:]:
            a, b = xs[0], ys[0]
            if sx == sy:
                if len(xs) < 2:
                    continue
                b = xs[1]
            ab = timing.get((sx, sy))
            if ab is None:
                ab = timing[sx, sy] = timing_allows(a, b, stops)
            ba = ab if sx == sy else timing.get((sy, sx))
            if ba is None:
                ba = timing[sy, sx] = timing_allows(b, a, stops)
            if ab and ba:
                blocks.append((a, b, xs, ys))
            elif ab or ba:
                return None
    return blocks


def _block(to, a, b, xs, ys) -> tuple:
    """A block of rules as indices (`to`: id(rule) -> index), or back
    (`to`: the rules); a kind with itself is one list, as found."""
    if isinstance(to, dict):
        a, b, xs2 = to[id(a)], to[id(b)], [to[id(r)] for r in xs]
        ys2 = xs2 if ys is xs else [to[id(r)] for r in ys]
    else:
        a, b, xs2 = to[a], to[b], [to[i] for i in xs]
        ys2 = xs2 if ys is xs else [to[i] for i in ys]
    return a, b, xs2, ys2


def _pairs(motor_rules, facts: _Rules) -> tuple:
    """The racing pairs of small groups and the blocks of big ones."""
    by_priority: dict = {}
    for r in motor_rules:
        by_priority.setdefault(r.priority, []).append(r)
    pairs, blocks = [], []
    for group in by_priority.values():
        found = _racing_pairs(group, facts)
        if len(group) > EXPAND_RULES:
            blocks += found
        else:
            pairs += found
    return pairs, blocks


class _MotorOrder:
    """What the warnings of big groups read of _Rules: the rules' order."""
    def __init__(self, rules: list):
        self.index = {id(r): i for i, r in enumerate(rules)}
        self.by_timing_only = False


def _report(checker, pairs, blocks, facts: _Rules, memo=None) -> None:
    if blocks:              # a big program: the pairs by kinds of rules
        _report_blocks(checker, blocks, facts, memo)
    pairs.sort(key=lambda p: (facts.index[id(p[0])], facts.index[id(p[1])]))
    for loser, winner in pairs[:MAX_REPORTS]:
        if facts.key(winner) < facts.key(loser):
            loser, winner = winner, loser
        checker.diags.warning(
            "W009", loser.node.event.span,
            f"{describe(loser)} and {describe(winner)} can fire in the same poll, both "
            f"command the motors and have the same priority ({loser.priority}): "
            f"{describe(winner)} runs later and wins",
            help=_help(loser, winner, facts), notes=[_note(winner)])
    rest = pairs[MAX_REPORTS:]
    if rest:
        partners: dict = {}             # each rule with the later ones it races with
        for a, b in rest:
            partners.setdefault(id(a), (a, []))[1].append(b)
        listed = "; ".join(f"{describe(a)} with {_list(others)}"
                           for a, others in partners.values())
        checker.diags.warning(
            "W009", rest[0][0].node.event.span,
            f"{len(rest)} more pair{'s' if len(rest) > 1 else ''} of rules of the same "
            f"priority can fire in the same poll and command the motors: {listed}",
            help="give the rules that should win higher priorities, or guards that "
                 "exclude each other")


def _report_blocks(checker, blocks, facts: _Rules, memo=None) -> None:
    """W009 for a big group: one warning a kind of rules (rules alike in
    timing and condition), naming every rule it races with (lines as
    ranges). With `memo` (RaceMemo), a kind's warning is the last one while
    its rules and those it races with are the same objects."""
    last, kept = (memo.kinds if memo is not None else {}), {}
    kinds: dict = {}        # id(first rule of a kind) -> [rule, its kind, others, among itself]
    for a, b, xs, ys in blocks:
        entry = kinds.setdefault(id(a), [a, xs, [], False])
        if xs is ys:
            entry[3] = True
        else:
            entry[2].extend(ys)
    for a, xs, others, itself in sorted(kinds.values(), key=lambda e: facts.index[id(e[0])]):
        key = (tuple(map(id, xs)), tuple(map(id, others)), itself, facts.by_timing_only)
        said = last.get(id(a))
        if said is not None and said[0] is a and said[1] == key:
            checker.diags.items.append(said[2])
            kept[id(a)] = said
            continue
        who = describe(a) if len(xs) == 1 else \
            f"the {len(xs)} rules like {_code(head_text(a))} ({_compact(xs)})"
        races = (["each other"] if itself else []) + ([_compact(others)] if others else [])
        checker.diags.warning(
            "W009", a.node.event.span,
            f"{who} can fire in the same poll as {' and as '.join(races)}, command the motors "
            f"and have the same priority ({a.priority})",
            help="give the rules that should win higher priorities, or guards that exclude "
                 "each other" + (
                     f" (this program has so many rules of priority {a.priority} that command "
                     f"the motors that they were compared by their timing only, not by their "
                     f"conditions)" if facts.by_timing_only else ""))
        kept[id(a)] = (a, key, checker.diags.items[-1], xs, others)
    if memo is not None:
        memo.kinds = kept


def _compact(rules) -> str:
    """Rules by name, and the others by their lines (`lines 3, 4, 12`),
    each line once. (Not as ranges: the language server makes the lines a
    message names real one by one, ide/incremental.py.)"""
    names = [f"rule {_code(r.name)}" for r in rules if r.name is not None]
    lines = sorted({r.node.span.line for r in rules if r.name is None})
    if lines:
        names.append(f"line{'s' if len(lines) > 1 else ''} {', '.join(map(str, lines))}")
    return ", ".join(names)


def _help(loser, winner, facts: _Rules) -> str:
    """The fix that fits the pair."""
    priority = (f"give the rule that should win a higher priority "
                f"(`... priority {loser.priority + 1} do ...`)")
    fa, fb = facts.condition[id(loser)], facts.condition[id(winner)]
    if fa == fb and _same_event(loser, winner) and loser.node.guard is None \
            and winner.node.guard is None:
        return (f"both fire on the same event: {priority}, give one a guard that excludes the "
                f"other (`if ...`), or merge them into one rule")
    shared = cond.names_of(fa) & cond.names_of(fb)
    unstable = facts.changing(loser, winner, shared)
    if shared - unstable:
        stable = cond.conjoin(cond.without(fa, unstable), cond.without(fb, unstable))
        where = cond.overlap(stable, facts.base) or {}
        spots = [f"{_code(n)} is {_span(*where[n])}" for n in sorted(shared - unstable)
                 if n in where]
        if spots:
            return (f"their conditions hold together where {', '.join(spots)}: make them "
                    f"exclude each other (e.g. `>` in one and `<=` in the other), or "
                    f"{priority}")
    if unstable:
        writers = [r for r in facts.rules if facts.writes(r) & unstable
                   and facts.key(r) < max(facts.key(loser), facts.key(winner))
                   and (facts.key(r) >= facts.key(loser) or _early(loser) or _early(winner))]
        names = ", ".join(sorted(_code(n) for n in unstable))
        them = "it" if len(unstable) == 1 else "them"
        why = (f"their conditions on {names} would exclude each other, but "
               f"{describe(writers[0])} changes {them} in the poll before {describe(winner)} "
               f"reads {them}")
        if writers == [loser] and not (facts.writes(winner) & unstable) \
                and not _is_enter(loser) and not _is_enter(winner):
            return (f"{why}: move {describe(winner)} above {describe(loser)} in the file, so "
                    f"that it reads {them} first, or {priority}")
        return f"{why}: {priority}"
    return priority


def _same_event(a, b) -> bool:
    ea, eb = a.event, b.event
    if "when" in (ea.name, eb.name):    # conditions compare by their text
        return ea.name == eb.name and \
            _shown(ea.node.args[0].value) == _shown(eb.node.args[0].value)
    return (ea.kind, ea.name, ea.values, ea.conditions) == (eb.kind, eb.name, eb.values,
                                                            eb.conditions)


def _list(rules) -> str:
    """rule `avoid`, rule `wander`, the rules of lines 9, 12: rules in a
    long list, by name, else by line."""
    parts = [f"rule {_code(r.name)}" for r in rules if r.name is not None]
    lines = [str(r.node.span.line) for r in rules if r.name is None]
    if lines:
        parts.append(f"the rule{'s' if len(lines) > 1 else ''} of line"
                     f"{'s' if len(lines) > 1 else ''} {', '.join(lines)}")
    return ", ".join(parts)


def _span(lo: int, hi: int) -> str:
    return str(lo) if lo == hi else f"{lo}..{hi}"


def _note(rule):
    return Note(f"{describe(rule)} is here", rule.node.span)
