"""How deep a statement may nest: one limit for every stage and every kind
of nesting, measured on the syntax tree's shape.

The stages after the parser walk the tree recursively (the checker, the
lowering to C, the formatter, the language server's hover and completion),
and so does the C compiler. Rather than each of them failing at its own
depth (Python's recursion limit, or gcc's), the parser's statement gate
(parser.ModePlacer, the same for the Python and the C front end) refuses a
statement whose tree is deeper than MAX_DEPTH with E056, the same in
`check`, `compile` and the language server, and drops the statement as it
drops one with a syntax error.

Depth is the number of nodes on the longest path from the statement down
to a leaf, whatever the nodes are (`children` knows no node kind): every
operator, parenthesis, index, function call and each of its arguments, an
`if`, each of its branches, a branch's actions and their step is a level,
and so will be the nodes of constructs the grammar gains later. `v = a + b
+ c` in `every 10 ms do ...` is 8 deep (the rule, its actions, the step,
the assignment, the two `+`, then `a` and its name); a sum of n terms,
n nested calls, n nested indexes or n nested `if`s costs about n, 2n, n
and 4n levels. MAX_DEPTH is far above what people write (a weighted sum of
the eight IR readings is 14 deep) and leaves every stage room to spare:
tests/syntax/test_limits.py runs each shape, and mixtures, through every
stage at exactly MAX_DEPTH with a stack already in use, and one past it.

Named actions are spliced where they are called (check/splice.py), so an
`if` in an action called in an `if`'s branch nests in the C and in
lowering though no statement nests it: the checker measures each action
once spliced (`depth_past` with `inserted`, check/names.py) and reports a
call that takes its statement past MAX_DEPTH with E056 too.
"""
from __future__ import annotations

from typing import Callable, Optional

from . import ast
from ..diagnostics import Collector, Note

MAX_DEPTH = 200

# A single-line statement `width` characters wide is at most width + SLACK
# deep: on a path, each node but the wrappers takes a character of its own
# (an operator, a parenthesis, a keyword), a wrapper (a step, an argument,
# an `if`'s branch) at most three in a row, and every nesting goes through
# characters; tests/syntax/test_depth_property.py holds every generated
# statement to it. A statement that narrow needs no walk.
SLACK = 8


def children(node):
    """The nodes directly below `node` (any node: statements hold tuples of
    nodes, and expressions sit in calls, steps and guards)."""
    for field in node._fields:
        value = getattr(node, field)
        if isinstance(value, ast.Node):
            yield value
        elif isinstance(value, tuple):
            for item in value:
                if isinstance(item, ast.Node):
                    yield item


def narrow(statement, limit: int) -> bool:
    """Whether `statement` is surely no deeper than `limit` (one line,
    narrow enough), without walking it."""
    span = statement.span
    return span.line == span.end_line and span.end_column - span.column + SLACK <= limit


class Deep:
    """A statement deeper than its limit: the node where a path first
    passes it (`at`, the one to show: see `shown`), the depth there, and
    the statement's whole depth."""
    __slots__ = ("at", "depth", "height")

    def __init__(self, at, depth: int, height: int):
        self.at, self.depth, self.height = at, depth, height


# (for messages only: where a path passes the limit is shown at the
# expression or action around it, not at the parts of the tree that only
# hold others; any other node, a new construct's too, is shown as it is)
_HOLDERS = (ast.ActionBody, ast.Step, ast.IfBranch, ast.PositionalArg, ast.NamedArg,
            ast.ConditionArg, ast.Ident)


def measure(node, limit: Optional[int] = MAX_DEPTH,
            inserted: Optional[Callable] = None) -> tuple:
    """(The depth of `node`: the number of nodes on its longest path down,
    Deep when a path passes `limit` levels (the first such path, left to
    right; never with limit None), else None). `inserted(node)`, when it
    gives a number, is the depth of what stands in for `node` (a named
    action's call: its body spliced in), counted instead of the node's own
    subtree. Iterative, so that no depth of input breaks it."""
    first, height = None, 0
    stack = [(node, 1, ())]
    while stack:
        node, depth, up = stack.pop()
        extra = inserted(node) if inserted is not None else None
        if extra is not None:
            reach = depth - 1 + extra
            if reach > height:
                height = reach
            if first is None and limit is not None and reach > limit:
                first = (node, up, limit + 1)
            continue
        if depth > height:
            height = depth
        if first is None and limit is not None and depth > limit:
            first = (node, up, depth)
        kids = list(children(node))
        if kids:
            below = (node, up) if first is None else ()
            stack.extend((child, depth + 1, below) for child in reversed(kids))
    if first is None:
        return height, None
    node, up, depth = first
    return height, Deep(shown(node, up), depth, height)


def depth_past(statement, limit: int = MAX_DEPTH,
               inserted: Optional[Callable] = None) -> Optional[Deep]:
    """Deep when a path from `statement` down passes `limit` levels, else
    None (see measure)."""
    return measure(statement, limit, inserted)[1]


def shown(node, up: tuple):
    """`node`, or the nearest node above it (`up`: (parent, its up)) that is
    not one that only holds others."""
    while isinstance(node, _HOLDERS) and up:
        node, up = up
    return node


def too_deep(statement) -> Optional[Deep]:
    """The syntax gate's question: Deep when `statement` passes MAX_DEPTH."""
    if narrow(statement, MAX_DEPTH):
        return None
    return depth_past(statement)


def what(node) -> str:
    """A node in the words of a message about its depth."""
    if node.__class__ is ast.IfAction:
        return "`if`"
    if isinstance(node, (ast.Call, ast.Assign, ast.CancelCall, ast.EnterCall)):
        return "action"
    return "expression"


_LEVELS = ("each operator, parenthesis, index, call and argument, `if`, branch and step is a "
           "level (docs/language.md, section 2.9)")


def _noun(statement) -> str:
    return (statement.described or "a statement").split(" ", 1)[1]


def report_too_deep(diags: Collector, statement, deep: Deep) -> None:
    """E056 for a statement deeper than MAX_DEPTH, at the expression or
    action where its nesting first passes the limit."""
    thing = what(deep.at)
    if thing == "`if`":
        help = ("join nested conditions with `and`, or use `else if`, which does not nest "
                "however long the chain")
    else:
        help = "compute a part of it into a variable first (`part = ...`), then use the variable"
    diags.error("E056", deep.at.span,
                f"this {thing} is nested too deeply: its {_noun(statement)} is {deep.height} "
                f"levels deep, more than {MAX_DEPTH}", help=f"{help}; {_LEVELS}")


def report_spliced(diags: Collector, statement, deep: Deep, action) -> None:
    """E056 for a call of a named action (`action`: its ActionDef) whose body,
    spliced in where it is called, takes `statement` past MAX_DEPTH."""
    name = action.name.name
    diags.error("E056", deep.at.span,
                f"`{name}` nests too deeply here: spliced in where it is called, its actions "
                f"make this {_noun(statement)} {deep.height} levels deep, more than {MAX_DEPTH}",
                help="a named action runs in the place of its call, so the `if`s in it nest "
                     "inside the `if` that calls it: call it from outside the `if` (or from a "
                     f"rule of its own), or join nested conditions with `and`; {_LEVELS}",
                notes=[Note(f"`{name}` is defined here", action.name.span)])
