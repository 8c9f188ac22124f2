"""The intervals of the variables, one strongly connected component of
their dependency graph at a time, and only where something changed.

A variable's interval is the union of its initial value and of every value
an assignment can give it. An assignment inside an `if` branch (or in the
first step of a guarded rule) is evaluated with the variables its
conditions compare narrowed to what they leave them, except those a call
before it may have assigned since (`if n < 100 { n += 1 }` gives 0..100).
An assignment `v = e` makes v depend on the variables e (and the conditions
around it) read, and `v += e` on v itself; those dependencies form a
graph whose strongly connected components (Tarjan, without recursion) are
solved in dependency order: the components a component reads are final
before it is iterated, so each one is a small fixpoint of its own
assignments (in file order, RANGE_PASSES passes, then the bounds still
growing are widened to the 16-bit range; the assignments of rules that
run at most once are joined once each; then narrowing gives back what
widening took where the assignments bound it), and a chain of variables
is exact however long it is.

The result of a component depends only on its assignments, its members'
declarations and the final intervals it reads (plus the constants and the
geometry, which every value may use). With a memo (the language server's,
ide/incremental.py), a component whose inputs are unchanged is not
evaluated again, and after an edit only the components that read what
changed are visited (by the graph's readers, in dependency order): an edit
costs the components it reaches, not the program. Within a fixpoint, and
from one analysis to the next, what an assignment gives is kept by the
state of what it read (_assigned_where). What an assignment is, what it
reads and the graph's components are dependencies.py's.
"""
from __future__ import annotations

import heapq
import itertools

from ..base.views import MISSING, NotingView, Overlaid
from ..stdlib.units import INT16_MAX, INT16_MIN
from . import conditions, reeval
from .dependencies import _needs, order_components, regraph_in_place
from .dependencies import statement_assignments  # noqa: F401 (the language server's)
from .messages import _shown
from .program import BOOL, VarInfo, with_interval

# passes of a component's assignments before the growing bounds are widened
RANGE_PASSES = 4
# rules that run at most once are joined once each, up to this many assignments
ONCE_MAX = 16
# passes that give back what widening took where the assignments bound it
NARROW_PASSES = 2


class RangeMemo:
    """What one document's intervals were computed from, kept between two
    analyses: the environment (geometry and constants), each statement's
    assignments, each variable's assignments and declaration, the graph
    and its components, each component's inputs and result, and every
    variable's interval."""
    def __init__(self):
        self.env = None
        self.statements: dict = {}  # id(statement) -> its StatementAssigns (dependencies.py)
        self.names = None           # the variables, in order
        self.assigns: dict = {}     # variable -> its assignments' entries, in file order
        self.decls: dict = {}       # variable -> (kind, initial value)
        self.graph = None           # variable -> the variables it depends on
        self.order: list = []       # its components: (members, members' set, what they read)
        self.readers: dict = {}     # variable -> the places in `order` of the components reading it
        self.place: dict = {}       # variable -> the place in `order` of its component
        self.results: dict = {}     # members -> (inputs, {name: (lo, hi)})
        self.ranges: dict = {}      # variable -> (lo, hi)
        self.solved = None          # variable -> its VarInfo, the last analysis's
        self.pieces: dict = {}      # what the language server keeps by piece (ide/passes.py)
        self.piece_list: list = []  # the last analysis's pieces, in order
        self.where: dict = {}       # id(statement) -> its piece (of those that assign)
        self.moved = None           # the variables whose intervals moved, when only theirs did
        self.values: dict = {}      # what each assignment gave, by what it read (_assigned_where)



def _copy(info: VarInfo, bounds=None) -> VarInfo:
    """A VarInfo of its own (with the interval `bounds`)."""
    return with_interval(info, bounds if bounds is not None else (info.lo, info.hi))


