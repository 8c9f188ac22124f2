"""Where names are: occurrences, definitions, references, rename and the
outline, answered from an Analysis.

Everything here works on epuckc's own types (spans with lines and columns
from 1, the AST, the checker's tables); epuckc/ide/lsp.py translates to and
from the Language Server Protocol. Nothing here imports pygls.
"""
from __future__ import annotations

import re
from dataclasses import dataclass
from pathlib import Path
from typing import Iterator, Optional

from ..base.source import Span
from ..stdlib.table import ACTION_ALIASES, EVENT_ALIASES, STANDARD_ACTIONS, STANDARD_EVENTS
from ..syntax import ast
from ..syntax.lexer import KEYWORDS
from .incremental import Analysis

NAME_RE = re.compile(r"[A-Za-z_][A-Za-z0-9_]*\Z")

# Namespaces of user names (as the checker's `claim`): a const, an action
# (named or extern), an extern event, a rule, a mode.
CONST, ACTION, EVENT, RULE, MODE = "const", "action", "event", "rule", "mode"


@dataclass(frozen=True)
class Occurrence:
    """A name in the text: its namespace, the identifier (virtual span),
    whether it is the definition, and the statement it is in."""
    namespace: str
    ident: ast.Ident
    definition: bool
    statement: object
    role: str = ""          # "call", "event", "cancel", "ref", "param", "setting", "sensor"


def _value_names(value, statement) -> Iterator[Occurrence]:
    """The names in a value or an expression: constants and variables (one
    namespace, as the checker's), readings (which resolve to nothing)."""
    cls = value.__class__
    if cls is ast.ConstRef:
        yield Occurrence(CONST, value.name, False, statement, "ref")
    elif cls is ast.BinOp:
        yield from _value_names(value.left, statement)
        yield from _value_names(value.right, statement)
    elif cls is ast.UnaryOp:
        yield from _value_names(value.operand, statement)
    elif cls is ast.Paren:
        yield from _value_names(value.expr, statement)
    elif cls is ast.FuncCall:
        yield from _arg_names(value.args, statement)
    elif cls is ast.Index:          # an array's element: the array, then the index
        yield Occurrence(CONST, value.name, False, statement, "ref")
        yield from _value_names(value.index, statement)
    elif cls is ast.Slice:          # `a[1:4]`: the array, then its constant bounds
        yield Occurrence(CONST, value.name, False, statement, "ref")
        for bound in (value.lo, value.hi):
            if bound is not None:
                yield from _value_names(bound, statement)
    elif cls is ast.ArrayLit:
        for item in value.items:
            yield from _value_names(item, statement)


def _arg_names(args, statement) -> Iterator[Occurrence]:
    for arg in args or ():
        if isinstance(arg, ast.NamedArg):
            yield Occurrence("param", arg.name, False, statement, "param")
        elif isinstance(arg, ast.ConditionArg):
            yield Occurrence("sensor", arg.sensor, False, statement, "sensor")
        yield from _value_names(arg.value, statement)


def _body_names(body: ast.ActionBody, statement) -> Iterator[Occurrence]:
    for step in body.steps:
        for call in ast.calls_within(step.calls):       # inside `if`s too
            if isinstance(call, ast.IfAction):
                for branch in call.branches:
                    yield from _value_names(branch.condition, statement)
            elif isinstance(call, ast.CancelCall):
                yield Occurrence(RULE, call.rule, False, statement, "cancel")
            elif isinstance(call, ast.EnterCall):
                yield Occurrence(MODE, call.mode, False, statement, "enter")
            elif isinstance(call, ast.Assign):
                yield Occurrence(CONST, call.target, False, statement, "assign")
                if call.index is not None:
                    yield from _value_names(call.index, statement)
                yield from _value_names(call.value, statement)
            else:
                yield Occurrence(ACTION, call.name, False, statement, "call")
                yield from _arg_names(call.args, statement)


def occurrences(statement) -> Iterator[Occurrence]:
    """Every name in a statement, in order."""
    s = statement
    if isinstance(s, (ast.ConstDef, ast.VarDef)):
        yield Occurrence(CONST, s.name, True, s)
        yield from _value_names(s.value, s)
    elif isinstance(s, ast.ActionDef):
        yield Occurrence(ACTION, s.name, True, s)
        yield from _body_names(s.body, s)
    elif isinstance(s, ast.ExternDef):
        yield Occurrence(s.kind, s.name, True, s)
    elif isinstance(s, ast.Rule):
        if s.name is not None:
            yield Occurrence(RULE, s.name, True, s)
        yield Occurrence(EVENT, s.event.name, False, s, "event")
        yield from _arg_names(s.event.args, s)
        if s.guard is not None:
            yield from _value_names(s.guard, s)
        yield from _body_names(s.body, s)
    elif isinstance(s, ast.RobotBlock):
        for setting in s.settings:
            yield Occurrence("setting", setting.name, False, s, "setting")
            yield from _value_names(setting.value, s)
    elif isinstance(s, ast.ModeDef):
        yield Occurrence(MODE, s.name, True, s)


