"""The editor's walks over a statement (navigate.occurrences for rename,
references and highlights; hover's descent to the expression under the
cursor) against the syntax tree's own fields: a kind of node the walks do
not know (as `a[1:4]`, a slice, once was) loses its names from a rename
and its expressions from hover. Checked on every example and on a program
with every form of expression, so a node added to the grammar is found."""
from pathlib import Path

import pytest

from epuckc.base.source import SourceFile
from epuckc.diagnostics import Collector
from epuckc.ide import hover, navigate
from epuckc.syntax import ast
from epuckc.syntax.parser import parse

REPO = Path(__file__).resolve().parents[2]

EVERY_EXPRESSION = """\
const K = [1, 2, 3]
const N = 2
var a = [0, 0, 0]
var v = 0
on immediate do a = [K[0], -K[1], abs(K[2])], a[K[0]] = sum(K[1:]) + max(a[:N]),
    fill(a, K[0]), v = (v + 1) * 2 & ~N << 1,
    if v > N and not v < 0 { v = min(a[N:3]) } else { v = 0 }
"""

# Identifiers that are not a name of the program's: a built-in function's
# name, an extern's C parameters and their types, and the mode of a rule in
# a mode block (the block's head, a statement of its own, is the occurrence)
_NOT_NAMES = {("FuncCall", "name"), ("ParamDecl", "name"), ("ParamDecl", "type"),
              ("Rule", "mode")}


def _texts():
    for path in sorted((REPO / "examples").glob("*.epk")):
        yield path.name, path.read_text(encoding="utf-8")
    yield "every_expression.epk", EVERY_EXPRESSION


def _statements(name: str, text: str):
    source = SourceFile(name, text)
    diags = Collector(source)
    program = parse(source, diags)
    assert not diags.items, (name, diags.items)
    return program.statements


def _fields(node, parent=None, field=None):
    """Every node under `node` by the tree's own fields, with its parent's
    class name and the field it is in."""
    if isinstance(node, (list, tuple)):
        for item in node:
            yield from _fields(item, parent, field)
    elif isinstance(node, ast.Node):
        yield node, type(parent).__name__, field
        for name in node._fields:
            yield from _fields(getattr(node, name), node, name)


@pytest.mark.parametrize("name,text", list(_texts()), ids=lambda v: v if v.endswith(".epk") else "")
def test_every_name_in_a_statement_is_an_occurrence(name, text):
    for statement in _statements(name, text):
        found = {id(o.ident) for o in navigate.occurrences(statement)}
        missed = [(parent, field, node.name) for node, parent, field in _fields(statement)
                  if isinstance(node, ast.Ident) and id(node) not in found
                  and (parent, field) not in _NOT_NAMES]
        assert missed == [], f"{name}:{statement.span.line}: names no walk finds"


def _descent(node):
    yield node
    for child in hover._children(node):
        if child is not None:
            yield from _descent(child)


@pytest.mark.parametrize("name,text", list(_texts()), ids=lambda v: v if v.endswith(".epk") else "")
def test_hover_reaches_every_expression_of_a_rule(name, text):
    """Each expression, and each array or variable named in one (an
    element's, a slice's, an assignment's), is on the way down."""
    for statement in _statements(name, text):
        if not isinstance(statement, (ast.Rule, ast.ActionDef)):
            continue
        reached = {id(node) for node in _descent(statement)}
        missed = [(parent, field, type(node).__name__) for node, parent, field in
                  _fields(statement) if id(node) not in reached and (
                      isinstance(node, hover._EXPRESSIONS) or isinstance(node, ast.Ident)
                      and parent in ("Index", "Slice", "Assign"))
                  # a priority is a number, not a value; a sensor condition's
                  # threshold has the condition's hover (the sensor and its range)
                  and parent != "ConditionArg" and (parent, field) != ("Rule", "priority")]
        assert missed == [], f"{name}:{statement.span.line}: expressions hover cannot reach"


def test_a_slice_is_renamed_with_its_array():
    from epuckc.ide.incremental import Analyzer
    text = "const W = [1, 2, 3]\nvar s = 0\nevery 10 ms do s = sum(W[1:2])\n"
    analysis = Analyzer("s.epk").analyse(text)
    navigate.symbols(analysis)
    target = navigate.renameable(analysis, navigate.occurrence_at(analysis, 1, 7))
    edits = navigate.rename_edits(analysis, target, "V")
    assert sorted((span.line, span.column) for span, _ in edits) == [(1, 7), (3, 24)]
