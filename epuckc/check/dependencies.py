"""The variables' dependency graph, for their intervals (ranges.py): each
statement's assignments (those inside `if` branches too, with the
conditions that hold where they run and the variables assigned before them
since), the names each reads, which variables each variable's assignments
read, and the graph's strongly connected components (Tarjan, without
recursion), dependencies first.

The conditions that hold where an assignment runs are a chain of `Held`
links shared by the assignments after them: the branches of an `else if`
chain of n branches make n links, not the n²/2 a list for each would
hold, and what is computed of a link (the names it reads, its text's
digest, ranges.py's boxes) is computed once."""
from __future__ import annotations

import hashlib

from ..syntax import ast
from .arrays import fill_assign
from .messages import _shown


_ANY = object()     # (a statement whose assignments do not depend on its mode)


class Entry:
    """One assignment as the intervals keep it: the Assign; whether it runs
    once; the names it reads (its conditions' too); its text, computed when
    a component's result is first kept (ranges._inputs); its statement's id
    and its place in the statement; the conditions that hold where it runs
    (a Held chain, or None); the variables assigned before it since (True:
    any). Equal when every field is, as the lists it replaced compared."""
    __slots__ = ("assign", "once", "reads", "text", "statement", "place", "context", "spoiled")

    def __init__(self, assign, once: bool, reads: frozenset, statement: int, place: int,
                 context, spoiled):
        self.assign, self.once, self.reads, self.text = assign, once, reads, None
        self.statement, self.place, self.context, self.spoiled = statement, place, context, spoiled

    def _fields(self) -> tuple:
        return (self.assign, self.once, self.reads, self.text, self.statement, self.place,
                self.context, self.spoiled)

    def __eq__(self, other) -> bool:
        return other.__class__ is Entry and self._fields() == other._fields()

    __hash__ = None


class StatementAssigns:
    """A statement's assignments (statement_assignments): the statement
    (kept alive, so that its id stays its own), the mode they were found
    for (_ANY: any), and ((target, Entry), ...) in the statement's order."""
    __slots__ = ("statement", "mode", "entries")

    def __init__(self, statement, mode, entries: tuple):
        self.statement, self.mode, self.entries = statement, mode, entries


def _runs_once(stmt) -> bool:
    """A rule that runs at most once (its assignments are joined once each)."""
    return isinstance(stmt, ast.Rule) and not stmt.repeat and stmt.mode is None \
        and stmt.trigger != "every"


def _names_read(value) -> frozenset:
    """The names an expression reads: variables, constants and readings (a
    loop: expressions may be deep)."""
    found, todo = set(), [value]
    while todo:
        node = todo.pop()
        cls = node.__class__
        if cls is ast.ConstRef:
            found.add(node.name.name)
        elif cls is ast.BinOp:
            todo += (node.left, node.right)
        elif cls is ast.UnaryOp:
            todo.append(node.operand)
        elif cls is ast.Paren:
            todo.append(node.expr)
        elif cls is ast.FuncCall:
            todo += [a.value for a in node.args or () if hasattr(a, "value")]
        elif cls is ast.Slice:          # `sum(a[1:3])`: a constant slice of a
            found.add(node.name.name)
        elif cls is ast.ArrayLit:       # `a = [e0, e1, ...]`
            todo += node.items
    return frozenset(found)


