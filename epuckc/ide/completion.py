"""Completion: what may come at the cursor, from the LALR tables' expected
tokens, the standard table, the program's names and the parameter being
written (its units, its choices)."""
from __future__ import annotations

from dataclasses import dataclass
from typing import Optional

from ..base.source import Span
from ..check.messages import _shown
from ..diagnostics import Collector
from ..stdlib.table import (ACTION_ALIASES, AGGREGATES, CHOICE, EVENT_ALIASES, FUNCTIONS,
                            READING_ARRAYS, READINGS, SENSOR_NAMES, STANDARD_ACTIONS,
                            STANDARD_EVENTS, STANDARD_READINGS, kind_name)
from ..stdlib.units import KIND_UNITS, UNITS
from ..syntax import ast
from ..syntax.lexer import KEYWORDS, STATEMENT_STARTS
from .hover import _line_of
from .incremental import Analysis


@dataclass(frozen=True)
class Completion:
    label: str
    kind: str               # "keyword", "action", "event", "param", "unit", "const", "rule",
                            # "sensor" (a reading), "variable", "function"
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


def _var_items(analysis: Analysis, kind: Optional[str] = None) -> list:
    return [Completion(name, "variable", f"var: {info.kind}, {info.lo}..{info.hi}")
            if not info.size else
            Completion(name, "variable", f"var: array of {info.size} {info.kind}, "
                                         f"{info.lo}..{info.hi}", insert=f"{name}[")
            for name, info in analysis.checker.vars.items() if kind in (None, info.kind)]


def _array_items(analysis: Analysis) -> list:
    """The constant arrays and the readings' arrays, inserted with `[`."""
    out = [Completion(name, "const", f"array of {len(values)}: "
                                     f"[{', '.join(str(v.value) for v in values)}]",
                      insert=f"{name}[")
           for name, (_, values) in analysis.checker.const_arrays.items()]
    for name, (names, _) in READING_ARRAYS.items():
        first = STANDARD_READINGS[names[0]]
        out.append(Completion(name, "sensor", f"array of {len(names)}: {names[0]}..{names[-1]}",
                              doc=f"{first.doc}, as an array", insert=f"{name}["))
    return out


def _value_items(analysis: Analysis, kind: Optional[str] = None) -> list:
    """What an expression may name: constants, variables, readings, functions."""
    return (_const_items(analysis, kind) + _var_items(analysis) + _array_items(analysis)
            + [Completion(r.name, "sensor", (f"{r.signature}: " if r.param else "")
                          + f"{r.kind}, {r.lo}..{r.hi}", doc=r.doc,
                          insert=f"{r.name}(" if r.param else None)
               for r in READINGS]
            + [Completion(name, "function", f"{name}({', '.join(params)})", doc=doc,
                          insert=f"{name}(")
               for name, (params, doc) in {**FUNCTIONS, **AGGREGATES}.items()])


# what may start a statement: the lexer's own list (where the parser restarts)
_STARTS = STATEMENT_STARTS
# after these, an expression's operand comes
_OPERAND_BEFORE = {"_PLUS", "_STAR", "_SLASH", "_PERCENT", "CMP", "_AND", "_OR", "_NOT", "_WHEN",
                   "_IF", "_PLUSEQ", "_MINUSEQ", "_LBRACK", "_AMP", "_PIPE", "_CARET",
                   "_TILDE", "_SHL", "_SHR"}


def _unit_items(kind: Optional[str]) -> list:
    kinds = [kind] if kind in KIND_UNITS else list(KIND_UNITS)
    return [Completion(u, "unit", k) for k in kinds for u in KIND_UNITS[k]]


def completions(analysis: Analysis, line: int, column: int) -> list:
    """What may be typed at a real position (the word being typed there is
    left out of the context; editors filter by it)."""
    from ..base.source import SourceFile
    from ..syntax.lexer import iter_tokens
    offset = analysis.offset(line, column)
    start = analysis.start_of(analysis.index_at(offset)) if analysis.layout.count else 0
    prefix = analysis.text[start:offset]
    source = SourceFile("", prefix)
    tokens = list(iter_tokens(source, Collector(source)))
    if tokens and (prefix[-1:].isalnum() or prefix[-1:] == "_") and (
            tokens[-1].type in ("NAME", "NUMBER") or tokens[-1].type in _TERMINAL_KEYWORD):
        tokens.pop()        # the word (or number) being typed
    expected = _expected(tokens)
    if expected is None:
        if not tokens:
            expected = {t for t in _TERMINAL_KEYWORD} & _STARTS
        else:
            return []
    items = []
    prev = tokens[-1] if tokens else None
    prev_type = prev.type if prev is not None else None
    if "$END" in expected:      # the statement may end here: another may start
        expected |= _STARTS
    for t in sorted(expected):
        if t in _TERMINAL_KEYWORD:
            items.append(Completion(_TERMINAL_KEYWORD[t], "keyword"))
    if "NAME" not in expected:
        return items
    call = _enclosing_call(tokens)
    if prev_type in _OPERAND_BEFORE or (prev_type in ("_LPAR", "MINUS") and call is None) \
            or (prev_type == "_EQUAL" and len(tokens) >= 2 and tokens[0].type != "_ACTION"
                and tokens[0].type not in ("_CONST", "_VAR") and call is None):
        return items + _value_items(analysis)
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
        return items + out + _value_items(analysis, param.kind if param else None)
    if call is not None and prev_type in ("_COLON", "MINUS"):
        param = _arg_param(analysis, tokens, call)
        if param is not None and param.kind == CHOICE:
            return items + _choice_items(param)
        return items + _value_items(analysis, _arg_kind(analysis, tokens, call))
    if prev_type == "_ENTER":
        return items + [Completion(name, "const", "mode") for name in analysis.checker.modes]
    if prev_type in ("_DO", "_THEN") or (prev_type == "_EQUAL" and tokens[0].type == "_ACTION") \
            or (prev_type == "_COMMA" and call is None and any(t.type == "_DO" for t in tokens)) \
            or (prev_type == "_LBRACE" and "_CANCEL" in expected):      # an `if` branch
        return items + _action_items(analysis) + _var_items(analysis)
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
