"""Whole-program arbitration check [W009]: two rules of the same priority
that can fire in the same poll and both command the motors.

Within a poll the runtime runs the actions of the events that occurred
highest priority first, then in file order (docs/runtime.md); the poll
after a mode's entry starts with its `on enter` rules. Between two rules
of one priority nothing arbitrates: both run, and the motor command of the
later one replaces the earlier one's, silently. That is the bug priorities
exist to prevent, so the checker names both rules and the one that wins.

Two rules are reported unless it is certain that they cannot fire in the
same poll (the reasoning must never drop a pair that can meet):
- they belong to two different modes (one mode is current at a time, and
  after `enter` no mode's rule fires in the rest of that poll);
- timing: a one-shot `immediate` outside modes fires at the first poll
  only, where no `stop_motor`, `timer`, `sensor`, `every` or `after` event
  can occur; `timer` rules outside modes whose firings (one-shot at T,
  repeat at the multiples of T, of one timer) never meet, and likewise
  `every` and `after` rules both outside modes or both of one mode (their
  own timers, armed at the first poll, or at the mode's entry); in one mode, its `on enter` rules and its one-shot
  `immediate` rules fire in the first poll after an entry, where its
  `every` and `after` rules are (re-)armed and fire one period later at the
  soonest; in one mode, an `on enter` whose first step runs `set_timer`
  and a later `timer` rule (polled after the timer restarted);
- in one mode, its `on enter` and a `stop_motor` rule, when nothing can end
  a motion at an entry: entering stops the motion of the mode left without
  an event, so only a motion of a rule outside modes (or an extern action),
  or a `stop_motor`/`set_speed` run before an `enter` in the same poll,
  could give one;
- conditions: the event's condition (a `when` condition; a `sensor`
  event's `irN > T` list, any of which) and the guard of each rule are read
  as comparisons of variables and readings with numbers
  (check/conditions.py); if no values satisfy both rules' together, they
  cannot both fire. The readings are read once per poll; a variable counts
  only if no rule whose action can run in the poll before the later of
  the two is evaluated assigns it.
A rule "commands the motors" when its action, through the named actions it
uses, calls a motor action (`start_straight`, `start_curve`, `stop_motor`,
`set_speed`); extern actions are not looked into.
"""
from __future__ import annotations

import bisect

from ..stdlib.table import MOTION_ACTIONS, MOTOR_ACTIONS, STANDARD_READINGS
from ..syntax import ast
from . import conditions as cond
from .messages import _shown
from .modes import flat_steps, may_run

# Pairs reported one by one; the rest are listed, every one, in one more
# warning: a file of hundreds of racing rules needs one fix, not thousands
# of warnings, but each pair is named.
# above this many racing candidates of one priority, pairs are found by kinds of rules
EXPAND_RULES = 40
# above this many pairs of kinds of rules, a big group is compared by timing alone
PAIR_BUDGET = 3000
# Motor actions that can end a motion without starting one.
_STOPPING = MOTOR_ACTIONS - MOTION_ACTIONS


def _code(text: str) -> str:
    return f"`{text}`"


def _commands_motors(checker, steps, named: dict) -> bool:
    """Whether `steps` call a motor action, themselves or through the named
    actions they use; `named` memoises the answer of each named action
    (from its steps spliced as lowering splices them)."""
    for step in steps:
        for call in step:
            kind = call.kind
            if kind == "standard":
                if call.name in MOTOR_ACTIONS:
                    return True
            elif kind == "if":              # any branch may run
                if any(c.kind == "standard" and c.name in MOTOR_ACTIONS
                       for c in may_run(checker, [call])):
                    return True
            elif kind == "named":
                found = named.get(call.name)
                if found is None:
                    found = named[call.name] = any(
                        c.kind == "standard" and c.name in MOTOR_ACTIONS
                        for spliced in flat_steps(checker, [[call]])
                        for c in may_run(checker, spliced))
                if found:
                    return True
    return False