def _inputs(checker, entries: list, members: tuple, outside) -> tuple:
    """What a component's result is computed from: its assignments' text
    (kept in their entries) and whether each runs once, its members'
    declarations, the intervals it reads of other components."""
    for entry in entries:
        if entry.text is None:      # (and the conditions that hold where it runs)
            entry.text = (entry.assign.op, _shown(entry.assign.value),
                          entry.context.key() if entry.context is not None else None,
                          entry.spoiled)
    variables = checker.vars
    return (tuple((e.text, e.once) for e in entries),
            tuple((m, variables[m].kind, variables[m].init) for m in members),
            tuple((n, variables[n].kind, variables[n].lo, variables[n].hi)
                  for n in sorted(outside)))


# the values of an assignment kept (_assigned_where), for as many states of what it reads
_KEPT_VALUES = 4
_MISSING = MISSING


def _state(info) -> tuple:
    """What an assignment's value can read of a variable."""
    if info is _MISSING:
        return ()
    return (info.lo, info.hi, info.kind, info.size)


class _Kept:
    """What is kept of one assignment (RangeMemo.values): the Assign node
    (kept alive, so that its id stays its own), its last values with what
    each read, and the plan of its value (check/reeval.py), or None."""
    __slots__ = ("call", "values", "plan")

    def __init__(self, call):
        self.call, self.values, self.plan = call, [], None


# where a plan cannot answer (_assigned_where)
_UNPLANNED = object()
# the value of an assignment that cannot run: where the conditions that hold
# where it runs cannot (_where_bounds)
NEVER = object()
# (tests: each value a plan gives is compared with the checker's)
_VERIFY_PLANS = False


class _Value:
    """What the intervals read of an assignment's value."""
    __slots__ = ("kind", "lo", "hi")

    def __init__(self, kind, lo, hi):
        self.kind, self.lo, self.hi = kind, lo, hi


class _Reads(NotingView):
    """The variables as an assignment's evaluation sees them, noting the
    state of each one it reads (the first time: before the conditions that
    hold where it runs narrow them); `read` None when it looked at all."""
    __slots__ = ("_table", "read")

    def __init__(self, table: dict):
        self._table, self.read = table, {}

    def get(self, name, default=None):
        found = self._table.get(name, _MISSING)
        read = self.read
        if read is not None and name not in read:
            read[name] = _state(found)
        return default if found is _MISSING else found

    def _all(self):
        self.read = None
        return self._table


