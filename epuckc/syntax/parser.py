"""Parse a rule file into a Program: tokens -> statements -> LALR -> AST.

Each statement is parsed on its own (see lexer.iter_statements), so a
syntax error costs only its statement: three broken rules give three errors
and the rest of the file is still checked.
"""
from __future__ import annotations

import re
from functools import lru_cache

from . import accel

from . import ast
from . import lalr
from ..diagnostics import Collector, Fix, Note
from .lexer import KEYWORDS, STATEMENT_STARTS, iter_statements, iter_tokens
from ..base.resources import grammar_path
from ..base.source import SourceFile, Span


@lru_cache(maxsize=1)
def _tables() -> lalr.Tables:
    """The LALR tables of grammar/epuck.lark (cached on disk, see lalr.py)."""
    return lalr.load_tables(grammar_path().read_text(encoding="utf-8"), "statement")


# ---- syntax errors in words -------------------------------------------------

_FRIENDLY = {
    "NAME": "a name", "NUMBER": "a number", "STRING": 'a file name in quotes ("blink.c")',
    "CMP": "`>` or `<`", "MINUS": "`-`", "$END": "the end of the statement",
    "_LPAR": "`(`", "_RPAR": "`)`", "_LBRACE": "`{`", "_RBRACE": "`}`", "_COMMA": "`,`",
    "_COLON": "`:`", "_EQUAL": "`=`", "_SLASH": "`/`", "_PLUS": "`+`", "_STAR": "`*`",
    "_PERCENT": "`%`", "_PLUSEQ": "`+=`", "_MINUSEQ": "`-=`",
}
_OPERATORS = {"_PLUS", "MINUS", "_STAR", "_SLASH", "_PERCENT"}
_STATEMENT_LIST = "a statement (`on`, `rule`, `action`, `const`, `extern`, `robot` or `mode`)"


def _friendly(term: str) -> str:
    if term in _FRIENDLY:
        return _FRIENDLY[term]
    if term.startswith("_"):
        return f"`{term[1:].lower()}`"
    return term


def _describe_found(tok) -> str:
    if tok.type == "$END":
        return "the end of the statement"
    if tok.type in ("NAME", "NUMBER", "STRING"):
        return f"`{tok.value}`"
    return f"`{tok.value}`"


def _describe_expected(prev, expected: set) -> tuple[str, str | None]:
    """What the parser wanted, in the user's words, and a hint."""
    prev_type = prev.type if prev is not None else None
    if prev is None and expected & {"_ON", "_RULE", "_ACTION"}:
        return _STATEMENT_LIST, "every statement starts with one of these keywords"
    if "_CANCEL" in expected:
        return "an action", "name an action, e.g. `stop_motor`, `start_straight(300, 10 cm)` or `cancel RULE`"
    if prev_type == "_ON":
        return "an event", "name an event, e.g. `immediate`, `stop_motor`, `timer(2 s)` or `sensor(ir0 > 300)`"
    if prev_type == "_ACTION":
        return "a name for the action", "write `action NAME = ...`"
    if prev_type == "_CONST":
        return "a name for the constant", "write `const NAME = VALUE`"
    if prev_type == "_RULE":
        return "a name for the rule", "write `rule NAME: on EVENT do ACTION`"
    if expected >= {"NUMBER", "NAME", "MINUS"}:
        wanted = "a value or `)`" if "_RPAR" in expected else "a value"
        return wanted, "a value is a number with an optional unit (`20 cm`) or a constant's name"
    operators = _OPERATORS <= expected
    names = sorted(_friendly(t) for t in expected if not (t == "NAME" and prev_type == "NUMBER")
                   and not (operators and t in _OPERATORS)
                   and not (operators and t == "CMP"))
    if prev_type == "NUMBER" and "NAME" in expected:
        names.append("a unit")
    if operators:
        names.append("an operator")
    if not names:
        return "nothing more", None
    wanted = ", ".join(names[:-1]) + " or " + names[-1] if len(names) > 1 else names[0]
    if "_DO" in expected:
        hint = "a rule reads `on EVENT do ACTION`"
    elif "_RPAR" in expected:
        hint = "is a `)` missing?"
    elif "_RBRACE" in expected:
        hint = "is a `}` missing?"
    else:
        hint = None
    return wanted, hint


