"""Parse a rule file into a Program: tokens -> statements -> LALR -> AST.

Each statement is parsed on its own (see lexer.iter_statements), so a
syntax error costs only its statement: three broken rules give three errors
and the rest of the file is still checked.
"""
from __future__ import annotations

from functools import lru_cache
from typing import Optional

from . import accel

from . import ast
from . import lalr
from ..diagnostics import Collector, Note
from . import aseba
from .errors import syntax_error
from .limits import report_too_deep, too_deep
from .lexer import KEYWORDS, STATEMENT_STARTS, iter_statements, iter_tokens
from ..base.resources import grammar_path
from ..base.source import SourceFile, Span


@lru_cache(maxsize=1)
def _tables() -> lalr.Tables:
    """The LALR tables of grammar/epuck.lark (cached on disk, see lalr.py)."""
    return lalr.load_tables(grammar_path().read_text(encoding="utf-8"), "statement")


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
_Index = ast.maker(ast.Index)
_IfBranch = ast.maker(ast.IfBranch)
_IfAction = ast.maker(ast.IfAction)


def number_value(text: str) -> float:
    """The value of a number's text: `12`, `0.5`, or a hexadecimal or binary
    one (`0x1F`, `0b101`), which is a 16-bit pattern: 0x8000..0xFFFF are the
    negative ints of that two's complement (0xFFFF is -1), as on the
    e-puck; a longer one keeps its value, for the checker to say it does
    not fit 16 bits."""
    if text[1:2] in ("x", "X", "b", "B"):
        v = int(text[2:], 16 if text[1] in "xX" else 2)
        return float(v - 0x10000 if 0x8000 <= v <= 0xFFFF else v)
    return float(text)


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
        return _Number(number_value(number.value), number.value, None, None, number.span)

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
        return _Assign(_ident(name), "=", value, span, None)

    def add_assign_call(self, span, children):
        name, value = children
        return _Assign(_ident(name), "+=", value, span, None)

    def sub_assign_call(self, span, children):
        name, value = children
        return _Assign(_ident(name), "-=", value, span, None)

    def _index_assign(op):
        def make(self, span, children):
            name, index, value = children
            return _Assign(_ident(name), op, value, span, index)
        return make

    index_assign_call = _index_assign("=")
    index_add_assign_call = _index_assign("+=")
    index_sub_assign_call = _index_assign("-=")
    del _index_assign

    def array_literal(self, span, children):
        return ast.ArrayLit(tuple(c for c in children if c is not None), span)

    def index_atom(self, span, children):
        name, index = children
        return _Index(_ident(name), index, span)

    def call(self, span, children):         # `call: ... | if_call`
        return children[0]

    def if_call(self, span, children):
        *branches, otherwise = children
        return _IfAction(tuple(branches), otherwise, span)

    def if_branch(self, span, children):
        condition, body = children
        return _IfBranch(condition, body, span)

    def else_branch(self, span, children):
        return children[0]

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
        value = number_value(number.value)
        value = value if minus is None else -value
        if unit is None:
            return _Number(value, text, None, None, span)
        return _Number(value, text, unit[0], unit[1], span)

    # -- expressions: a level without its operator passes its one child on --

    def _pass(self, span, children):
        return children[0]
    _pass.passes_child = True       # (the drivers skip the call: lalr.PASS)

    expr = conjunction = negation = comparison = sum = product = unary = _pass
    bit_xor = bit_and = shift = term = _pass

    def _binary(op):
        def make(self, span, children):
            return _BinOp(op, children[0], children[-1], span)
        return make

    or_op, and_op = _binary("or"), _binary("and")
    add_op, sub_op = _binary("+"), _binary("-")
    mul_op, div_op, mod_op = _binary("*"), _binary("/"), _binary("%")
    bitor_op, bitxor_op, bitand_op = _binary("|"), _binary("^"), _binary("&")
    shl_op, shr_op = _binary("<<"), _binary(">>")
    del _binary

    def bitnot_op(self, span, children):
        return _UnaryOp("~", children[0], span)

    def slice_atom(self, span, children):
        name, lo, hi = children
        return ast.Slice(_ident(name), lo, hi, span)

    def array_assign_call(self, span, children):
        """`a = [e0, e1, ...]`: every element at once (the values are
        computed before any is stored)."""
        name, *items = children
        return _Assign(_ident(name), "=", ast.ArrayLit(tuple(items), span), span, None)

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
            return _Number(number_value(number.value), number.value, None, None, span)
        return _Number(number_value(number.value), number.value, unit[0], unit[1], span)

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
        rules.append((sym[origin], size, func, include, after, arg if how == lalr.GROW else 0,
                      int(how == lalr.PASS)))
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
        foreign = aseba.report(chunk, diags)        # Aseba's constructs, by name
        if foreign is None:
            syntax_error(exc, chunk, following, source, diags)
        elif foreign > 0 and chunk[foreign - 1].end_line < chunk[foreign].line:
            # the lines before it may be a statement of their own (`var s = 0`)
            try:
                return lalr.parse(tables or _tables(), chunk[:foreign], _CALLBACKS, meta=Span)
            except lalr.ParseError:
                pass
        return None


# (what a mode's head or `}` came to, in ModePlacer's memory: never appended as it is)
_MODE_MARK = object()