def _periods_meet(va: dict, every_a: bool, vb: dict, every_b: bool) -> bool:
    """Whether an `every`/`after` rule and another, armed at the same poll,
    can fire at the same time."""
    ta, tb = va.get("period", va.get("delay")), vb.get("period", vb.get("delay"))
    if every_a and every_b:
        return True                     # at the least common multiple
    if not every_a and not every_b:
        return ta == tb
    period, once = (ta, tb) if every_a else (tb, ta)
    return once % period == 0


def _timer_meets(a, b) -> bool:
    """Whether timer rules a, b (outside modes) can fire at the same time."""
    ta, tb = a.event.values["time"], b.event.values["time"]
    if a.repeat and b.repeat:
        return True                     # at the least common multiple
    if not a.repeat and not b.repeat:
        return ta == tb
    every, once = (ta, tb) if a.repeat else (tb, ta)
    return once % every == 0


def _at_first_poll_only(rule) -> bool:
    """A one-shot `immediate` rule outside modes."""
    return rule.event.name == "immediate" and not rule.repeat and rule.mode is None


def _at_entry_only(rule) -> bool:
    """A rule of a mode that fires only in the first poll after its entry:
    `on enter`, or a one-shot `immediate` (both re-armed by each entry)."""
    return rule.mode is not None and rule.event.kind == "standard" and (
        rule.event.name == "enter" or (rule.event.name == "immediate" and not rule.repeat))


def timing_allows(a, b, entry_stops: bool = True) -> bool:
    """Whether the events of a and b (their modes and timing) allow them to
    fire in the same poll; `entry_stops`: nothing can give a `stop_motor`
    event in the poll after a mode's entry."""
    ma, mb = a.mode, b.mode
    if ma is not None and mb is not None and ma != mb:
        return False
    ea, eb = a.event, b.event
    if ea.kind != "standard" or eb.kind != "standard":
        return True
    na, nb = ea.name, eb.name
    # (stop_motor and timer events cannot occur at the first poll, nor
    # can `every` and `after`, which count from it, nor a sensor event: the
    # sensors are off at start, and read from the poll after start_sensor)
    later = ("stop_motor", "timer", "every", "after", "sensor")
    if (nb in later and _at_first_poll_only(a)) or (na in later and _at_first_poll_only(b)):
        return False
    if na == "timer" and nb == "timer" and ma is None and mb is None:
        return _timer_meets(a, b)
    own = ("every", "after")
    if na in own and nb in own and ma == mb:
        # both timers start at the same poll (the first one, or their mode's
        # entry, when every rule of the mode is armed): they meet as one
        # timer's would
        return _periods_meet(ea.values, na == "every", eb.values, nb == "every")
    if ma is not None and ma == mb:
        for first, second in ((a, b), (b, a)):
            if _at_entry_only(first) and second.event.name in own:
                return False            # armed at the entry, fires a period later
            if first.event.name != "enter":
                continue
            if second.event.name == "stop_motor" and entry_stops:
                return False
            if second.event.name == "timer" and second is b and _sets_timer_first(first):
                return False
    return True


def _sets_timer_first(rule) -> bool:
    """The rule's first step runs `set_timer` itself."""
    return any(c.kind == "standard" and c.name == "set_timer" for c in rule.body[0]) \
        if rule.body else False


def condition_of(rule) -> tuple:
    """What must hold when the rule fires: its event's condition and its
    guard, as a formula (check/conditions.py)."""
    parts = []
    event = rule.event
    if event.kind == "standard" and event.name == "when":
        parts.append(cond.formula(event.values["condition"]))
    elif event.kind == "standard" and event.name == "sensor" and event.conditions:
        parts.append(("or", tuple(("atom", f"ir{index}", op, threshold)
                                  for index, op, threshold in event.conditions)))
    if rule.guard is not None:
        parts.append(cond.formula(rule.guard))
    return cond.conjoin(*parts) if parts else cond.TRUE


