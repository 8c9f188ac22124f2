"""Typed syntax tree of a rule file. Every node knows its span."""
from __future__ import annotations

from dataclasses import dataclass, field
from typing import Optional, Union

from .source import Span


@dataclass(frozen=True)
class Ident:
    name: str
    span: Span


@dataclass(frozen=True)
class Number:
    """A literal such as `-2.5 cm`; `text` is the number as written."""
    value: float
    text: str
    unit: Optional[str]
    unit_span: Optional[Span]
    span: Span


@dataclass(frozen=True)
class ConstRef:
    name: Ident
    negative: bool
    span: Span


Value = Union[Number, ConstRef]


@dataclass(frozen=True)
class NamedArg:
    name: Ident
    value: Value
    span: Span


@dataclass(frozen=True)
class PositionalArg:
    value: Value
    span: Span


@dataclass(frozen=True)
class ConditionArg:
    """`ir0 > 300` inside sensor(...)."""
    sensor: Ident
    op: str
    value: Value
    span: Span


Arg = Union[NamedArg, PositionalArg, ConditionArg]


@dataclass(frozen=True)
class Call:
    """An action or event named with optional arguments: `stop_motor`,
    `start_straight(300, 2 m)`. `args` is None without parentheses."""
    name: Ident
    args: Optional[tuple]
    span: Span


@dataclass(frozen=True)
class CancelCall:
    rule: Ident
    span: Span


@dataclass(frozen=True)
class EnterCall:
    """`enter MODE`: makes MODE the current mode."""
    mode: Ident
    span: Span


@dataclass(frozen=True)
class Step:
    """Calls that run together, in order, in one poll: `A, B`."""
    calls: tuple
    span: Span


@dataclass(frozen=True)
class ActionBody:
    """`step then step then ...`; a single step is a plain action list."""
    steps: tuple
    span: Span


@dataclass(frozen=True)
class Setting:
    name: Ident
    value: Value
    span: Span


@dataclass(frozen=True)
class RobotBlock:
    settings: tuple
    span: Span


@dataclass(frozen=True)
class ConstDef:
    name: Ident
    value: Value
    span: Span


@dataclass(frozen=True)
class ActionDef:
    name: Ident
    body: ActionBody
    span: Span


@dataclass(frozen=True)
class ParamDecl:
    name: Ident
    type: Ident
    span: Span


@dataclass(frozen=True)
class ExternDef:
    kind: str                 # "action" | "event"
    name: Ident
    params: tuple
    file: str
    file_span: Span
    span: Span


@dataclass(frozen=True)
class Rule:
    name: Optional[Ident]
    event: Call
    repeat: bool
    body: ActionBody
    span: Span
    priority: Optional[Value] = None    # `priority N`; None: 0
    mode: Optional[Ident] = None        # the mode whose block holds it


@dataclass(frozen=True)
class ModeDef:
    """`[initial] mode NAME { ... }`. Its rules are Rule statements of their
    own (in file order, with `mode` set); `span` is the head `mode NAME {`."""
    name: Ident
    initial: bool
    span: Span


@dataclass(frozen=True)
class ModeOpen:
    """The parser's view of a mode's head; parse() turns it into a ModeDef."""
    name: Ident
    initial: bool
    span: Span


@dataclass(frozen=True)
class ModeClose:
    span: Span


@dataclass(frozen=True)
class ModeEnd:
    """The `}` that closes a mode block: kept in the statements so that they
    match the lexer's statement chunks one to one (the formatter needs it)."""
    span: Span


Statement = Union[RobotBlock, ConstDef, ActionDef, ExternDef, Rule, ModeDef, ModeEnd]


@dataclass
class Program:
    file: str
    statements: list = field(default_factory=list)

    def of_type(self, kind):
        return [s for s in self.statements if isinstance(s, kind)]