class ModePlacer:
    """Builds a program's statements from the parsed ones, minding mode
    blocks: a mode's head becomes a ModeDef, its `}` a ModeEnd, and each
    rule between them gets its `mode`. Used by `parse` and by the language
    server's incremental analysis (incremental.py), which parses statements
    on its own."""

    def __init__(self, program: ast.Program, diags: Collector, placed: Optional[dict] = None):
        self.program = program
        self.diags = diags
        self.modes: list = []       # the ModeOpens of the blocks open, innermost last
        # With `placed` (the last program's, the language server's), what
        # each statement came to is kept by it: id(statement) -> (it, the
        # Ident of its mode, its too-deep node, the statement placed), so
        # that a statement placed again is not walked again and a rule in
        # a mode is the same object as last time (its checks are replayed).
        self._last = placed
        self.placed = None if placed is None else {}

    def extend(self, statements) -> None:
        """add() each of `statements`; one kept from last time (`placed`),
        outside any mode and not too deep, is appended as it is."""
        last, placed = self._last, self.placed
        if last is None or self.modes:
            for statement in statements:
                self.add(statement)
            return
        append = self.program.statements.append
        for statement in statements:
            hit = last.get(id(statement))
            if hit is not None and hit[0] is statement and hit[1] is None and hit[2] is None \
                    and not self.modes:
                placed[id(statement)] = hit
                append(statement)
            else:
                self.add(statement)

    def add(self, statement) -> None:
        program, diags = self.program, self.diags
        mode = self.modes[-1] if self.modes else None
        if isinstance(statement, (ast.ModeOpen, ast.ModeClose)):
            # (what a mode's head or `}` becomes is kept too: the same
            # ModeDef as last time, and its declaration is the same)
            last = self._last
            hit = None if last is None else last.get(id(statement))
            if hit is None or hit[0] is not statement:
                hit = (statement, _MODE_MARK, None,
                       ast.ModeDef(statement.name, statement.initial, statement.span)
                       if isinstance(statement, ast.ModeOpen) else ast.ModeEnd(statement.span))
            if self.placed is not None:
                self.placed[id(statement)] = hit
        if isinstance(statement, ast.ModeOpen):
            if mode is not None:
                diags.error("E001", statement.span,
                            f"mode `{statement.name.name}` starts inside mode `{mode.name.name}`",
                            help="modes do not nest: close the first with `}` before this one",
                            notes=[Note(f"mode `{mode.name.name}` starts here", mode.span)])
            program.statements.append(hit[3])
            self.modes.append(statement)
            return
        if isinstance(statement, ast.ModeClose):
            if mode is None:
                diags.error("E001", statement.span, "this `}` closes no mode",
                            help="remove it, or open a mode with `mode NAME {`")
            else:
                self.modes.pop()
                program.statements.append(hit[3])
            return
        mode_name = mode.name if mode is not None else None
        last = self._last
        hit = None if last is None else last.get(id(statement))
        if hit is None or hit[0] is not statement or hit[1] is not mode_name:
            deep = too_deep(statement)
            placed = statement
            if deep is None and mode is not None and isinstance(statement, ast.Rule):
                placed = statement.in_mode(mode.name)
            hit = (statement, mode_name, deep, placed)
        if self.placed is not None:
            self.placed[id(statement)] = hit
        deep = hit[2]
        if deep is not None:
            report_too_deep(diags, statement, deep)
            return
        if mode is not None and not isinstance(statement, ast.Rule):
            if isinstance(statement, ast.VarDef):
                help = ("variables belong to the whole program and keep their value across "
                        "modes: declare it before the mode; to start it afresh when the mode "
                        f"is entered, assign it in the mode: `on enter do {statement.name.name}"
                        " = ...`")
            else:
                help = ("only rules go in a mode; define it before the mode (names are "
                        "visible everywhere)")
            diags.error("E001", statement.span,
                        f"{statement.described} cannot be defined inside mode "
                        f"`{mode.name.name}`", help=help,
                        notes=[Note(f"mode `{mode.name.name}` starts here", mode.span)])
        elif mode is not None:
            statement = hit[3]
        # a definition misplaced in a mode still defines its name: no follow-up errors
        program.statements.append(statement)

    def finish(self) -> None:
        for mode in self.modes:
            last = self.program.statements[-1] if self.program.statements else None
            if isinstance(last, ast.Rule) and last.mode is not None \
                    and last.mode.name == mode.name.name and any(
                        isinstance(c, ast.IfAction)
                        for step in last.body.steps for c in ast.calls_within(step.calls)):
                # the mode's `}` may have closed an `if` whose own `}` is missing
                end = Span(last.span.end_line, last.span.end_column - 1, last.span.end_line,
                           last.span.end_column)
                self.diags.error("E001", mode.span, f"mode `{mode.name.name}` is not closed",
                                 help="end the mode's rules with `}`; if the `}` of the last "
                                      "rule's `if` was meant to close the mode, a `}` of the "
                                      "`if` is missing before it",
                                 notes=[Note("this `}` closes an `if`, not the mode", end)])
                continue
            self.diags.error("E001", mode.span, f"mode `{mode.name.name}` is not closed",
                             help="end the mode's rules with `}`")
        self.modes = []