def _inside(span: Span, line: int, column: int) -> bool:
    """Is (line, column) on the span, its end included (a cursor just after
    a name is still on it)?"""
    return (span.line, span.column) <= (line, column) <= (span.end_line, span.end_column)


def statement_at(analysis: Analysis, line: int, column: int):
    """The statement at a real position, and the position in its lines."""
    vline, vcol = analysis.virtual(line, column)
    for s in analysis.statements_on(vline):
        if _inside(s.span, vline, vcol):
            return s, vline, vcol
    return None, vline, vcol


def occurrence_at(analysis: Analysis, line: int, column: int) -> Optional[Occurrence]:
    s, vline, vcol = statement_at(analysis, line, column)
    if s is None:
        return None
    for occ in occurrences(s):
        if _inside(occ.ident.span, vline, vcol):
            return occ
    return None


# ---- what a name refers to ----------------------------------------------------

@dataclass(frozen=True)
class Target:
    """What a name means: a user definition (its statement and identifier),
    or a standard action/event (`standard` is its canonical name)."""
    namespace: str
    name: str
    statement: object = None
    ident: Optional[ast.Ident] = None
    standard: Optional[str] = None


def definition(statement) -> Optional[Occurrence]:
    """The name a statement defines (the first of its occurrences, when it
    defines one), found without a walk over the rest of it."""
    s = statement
    if isinstance(s, (ast.ConstDef, ast.VarDef)):
        return Occurrence(CONST, s.name, True, s)
    if isinstance(s, ast.ActionDef):
        return Occurrence(ACTION, s.name, True, s)
    if isinstance(s, ast.ExternDef):
        return Occurrence(s.kind, s.name, True, s)
    if isinstance(s, ast.Rule):
        return Occurrence(RULE, s.name, True, s) if s.name is not None else None
    if isinstance(s, ast.ModeDef):
        return Occurrence(MODE, s.name, True, s)
    return None


def definitions(analysis: Analysis) -> dict:
    """(namespace, name) -> the first definition (as the checker keeps the
    first of a name defined twice). A statement's names other than the one
    it defines are not looked at: a hover on a name no check resolved (in
    a rule with an error) costs a look at each statement, not a walk over
    every name of the program."""
    found: dict = {}
    for s in analysis.program.statements:
        occ = definition(s)
        if occ is not None:
            found.setdefault((occ.namespace, occ.ident.name), occ)
    return found


def resolve(analysis: Analysis, occ: Occurrence) -> Optional[Target]:
    name = occ.ident.name
    defs = definitions(analysis)
    if occ.namespace == ACTION:
        canonical = ACTION_ALIASES.get(name, name)
        if canonical in STANDARD_ACTIONS:
            return Target(ACTION, name, standard=canonical)
    if occ.namespace == EVENT:
        canonical = EVENT_ALIASES.get(name, name)
        if canonical in STANDARD_EVENTS:
            return Target(EVENT, name, standard=canonical)
    d = defs.get((occ.namespace, name))
    if d is None:
        return None
    return Target(occ.namespace, name, d.statement, d.ident)


def references(analysis: Analysis, target: Target, include_definition: bool = True) -> list:
    """Every occurrence of the name that means `target`, in text order."""
    out = []
    for s in analysis.program.statements:
        for occ in occurrences(s):
            if occ.namespace != target.namespace or occ.ident.name != target.name:
                continue
            if occ.definition:
                # only the first definition is the one the uses refer to
                if occ.ident is target.ident and include_definition:
                    out.append(occ)
                continue
            out.append(occ)
    return out


def extern_location(analysis: Analysis, statement: ast.ExternDef,
                    base_dir: Optional[Path]) -> Optional[tuple]:
    """(path, line, column, end_column) of the C function of an extern:
    its definition in the C file, else its first mention, else the file's
    start; None when the file cannot be read."""
    if base_dir is None:
        return None
    path = (base_dir / statement.file)
    try:
        text = path.read_text(encoding="utf-8", errors="replace")
    except (OSError, ValueError):
        return None
    name = re.escape(statement.name.name)
    definition = re.compile(rf"\b{name}\s*\([^;{{}}]*\)\s*\{{")
    mention = re.compile(rf"\b{name}\b")
    m = definition.search(text) or mention.search(text)
    if m is None:
        return path, 1, 1, 1
    line = text.count("\n", 0, m.start()) + 1
    column = m.start() - (text.rfind("\n", 0, m.start()) + 1) + 1
    return path, line, column, column + len(statement.name.name)