def describe(rule) -> str:
    """rule `avoid`, or `on enter if y > 0` (line 12): a rule without a
    name is its head as written, and its line."""
    if rule.name is not None:
        return f"rule {_code(rule.name)}"
    return f"{_code(head_text(rule))} (line {rule.node.span.line})"


def head_text(rule) -> str:
    """`on sensor(ir0 > 500) repeat if n < 3`: a rule's head, in the
    formatter's layout."""
    node = rule.node
    text = ("on " if node.trigger == "on" else "") + event_text(node.event)
    if node.repeat:
        text += " repeat"
    if node.guard is not None:
        text += f" if {_shown(node.guard)}"
    return text


def event_text(call) -> str:
    """An event as written, in the formatter's layout."""
    if call.name.name in ("when", "every", "after"):     # a rule head: `when COND`
        return f"{call.name.name} {_shown(call.args[0].value)}"
    if call.args is None:
        return call.name.name
    args = []
    for arg in call.args:
        if isinstance(arg, ast.NamedArg):
            args.append(f"{arg.name.name}: {_shown(arg.value)}")
        elif isinstance(arg, ast.ConditionArg):
            args.append(f"{arg.sensor.name} {arg.op} {_shown(arg.value)}")
        else:
            args.append(_shown(arg.value))
    return f"{call.name.name}({', '.join(args)})"


def _events_that_never_occur(checker) -> set:
    """The standard events of the rules W001..W003 report: they race with
    nothing."""
    never = set()
    if "start_sensor" not in checker.called:
        never.add("sensor")
    if "set_timer" not in checker.called:
        never.add("timer")
    if not (checker.called & MOTION_ACTIONS) and not any(
            e.kind == "action" for e in checker.externs.values()):
        never.add("stop_motor")
    return never


class RuleFacts:
    """What W009 reads of one resolved rule (through the named actions it
    uses), computed once per rule; the language server keeps them between
    edits while the named actions are the same (races.RaceMemo)."""
    __slots__ = ("writes", "motor", "moves_outside", "enters", "entry_moves", "stops",
                 "condition", "names", "shape", "key", "pair")

    def __init__(self, checker, rule, named: dict):
        steps = flat_steps(checker, rule.body)
        calls = [c for step in steps for c in may_run(checker, step)]     # (an `if`'s: any branch)
        self.writes = frozenset(c.name for c in calls if c.kind == "assign")
        self.motor = _commands_motors(checker, rule.body, named)
        self.moves_outside = rule.mode is None and any(
            c.kind == "standard" and c.name in MOTION_ACTIONS for c in calls)
        self.enters = any(c.kind == "enter" for c in calls)
        self.entry_moves = _is_enter(rule) and bool(steps) and any(
            c.kind == "standard" and c.name in MOTION_ACTIONS for c in may_run(checker, steps[0]))
        # a stop not followed by exit_main in its step: the wheels stopped
        # between two polls, which an entry in that poll does not undo
        self.stops = any(_stops_and_goes_on(checker, step) for step in steps)
        self.condition = condition_of(rule)
        self.names = tuple(sorted(cond.names_of(self.condition)))
        self.shape = _timing_shape(rule)
        # what the pair analysis reads of the rule, besides its place: equal
        # keys (and places) give equal pairs
        self.key = (_is_enter(rule), rule.priority, self.writes,
                    (self.shape, self.condition, _early(rule)) if self.motor else None)
        self.pair = None    # (the intervals its condition reads, rule_facts' answers)


def entry_stops(checker, every_rule, facts: dict) -> bool:
    """Whether no `stop_motor` event can occur in the poll after a mode's
    entry (see the module's doc); `facts`: id(rule) -> RuleFacts."""
    if any(e.kind == "action" for e in checker.externs.values()):
        return False
    enters, stops, entry_moves = False, [], set()
    for r in every_rule:
        f = facts[id(r)]
        if f.moves_outside:
            return False                # its motion goes on across an entry
        enters = enters or f.enters
        if f.entry_moves:
            entry_moves.add(r.mode)
        if f.stops:
            stops.append(r)
    # An `on enter` that stops runs where nothing moves (the motion of the
    # mode left was stopped), unless an `on enter` of its mode started one.
    stops = [r for r in stops if not _is_enter(r) or r.mode in entry_moves]
    return not (enters and stops)


