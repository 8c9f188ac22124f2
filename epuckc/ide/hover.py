"""Hover: what a name, an argument or a unit means, from the standard table
and the program's own definitions, as markdown."""
from __future__ import annotations

from typing import Iterator, Optional

from ..check.messages import _shown
from ..stdlib.table import (ACTION_ALIASES, AGGREGATES, CHOICE, EVENT_ALIASES, FUNCTIONS,
                            READING_ARRAYS, SENSOR_CONDITION_DOC, STANDARD_ACTIONS, STANDARD_EVENTS,
                            STANDARD_READINGS, Param)
from ..stdlib.units import (ANGLE, ARTICLE, DISTANCE, DURATION, INT, KIND_UNITS, KINDS,
                            NATURAL_UNIT, SPEED, UNITS)
from ..syntax import ast
from .incremental import Analysis
from .navigate import ACTION, _inside, _text_of, occurrences, resolve, statement_at


def _units_of(kind: str) -> str:
    if kind == INT:
        return "a plain number"
    if kind not in KIND_UNITS:          # `condition`: a kind without units
        return "true or false" if kind == "condition" else kind
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
            for call in ast.calls_within(step.calls):   # inside `if`s too
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
    if param.kind == CHOICE or param.kind not in KINDS:
        return None         # a name of the set, `fill`'s array: nothing to convert
    if not isinstance(value, (ast.Number, ast.ConstRef)):
        return None         # an expression: its hover gives its unit and interval
    checker = analysis.checker
    found = checker.converted(value, param)
    if found is None or found[1] is None:
        return None
    q, v = found
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


_EXPRESSIONS = (ast.BinOp, ast.UnaryOp, ast.FuncCall, ast.Paren, ast.ConstRef, ast.Number,
                ast.Index)


def _children(node) -> Iterator:
    """The expressions directly inside a node of a statement."""
    if isinstance(node, ast.Rule):
        yield node.event
        if node.guard is not None:
            yield node.guard
        yield node.body
    elif isinstance(node, ast.ActionBody):
        for step in node.steps:
            yield from step.calls
    elif isinstance(node, (ast.Call, ast.FuncCall)):
        for arg in node.args or ():
            if isinstance(arg, (ast.NamedArg, ast.PositionalArg)):
                yield arg.value
    elif isinstance(node, ast.Assign):
        yield node.target
        if node.index is not None:
            yield node.index
        yield node.value
    elif isinstance(node, ast.Index):
        yield node.name
        yield node.index
    elif isinstance(node, ast.Slice):
        yield node.name
        yield from (bound for bound in (node.lo, node.hi) if bound is not None)
    elif isinstance(node, ast.ArrayLit):
        yield from node.items
    elif isinstance(node, ast.IfAction):
        for branch in node.branches:
            yield branch.condition
            yield branch.body
        if node.otherwise is not None:
            yield node.otherwise
    elif isinstance(node, ast.ActionDef):
        yield node.body
    elif isinstance(node, ast.BinOp):
        yield node.left
        yield node.right
    elif isinstance(node, ast.UnaryOp):
        yield node.operand
    elif isinstance(node, ast.Paren):
        yield node.expr


def _expression_at(statement, line: int, column: int):
    """The innermost expression (or assigned variable) at a position."""
    found, node = None, statement
    while node is not None:
        inner = None
        for child in _children(node):
            if child is not None and _inside(child.span, line, column):
                inner = child
                break
        if inner is None:
            break
        if isinstance(inner, _EXPRESSIONS + (ast.Ident,)):
            found = inner
        node = inner
    return found


def _kind_words(kind: str) -> str:
    from ..check.messages import KIND_WORDS
    return KIND_WORDS.get(kind, kind)


def _expression_hover(analysis: Analysis, node) -> Optional[str]:
    """A variable, a reading, or an expression: its unit and its interval."""
    checker = analysis.checker
    name = node.name if isinstance(node, ast.Ident) else \
        node.name.name if isinstance(node, ast.ConstRef) else None
    if name is not None and name not in checker.consts:
        info = checker.vars.get(name)
        if info is not None and info.size:
            return (f"```epuck\nvar {name}\n```\n\nArray variable of {info.size} elements: "
                    f"{_kind_words(info.kind)}, [{', '.join(map(str, info.inits))}] at start; "
                    f"every value an element is given lies in {info.lo}..{info.hi}.")
        if name in checker.const_arrays:
            elements = checker.const_arrays[name][1]
            values = [e.value for e in elements]
            return (f"```epuck\nconst {name} = [{', '.join(map(str, values))}]\n```\n\n"
                    f"Constant array of {len(values)} elements: "
                    f"{_kind_words(elements[0].kind)}, {min(values)}..{max(values)}.")
        if name in READING_ARRAYS:
            names = READING_ARRAYS[name][0]
            first = STANDARD_READINGS[names[0]]
            return (f"```epuck\n{name}\n```\n\nReadings as an array of {len(names)}: "
                    f"`{name}[0]` is `{names[0]}`, ..., `{name}[{len(names) - 1}]` is "
                    f"`{names[-1]}`; {_kind_words(first.kind)}, {first.lo}..{first.hi}.")
        if info is not None:
            return (f"```epuck\nvar {name}\n```\n\nVariable: {_kind_words(info.kind)}, "
                    f"{info.init} at start; every value it is given lies in "
                    f"{info.lo}..{info.hi}.")
        reading = STANDARD_READINGS.get(name)
        if reading is not None:
            return (f"```epuck\n{name}\n```\n\nReading: {reading.doc}; "
                    f"{_kind_words(reading.kind)}, {reading.lo}..{reading.hi}.")
        return None
    if isinstance(node, ast.Number) or isinstance(node, ast.ConstRef):
        return None
    e = checker.evaluated(node)
    if e is None:
        return None
    text = _shown(node)
    if e.kind == "bool":
        value = ("always true" if e.value else "always false") if e.constant else \
            "true or false"
        return f"```epuck\n{text}\n```\n\nA condition: {value}."
    head = f"```epuck\n{text}\n```\n\n{_kind_words(e.kind).capitalize()}"
    functions = {**FUNCTIONS, **AGGREGATES}
    if isinstance(node, ast.FuncCall) and node.name.name in functions:
        head += f"; `{node.name.name}`: {functions[node.name.name][1]}"
    if e.constant:
        return f"{head}: always {e.value}."
    stored = "" if -32768 <= e.lo and e.hi <= 32767 else \
        " (exact here; saturated to -32768..32767 where it is stored)"
    return f"{head}, within {e.lo}..{e.hi}{stored}."


def hover(analysis: Analysis, line: int, column: int) -> Optional[tuple]:
    """(markdown, real span of what it is about), or None."""
    s, vline, vcol = statement_at(analysis, line, column)
    if s is None:
        return None
    node = _expression_at(s, vline, vcol)
    if node is not None:
        markdown = _expression_hover(analysis, node)
        if markdown is not None:
            return markdown, analysis.real(node.span)
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
