"""What an editor asks about a rule file, answered from an Analysis.

Everything here works on epuckc's own types (spans with lines and columns
from 1, the AST, the checker's tables); epuckc/ide/lsp.py translates to and
from the Language Server Protocol. Nothing here imports pygls.
"""
from __future__ import annotations

import re
from dataclasses import dataclass
from pathlib import Path
from typing import Iterator, Optional

from ..syntax import ast
from ..check.messages import _shown
from ..diagnostics import Collector
from .incremental import Analysis
from ..syntax.lexer import KEYWORDS
from ..base.source import Span
from ..stdlib.table import (ACTION_ALIASES, CHOICE, EVENT_ALIASES, SENSOR_CONDITION_DOC, SENSOR_NAMES,
                     STANDARD_ACTIONS, STANDARD_EVENTS, Param, kind_name)
from ..stdlib.units import (ANGLE, ARTICLE, DISTANCE, DURATION, INT, KIND_UNITS, NATURAL_UNIT, SPEED,
                    UNITS)

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
    if isinstance(value, ast.ConstRef):
        yield Occurrence(CONST, value.name, False, statement, "ref")


def _arg_names(args, statement) -> Iterator[Occurrence]:
    for arg in args or ():
        if isinstance(arg, ast.NamedArg):
            yield Occurrence("param", arg.name, False, statement, "param")
        elif isinstance(arg, ast.ConditionArg):
            yield Occurrence("sensor", arg.sensor, False, statement, "sensor")
        yield from _value_names(arg.value, statement)


def _body_names(body: ast.ActionBody, statement) -> Iterator[Occurrence]:
    for step in body.steps:
        for call in step.calls:
            if isinstance(call, ast.CancelCall):
                yield Occurrence(RULE, call.rule, False, statement, "cancel")
            elif isinstance(call, ast.EnterCall):
                yield Occurrence(MODE, call.mode, False, statement, "enter")
            else:
                yield Occurrence(ACTION, call.name, False, statement, "call")
                yield from _arg_names(call.args, statement)


def occurrences(statement) -> Iterator[Occurrence]:
    """Every name in a statement, in order."""
    s = statement
    if isinstance(s, ast.ConstDef):
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
    for s in analysis.program.statements:
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


def definitions(analysis: Analysis) -> dict:
    """(namespace, name) -> the first definition (as the checker keeps the
    first of a name defined twice)."""
    found: dict = {}
    for s in analysis.program.statements:
        for occ in occurrences(s):
            if occ.definition:
                found.setdefault((occ.namespace, occ.ident.name), occ)
                break
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
        raise RenameError("only a constant, an action or a rule can be renamed here")
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
            on = "on " + _event_text(s.event, analysis) + (" repeat" if s.repeat else "")
            if s.name is not None:
                out.append(Symbol(s.name.name, "rule", on, real, analysis.real(s.name.span)))
            else:
                out.append(Symbol(on, "rule", "", real, analysis.real(s.event.span)))
    return out


# ---- hover --------------------------------------------------------------------

def _units_of(kind: str) -> str:
    if kind == INT:
        return "a plain number"
    return f"{', '.join(KIND_UNITS[kind])}; a bare number is {NATURAL_UNIT[kind]}"


def _param_line(p) -> str:
    if getattr(p, "choices", None) is not None:
        text = f"- `{p.name}`: {p.choices.what}, one of {p.choices.describe()}"
        return text + (f", {p.doc}" if p.doc else "")
    text = f"- `{p.name}`: {p.kind} ({_units_of(p.kind)})"
    if getattr(p, "doc", ""):
        text += f", {p.doc}"
    if getattr(p, "range", ""):
        text += f"; range {p.range}"
    return text


def _spec_markdown(spec, what: str) -> str:
    out = [f"```epuck\n{spec.signature}\n```", f"Standard {what}: {spec.doc}."]
    if spec.params is None:
        out.append(f"Conditions: {getattr(spec, 'conditions_doc', '') or SENSOR_CONDITION_DOC}.")
    elif spec.params:
        out.append("\n".join(_param_line(p) for p in spec.params))
    return "\n\n".join(out)