class Held:
    """Where an assignment runs, `condition` held (`held` True) or failed,
    after the conditions of `parent` (None: the first): an enclosing
    branch's condition, a rule's guard, a branch before in the same chain.
    `names`: what all of them read."""
    __slots__ = ("parent", "condition", "held", "names", "_key")

    def __init__(self, parent, condition, held: bool):
        self.parent, self.condition, self.held = parent, condition, held
        names = _names_read(condition)
        if parent is not None:
            names = parent.names if names <= parent.names else parent.names | names
        self.names, self._key = names, None

    def pairs(self) -> list:
        """The (condition, held) pairs, the first one first."""
        out, link = [], self
        while link is not None:
            out.append((link.condition, link.held))
            link = link.parent
        return out[::-1]

    def key(self) -> bytes:
        """A digest of the conditions' text and whether each held (what the
        language server compares between analyses): each link's from its
        parent's, so that a chain's are computed once each."""
        todo, link = [], self
        while link is not None and link._key is None:
            todo.append(link)
            link = link.parent
        for link in reversed(todo):
            above = link.parent._key if link.parent is not None else b""
            link._key = hashlib.blake2b(
                above + (b"+" if link.held else b"-") + _shown(link.condition).encode(),
                digest_size=16).digest()
        return self._key


def _assignments(calls, context, actions, spoiled=frozenset(), variables=None) -> list:
    """(Assign, context, spoiled) for each assignment of a step's `calls`,
    those inside `if` branches too: `context` the conditions that hold
    where it runs (a Held chain: its branch's condition held, the ones
    before it did not; None: none), `spoiled` the variables a call before
    it in those branches may have assigned since (True: any, after a named
    action)."""
    out = []
    spoiled = spoiled if spoiled is True else set(spoiled)
    for call in calls:
        cls = call.__class__
        if cls is ast.Call and call.name.name == "fill" and "fill" not in actions:
            call = fill_assign(variables or {}, call) or call      # `a = [v, v, ...]`
            cls = call.__class__
        if cls is ast.Assign:
            out.append((call, context, spoiled if spoiled is True else frozenset(spoiled)))
            if spoiled is not True:
                spoiled.add(call.target.name)
        elif cls is ast.IfAction:
            failed = context
            for branch in call.branches:
                here = Held(failed, branch.condition, True)
                for k, step in enumerate(branch.body.steps):
                    out += _assignments(step.calls, here if k == 0 else None, actions,
                                        spoiled if k == 0 else frozenset(), variables)
                failed = Held(failed, branch.condition, False)
            if call.otherwise is not None:
                for k, step in enumerate(call.otherwise.steps):
                    out += _assignments(step.calls, failed if k == 0 else None,
                                        actions, spoiled if k == 0 else frozenset(), variables)
            if spoiled is not True:
                for inner in ast.calls_within((call,)):
                    if inner.__class__ is ast.Assign:
                        spoiled.add(inner.target.name)
                    elif inner.__class__ is ast.Call and inner.name.name == "fill" \
                            and "fill" not in actions and fill_assign(variables or {}, inner):
                        spoiled.add(fill_assign(variables or {}, inner).target.name)
                    elif inner.__class__ is ast.Call and inner.name.name in actions:
                        spoiled = True
                        break
        elif cls is ast.Call and call.name.name in actions:
            spoiled = True
    return out


def statement_assignments(checker, known: dict, stmt) -> tuple:
    """What the intervals need of a statement (`known`: the last ones, by
    id, reused while the statement is the same object and, for a rule with
    assignments, in the same mode): its StatementAssigns."""
    hit = known.get(id(stmt))
    if hit is not None and hit.statement is stmt and (hit.mode is _ANY or hit.mode is stmt.mode):
        return hit
    body = stmt.body if isinstance(stmt, (ast.Rule, ast.ActionDef)) else None
    runs_once = _runs_once(stmt)
    guard = stmt.guard if isinstance(stmt, ast.Rule) else None
    calls = []
    for k, step in enumerate(() if body is None else body.steps):
        # (an `if`'s assignments may run, where its conditions held)
        start = Held(None, guard, True) if guard is not None and k == 0 else None
        calls += _assignments(step.calls, start, checker.actions, variables=checker.vars)
    hit = known[id(stmt)] = StatementAssigns(
        stmt, stmt.mode if calls and isinstance(stmt, ast.Rule) else _ANY,
        tuple((c.target.name, Entry(c, runs_once, _names_read(c.value) | (
            context.names if context is not None else frozenset()), id(stmt), j, context, spoiled))
              for j, (c, context, spoiled) in enumerate(calls)))
    return hit


