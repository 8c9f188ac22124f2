"""Typed syntax tree of a rule file. Every node knows its span.

The nodes behave like frozen dataclasses (fields by position or by name,
equality and hashing by type and fields, a `Name(field=...)` repr, and
assigning to a field raises FrozenInstanceError, see records.py), but they are
plain classes with `__slots__`: a 1,000-rule file makes some 20,000 nodes,
and a frozen dataclass costs four times as much to build, and its module
ten milliseconds to import. `_fields` lists a node's fields in order.

The parser builds nodes without calling `__init__` (see `maker`), which
is why the fields are also listed as `__slots__` and nothing else happens
in `__init__`.
"""
from __future__ import annotations

from typing import Optional, Union

from ..base.records import _MISSING, FrozenInstanceError, _LazyDataclassFields
from ..base.source import Span

_set = object.__setattr__


class Node:
    """The base of every node: its `_fields` are its `__slots__`. A
    statement's class says what it is in words (`described`, "a variable"),
    for messages about where it stands."""
    __slots__ = ()
    _fields: tuple = ()
    described: str = ""
    # Generic walkers (`dataclasses.fields(node)`, `hasattr(node,
    # "__dataclass_fields__")`, `dataclasses.replace`) work as on the
    # dataclasses these nodes were; made on first use (see records.py).
    __dataclass_fields__ = _LazyDataclassFields()

    def __init__(self, *args, **kwargs):
        fields = self._fields
        if len(args) > len(fields):
            raise TypeError(f"{type(self).__name__}() takes {len(fields)} arguments, "
                            f"{len(args)} were given")
        for name, value in zip(fields, args):
            _set(self, name, value)
        for name, value in kwargs.items():
            if name not in fields:
                raise TypeError(f"{type(self).__name__}() has no field {name!r}")
            if fields.index(name) < len(args):
                raise TypeError(f"{type(self).__name__}() got two values for {name!r}")
            _set(self, name, value)
        missing = [f for f in fields[len(args):] if f not in kwargs]
        if missing:
            raise TypeError(f"{type(self).__name__}() is missing {', '.join(missing)}")

    def __init_subclass__(cls, **kwargs):
        super().__init_subclass__(**kwargs)
        if cls.__slots__:           # not for a subclass that adds no field
            cls._fields = cls.__match_args__ = tuple(cls.__slots__)
            cls.__record_fields__ = tuple((f, _MISSING, _MISSING) for f in cls._fields)

    def __setattr__(self, name, value):
        raise FrozenInstanceError(f"cannot assign to field {name!r}")

    def __delattr__(self, name):
        raise FrozenInstanceError(f"cannot delete field {name!r}")

    # Equality and hashing walk the tree with a loop, not recursion, so that
    # an expression as deep as syntax/limits.py allows costs no stack.
    def __eq__(self, other):
        if type(other) is not type(self):
            return NotImplemented
        todo = [(self, other)]
        while todo:
            a, b = todo.pop()
            if type(a) is not type(b):
                return False
            if isinstance(a, Node):
                todo.extend((getattr(a, f), getattr(b, f)) for f in a._fields)
            elif type(a) is tuple:
                if len(a) != len(b):
                    return False
                todo.extend(zip(a, b))
            elif a != b:
                return False
        return True

    def __ne__(self, other):
        equal = self.__eq__(other)
        return equal if equal is NotImplemented else not equal

    def __hash__(self):
        flat, todo = [], [self]
        while todo:
            x = todo.pop()
            if isinstance(x, Node):
                flat.append(type(x).__name__)
                todo.extend(getattr(x, f) for f in x._fields)
            elif type(x) is tuple:
                flat.append(len(x))
                todo.extend(x)
            else:
                flat.append(x)
        return hash(tuple(flat))

    def __repr__(self):
        inside = ", ".join(f"{f}={getattr(self, f)!r}" for f in self._fields)
        return f"{type(self).__name__}({inside})"

    def __reduce__(self):
        return (type(self), tuple(getattr(self, f) for f in self._fields))


def maker(cls):
    """A constructor of `cls` for the parser, which makes some 20,000 nodes
    for 1,000 rules: `maker(cls)(*fields)` equals `cls(*fields)` (every
    field, by position, in `_fields` order) without `__init__`'s checks,
    and the node is as frozen. The C accelerator's (see accel.py) fills the
    slots in one call; the Python one sets each slot through its descriptor,
    around the class's frozen `__setattr__`."""
    from . import accel
    front = accel.front()
    if front is not None:
        return front.maker(cls)
    names = [f"f{i}" for i in range(len(cls._fields))]
    namespace = {"new": object.__new__, "cls": cls}
    body = []
    for name, field in zip(names, cls._fields):
        namespace[f"set_{name}"] = getattr(cls, field).__set__
        body.append(f"set_{name}(node, {name})")
    exec(f"def make({', '.join(names)}):\n    node = new(cls)\n    "
         + "".join(line + "\n    " for line in body) + "return node\n", namespace)
    return namespace["make"]