def _statement_text(analysis: Analysis, statement) -> str:
    return _text_of(analysis, statement.span)


def _line_of(analysis: Analysis, statement) -> int:
    return analysis.real(statement.span).line


def _call_params(analysis: Analysis, occ_statement, call) -> Optional[tuple]:
    """The parameters of the action or event that `call` names."""
    name = call.name.name
    if isinstance(occ_statement, ast.Rule) and call is occ_statement.event:
        spec = STANDARD_EVENTS.get(EVENT_ALIASES.get(name, name))
        if spec is not None:
            return spec.params
        info = analysis.checker.externs.get(name)
        return info.params if info is not None and info.kind == "event" else None
    spec = STANDARD_ACTIONS.get(ACTION_ALIASES.get(name, name))
    if spec is not None:
        return spec.params
    info = analysis.checker.externs.get(name)
    return info.params if info is not None and info.kind == "action" else None


def _calls(statement) -> Iterator:
    if isinstance(statement, ast.Rule):
        yield statement.event
    body = getattr(statement, "body", None)
    if isinstance(body, ast.ActionBody):
        for step in body.steps:
            for call in step.calls:
                if isinstance(call, ast.Call):
                    yield call


def bind(params, args) -> dict:
    """id(arg) -> the parameter it gives, as the checker binds them
    (positional in order, then by name)."""
    out, position = {}, 0
    by_name = {p.name: p for p in params}
    for arg in args or ():
        if isinstance(arg, ast.NamedArg):
            if arg.name.name in by_name:
                out[id(arg)] = by_name[arg.name.name]
        elif isinstance(arg, ast.PositionalArg):
            if position < len(params):
                out[id(arg)] = params[position]
            position += 1
    return out


def on_robot(analysis: Analysis, value, param) -> Optional[str]:
    """What a value becomes on the robot where `param` wants it, computed
    by the checker's own conversion ("50 cm = 3,882 steps at this robot's
    geometry"); None when the value is not valid there."""
    if param.kind == CHOICE:
        return None         # a name of the set: nothing to convert
    checker = analysis.checker
    saved, saved_used = checker.diags, set(checker.const_used)
    checker.diags = Collector(checker.diags.source)
    try:
        q = checker._value(value, param.kind, param.name)
        v = checker._to_runtime(q, param, value) if q is not None else None
    finally:
        checker.diags, checker.const_used = saved, saved_used
    if v is None:
        return None
    shown = _shown(value)
    geo = checker.geo
    if param.kind == DISTANCE:
        mm = q.mm(geo)
        extra = f" ({mm:,.1f} mm)" if q.in_steps else ""
        return f"{shown} = {v:,} steps{extra} at this robot's geometry"
    if param.kind == SPEED:
        return f"{shown} = {v:,} steps/s at this robot's geometry ({v * geo.step_mm:,.1f} mm/s)"
    if param.kind == ANGLE:
        return f"{shown} = {v:,} deg"
    if param.kind == DURATION:
        return f"{shown} = {v:,} ms"
    return f"{shown} = {v:,}"


def _const_markdown(analysis: Analysis, const: ast.ConstDef) -> str:
    out = [f"```epuck\n{_statement_text(analysis, const)}\n```"]
    value = const.value
    if isinstance(value, ast.Number) and value.unit in UNITS:
        kind = UNITS[value.unit][0]
        becomes = on_robot(analysis, value, Param(const.name.name, kind))
        if becomes:
            out.append(f"{ARTICLE[kind].capitalize()}: {becomes}.")
    elif isinstance(value, ast.Number):
        out.append("A bare number: it takes the natural unit of where it is used "
                   f"({', '.join(NATURAL_UNIT[k] for k in (DISTANCE, SPEED, ANGLE, DURATION))}).")
    return "\n\n".join(out)