def _syntax_error(exc: lalr.ParseError, chunk: list, following, source: SourceFile,
                  diags: Collector):
    tok = exc.token
    if getattr(tok, "after_bad", False) and chunk and tok is not chunk[0]:
        # the unexpected character just before it, in this statement, is
        # already reported (E002). One before the statement's first token
        # belongs to the statement before: the language server, which lexes
        # each statement on its own, could not see it, and must say the same.
        return
    if tok.type == "$END":
        # Point at the last token read: that is where something is missing.
        prev = chunk[-1]
        span = Span(prev.line, prev.column, prev.end_line, prev.end_column)
        if following is not None:
            found = f"`{following.value}`, which starts a new statement"
        else:
            found = "the end of the file"
    else:
        index = next(i for i, t in enumerate(chunk) if t is tok)
        prev = chunk[index - 1] if index > 0 else None
        found = _describe_found(tok)
        span = Span(tok.line, tok.column, tok.end_line, tok.end_column)
    expected = set(exc.before)
    wanted, hint = _describe_expected(prev, expected)
    after = f" after `{prev.value}`" if prev is not None else ""
    if tok.type == "_EQUAL" and "_COLON" in expected and prev is not None:
        # `start_straight(speed = 300, ...)`: arguments are named with `:`
        diags.error("E001", span, f"expected `:` after `{prev.value}`, found `=`",
                    help=_fix(tok, prev, expected,
                              f"arguments are named with `:`: write `{prev.value}: ...`"))
        return
    joint = _joining_word(chunk, tok, prev, expected)
    if joint is not None:
        # `sensor(ir0 > 300 and ir7 > 300)`: `and` (read as a unit after a
        # number, or found after a constant) joins two conditions
        word, before = joint.value, chunk[chunk.index(joint) - 1]
        where = Span(joint.line, joint.column, joint.end_line, joint.end_column)
        if word == "or":
            help = Fix(Span(before.end_line, before.end_column, joint.end_line, joint.end_column),
                       ",", "conditions are separated by `,`, which means or: "
                            "write `,` for `or`")
        else:
            help = _when_fix(chunk, source) or (
                "conditions are separated by `,`, which means *or*: the rule occurs when "
                "any of them becomes true; to wait for two at once, write a `when` rule: "
                "`when ir0 > 300 and ir7 > 300 do ...`")
        diags.error("E001", where, f"`{word}` cannot join the conditions of an event", help=help)
        return
    if tok.type == "_REPEAT" and "_DO" in expected and index >= 2 \
            and chunk[index - 2].type == "_PRIORITY":
        # `on ... priority 1 repeat do`: the words go the other way round
        first = chunk[index - 2]
        order = f"repeat priority {prev.value}"
        diags.error("E001", span, f"expected {wanted}{after}, found `repeat`",
                    help=Fix(Span(first.line, first.column, tok.end_line, tok.end_column), order,
                             f"`repeat` comes before `priority`: write `{order}`"))
        return
    keyword = KEYWORDS.get(tok.value.lower()) if tok.type == "NAME" else None
    if keyword is not None and (keyword in expected
                                or (prev is None and keyword in STATEMENT_STARTS)):
        diags.error("E001", span, f"expected {wanted}{after}, found `{tok.value}`",
                    help=Fix(span, tok.value.lower(),
                             f"keywords are lower case: write `{tok.value.lower()}`, "
                             f"not `{tok.value}`"))
        return
    diags.error("E001", span, f"expected {wanted}{after}, found {found}",
                help=_fix(tok, prev, expected, hint))