class Ranges:
    """The checker's variables' intervals (a part of Checker; the
    expressions are exprs.py's, the assignments variables.py's)."""

    range_memo = None       # a RangeMemo where the language server keeps one

    # (the language server: whether the declarations are the last analysis's,
    # their variables the same objects, ide/passes.py)
    _declared_same = False

    def _var_ranges(self):
        """Each variable's interval, component by component. With the
        language server's memo, a component is evaluated again only when
        its assignments or its members' declarations changed (a variable's
        assignments are the same objects, in the same order, when no
        statement assigning it was parsed again), or when an interval it
        reads moved; and then only if its inputs' text differs.

        A VarInfo is never changed here: a variable's interval is a new one
        (the declared one is kept as it is, and the language server keeps
        the last analysis's while its interval does not move, so that what
        was checked with it compares by identity)."""
        keep = self.range_memo is not None
        memo = self.range_memo if keep else RangeMemo()
        memo.moved = None
        if not self.vars:
            memo.solved = None
            return
        # (what a statement's assignments read beside the statement: the
        # named actions, what an assignment in a branch counts as spoiling;
        # the constant arrays, what an element read gives; the arrays'
        # sizes, the elements a `fill` assigns, check/arrays.fill_assign)
        env = (self.geo, tuple(self.consts.items()), tuple(self.const_arrays.items()),
               frozenset(self.actions),
               tuple((name, info.size) for name, info in self.vars.items() if info.size))
        if memo.env != env:
            memo.results, memo.ranges, memo.statements, memo.solved = {}, {}, {}, None
            memo.pieces, memo.where, memo.values = {}, {}, {}
        memo.env = env
        pristine = self.vars                # as declared
        names = tuple(pristine)
        same_names = names == memo.names
        assigns, changed, place = self._assignments_by_variable(memo, same_names)
        if len(memo.values) > 2 * sum(map(len, assigns.values())) + 1000:
            # (the values of assignments gone: those of the others stay)
            live = {id(e.assign) for entries in assigns.values() for e in entries}
            memo.values = {k: v for k, v in memo.values.items() if k in live}
        self._values = memo.values
        fast = same_names and changed is not None and self._declared_same \
            and memo.solved is not None
        old_assigns, old_decls, old_graph = memo.assigns, memo.decls, memo.graph
        if fast:            # (the declarations are the same objects: only what changed)
            graph, decls = old_graph, old_decls
            dirty = {n for n in changed if assigns[n] != old_assigns.get(n)}
            for name in dirty:
                needs = _needs(name, assigns[name], pristine)
                if needs != graph[name]:
                    if graph is old_graph:
                        graph = dict(old_graph)
                    graph[name] = needs
        else:
            graph, decls, dirty = {}, {}, set()
            for name, entries in assigns.items():
                info = pristine[name]
                decl = decls[name] = (info.kind, info.init)
                if same_names and entries == old_assigns.get(name) and decl == old_decls.get(name):
                    graph[name] = old_graph[name]
                    continue
                dirty.add(name)
                graph[name] = _needs(name, entries, pristine)
        memo.names, memo.assigns, memo.decls = names, assigns, decls
        regraphed = graph is not old_graph and graph != old_graph
        if regraphed and fast and regraph_in_place(memo.order, memo.readers, memo.place, graph,
                                                   old_graph, dirty):
            memo.graph, regraphed = graph, False    # (the same components: see there)
        if regraphed:
            memo.graph = graph
            memo.order, memo.readers, memo.place = order_components(graph)
        old_results, old_ranges = memo.results, memo.ranges
        last = memo.solved if fast else None
        variables = self.vars = dict(last) if fast else pristine
        moved = set()               # variables whose interval is not the last analysis's
        solving = (assigns, place, keep, variables, pristine, last, old_ranges)
        if fast and not regraphed:
            # only the components that read what changed, in dependency order
            results, todo = old_results, []
            for name in dirty:
                todo += memo.readers.get(name, ())
            heapq.heapify(todo)
            done = -1
            while todo:
                at = heapq.heappop(todo)
                if at == done:
                    continue
                done = at
                for name in self._component(memo.order[at], results, results.get, solving):
                    moved.add(name)
                    for reader in memo.readers.get(name, ()):
                        if reader > at:
                            heapq.heappush(todo, reader)
        else:
            results = {}
            for members, inside, reads in memo.order:
                old = old_results.get(members)
                if old is not None and not (dirty & reads) and not (moved & reads):
                    results[members] = old
                    if not fast:
                        moved.update(self._give(old[1], variables, pristine, None, old_ranges))
                    continue
                moved.update(self._component((members, inside, reads), results,
                                             old_results.get, solving))
        memo.results = results
        if fast:
            for name in moved:
                info = variables[name]
                old_ranges[name] = (info.lo, info.hi)
        else:
            memo.ranges = {name: (info.lo, info.hi) for name, info in variables.items()}
        memo.solved = variables
        # (when the variables are the last analysis's VarInfo objects but
        # these: what the language server revalidates by, ide/recheck.py)
        memo.moved = moved if fast else None

    def _component(self, component: tuple, results: dict, old_result, solving: tuple) -> list:
        """Solve one component again (when its inputs' text differs from the
        last result's) and give its members their intervals; the members
        whose intervals moved."""
        members, inside, reads = component
        assigns, place, keep, variables, pristine, last, old_ranges = solving
        entries = [e for m in members for e in assigns[m]]
        if not entries:         # its members keep their declared intervals
            results.pop(members, None)
            out = []
            for m in members:
                info = variables[m] = pristine[m]
                if old_ranges.get(m) != (info.lo, info.hi):
                    out.append(m)
            return out
        if len(members) > 1:                                # in file order
            entries.sort(key=place)
        inputs = _inputs(self, entries, members, reads - inside) if keep else None
        old = old_result(members)
        if old is not None and old[0] == inputs:
            result = old[1]
        else:
            for m in members:           # (solved from the declared intervals)
                variables[m] = _copy(pristine[m])
            self._contexts = {id(e.assign): (e.context, e.spoiled) for e in entries
                              if e.context is not None}
            result = self._solve([e.assign for e in entries],
                                 {id(e.assign) for e in entries if e.once})
        results[members] = (inputs, result)
        return self._give(result, variables, pristine, last, old_ranges)

    @staticmethod
    def _give(result: dict, variables: dict, pristine: dict, last, old_ranges: dict) -> list:
        """The variables of a component their intervals: the last analysis's
        VarInfo (`last`) where it has them, the declared one where they are
        declared, else a new one; those whose intervals moved."""
        moved = []
        for m, bounds in result.items():
            info = variables[m]
            if (info.lo, info.hi) != bounds:
                info = variables[m] = _copy(pristine[m], bounds)
            if last is not None:
                before = last.get(m)
                if before is not None and before is not info and (before.lo, before.hi) == bounds:
                    variables[m] = before
            if old_ranges.get(m) != bounds:
                moved.append(m)
        return moved

    def _assignments_by_variable(self, memo: RangeMemo, same_names: bool) -> tuple:
        """(variable -> its assignments' entries in file order, the variables
        whose assignments may differ from the memo's (None: any), the key
        that puts entries in file order). The language server's does it by
        pieces of the document (ide/passes.py)."""
        assigns: dict = {name: [] for name in self.vars}
        known, seen = memo.statements, {}
        for stmt in self.program.statements:
            hit = seen[id(stmt)] = statement_assignments(self, known, stmt)
            for name, entry in hit.entries:
                found = assigns.get(name)
                if found is not None:
                    found.append(entry)
        memo.statements = seen
        place: dict = {}

        def in_file_order(entry):
            if not place:
                place.update(zip(seen, itertools.count()))
            return place[entry.statement], entry.place
        return assigns, None, in_file_order

    def _solve(self, calls: list, once: set) -> dict:
        """A component's intervals: its assignments (in file order) joined
        to a fixpoint, widened where they keep growing; those of rules that
        run at most once joined once each, in any order among the others;
        then narrowed where the assignments bound what widening took."""
        repeated = [c for c in calls if id(c) not in once]
        single = [c for c in calls if id(c) in once]
        if len(single) > ONCE_MAX:
            repeated, single = calls, []
        # (what is said here is dropped: the rules say it; so the memories
        # of what was said once must not keep it either, or a rule would
        # not say it: an unknown constant behind a constant was lost so)
        memories = self.memories
        self.memories = memories.copy()
        try:
            with self.diags.capture():
                self._held_boxes(calls)
                self._join_assigned(repeated)
                for _ in single:
                    if not self._join_assigned(single, widen=False):
                        break
                    self._join_assigned(repeated)
                self._narrow_ranges(repeated + single)
        finally:
            self.memories = memories
        return {name: (self.vars[name].lo, self.vars[name].hi)
                for name in dict.fromkeys(c.target.name for c in calls)}

    def _join_assigned(self, calls, widen: bool = True) -> bool:
        """Joins what `calls` can give into their variables' intervals,
        repeated to a fixed point (widened where they keep growing); with
        widen False, once. Whether an interval grew."""
        grew = False
        attempt = 0
        while True:                     # each widening takes a bound to an end: it stops
            changed = False
            for call in calls:
                info = self.vars[call.target.name]
                value = self._assigned_where(call, info)
                if value is None or value is NEVER or value.kind == BOOL:
                    continue
                lo, hi = min(info.lo, value.lo), max(info.hi, value.hi)
                if (lo, hi) != (info.lo, info.hi):
                    if widen and attempt >= RANGE_PASSES:       # still growing: widen
                        lo = INT16_MIN if lo < info.lo else lo
                        hi = INT16_MAX if hi > info.hi else hi
                    info.lo, info.hi = lo, hi
                    changed = grew = True
            attempt += 1
            if not changed or not widen:
                break
        return grew

    _contexts = None        # id(Assign) -> (conditions that hold where it runs, spoiled)
    _boxes = None           # id(Held) -> (it, the boxes where its conditions hold)

    def _held_boxes(self, calls) -> None:
        """The boxes where each chain of conditions (dependencies.Held) of
        `calls`' assignments holds, a link's from its parent's (each link
        once: a chain of n branches costs n). A condition's formula is read
        with the component's variables (those `calls` assign) over the whole
        16-bit range, so that it holds for every interval the fixpoint gives
        them (folded with a narrower one, a comparison could be decided where
        a wider one leaves it open); the intervals are met where the
        assignment is evaluated (_evaluated_where)."""
        boxes = self._boxes = {}
        table = self.vars
        members = [table[n] for n in dict.fromkeys(c.target.name for c in calls)]
        self.vars = Overlaid(table, {info.name: _copy(info, (INT16_MIN, INT16_MAX))
                                      for info in members if info.kind != BOOL})
        try:
            for call in calls:
                link = (self._contexts or {}).get(id(call), (None,))[0]
                todo = []
                while link is not None and id(link) not in boxes:
                    todo.append(link)
                    link = link.parent
                for link in reversed(todo):
                    above = boxes[id(link.parent)][1] if link.parent is not None \
                        else conditions.TRUE_BOXES
                    e = self._expr(link.condition)
                    if e is not None and e.kind == BOOL:
                        above = conditions.conjoined(above, conditions.formula(e, link.held))
                    boxes[id(link)] = (link, above)
        finally:
            self.vars = table

    _values = None      # id(Assign) -> its _Kept: see _assigned_where

    def _assigned_where(self, call, info):
        """_evaluated_where's value, kept: an assignment's value depends on
        the variables it reads (noted while it is evaluated, _Reads) and on
        its target's interval (and on the constants, geometry and named
        actions, which the memo is kept with: RangeMemo.env); a fixpoint
        asks the same again and again, and the language server's next
        analysis too. For intervals not asked before, the plan of its
        first evaluation (check/reeval.py) computes it where it can."""
        memo = self._values
        if memo is None:
            return self._evaluated_where(call, info)
        table, target = self.vars, _state(info)
        known = memo.get(id(call))
        if known is not None and known.call is call:
            for read, state, value in known.values:
                if state == target and all(_state(table.get(n, _MISSING)) == s
                                           for n, s in read.items()):
                    return value
        else:
            known = None
        reads = _Reads(table)
        value = _UNPLANNED
        if known is not None and known.plan is not None:
            bounds = self._where_bounds(call, reads)
            found = NEVER if bounds is NEVER else reeval.evaluate(known.plan, reads, bounds, info)
            if found is NEVER:
                value = NEVER
            elif found is not reeval.MISMATCH:
                value = None if found is None else _Value(*found)
                if _VERIFY_PLANS:
                    _verify_plan(self, call, info, value)
        if value is _UNPLANNED:
            reads.read = {}
            self.vars = reads
            try:
                found = self._evaluated_where(call, info)
            finally:
                self.vars = table
            if reads.read is None:          # (it looked at every variable)
                return found
            value = found if found is None or found is NEVER else \
                _Value(found.kind, found.lo, found.hi)
            if known is None:
                known = memo[id(call)] = _Kept(call)
            if value is not None and value is not NEVER:
                known.plan = _plan(self, call, info, found, reads.read)
        known.values.insert(0, (reads.read, target, value))
        del known.values[_KEPT_VALUES:]
        return value

    def _where_bounds(self, call, variables) -> dict:
        """The intervals the conditions that hold where an assignment runs
        leave the variables they compare (its `if` branches, a rule's guard
        in its first step), read from `variables`: except those a call
        before it, since those conditions were evaluated, may have
        assigned (`spoiled`; True: every one). Empty where none narrows;
        NEVER where they cannot hold (a branch whose condition is always
        false, as `if v != v`: the C compiler drops it, and then knows what
        the variables it alone assigned are)."""
        context, spoiled = (self._contexts or {}).get(id(call), (None, ()))
        if context is None or spoiled is True:
            return {}
        base = {}
        for n in sorted(context.names):     # (what the conditions read, noted: _Reads)
            found = variables.get(n)
            if found is not None and n not in spoiled:
                base[n] = (found.lo, found.hi)
        held = (self._boxes or {}).get(id(context))
        if held is None or held[0] is not context:
            return {}
        narrowed = conditions.narrowed_where(held[1], base)
        return NEVER if narrowed is None else narrowed

    def _evaluated_where(self, call, info):
        """The value an assignment gives (variables.py's `_assigned`), with
        the variables narrowed to what the conditions that hold where it
        runs leave them (_where_bounds), as the checker narrows them for
        the call (branches.py)."""
        table = self.vars
        bounds = self._where_bounds(call, table)
        if bounds is NEVER:
            return NEVER
        if not bounds:
            return self._assigned(call, info)
        narrowed = {n: _copy(table[n], b) for n, b in bounds.items()}
        self.vars = Overlaid(table, narrowed)
        try:
            return self._assigned(call, narrowed.get(info.name, info))
        finally:
            self.vars = table

    def _narrow_ranges(self, calls):
        """Gives back what widening took where the assignments bound it
        (`n = min(n + 1, 1000)`): every value a variable takes is its initial
        value or one an assignment gives from values within the intervals,
        so each interval may be met with the hull of those."""
        members = dict.fromkeys(c.target.name for c in calls)
        for _ in range(NARROW_PASSES):
            hulls = {name: (self.vars[name].init, self.vars[name].init) for name in members}
            for call in calls:
                info = self.vars[call.target.name]
                value = self._assigned_where(call, info)
                if value is NEVER:
                    continue            # it cannot run: it gives nothing
                if value is None or value.kind == BOOL:
                    return              # not every value is known: keep the intervals
                lo, hi = hulls[info.name]
                hulls[info.name] = (min(lo, value.lo), max(hi, value.hi))
            changed = False
            for name, (lo, hi) in hulls.items():
                info = self.vars[name]
                met = (max(info.lo, lo), min(info.hi, hi))
                if met != (info.lo, info.hi):
                    info.lo, info.hi = met
                    changed = True
            if not changed:
                return


def _plan(checker, call, info, found, read: dict):
    """The plan (reeval.Plan) of an assignment's value as the checker
    found it, when a plan reads what the checker read (the variables its
    conditions compare, then those the value names), else None."""
    if call.index is not None:
        return None
    plan = reeval.plan_of(found, info, call.op != "=")
    if plan is None:
        return None
    context, spoiled = (checker._contexts or {}).get(id(call), (None, ()))
    names = set(plan.names)
    if context is not None and spoiled is not True:
        names.update(context.names)
    return plan if names == set(read) else None


def _verify_plan(checker, call, info, value) -> None:
    """(tests: a plan's value is the checker's)"""
    table = checker.vars
    checker.vars = _Reads(table)
    try:
        found = checker._evaluated_where(call, info)
    finally:
        checker.vars = table
    expected = found if found is None or found is NEVER else (found.kind, found.lo, found.hi)
    got = value if value is None or value is NEVER else (value.kind, value.lo, value.hi)
    assert got == expected, (_shown(call.value), got, expected)