# ---- rename -------------------------------------------------------------------

class RenameError(Exception):
    """Why a rename is refused (shown to the user)."""


def check_new_name(analysis: Analysis, target: Target, new: str):
    if not NAME_RE.match(new):
        raise RenameError(f"`{new}` is not a name: a name is a letter or `_`, then letters, "
                          "digits and `_` (ASCII)")
    if new in KEYWORDS:
        raise RenameError(f"`{new}` is a keyword")
    if target.namespace == ACTION and (new in STANDARD_ACTIONS or new in ACTION_ALIASES):
        raise RenameError(f"`{new}` is a standard action")
    if target.namespace == EVENT and (new in STANDARD_EVENTS or new in EVENT_ALIASES):
        raise RenameError(f"`{new}` is a standard event")
    if new != target.name and (target.namespace, new) in definitions(analysis):
        raise RenameError(f"there is already a {target.namespace} named `{new}`")


def renameable(analysis: Analysis, occ: Optional[Occurrence]) -> Target:
    """The user definition a rename at `occ` would rename, or RenameError."""
    if occ is None or occ.namespace not in (CONST, ACTION, EVENT, RULE):
        raise RenameError("only a constant, a variable, an action or a rule can be renamed here")
    target = resolve(analysis, occ)
    if target is None:
        raise RenameError(f"`{occ.ident.name}` is not defined in this file")
    if target.standard is not None:
        raise RenameError(f"`{occ.ident.name}` is a standard {occ.namespace}: it cannot be renamed")
    if isinstance(target.statement, ast.ExternDef):
        raise RenameError(f"`{occ.ident.name}` is a C function ({target.statement.file}): "
                          "rename it there too, by hand")
    return target


def rename_edits(analysis: Analysis, target: Target, new: str) -> list:
    """(real span, new text) of every occurrence."""
    check_new_name(analysis, target, new)
    return [(analysis.real(o.ident.span), new) for o in references(analysis, target)]


# ---- outline --------------------------------------------------------------------

@dataclass
class Symbol:
    name: str
    kind: str               # "robot", "const", "action", "extern action", "extern event", "rule"
    detail: str
    span: Span              # real
    selection: Span         # real


def _event_text(event: ast.Call, analysis: Analysis) -> str:
    return _text_of(analysis, event.span)


def _text_of(analysis: Analysis, span: Span) -> str:
    real = analysis.real(span)
    start = analysis.offset(real.line, real.column)
    end = analysis.offset(real.end_line, real.end_column)
    return " ".join(analysis.text[start:end].split())


def symbols(analysis: Analysis) -> list:
    out = []
    for s in analysis.program.statements:
        real = analysis.real(s.span)
        if isinstance(s, ast.RobotBlock):
            out.append(Symbol("robot", "robot", "", real, real))
        elif isinstance(s, ast.ConstDef):
            out.append(Symbol(s.name.name, "const", _text_of(analysis, s.value.span), real,
                              analysis.real(s.name.span)))
        elif isinstance(s, ast.VarDef):
            out.append(Symbol(s.name.name, "variable", _text_of(analysis, s.value.span), real,
                              analysis.real(s.name.span)))
        elif isinstance(s, ast.ActionDef):
            out.append(Symbol(s.name.name, "action", _text_of(analysis, s.body.span), real,
                              analysis.real(s.name.span)))
        elif isinstance(s, ast.ExternDef):
            out.append(Symbol(s.name.name, f"extern {s.kind}", f'from "{s.file}"', real,
                              analysis.real(s.name.span)))
        elif isinstance(s, ast.ModeDef):
            out.append(Symbol(s.name.name, "mode", "initial" if s.initial else "", real,
                              analysis.real(s.name.span)))
        elif isinstance(s, ast.Rule):
            on = ("on " if s.trigger == "on" else "") + _event_text(s.event, analysis) \
                + (" repeat" if s.repeat else "")
            if s.name is not None:
                out.append(Symbol(s.name.name, "rule", on, real, analysis.real(s.name.span)))
            else:
                out.append(Symbol(on, "rule", "", real, analysis.real(s.event.span)))
    return out


# ---- hover --------------------------------------------------------------------


# ---- completion ---------------------------------------------------------------


