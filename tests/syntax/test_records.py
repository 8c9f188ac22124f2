"""Records (epuckc/base/records.py) and AST nodes (epuckc/syntax/ast.py) behave as the
frozen dataclasses they replace, and answer to the dataclasses module."""
import copy
import dataclasses
import pickle

import pytest

from epuckc.syntax import ast
from epuckc.base.records import FrozenInstanceError, field, record
from epuckc.base.source import Span


@record(frozen=True)
class Point:
    """A frozen record with a default."""
    x: int
    y: int = 0


@dataclasses.dataclass(frozen=True)
class PointDC:
    x: int
    y: int = 0


@record
class Bag:
    name: str
    items: list = field(default_factory=list)


def test_construction_like_a_dataclass():
    assert Point(1) == Point(x=1, y=0) == Point(1, y=0)
    assert Point(1, 2).y == 2
    with pytest.raises(TypeError):
        Point()
    with pytest.raises(TypeError):
        Point(1, 2, 3)
    with pytest.raises(TypeError):
        Point(1, z=3)


def test_repr_eq_and_hash_like_a_dataclass():
    assert repr(Point(1, 2)).replace("Point", "PointDC") == repr(PointDC(1, 2)).split(".")[-1]
    assert Point(1, 2) != Point(2, 1)
    assert Point(1, 2) != PointDC(1, 2)           # another type is never equal
    assert hash(Point(1, 2)) == hash(Point(1, 2)) == hash(PointDC(1, 2))
    assert len({Point(1, 2), Point(1, 2), Point(3)}) == 2


def test_frozen_records_refuse_assignment():
    p = Point(1)
    with pytest.raises(FrozenInstanceError):
        p.x = 2
    with pytest.raises(AttributeError):
        del p.x
    assert p.x == 1


def test_mutable_records_with_a_factory():
    a, b = Bag("a"), Bag("b")
    a.items.append(1)
    assert b.items == [] and a.items == [1]
    a.name = "c"
    assert a == Bag("c", [1])
    with pytest.raises(TypeError):
        hash(a)


def test_the_dataclasses_module_understands_records():
    assert dataclasses.is_dataclass(Point(1))
    assert [f.name for f in dataclasses.fields(Bag)] == ["name", "items"]
    assert dataclasses.replace(Point(1, 2), y=5) == Point(1, 5)
    assert dataclasses.asdict(Bag("a", [1])) == {"name": "a", "items": [1]}
    assert copy.deepcopy(Bag("a", [1])) == Bag("a", [1])


def test_ast_nodes_behave_as_frozen_dataclasses():
    span = Span(1, 2, 1, 5)
    ident = ast.Ident("go", span)
    assert ident == ast.Ident(name="go", span=span) and ident != ast.Ident("stop", span)
    assert ident != ("go", span)
    assert hash(ident) == hash(ast.Ident("go", span))
    assert repr(ident) == "Ident(name='go', span=Span(line=1, column=2, end_line=1, end_column=5))"
    assert ast.Ident._fields == ("name", "span")
    with pytest.raises(FrozenInstanceError):
        ident.name = "x"
    with pytest.raises(TypeError):
        ast.Ident("go")
    call = ast.Call(ident, None, span)
    assert pickle.loads(pickle.dumps(call)) == call and copy.copy(call) == call
    # generic walkers written for the dataclasses still work
    assert hasattr(call, "__dataclass_fields__") and dataclasses.is_dataclass(call)
    assert [f.name for f in dataclasses.fields(call)] == ["name", "args", "span"]
    assert dataclasses.replace(call, args=()) == ast.Call(ident, (), span)
    assert dataclasses.asdict(ident) == {"name": "go", "span": span}


def test_parsed_nodes_are_frozen_and_of_the_public_classes():
    from epuckc.diagnostics import Collector
    from epuckc.syntax.parser import parse
    from epuckc.base.source import SourceFile
    source = SourceFile("x.epk", "on sensor(ir0 > 300) repeat do stop_motor, go\n")
    program = parse(source, Collector(source))
    rule = program.statements[0]
    assert type(rule) is ast.Rule and type(rule.event) is ast.Call
    assert type(rule.event.args[0]) is ast.ConditionArg
    assert type(rule.body.steps[0].calls[1].name) is ast.Ident
    with pytest.raises(FrozenInstanceError):
        rule.repeat = False
    assert rule == parse(source, Collector(source)).statements[0]