def hover(analysis: Analysis, line: int, column: int) -> Optional[tuple]:
    """(markdown, real span of what it is about), or None."""
    s, vline, vcol = statement_at(analysis, line, column)
    if s is None:
        return None
    # an argument: its parameter and what its value becomes on the robot
    for call in _calls(s):
        for arg in call.args or ():
            if not _inside(arg.span, vline, vcol) or isinstance(arg, ast.ConditionArg):
                continue
            params = _call_params(analysis, s, call)
            param = bind(params, call.args).get(id(arg)) if params else None
            if param is None:
                break
            out = [_param_line(param).lstrip("- ")]
            becomes = on_robot(analysis, arg.value, param)
            if becomes:
                out.append(becomes)
            if isinstance(arg.value, ast.ConstRef):
                const = analysis.checker.consts.get(arg.value.name.name)
                if const is not None:
                    out.append(f"```epuck\n{_statement_text(analysis, const)}\n```")
            return "\n\n".join(out), analysis.real(arg.span)
    occ = None
    for o in occurrences(s):
        if _inside(o.ident.span, vline, vcol):
            occ = o
            break
    if occ is None:
        return None
    span = analysis.real(occ.ident.span)
    if occ.namespace == "sensor":
        return f"Proximity sensor. {SENSOR_CONDITION_DOC}.", span
    target = resolve(analysis, occ)
    if target is None:
        return None
    if target.standard is not None:
        spec = (STANDARD_ACTIONS if target.namespace == ACTION else STANDARD_EVENTS)[target.standard]
        return _spec_markdown(spec, target.namespace), span
    d = target.statement
    if isinstance(d, ast.ConstDef):
        return _const_markdown(analysis, d), span
    where = f"line {_line_of(analysis, d)}"
    if isinstance(d, ast.Rule):
        return f"```epuck\n{_statement_text(analysis, d)}\n```\n\nRule `{d.name.name}`, {where}.", span
    if isinstance(d, ast.ActionDef):
        return f"```epuck\n{_statement_text(analysis, d)}\n```\n\nNamed action, {where}.", span
    if isinstance(d, ast.ModeDef):
        initial = " (the initial mode)" if d.name.name == analysis.checker.initial_mode else ""
        return f"```epuck\n{_statement_text(analysis, d)}\n```\n\nMode `{d.name.name}`{initial}, {where}.", span
    if isinstance(d, ast.ExternDef):
        params = "\n".join(_param_line(Param(p.name.name, p.type.name)) for p in d.params)
        text = f"```epuck\n{_statement_text(analysis, d)}\n```\n\nExtern {d.kind} in C, {where}."
        return text + ("\n\n" + params if params else ""), span
    return None


# ---- completion ---------------------------------------------------------------

@dataclass(frozen=True)
class Completion:
    label: str
    kind: str               # "keyword", "action", "event", "param", "unit", "const", "rule", "sensor"
    detail: str = ""
    insert: Optional[str] = None
    doc: str = ""


_TERMINAL_KEYWORD = {t: k for k, t in KEYWORDS.items()}


class _Probe:
    """A token no grammar rule accepts: parsing up to it yields what could
    come there instead."""
    type = "<cursor>"
    value = ""
    line = column = end_line = end_column = 1
    start_pos = end_pos = 0
    after_bad = False


def _expected(tokens) -> Optional[set]:
    from ..syntax import lalr
    from ..syntax.parser import _CALLBACKS, _tables
    try:
        lalr.parse(_tables(), list(tokens) + [_Probe()], _CALLBACKS, meta=Span)
    except lalr.ParseError as exc:
        if exc.token.type == "<cursor>":
            return set(exc.expected)
        return None         # a syntax error before the cursor
    return None