class _Rules:
    """What the pair checks need of each rule, computed once (`facts`:
    id(rule) -> RuleFacts, computed here when not given; `stops`: entry_stops
    when known); the walk's order only when a pair asks for it."""

    def __init__(self, checker, rules, every_rule, facts: dict = None, stops=None):
        if facts is None:
            named: dict = {}
            facts = {id(r): RuleFacts(checker, r, named) for r in every_rule}
        self.facts = facts
        self.rules = every_rule         # (any rule may write a variable a guard reads)
        self._index = None
        self.condition = {id(r): facts[id(r)].condition for r in rules}
        self.memo_names, self.memo_boxes, self.memo_alone = {}, {}, {}
        self.memo_timing: dict = {}
        self.base = {name: (info.lo, info.hi) for name, info in checker.vars.items()}
        self.base.update((name, (r.lo, r.hi)) for name, r in STANDARD_READINGS.items())
        self.variables = set(checker.vars)
        self._walk = None
        self.entry_stops = entry_stops(checker, every_rule, facts) if stops is None else stops
        self.by_timing_only = False     # a big group was compared by timing alone

    @property
    def index(self) -> dict:
        """id(rule) -> its place among every rule (made when first asked)."""
        if self._index is None:
            self._index = {id(r): i for i, r in enumerate(self.rules)}
        return self._index

    def writes(self, rule) -> frozenset:
        """The variables the rule's action (named actions spliced) assigns."""
        return self.facts[id(rule)].writes

    def walk(self) -> tuple:
        """(place: id(rule) -> its place in a poll's walk, write_places:
        variable -> the places that write it, in order)."""
        if self._walk is None:
            ordered = sorted(self.rules, key=self.key)
            place = {id(r): i for i, r in enumerate(ordered)}
            write_places: dict = {}
            for i, r in enumerate(ordered):
                for name in self.facts[id(r)].writes:
                    write_places.setdefault(name, []).append(i)
            self._walk = place, write_places
        return self._walk

    def key(self, rule) -> tuple:
        """The rule's place in a poll's walk: a mode's `on enter` rules
        first, then by priority, highest first, then in file order."""
        first = rule.event.kind == "standard" and rule.event.name == "enter"
        return (0 if first else 1, 0 if first else -rule.priority, self.index[id(rule)])

    def changing(self, a, b, among) -> set:
        """The variables of `among` that can change in a poll between the evaluations
        of a's and b's conditions: by the actions from the first one's on,
        before the later one's turn (a `when` condition without a guard is
        compiled with the others and may be evaluated early in the poll:
        then every action before the later one's turn counts)."""
        place, write_places = self.walk()
        first, later = sorted((place[id(a)], place[id(b)]))
        found = set()
        early = _early(a) or _early(b)
        for name in among:
            places = write_places.get(name, ())
            if early:                   # any write before the later one's turn
                if places and places[0] < later:
                    found.add(name)
                continue
            i = bisect.bisect_left(places, first)   # from the first one's action on:
            if i < len(places) and places[i] < later:   # a write in first..later-1
                found.add(name)
        return found

    def conditions_allow(self, a, b) -> bool:
        fa, fb = self.condition[id(a)], self.condition[id(b)]
        if fa is cond.TRUE or fb is cond.TRUE:
            # (one condition that always may hold: the other alone decides)
            return fa is cond.TRUE and fb is cond.TRUE or self._alone(fa if fb is cond.TRUE else fb)
        read = (self._names(fa) | self._names(fb)) & self.variables
        unstable = self.changing(a, b, read) if read else ()
        if unstable:
            both = cond.conjoin(cond.without(fa, unstable), cond.without(fb, unstable))
            return cond.satisfiable(both, self.base)
        return cond.satisfiable_together(self._boxes(fa), self._boxes(fb))

    # Each rule's formula is asked the same questions for every pair: the
    # answers are kept (by the formula's id: self.condition keeps it alive).

    def _memo(self, memo: dict, f: tuple, compute):
        found = memo.get(id(f))
        if found is None:
            found = memo[id(f)] = (compute(f),)
        return found[0]

    def _names(self, f: tuple) -> set:
        return self._memo(self.memo_names, f, cond.names_of)

    def _boxes(self, f: tuple):
        return self._memo(self.memo_boxes, f, lambda g: cond.boxes(g, self.base))

    def _alone(self, f: tuple) -> bool:
        return self._memo(self.memo_alone, f, lambda g: cond.satisfiable(g, self.base))