def _when_fix(chunk: list, source: SourceFile):
    """`on sensor(ir0 > 300 and ir7 > 300)` as the `when` rule it means:
    `when ir0 > 300 and ir7 > 300` (for `ambient`, on the ambient readings)."""
    types = [t.type for t in chunk]
    if "_ON" not in types:
        return None
    at = types.index("_ON")
    if at + 2 >= len(chunk) or chunk[at + 1].value not in ("sensor", "ambient") \
            or types[at + 2] != "_LPAR":
        return None
    depth, close = 0, None
    for i in range(at + 2, len(chunk)):
        depth += {"_LPAR": 1, "_RPAR": -1}.get(types[i], 0)
        if depth == 0:
            close = i
            break
    if close is None:
        return None
    inside = [t for t in chunk[at + 3:close]]
    if any(t.type in ("_COMMA", "_OR") for t in inside):
        return None         # `,` is already an or: mixing them needs a person
    text = " ".join(t.value for t in inside)
    if chunk[at + 1].value == "ambient":
        text = re.sub(r"\bir([0-7])\b", r"ambient\1", text)
    start, end = chunk[at], chunk[close]
    return Fix(Span(start.line, start.column, end.end_line, end.end_column), f"when {text}",
               f"a sensor rule's conditions are or-ed; to wait for both, write a `when` "
               f"rule: `when {text}`")


def _joining_word(chunk: list, tok, prev, expected: set):
    """The `and` or `or` token that joins two conditions of an event's
    arguments, or None."""
    if tok.type == "$END":
        return None
    for word in (prev, tok):
        if word is not None and word.type in ("_AND", "_OR") \
                and ("_RPAR" in expected or "_COMMA" in expected) and chunk.index(word) > 0:
            return word
    return None


_CLOSERS = {"is a `)` missing?": ")", "is a `}` missing?": "}"}

# One punctuation mark mistaken for the other: `speed = 300`, `const X: 5`.
_SWAPS = {("_EQUAL", "_COLON"): ":", ("_COLON", "_EQUAL"): "="}


def _fix(tok, prev, expected: set, hint: str):
    """A machine-applicable fix for the likeliest mistake, with `hint` as
    its sentence; or the hint alone."""
    span = Span(tok.line, tok.column, tok.end_line, tok.end_column)
    for (found, wanted), mark in _SWAPS.items():
        if tok.type == found and wanted in expected:
            # in the usual layout: `speed: 300`, `const X = 5`
            text = mark
            if prev is not None and prev.end_line == tok.line:
                if mark == ":":
                    span = Span(prev.end_line, prev.end_column, tok.end_line, tok.end_column)
                elif prev.end_column == tok.column:
                    text = " ="
            return Fix(span, text, hint or f"write `{mark}` here, not `{tok.value}`")
    if hint in _CLOSERS and prev is not None:
        # `start_straight(300, 2 m do ...`: close it after the last token
        return Fix(Span(prev.end_line, prev.end_column, prev.end_line, prev.end_column),
                   _CLOSERS[hint], hint)
    if tok.type == "$END":
        return hint
    if "_DO" in expected and tok.type in ("NAME", "_CANCEL"):
        # `on immediate start_sensor`: the `do` is missing before the action
        return Fix(Span(tok.line, tok.column, tok.line, tok.column), "do ", hint)
    return hint


# ---- tree -> AST --------------------------------------------------------------
#
# These run once per node of a file (some 20,000 for 1,000 rules), so they
# build nodes with ast.maker: every field by position, in the order of the
# node's `_fields`, without __init__'s checks.

_Ident = ast.maker(ast.Ident)
_Number = ast.maker(ast.Number)
_ConstRef = ast.maker(ast.ConstRef)
_Call = ast.maker(ast.Call)
_PositionalArg = ast.maker(ast.PositionalArg)
_NamedArg = ast.maker(ast.NamedArg)
_ConditionArg = ast.maker(ast.ConditionArg)
_CancelCall = ast.maker(ast.CancelCall)
_EnterCall = ast.maker(ast.EnterCall)
_Step = ast.maker(ast.Step)
_ActionBody = ast.maker(ast.ActionBody)
_Rule = ast.maker(ast.Rule)
_Setting = ast.maker(ast.Setting)
_ConstDef = ast.maker(ast.ConstDef)
_ActionDef = ast.maker(ast.ActionDef)
_BinOp = ast.maker(ast.BinOp)
_UnaryOp = ast.maker(ast.UnaryOp)
_FuncCall = ast.maker(ast.FuncCall)
_Paren = ast.maker(ast.Paren)
_Assign = ast.maker(ast.Assign)


def _ident(tok) -> ast.Ident:
    return _Ident(tok.value, tok.span)