def _enclosing_call(tokens) -> Optional[tuple]:
    """(name token, arguments so far as token lists) of the innermost call
    whose `(` is still open at the end of `tokens`."""
    stack = []
    for i, tok in enumerate(tokens):
        if tok.type == "_LPAR":
            stack.append(i)
        elif tok.type == "_RPAR" and stack:
            stack.pop()
    if not stack or stack[-1] == 0 or tokens[stack[-1] - 1].type != "NAME":
        return None
    open_at = stack[-1]
    args, current = [], []
    for tok in tokens[open_at + 1:]:
        if tok.type == "_COMMA":
            args.append(current)
            current = []
        else:
            current.append(tok)
    args.append(current)
    return tokens[open_at - 1], args


def _params_for(analysis: Analysis, name: str, is_event: bool):
    if is_event:
        spec = STANDARD_EVENTS.get(EVENT_ALIASES.get(name, name))
        if spec is not None:
            return spec.params or ()
    else:
        spec = STANDARD_ACTIONS.get(ACTION_ALIASES.get(name, name))
        if spec is not None:
            return spec.params
    info = analysis.checker.externs.get(name)
    if info is not None and info.kind == ("event" if is_event else "action"):
        return info.params
    return ()


def _action_items(analysis: Analysis) -> list:
    items = [Completion(a.name, "action", a.signature, doc=a.doc) for a in STANDARD_ACTIONS.values()]
    for name, node in analysis.checker.actions.items():
        items.append(Completion(name, "action", "named action"))
    for name, info in analysis.checker.externs.items():
        if info.kind == "action":
            items.append(Completion(name, "action", f'extern action from "{info.file}"'))
    return items


def _event_items(analysis: Analysis) -> list:
    # (`enter` is offered as the keyword it is)
    items = [Completion(e.name, "event", e.signature, doc=e.doc) for e in STANDARD_EVENTS.values()
             if e.name not in KEYWORDS]
    for name, info in analysis.checker.externs.items():
        if info.kind == "event":
            items.append(Completion(name, "event", f'extern event from "{info.file}"'))
    return items


def _const_items(analysis: Analysis, kind: Optional[str] = None) -> list:
    out = []
    for name, const in analysis.checker.consts.items():
        value = const.value
        if kind is not None and isinstance(value, ast.Number) and value.unit in UNITS \
                and UNITS[value.unit][0] != kind:
            continue            # a constant of another kind would be E019
        out.append(Completion(name, "const", _shown(value)))
    return out


def _unit_items(kind: Optional[str]) -> list:
    kinds = [kind] if kind in KIND_UNITS else list(KIND_UNITS)
    return [Completion(u, "unit", k) for k in kinds for u in KIND_UNITS[k]]


