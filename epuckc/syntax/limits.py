"""How deep an expression may nest: one limit for every stage.

The stages after the parser walk expressions recursively (the checker, the
lowering to C, the formatter, hover), and so does the C compiler, which
gets one nested call per operator. Rather than each of them failing at its
own depth (Python's recursion limit, or gcc's), the parser's statement gate
(parser.ModePlacer) refuses an expression nested deeper than MAX_DEPTH with
E056, the same in `check`, `compile` and the language server, and drops the
statement as it drops one with a syntax error. MAX_DEPTH is far above what
people write (a weighted sum of the eight IR readings is 8 deep, GCtronic's
demos stay under 10); tests/syntax/test_limits.py runs every stage at
exactly MAX_DEPTH, so that no stage may need more.

Depth counts operators, function calls and parentheses on the way from the
expression's root to its deepest leaf: `a + b + c` is 2 deep (the left
operand of the second `+` is the first), `abs((x))` is 2. An `if` action
counts IF_LEVELS levels, above everything in its branches (its conditions
and actions, and the `if`s inside): each stage walks a branch with a few
nested calls (the call, its branches, their steps), where an operator
costs one. So in `if a > 0 { if b > 0 { v = v + 1 } }` the `+` is 11 deep,
and 39 `if`s nest (`else if` does not nest: a chain of them is flat).
"""
from __future__ import annotations

from typing import Optional

from . import ast

MAX_DEPTH = 200
IF_LEVELS = 5

_NESTING = (ast.BinOp, ast.UnaryOp, ast.FuncCall, ast.Paren, ast.IfAction)


def _children(node):
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


def too_deep(statement) -> Optional[ast.Node]:
    """The outermost expression node of `statement` whose nesting passes
    MAX_DEPTH, or None. Iterative, so that no depth of input breaks it."""
    span = statement.span
    if span.line == span.end_line and span.end_column - span.column <= MAX_DEPTH:
        return None     # each level of nesting takes at least one character
    stack = [(statement, 0, None)]
    while stack:
        node, depth, root = stack.pop()
        if isinstance(node, _NESTING):
            depth += IF_LEVELS if node.__class__ is ast.IfAction else 1
            if root is None:
                root = node
            if depth > MAX_DEPTH:
                return root
        stack.extend((child, depth, root) for child in _children(node))
    return None