class Ident(Node):
    __slots__ = ("name", "span")
    name: str
    span: Span


class Number(Node):
    """A literal such as `-2.5 cm`; `text` is the number as written."""
    __slots__ = ("value", "text", "unit", "unit_span", "span")
    value: float
    text: str
    unit: Optional[str]
    unit_span: Optional[Span]
    span: Span


class ConstRef(Node):
    __slots__ = ("name", "negative", "span")
    name: Ident
    negative: bool
    span: Span


Value = Union[Number, ConstRef]


# ---- expressions ----------------------------------------------------------------
# A plain number or name (with its minus) stays a Number or ConstRef, as in
# a `value`; these nodes are made by the operators.

class BinOp(Node):
    """`left OP right`: OP is one of `+ - * / %`, a bitwise one (`& | ^ <<
    >>`), a comparison (`< <= > >= == !=`), `and` or `or`."""
    __slots__ = ("op", "left", "right", "span")
    op: str
    left: object
    right: object
    span: Span


class UnaryOp(Node):
    """`-x` (of something other than a number or a name), `~x` or `not x`."""
    __slots__ = ("op", "operand", "span")
    op: str
    operand: object
    span: Span


class FuncCall(Node):
    """`abs(x)`, `min(a, b)`, `clamp(x, lo, hi)`, `random(lo, hi)`: `args`
    are PositionalArg (or what else the user wrote, for the checker to
    report)."""
    __slots__ = ("name", "args", "span")
    name: Ident
    args: tuple
    span: Span


class Paren(Node):
    """`( expr )`, kept so that the formatter meets its parentheses."""
    __slots__ = ("expr", "span")
    expr: object
    span: Span


Expr = Union[Number, ConstRef, BinOp, UnaryOp, FuncCall, Paren]


class NamedArg(Node):
    __slots__ = ("name", "value", "span")
    name: Ident
    value: Value
    span: Span


class PositionalArg(Node):
    __slots__ = ("value", "span")
    value: Value
    span: Span


class ConditionArg(Node):
    """`ir0 > 300` inside sensor(...)."""
    __slots__ = ("sensor", "op", "value", "span")
    sensor: Ident
    op: str
    value: Value
    span: Span


Arg = Union[NamedArg, PositionalArg, ConditionArg]


class Call(Node):
    """An action or event named with optional arguments: `stop_motor`,
    `start_straight(300, 2 m)`. `args` is None without parentheses."""
    __slots__ = ("name", "args", "span")
    name: Ident
    args: Optional[tuple]
    span: Span


class CancelCall(Node):
    __slots__ = ("rule", "span")
    rule: Ident
    span: Span


class EnterCall(Node):
    """`enter MODE`: makes MODE the current mode."""
    __slots__ = ("mode", "span")
    mode: Ident
    span: Span


class Assign(Node):
    """`NAME = EXPR`, `NAME += EXPR`, `NAME -= EXPR`, and the same of an
    array's element `NAME[EXPR] = EXPR`: an action."""
    __slots__ = ("target", "op", "value", "span", "index")
    target: Ident
    op: str                 # "=", "+=" or "-="
    value: object
    span: Span
    index: Optional[object]     # the element's index expression, or None


class Index(Node):
    """`NAME[EXPR]`: an element of an array (a constant, a variable, or a
    reading of several sensors such as `ir`)."""
    __slots__ = ("name", "index", "span")
    name: Ident
    index: object
    span: Span


class Slice(Node):
    """`NAME[LO:HI]`: the elements LO..HI-1 of an array, where a whole
    array is read (`sum(a[1:4])`); LO and HI are constants (None where
    left out: from the first, to the last)."""
    __slots__ = ("name", "lo", "hi", "span")
    name: Ident
    lo: object
    hi: object
    span: Span


class ArrayLit(Node):
    """`[V, V, ...]`: the elements of an array constant or variable."""
    __slots__ = ("items", "span")
    items: tuple
    span: Span


class IfBranch(Node):
    """`if COND { ACTIONS }` (or `else if ...`): `body` runs when `condition`
    holds and no branch before it did."""
    __slots__ = ("condition", "body", "span")
    condition: object
    body: "ActionBody"
    span: Span


class IfAction(Node):
    """`if C { A } else if D { B } else { E }`: an action that runs the body
    of the first branch whose condition holds, else `otherwise` (the
    `else { ... }` body, or None). `branches` are IfBranch, in order."""
    __slots__ = ("branches", "otherwise", "span")
    branches: tuple
    otherwise: Optional["ActionBody"]
    span: Span


