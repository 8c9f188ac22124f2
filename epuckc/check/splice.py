"""How named actions splice into a body's steps, for the checker's
whole-program analyses and for lowering alike.

A named action used alone as a step is replaced by its own steps; inside a
comma list its first step runs in the list's place and its later steps
follow the list. Named actions are expanded on a stack of our own, in the
order recursion would take, because a chain of thousands of named actions
is deeper than Python's stack; resolved bodies hold no cycles (a call that
would close one is E023 and left out).

Spliced, a named action's `if`s nest inside the `if` that calls it: the
depth of each action once spliced, and E056 where it takes a statement
past the limit of syntax/limits.py, are here too.
"""
from __future__ import annotations

from ..syntax import ast, limits
from ..syntax.limits import MAX_DEPTH


def splice(steps, leaf, body_of, memo: dict) -> list:
    """`steps` with every named call spliced in and every other call mapped
    by `leaf(call, context)`. `body_of(name)` gives a named action's
    (steps, context); `memo` maps a named action to its spliced steps and
    is filled as they are made. The outer body's context is None."""

    def walk(body, context):
        out = []
        for step in body:
            current, later = [], []
            for call in step:
                if call.kind == "named":
                    inner = memo.get(call.name)
                    if inner is None:
                        inner = yield call.name
                    if inner:
                        current.extend(inner[0])
                        later.extend(inner[1:])
                else:
                    current.append(leaf(call, context))
            out.append(current)
            out.extend(later)
        return out

    stack = [(walk(steps, None), None)]
    result = None
    while True:
        gen, name = stack[-1]
        try:
            needed = gen.send(result)
        except StopIteration as done:
            stack.pop()
            if name is not None:
                memo[name] = done.value
            if not stack:
                return done.value
            result = done.value
            continue
        stack.append((walk(*body_of(needed)), needed))
        result = None


def named_calls(checker, body) -> list:
    """The calls of named actions in a body's steps (inside its `if`s too):
    named actions are called in steps only, never inside an expression."""
    actions, externs = checker.actions, checker.externs
    return [call for step in body.steps for call in ast.calls_within(step.calls)
            if call.__class__ is ast.Call and not call.args and call.name.name in actions
            and call.name.name not in externs]


def _inserted(checker, calls: list):
    """`limits.measure`'s `inserted` for a statement whose named calls are
    `calls`: a named call counts the depth of its action's calls (what
    stands in its place once spliced), except one that closes a cycle
    (E023) or calls an action too deep itself (reported there)."""
    depths, cycle = checker.action_depths, checker._cycle_calls
    ids = {id(c): depths.get(c.name.name) for c in calls if id(c) not in cycle}

    def inserted(node):
        return ids.get(id(node))
    return inserted, max((d for d in ids.values() if d is not None), default=None)


def action_depths(checker, order) -> None:
    """Each named action's depth once spliced (the depth of its calls with
    the named ones spliced in: what stands in the place of its call), in
    `order` (those it calls first), into `checker.action_depths`; E056
    where an action's own definition passes MAX_DEPTH once spliced (its
    depth is then None, and its calls say nothing more: one error)."""
    depths = checker.action_depths
    for name in order:
        node = checker.actions[name]
        inserted, extra = _inserted(checker, named_calls(checker, node.body))
        if extra is not None and not limits.narrow(node, MAX_DEPTH - extra):
            _, deep = limits.measure(node, MAX_DEPTH, inserted)
            if deep is not None:
                _report(checker, node, deep)
                depths[name] = None
                continue
        height, _ = limits.measure(node.body, None, inserted)
        depths[name] = height - 2       # (the body and its step above the calls)


def check_depth(checker, statement) -> None:
    """E056 where the named actions a rule calls, spliced in, take it past
    MAX_DEPTH (the parser's gate measured it without them)."""
    calls = named_calls(checker, statement.body)
    if not calls:
        return
    inserted, extra = _inserted(checker, calls)
    if extra is None or limits.narrow(statement, MAX_DEPTH - extra):
        return
    _, deep = limits.measure(statement, MAX_DEPTH, inserted)
    if deep is not None:
        _report(checker, statement, deep)


def _report(checker, statement, deep) -> None:
    """(a path can pass the limit only at a named call: the parser's gate
    measured the statement itself)"""
    called = checker.actions.get(deep.at.name.name) if deep.at.__class__ is ast.Call else None
    if called is None:
        limits.report_too_deep(checker.diags, statement, deep)
    else:
        limits.report_spliced(checker.diags, statement, deep, called)