def _unescape(literal: str) -> str:
    body = literal[1:-1]
    out, i = [], 0
    while i < len(body):
        if body[i] == "\\" and i + 1 < len(body):
            i += 1
        out.append(body[i])
        i += 1
    return "".join(out)


class _ToAst:
    """Builds the AST while parsing: lalr.parse calls the method named after
    each grammar rule (or its `-> alias`) with its span and kept children."""
    def statement(self, span, children):
        return children[0]

    def robot_block(self, span, children):
        return ast.RobotBlock(tuple(c for c in children if c is not None), span)

    def setting(self, span, children):
        name, value = children
        return _Setting(_ident(name), value, span)

    def const_def(self, span, children):
        name, value = children
        return _ConstDef(_ident(name), value, span)

    def action_def(self, span, children):
        name, body = children
        return _ActionDef(_ident(name), body, span)

    def extern_action(self, span, children):
        return "action"

    def extern_event(self, span, children):
        return "event"

    def extern_def(self, span, children):
        kind, name, *params, file_tok = children
        return ast.ExternDef(kind, _ident(name), tuple(p for p in params if p is not None),
                             _unescape(file_tok.value), file_tok.span, span)

    def param_decl(self, span, children):
        name, type_ = children
        return ast.ParamDecl(_ident(name), _ident(type_), span)

    def repeat(self, span, children):
        return True

    def var_def(self, span, children):
        name, value = children
        return ast.VarDef(_ident(name), value, span)

    def rule_def(self, span, children):
        name, (trigger, event), repeat, priority, guard, body = children
        return _Rule(_ident(name) if name is not None else None, event, bool(repeat), body,
                     span, priority, None, guard, trigger)

    def trigger(self, span, children):
        return "on", children[0]

    @staticmethod
    def _keyword_event(word, span, children):
        """`when COND`, `every D`, `after D` as the event Call(word, (COND or D,))."""
        keyword = _Ident(word, Span(span.line, span.column, span.line, span.column + len(word)))
        (arg,) = children
        return word, _Call(keyword, (_PositionalArg(arg, arg.span),), span)

    def when_trigger(self, span, children):
        return self._keyword_event("when", span, children)

    def every_trigger(self, span, children):
        return self._keyword_event("every", span, children)

    def after_trigger(self, span, children):
        return self._keyword_event("after", span, children)

    def guard(self, span, children):
        return children[0]

    def priority_number(self, span, children):
        (number,) = children
        return _Number(float(number.value), number.value, None, None, number.span)

    def priority_const(self, span, children):
        (name,) = children
        ident = _ident(name)
        return _ConstRef(ident, False, ident.span)

    def event_ref(self, span, children):
        name, args = children
        return _Call(_ident(name), args, span)

    def enter_event(self, span, children):
        return _Call(_Ident("enter", span), None, span)

    def enter_call(self, span, children):
        (name,) = children
        return _EnterCall(_ident(name), span)

    def initial(self, span, children):
        return True

    def mode_open(self, span, children):
        initial, name = children
        return ast.ModeOpen(_ident(name), bool(initial), span)

    def mode_close(self, span, children):
        return ast.ModeClose(span)

    def action_body(self, span, children):
        return _ActionBody(tuple(children), span)

    def step(self, span, children):
        return _Step(tuple(children), span)

    plain_call = event_ref

    def assign_call(self, span, children):
        name, value = children
        return _Assign(_ident(name), "=", value, span)

    def add_assign_call(self, span, children):
        name, value = children
        return _Assign(_ident(name), "+=", value, span)

    def sub_assign_call(self, span, children):
        name, value = children
        return _Assign(_ident(name), "-=", value, span)

    def cancel_call(self, span, children):
        (name,) = children
        return _CancelCall(_ident(name), span)

    def arg_list(self, span, children):
        return tuple(c for c in children if c is not None)

    def named_arg(self, span, children):
        name, value = children
        return _NamedArg(_ident(name), value, span)

    def positional_arg(self, span, children):
        return _PositionalArg(children[0], span)

    def condition_arg(self, span, children):
        name, op, value = children
        return _ConditionArg(_ident(name), op.value, value, span)

    def number(self, span, children):
        minus, number, unit = children
        text = number.value if minus is None else "-" + number.value
        if unit is None:
            return _Number(float(text), text, None, None, span)
        return _Number(float(text), text, unit[0], unit[1], span)

    # -- expressions: a level without its operator passes its one child on --

    def _pass(self, span, children):
        return children[0]

    expr = conjunction = negation = comparison = sum = product = unary = _pass

    def _binary(op):
        def make(self, span, children):
            return _BinOp(op, children[0], children[-1], span)
        return make

    or_op, and_op = _binary("or"), _binary("and")
    add_op, sub_op = _binary("+"), _binary("-")
    mul_op, div_op, mod_op = _binary("*"), _binary("/"), _binary("%")
    del _binary

    def compare_op(self, span, children):
        left, op, right = children
        return _BinOp(op.value, left, right, span)

    def not_op(self, span, children):
        return _UnaryOp("not", children[0], span)

    def neg_op(self, span, children):
        """`-3 cm` and `-NAME` are the Number and ConstRef a `value` makes;
        a minus before anything else is an operator."""
        _, operand = children
        cls = operand.__class__
        if cls is ast.Number and not operand.text.startswith("-"):
            return _Number(-operand.value, "-" + operand.text, operand.unit, operand.unit_span,
                           span)
        if cls is ast.ConstRef and not operand.negative:
            return _ConstRef(operand.name, True, span)
        return _UnaryOp("-", operand, span)

    def number_atom(self, span, children):
        number, unit = children
        if unit is None:
            return _Number(float(number.value), number.value, None, None, span)
        return _Number(float(number.value), number.value, unit[0], unit[1], span)

    def name_atom(self, span, children):
        ident = _ident(children[0])
        return _ConstRef(ident, False, span)

    def function_atom(self, span, children):
        name, args = children
        return _FuncCall(_ident(name), args, span)

    def paren_atom(self, span, children):
        return _Paren(children[0], span)

    def const_ref(self, span, children):
        minus, name = children
        return _ConstRef(_ident(name), minus is not None, span)

    def unit(self, span, children):
        first, second = children
        text = first.value if second is None else f"{first.value}/{second.value}"
        return text, span


