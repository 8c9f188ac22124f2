"""Lark's own LALR parser over epuckc's grammar and tokens: the reference
that the hand-written driver (epuckc/syntax/lalr.py) is held to, and the
alternatives that bench/parser_bench.py times against it.

Lark parses each statement's tokens (epuckc's lexer makes them) with its
tree builder (`propagate_positions`, `maybe_placeholders`), and a
Transformer then calls the same AST callbacks the driver calls at each
reduction, with the span Lark computed. Equal ASTs therefore mean that the
driver shapes children and spans exactly as Lark does.
"""
from __future__ import annotations

from lark import Lark, Token, Transformer
from lark.visitors import Transformer_NonRecursive
from lark.exceptions import UnexpectedInput, UnexpectedToken
from lark.lexer import Lexer

from epuckc.syntax.parser import _CALLBACKS
from epuckc.base.resources import grammar_path
from epuckc.base.source import Span


class TokenList(Lexer):
    """The 'lexer' Lark is given: the tokens are already made."""

    def __init__(self, conf=None):
        pass

    def lex(self, data, *parser_state):
        return iter(data)


_SPANNED: dict = {}


def _spanned(token_class):
    """`token_class` with the `span` epuckc's tokens have (the callbacks
    read it)."""
    if token_class not in _SPANNED:
        _SPANNED[token_class] = type("Spanned" + token_class.__name__, (token_class,), {
            "span": property(lambda t: Span(t.line, t.column, t.end_line, t.end_column))})
    return _SPANNED[token_class]


def lark_tokens(chunk, token_class=Token) -> list:
    """Lark's tokens (a standalone module has its own Token class, which its
    tree builder needs to see to give spans)."""
    token_class = _spanned(token_class)
    return [token_class(t.type, t.value, t.start_pos, t.line, t.column, t.end_line, t.end_column,
                  t.end_pos) for t in chunk]


def lark_parser(cache=None) -> Lark:
    """Lark's LALR parser for grammar/epuck.lark, tables built now or, with
    `cache` (a file path), loaded from Lark's own cache file."""
    return Lark(grammar_path().read_text(encoding="utf-8"), parser="lalr", lexer=TokenList,
                start="statement", propagate_positions=True, maybe_placeholders=True,
                cache=cache)


class _StateTokens:
    """The same, for a standalone parser's frontend, which calls its lexer
    with a lexer state whose `text` is what was given to parse()."""

    def lex(self, lexer_state, parser_state):
        return iter(lexer_state.text)


def standalone_parser(module):
    """The parser of a module made by `python -m lark.tools.standalone`,
    fed epuckc's tokens."""
    parser = module.Lark_StandAlone()
    parser.parser.lexer = _StateTokens()
    return parser


def _default(self, data, children, meta):
    span = Span(1, 1, 1, 1) if meta.empty else Span(meta.line, meta.column, meta.end_line,
                                                    meta.end_column)
    return _CALLBACKS[str(data)](span, children)


def to_ast_transformer(transformer_class=Transformer):
    """A Lark tree -> epuckc's AST, through the parser's own callbacks (a
    standalone module has its own Transformer and Tree classes)."""
    return type("ToAst", (transformer_class,), {"__default__": _default})()


# not recursive: the corpus holds expressions nested right up to and past
# the depth limit (syntax/limits.py), deeper than Lark's recursive walk goes
TO_AST = to_ast_transformer(Transformer_NonRecursive)


def parse_with_lark(parser, chunk):
    """('ok', ast) or ('error', (start_pos of the unexpected token or None
    at the end, the terminals Lark accepts there))."""
    try:
        tree = parser.parse(lark_tokens(chunk))
    except UnexpectedToken as exc:
        tok = exc.token
        at_end = tok.type == "$END"
        return "error", (None if at_end else tok.start_pos, set(exc.accepts or exc.expected))
    except UnexpectedInput as exc:      # pragma: no cover - other Lark errors
        return "error", (getattr(exc, "pos_in_stream", None), set())
    return "ok", TO_AST.transform(tree)