def completions(analysis: Analysis, line: int, column: int) -> list:
    """What may be typed at a real position (the word being typed there is
    left out of the context; editors filter by it)."""
    from ..syntax.lexer import iter_tokens
    from ..base.source import SourceFile
    offset = analysis.offset(line, column)
    start = analysis.starts[analysis.index_at(offset)] if analysis.starts else 0
    prefix = analysis.text[start:offset]
    source = SourceFile("", prefix)
    tokens = list(iter_tokens(source, Collector(source)))
    if tokens and (prefix[-1:].isalnum() or prefix[-1:] == "_") and (
            tokens[-1].type in ("NAME", "NUMBER") or tokens[-1].type in _TERMINAL_KEYWORD):
        tokens.pop()        # the word (or number) being typed
    expected = _expected(tokens)
    if expected is None:
        if not tokens:
            expected = {t for t in _TERMINAL_KEYWORD} & {"_ROBOT", "_CONST", "_ACTION",
                                                        "_EXTERN", "_ON", "_RULE"}
        else:
            return []
    items = []
    prev = tokens[-1] if tokens else None
    prev_type = prev.type if prev is not None else None
    if "$END" in expected:      # the statement may end here: another may start
        expected |= {"_ROBOT", "_CONST", "_ACTION", "_EXTERN", "_ON", "_RULE"}
    for t in sorted(expected):
        if t in _TERMINAL_KEYWORD:
            items.append(Completion(_TERMINAL_KEYWORD[t], "keyword"))
    if "NAME" not in expected:
        return items
    call = _enclosing_call(tokens)
    if prev_type == "_ON":
        return items + _event_items(analysis)
    if prev_type == "_CANCEL":
        return items + [Completion(name, "rule", "on line "
                                   f"{_line_of(analysis, rule)}")
                        for name, rule in analysis.checker.rule_names.items()]
    if prev_type == "NUMBER":
        kind = None
        if call is not None:
            kind = _arg_kind(analysis, tokens, call)
        return items + _unit_items(kind)
    if call is not None and prev_type in ("_LPAR", "_COMMA"):
        name_tok, args = call
        is_event = _is_event_call(tokens, name_tok)
        if EVENT_ALIASES.get(name_tok.value, name_tok.value) in ("sensor", "ambient") and is_event:
            given = {a[0].value for a in args[:-1] if a}
            return items + [Completion(s, "sensor", "proximity sensor") for s in SENSOR_NAMES
                            if s not in given]
        params = _params_for(analysis, name_tok.value, is_event)
        given = {a[0].value for a in args[:-1] if len(a) >= 2 and a[1].type == "_COLON"}
        positional = sum(1 for a in args[:-1] if a and not (len(a) >= 2 and a[1].type == "_COLON"))
        given |= {p.name for p in params[:positional]}
        out = [Completion(p.name, "param", kind_name(p), insert=f"{p.name}: ",
                          doc=getattr(p, "doc", "")) for p in params if p.name not in given]
        if any(len(a) >= 2 and a[1].type == "_COLON" for a in args[:-1]):
            return items + out      # after a named argument, only named ones [E021]
        param = params[positional] if positional < len(params) else None
        if param is not None and param.kind == CHOICE:
            return items + out + _choice_items(param)
        return items + out + _const_items(analysis, param.kind if param else None)
    if call is not None and prev_type in ("_COLON", "MINUS"):
        param = _arg_param(analysis, tokens, call)
        if param is not None and param.kind == CHOICE:
            return items + _choice_items(param)
        return items + _const_items(analysis, _arg_kind(analysis, tokens, call))
    if prev_type == "_ENTER":
        return items + [Completion(name, "const", "mode") for name in analysis.checker.modes]
    if prev_type in ("_DO", "_THEN") or (prev_type == "_EQUAL" and tokens[0].type == "_ACTION") \
            or (prev_type == "_COMMA" and call is None and any(t.type == "_DO" for t in tokens)):
        return items + _action_items(analysis)
    if prev_type in ("_COLON", "_EQUAL", "MINUS"):
        return items + _const_items(analysis)
    return items


def _is_event_call(tokens, name_tok) -> bool:
    """Is this call the event of a rule (`on NAME(`)?"""
    i = next(i for i, t in enumerate(tokens) if t is name_tok)
    return i > 0 and tokens[i - 1].type == "_ON"


def _arg_kind(analysis: Analysis, tokens, call) -> Optional[str]:
    """The kind of the parameter the argument being typed gives."""
    param = _arg_param(analysis, tokens, call)
    return param.kind if param is not None else None


def _arg_param(analysis: Analysis, tokens, call):
    """The parameter the argument being typed gives, or None."""
    name_tok, args = call
    params = _params_for(analysis, name_tok.value, _is_event_call(tokens, name_tok)) or ()
    current = args[-1]
    if len(current) >= 2 and current[1].type == "_COLON":
        return next((p for p in params if p.name == current[0].value), None)
    if any(len(a) >= 2 and a[1].type == "_COLON" for a in args[:-1]):
        return None
    index = len(args) - 1
    return params[index] if index < len(params) else None


def _choice_items(param) -> list:
    """The names an enumerated parameter takes (LEDs, sounds, keys)."""
    return [Completion(c.name, "const", param.choices.what, doc=c.doc)
            for c in param.choices.values]