_TO_AST = _ToAst()
_CALLBACKS = {name: getattr(_TO_AST, name) for name in dir(_ToAst) if not name.startswith("_")}


@lru_cache(maxsize=1)
def _c_driver():
    """The C front end (epuckc/syntax/_front.c) over the grammar's tables, the
    lexer's keywords and this module's callbacks; None without it (see
    accel.py)."""
    front = accel.front()
    return None if front is None else make_c_driver(front, _tables(), _CALLBACKS)


def make_c_driver(front, tables: lalr.Tables, callbacks):
    """A C driver over `tables` and `callbacks`: the packed table as it is,
    and the lexer's own tables for which word or character is which
    terminal and which ones start a statement."""
    from .lexer import MODE_STARTS, PUNCTUATION, TRIGGERS
    terminals = {"NAME", "NUMBER", "STRING", "$END"} | set(KEYWORDS.values()) \
        | set(PUNCTUATION.values())
    names, packed = tables.names, tables.packed
    if not terminals <= set(names):     # a terminal the grammar does not use
        names, packed = lalr.pack(tables.states, tables.rules, terminals)
    sym = {name: i for i, name in enumerate(names)}
    rules = []
    for (origin, _, size, include, after), (_, _, func, how, arg, _) in zip(
            tables.rules, lalr._plan(tables.rules, callbacks)):
        rules.append((sym[origin], size, func, include, after, arg if how == lalr.GROW else 0))
    lexer = (tuple((word, sym[t]) for word, t in KEYWORDS.items()),
             tuple((char, sym[t]) for char, t in PUNCTUATION.items()),
             sym["NAME"], sym["NUMBER"], sym["STRING"], sym["$END"], sym["_LBRACE"],
             sym["_RBRACE"], sym["_ACTION"], sym["_EXTERN"], sym["_MODE"], sym["_INITIAL"],
             sym["_ON"], sym["_RULE"], tuple(sym[t] for t in STATEMENT_STARTS),
             tuple(sym[t] for t in MODE_STARTS), tuple(sym[t] for t in TRIGGERS))
    return front.make_driver(names, packed, tables.start, tables.end, rules, Span, lexer)


