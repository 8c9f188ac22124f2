"""How named actions splice into a body's steps, for the checker's
whole-program analyses and for lowering alike.

A named action used alone as a step is replaced by its own steps; inside a
comma list its first step runs in the list's place and its later steps
follow the list. Named actions are expanded on a stack of our own, in the
order recursion would take, because a chain of thousands of named actions
is deeper than Python's stack; resolved bodies hold no cycles (a call that
would close one is E023 and left out).
"""
from __future__ import annotations


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