def _needs(name: str, entries: list, variables: dict) -> list:
    """The variables a variable's assignments read (itself for `+=`)."""
    needs = set()
    keys = variables.keys()
    for entry in entries:
        needs |= entry.reads & keys
        if entry.assign.op != "=":
            needs.add(name)
    return sorted(needs)


def components(graph: dict) -> list:
    """The strongly connected components of `graph` (node -> the nodes it
    depends on), each a tuple in the order of `graph`, dependencies first.
    Tarjan's algorithm with an explicit stack."""
    order = {n: i for i, n in enumerate(graph)}
    index, low, on_stack, stack, out = {}, {}, set(), [], []
    counter = 0
    for root in graph:
        if root in index:
            continue
        work = [(root, iter(graph[root]))]
        index[root] = low[root] = counter
        counter += 1
        stack.append(root)
        on_stack.add(root)
        while work:
            node, edges = work[-1]
            pushed = False
            for nxt in edges:
                if nxt not in index:
                    index[nxt] = low[nxt] = counter
                    counter += 1
                    stack.append(nxt)
                    on_stack.add(nxt)
                    work.append((nxt, iter(graph[nxt])))
                    pushed = True
                    break
                if nxt in on_stack:
                    low[node] = min(low[node], index[nxt])
            if pushed:
                continue
            work.pop()
            if work:
                parent = work[-1][0]
                low[parent] = min(low[parent], low[node])
            if low[node] == index[node]:
                members = []
                while True:
                    m = stack.pop()
                    on_stack.discard(m)
                    members.append(m)
                    if m == node:
                        break
                out.append(tuple(sorted(members, key=order.__getitem__)))
    return out


def order_components(graph: dict) -> tuple:
    """The graph's components in dependency order as ranges.py keeps them:
    (members, their set, what they read: themselves and what they depend
    on), the places in that order of the components reading each variable,
    and each variable's component's place."""
    order, readers, place = [], {}, {}
    for at, members in enumerate(components(graph)):
        inside = frozenset(members)
        reads = inside.union(*(graph[m] for m in members))
        order.append((members, inside, reads))
        for name in members:
            place[name] = at
        for name in reads:
            readers.setdefault(name, []).append(at)
    return order, readers, place


def regraph_in_place(order: list, readers: dict, place: dict, graph: dict, old_graph: dict,
                     names) -> bool:
    """After the variables `names` (and no other) changed what they depend
    on (`old_graph` to `graph`, the same variables), the components kept
    (`order`, `readers`, `place`: order_components's) made those of
    `graph` in place, when the edit cannot have changed which variables
    make a component: every dependency it added is on a component before
    (or its own), and a component that lost a dependency inside itself
    still is one. Then the order is still one where what a component reads
    comes before it, each component is what `components` finds, and only
    the changed components' `reads` (and their readers) are made again.
    False, and nothing changed, otherwise."""
    touched, split = set(), set()
    for name in names:
        old, new = old_graph[name], graph[name]
        if old == new:
            continue
        at = place[name]
        touched.add(at)
        new_set, old_set = set(new), set(old)
        if any(place[v] > at for v in new_set - old_set):
            return False        # (it may join components, or come after one)
        if any(place[v] == at for v in old_set - new_set):
            split.add(at)
    for at in split:
        members, inside, _ = order[at]
        if len(components({m: [v for v in graph[m] if v in inside] for m in members})) > 1:
            return False
    for at in touched:
        members, inside, reads = order[at]
        now = inside.union(*(graph[m] for m in members))
        for name in reads - now:
            readers[name].remove(at)
            if not readers[name]:
                del readers[name]
        for name in now - reads:
            readers.setdefault(name, []).append(at)
        order[at] = (members, inside, now)
    return True