def _early(rule) -> bool:
    """A `when` rule without a guard: its condition is compiled, and
    evaluated with the others at the first of them in the poll."""
    return rule.event.kind == "standard" and rule.event.name == "when" and rule.guard is None


def _is_enter(rule) -> bool:
    return rule.event.kind == "standard" and rule.event.name == "enter"


def _stops_and_goes_on(checker, step) -> bool:
    """A step that may stop the wheels and goes on (no `exit_main` after
    the stop in it that surely runs: one inside an `if` may not)."""
    for i, call in enumerate(step):
        if any(c.kind == "standard" and c.name in _STOPPING for c in may_run(checker, [call])):
            return not any(c.kind == "standard" and c.name == "exit_main" for c in step[i:])
    return False


def _racing_pairs(group: list, facts: _Rules) -> list:
    """The pairs of `group` (rules of one priority, in file order) that can
    fire together: can_fire_together over every pair, with what it reads of
    each rule computed once (a file of a thousand racing rules has half a
    million pairs)."""
    info = rule_facts(group, facts)
    timing = {}
    meet = cond.boxes_meet
    if len(group) > EXPAND_RULES:
        return _racing_blocks(group, info, facts, timing)
    found = []
    for i, a in enumerate(group):
        sa, ta, ba, va, ala = info[i]
        for j in range(i + 1, len(group)):
            sb, tb, bb, vb, alb = info[j]
            t = timing.get((sa, sb))
            if t is None:
                t = timing[sa, sb] = timing_allows(a, group[j], facts.entry_stops)
            if not t:
                continue
            if ta or tb:
                ok = alb if ta else ala
            elif va or vb:
                ok = facts.conditions_allow(a, group[j])
            else:
                ok = ba is None or bb is None or meet(ba, bb)
            if ok:
                found.append((a, group[j]))
    return found


def rule_facts(group: list, facts: _Rules) -> list:
    """What the pair loop reads of each rule, computed once: (its timing
    shape's number, no condition, its condition's boxes, reads a variable,
    its condition can hold)."""
    shapes: dict = {}
    info = []
    base, variables = facts.base, facts.variables
    for r in group:
        rf = facts.facts[id(r)]
        f = rf.condition
        # (kept by the rule's facts while the intervals its condition reads are the same)
        key = tuple((n, n in variables, base.get(n)) for n in rf.names)
        if rf.pair is None or rf.pair[0] != key:
            rf.pair = (key, f is not cond.TRUE and not variables.isdisjoint(rf.names),
                       None if f is cond.TRUE else cond.boxes(f, base),
                       f is cond.TRUE or cond.satisfiable(f, base))
        _, reads_vars, boxes, alone = rf.pair
        info.append((shapes.setdefault(rf.shape, len(shapes)), f is cond.TRUE, boxes,
                     reads_vars, alone))
    return info