def calls_within(calls):
    """Every call of `calls` and, inside each IfAction, of its branches'
    bodies (any branch may run), in order; without recursion."""
    todo = list(reversed(calls))
    while todo:
        call = todo.pop()
        yield call
        if call.__class__ is IfAction:
            inner = [c for body in if_bodies(call) for step in body.steps for c in step.calls]
            todo.extend(reversed(inner))


def if_bodies(call: "IfAction") -> list:
    """The ActionBody of each branch of an `if`, its `else` last."""
    bodies = [b.body for b in call.branches]
    if call.otherwise is not None:
        bodies.append(call.otherwise)
    return bodies


class Step(Node):
    """Calls that run together, in order, in one poll: `A, B`."""
    __slots__ = ("calls", "span")
    calls: tuple
    span: Span


class ActionBody(Node):
    """`step then step then ...`; a single step is a plain action list."""
    __slots__ = ("steps", "span")
    steps: tuple
    span: Span


class Setting(Node):
    __slots__ = ("name", "value", "span")
    name: Ident
    value: Value
    span: Span


class RobotBlock(Node):
    described = "the robot block"
    __slots__ = ("settings", "span")
    settings: tuple
    span: Span


class ConstDef(Node):
    described = "a constant"
    __slots__ = ("name", "value", "span")
    name: Ident
    value: Value
    span: Span


class VarDef(Node):
    """`var NAME = VALUE`."""
    described = "a variable"
    __slots__ = ("name", "value", "span")
    name: Ident
    value: Value
    span: Span


class ActionDef(Node):
    described = "an action"
    __slots__ = ("name", "body", "span")
    name: Ident
    body: ActionBody
    span: Span


class ParamDecl(Node):
    __slots__ = ("name", "type", "span")
    name: Ident
    type: Ident
    span: Span


class ExternDef(Node):
    described = "an extern"
    __slots__ = ("kind", "name", "params", "file", "file_span", "span")
    kind: str                 # "action" | "event"
    name: Ident
    params: tuple
    file: str
    file_span: Span
    span: Span


class Rule(Node):
    """A rule. `trigger` is its head's keyword: `on EVENT`; `when COND`,
    `every D` and `after D` have `event` Call(`when`|`every`|`after`,
    (PositionalArg(COND or D),)) so that every rule has an event."""
    __slots__ = ("name", "event", "repeat", "body", "span", "priority", "mode", "guard",
                 "trigger")
    name: Optional[Ident]
    event: Call
    repeat: bool
    body: ActionBody
    span: Span
    priority: Optional[Value]           # `priority N`; None: 0
    mode: Optional[Ident]               # the mode whose block holds it, or None
    guard: Optional[object]             # `if COND`, or None
    trigger: str                        # "on", "when", "every" or "after"
    described = "a rule"

    def in_mode(self, mode: Ident) -> "Rule":
        """The same rule, inside the block of `mode`."""
        return Rule(self.name, self.event, self.repeat, self.body, self.span, self.priority,
                    mode, self.guard, self.trigger)


class ModeDef(Node):
    """`[initial] mode NAME { ... }`. Its rules are Rule statements of their
    own (in file order, with `mode` set); `span` is the head `mode NAME {`."""
    described = "a mode"
    __slots__ = ("name", "initial", "span")
    name: Ident
    initial: bool
    span: Span


class ModeOpen(Node):
    """The parser's view of a mode's head; parse() turns it into a ModeDef."""
    __slots__ = ("name", "initial", "span")
    name: Ident
    initial: bool
    span: Span


class ModeClose(Node):
    __slots__ = ("span",)
    span: Span


class ModeEnd(Node):
    """The `}` that closes a mode block: kept in the statements so that they
    match the lexer's statement chunks one to one (the formatter needs it)."""
    described = "the end of a mode"
    __slots__ = ("span",)
    span: Span


Statement = Union[RobotBlock, ConstDef, VarDef, ActionDef, ExternDef, Rule, ModeDef, ModeEnd]


class Program:
    """The statements of one file, in order (the only mutable node)."""
    __slots__ = ("file", "statements")

    def __init__(self, file: str, statements: Optional[list] = None):
        self.file = file
        self.statements = [] if statements is None else statements

    def __eq__(self, other):
        if type(other) is not Program:
            return NotImplemented
        return self.file == other.file and self.statements == other.statements

    __hash__ = None     # mutable, as the dataclass it replaces

    def __repr__(self):
        return f"Program(file={self.file!r}, statements={self.statements!r})"

    def of_type(self, kind):
        return [s for s in self.statements if isinstance(s, kind)]