def parse(source: SourceFile, diags: Collector) -> ast.Program:
    """The statements that parse; a diagnostic for each one that does not."""
    driver = _c_driver()
    if driver is not None:
        program = parse_c(driver, source, diags)
        if program is not None:
            return program
    return parse_python(source, diags)


def parse_c(driver, source: SourceFile, diags: Collector):
    """`parse` by the C front end, or None when the file has something to
    report (a bad character, a syntax error, ...): the C front end reports
    nothing, and leaves such a file to parse_python."""
    statements = driver.parse(source.text)
    if statements is None:
        return None
    program = ast.Program(source.name)
    placer = ModePlacer(program, diags)
    for statement in statements:
        placer.add(statement)
    placer.finish()
    return program


def parse_python(source: SourceFile, diags: Collector) -> ast.Program:
    """`parse` by the Python front end, which reports every problem."""
    program = ast.Program(source.name)
    tables = _tables()
    # One statement at a time, so that a huge file never holds all its
    # tokens at once; `following` is the next statement's first token.
    chunks = iter_statements(iter_tokens(source, diags))
    chunk = next(chunks, None)
    placer = ModePlacer(program, diags)
    while chunk is not None:
        following_chunk = next(chunks, None)
        following = following_chunk[0] if following_chunk is not None else None
        statement = parse_statement(chunk, following, source, diags, tables)
        if statement is not None:
            placer.add(statement)
        chunk = following_chunk
    placer.finish()
    return program


def parse_statement(chunk: list, following, source: SourceFile, diags: Collector,
                    tables=None):
    """One statement's AST from its tokens, or None after reporting why not.
    `following` is the next statement's first token (None at the end)."""
    try:
        return lalr.parse(tables or _tables(), chunk, _CALLBACKS, meta=Span)
    except lalr.ParseError as exc:
        _syntax_error(exc, chunk, following, source, diags)
        return None


class ModePlacer:
    """Builds a program's statements from the parsed ones, minding mode
    blocks: a mode's head becomes a ModeDef, its `}` a ModeEnd, and each
    rule between them gets its `mode`. Used by `parse` and by the language
    server's incremental analysis (incremental.py), which parses statements
    on its own."""

    def __init__(self, program: ast.Program, diags: Collector):
        self.program = program
        self.diags = diags
        self.modes: list = []       # the ModeOpens of the blocks open, innermost last

    def add(self, statement) -> None:
        program, diags = self.program, self.diags
        mode = self.modes[-1] if self.modes else None
        if isinstance(statement, ast.ModeOpen):
            if mode is not None:
                diags.error("E001", statement.span,
                            f"mode `{statement.name.name}` starts inside mode `{mode.name.name}`",
                            help="modes do not nest: close the first with `}` before this one",
                            notes=[Note(f"mode `{mode.name.name}` starts here", mode.span)])
            program.statements.append(ast.ModeDef(statement.name, statement.initial,
                                                  statement.span))
            self.modes.append(statement)
            return
        if isinstance(statement, ast.ModeClose):
            if mode is None:
                diags.error("E001", statement.span, "this `}` closes no mode",
                            help="remove it, or open a mode with `mode NAME {`")
            else:
                self.modes.pop()
                program.statements.append(ast.ModeEnd(statement.span))
            return
        if mode is not None and not isinstance(statement, ast.Rule):
            what = {ast.ConstDef: "a constant", ast.ActionDef: "an action",
                    ast.ExternDef: "an extern", ast.RobotBlock: "the robot block"}[type(statement)]
            diags.error("E001", statement.span,
                        f"{what} cannot be defined inside mode `{mode.name.name}`",
                        help="only rules go in a mode; define it before the mode (names are "
                             "visible everywhere)",
                        notes=[Note(f"mode `{mode.name.name}` starts here", mode.span)])
        elif mode is not None:
            statement = statement.in_mode(mode.name)
        # a definition misplaced in a mode still defines its name: no follow-up errors
        program.statements.append(statement)

    def finish(self) -> None:
        for mode in self.modes:
            self.diags.error("E001", mode.span, f"mode `{mode.name.name}` is not closed",
                             help="end the mode's rules with `}`")
        self.modes = []