def _racing_blocks(group: list, info: list, facts: _Rules, timing: dict) -> list:
    """_racing_pairs for a big group, in time and memory that grow with its
    kinds of rules rather than with its pairs: rules whose conditions read
    no variable are alike when their timing and condition are, so one pair
    of each two kinds decides for all their pairs. Returns the pairs as
    blocks (a, b, members of a's kind, members of b's kind), a kind with
    itself once."""
    kinds: dict = {}            # key -> [rules in file order]
    keys = []
    for r, (sa, ta, ba, va, ala) in zip(group, info):
        key = (sa, ta, id(ba), ala) if not va else ("rule", id(r))
        kinds.setdefault(key, []).append(r)
        keys.append(key)
    if len(kinds) * (len(kinds) + 1) // 2 > PAIR_BUDGET:
        # too many kinds to compare two by two: by timing alone (a race
        # is never missed; conditions that exclude each other are not seen)
        facts.by_timing_only = True
        info = [(sa, True, None, False, True) for sa, _, _, _, _ in info]
        kinds, keys = {}, []
        for r, (sa, *_) in zip(group, info):
            kinds.setdefault((sa, True, id(None), True), []).append(r)
            keys.append((sa, True, id(None), True))
    first = {key: members[0] for key, members in kinds.items()}
    where = {key: i for i, key in reversed(list(enumerate(keys)))}   # first index of each
    order = sorted(kinds, key=where.__getitem__)
    blocks = []
    index: dict = {}            # id(rule) -> its place in the group, when asked
    for x, kx in enumerate(order):
        for ky in order[x:]:
            a, b = first[kx], first[ky]
            if kx == ky and len(kinds[kx]) < 2:
                continue
            if kx == ky and kx[0] == "rule":
                continue
            ia, ib = where[kx], where[ky]
            if kx == ky:
                if not index:
                    index.update((id(r), i) for i, r in enumerate(group))
                b = kinds[kx][1]
                ib = index[id(b)]       # (by identity: rules compare by value, slowly)
            ab = _pair_races(a, b, info[ia], info[ib], facts, timing)
            ba = ab if kx == ky else _pair_races(b, a, info[ib], info[ia], facts, timing)
            if ab and ba:
                blocks.append((a, b, kinds[kx], kinds[ky]))
            elif ab or ba:      # it depends on which comes first: pair by pair
                if not index:
                    index.update((id(r), i) for i, r in enumerate(group))
                for x in kinds[kx]:
                    for y in kinds[ky]:
                        if (ab if index[id(x)] < index[id(y)] else ba):
                            first_, second = sorted((x, y), key=lambda r: index[id(r)])
                            blocks.append((first_, second, [first_], [second]))
    return blocks


def _pair_races(a, b, ia, ib, facts: _Rules, timing: dict) -> bool:
    """_racing_pairs's decision for one pair, a before b."""
    sa, ta, ba, va, ala = ia
    sb, tb, bb, vb, alb = ib
    t = timing.get((sa, sb))
    if t is None:
        t = timing[sa, sb] = timing_allows(a, b, facts.entry_stops)
    if not t:
        return False
    if ta or tb:
        return alb if ta else ala
    if va or vb:
        return facts.conditions_allow(a, b)
    return ba is None or bb is None or cond.boxes_meet(ba, bb)


def can_fire_together(a, b, facts: _Rules) -> bool:
    """a before b in the file."""
    key = (_timing_shape(a), _timing_shape(b))
    timing = facts.memo_timing.get(key)
    if timing is None:
        timing = facts.memo_timing[key] = timing_allows(a, b, facts.entry_stops)
    return timing and facts.conditions_allow(a, b)


def _timing_shape(rule) -> tuple:
    """What timing_allows reads of a rule: rules of one shape are alike."""
    event = rule.event
    values = tuple(sorted(event.values.items())) if event.name in (
        "timer", "every", "after") and event.kind == "standard" else ()
    return (rule.mode, event.kind, event.name, rule.repeat, values,
            event.name == "enter" and _sets_timer_first(rule))
