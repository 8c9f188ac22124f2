"""`epuckc fmt`: the one canonical layout of a rule file.

The layout is a function of the program alone (its syntax tree, read by the
parser), of its comments (kept next to the token they were next to) and of
where blank lines separated top-level statements, never of the original
spacing. So formatting is idempotent, and two files that differ only in
layout format to the same text.

The rules (docs/formatting.md has them with examples):

- one statement per line, starting in column 0; runs of blank lines between
  statements (and top-level comments) become one blank line, and a file
  ends with exactly one newline;
- single spaces between words; `name: value`, `a, b`, `f(x)`, `300 steps/s`,
  `ir0 > 300`, `-5 cm`, `const X = 1`, `robot { axle: 53 mm }`;
- a statement longer than WIDTH characters is wrapped with a hanging indent
  of INDENT spaces: first a rule's `do` goes to the next line, then each
  `then` starts a line, then the calls of a step go one per line after their
  `,` (one more indent), and last an argument list fills its lines, breaking
  after a `,` (one more indent);
- an `if` that does not fit on a line has each branch's actions on lines
  of their own, one indent in, and `} else {` between them;
- a robot block that does not fit on a line, or whose last setting is
  followed by a comma, has one setting per line, each with a comma;
- a comment at the end of a line stays at the end of the line of the same
  token (two spaces before `#`); a comment on its own line stays on its own
  line before the same token. Trailing spaces in comments are dropped.

The formatter works on the token stream of the lexer and the syntax tree of
the parser: it walks the tree, takes the tokens off the stream one by one
as it prints them (so nothing can be lost or reordered), and builds a
document of groups that a Wadler-style printer lays out in WIDTH columns.
"""
from __future__ import annotations

import re
from dataclasses import dataclass, field
from typing import Optional

from ..base.source import SourceFile
from ..diagnostics import Collector
from ..syntax import ast
from ..syntax.lexer import iter_statements, iter_tokens
from ..syntax.parser import parse
from .layout import HARD, INDENT, LINE, WIDTH, _Comment, _Fill, _Group, _IfBreak, _Indent, _render


class FormatError(Exception):
    """The text has syntax errors; `diagnostics` are the front end's."""

    def __init__(self, diagnostics: list):
        self.diagnostics = list(diagnostics)
        first = self.diagnostics[0] if self.diagnostics else None
        where = f"{first.file}:{first.span.line}:{first.span.column}: " if first else ""
        super().__init__(f"{where}cannot format a file with syntax errors")



# ---- comments ----------------------------------------------------------------------

_COMMENT_RE = re.compile(r"#[^\n]*")
_COMMENT_STRIP = " \t\r\f\v"       # the lexer's whitespace, besides the newline


@dataclass
class _Comments:
    """The comments of a file, by the token they belong to (its offset)."""
    trailing: dict = field(default_factory=dict)     # token offset -> comment text
    leading: dict = field(default_factory=dict)      # token offset -> [(blank_before, text)]
    blank_before: dict = field(default_factory=dict)  # token offset -> a blank line before it
    at_end: list = field(default_factory=list)       # [(blank_before, text)] after the last token
    blank_before_end: bool = False


def _collect_comments(text: str, tokens: list) -> _Comments:
    """Everything between two tokens is whitespace and comments (the file
    has no lexical errors). A comment on the line of the token before it
    trails that token; any other comment leads the token after it."""
    found = _Comments()
    previous_end = 0
    previous = None
    for token in tokens + [None]:
        start = token.start_pos if token is not None else len(text)
        leading: list = []
        gap_start = previous_end
        for m in _COMMENT_RE.finditer(text, previous_end, start):
            comment = m.group().rstrip(_COMMENT_STRIP)
            between = text[gap_start:m.start()]
            if previous is not None and not leading and "\n" not in text[previous_end:m.start()]:
                found.trailing[previous.start_pos] = comment
            else:
                leading.append((between.count("\n") >= 2, comment))
            gap_start = m.end()
        blank = text.count("\n", gap_start, start) >= 2
        if token is None:
            found.at_end, found.blank_before_end = leading, blank
        else:
            if leading:
                found.leading[token.start_pos] = leading
            found.blank_before[token.start_pos] = blank
            previous_end, previous = token.end_pos, token
    return found


# ---- from the syntax tree to the document ---------------------------------------------

_ASSIGN_TOKENS = {"=": "_EQUAL", "+=": "_PLUSEQ", "-=": "_MINUSEQ"}
_OPERATOR_TOKENS = {"+": "_PLUS", "-": "MINUS", "*": "_STAR", "/": "_SLASH", "%": "_PERCENT",
                    "and": "_AND", "or": "_OR", "&": "_AMP", "|": "_PIPE", "^": "_CARET",
                    "<<": "_SHL", ">>": "_SHR"}


class _Builder:
    """Builds one statement's document, taking its tokens in order."""

    def __init__(self, tokens: list, comments: _Comments):
        self.tokens = tokens
        self.index = 0
        self.comments = comments
        self.root = _Group()
        self.stack = [self.root.items]
        self.separator = None        # (container, position, doc) before the next token
        self.trailing: Optional[str] = None

    # -- containers --

    def open(self, node):
        self.stack[-1].append(node)
        self.stack.append(node.items)

    def close(self):
        self.stack.pop()

    # -- separators and tokens --

    def sep(self, doc):
        """What goes between the last token and the next one: "" (nothing),
        " " or LINE. A comment in between turns it into a line break."""
        container = self.stack[-1]
        self.separator = (container, len(container), doc)

    def token(self, type_: str, text: Optional[str] = None, if_break: bool = False):
        tok = self.tokens[self.index]
        if tok.type != type_:       # the tree and the tokens disagree: a bug here
            raise AssertionError(f"formatter expected {type_}, found {tok!r}")
        # the comments before a statement are laid out with the statements
        leading = self.comments.leading.get(tok.start_pos, ()) if self.index else ()
        self.index += 1
        self._place_separator(leading)
        value = text if text is not None else tok.value
        self.stack[-1].append(_IfBreak(value) if if_break else value)
        self.trailing = self.comments.trailing.get(tok.start_pos)

    def peek(self) -> Optional[str]:
        return self.tokens[self.index].type if self.index < len(self.tokens) else None

    def _place_separator(self, leading):
        if self.separator is not None:
            container, position, doc = self.separator
        else:
            container, doc = self.stack[-1], ""
            position = len(container)
        self.separator = None
        if self.trailing is None and not leading:
            if doc != "":
                container.insert(position, doc)
            return
        docs: list = []
        if self.trailing is not None:
            docs.append(_Comment("  " + self.trailing))
            self.trailing = None
        docs.append(HARD)
        for _, comment in leading:
            docs += [_Comment(comment), HARD]
        container[position:position] = docs

    def finish(self) -> _Group:
        if self.index != len(self.tokens):
            raise AssertionError(f"formatter left tokens out: {self.tokens[self.index:]!r}")
        if self.trailing is not None:
            self.root.items.append(_Comment("  " + self.trailing))
        return self.root

    # -- the grammar --

    def statement(self, node):
        if isinstance(node, ast.Rule):
            self.rule(node)
        elif isinstance(node, ast.ActionDef):
            self.token("_ACTION")
            self.sep(" ")
            self.token("NAME")
            self.sep(" ")
            self.token("_EQUAL")
            self.sep(" ")
            self.open(_Indent())
            self.body(node.body)
            self.close()
        elif isinstance(node, (ast.ConstDef, ast.VarDef)):
            self.token("_CONST" if isinstance(node, ast.ConstDef) else "_VAR")
            self.sep(" ")
            self.token("NAME")
            self.sep(" ")
            self.token("_EQUAL")
            self.sep(" ")
            self.value(node.value)
        elif isinstance(node, ast.ExternDef):
            self.extern(node)
        elif isinstance(node, ast.RobotBlock):
            self.robot(node)
        elif isinstance(node, ast.ModeDef):
            if node.initial:
                self.token("_INITIAL")
                self.sep(" ")
            self.token("_MODE")
            self.sep(" ")
            self.token("NAME")
            self.sep(" ")
            self.token("_LBRACE")
        elif isinstance(node, ast.ModeEnd):
            self.token("_RBRACE")
        else:                                       # pragma: no cover
            raise AssertionError(f"unknown statement {node!r}")

    def rule(self, node: ast.Rule):
        if node.name is not None:
            self.token("_RULE")
            self.sep(" ")
            self.token("NAME")
            self.token("_COLON")
            self.sep(" ")
        if node.trigger == "on":
            self.token("_ON")
            self.sep(" ")
            self.call(node.event)
        else:                               # `when COND`, `every D`, `after D`
            self.token("_" + node.trigger.upper())
            self.sep(" ")
            self.open(_Indent())            # a line broken by a comment goes on indented
            self.expr(node.event.args[0].value)
            self.close()
        if node.repeat:
            self.sep(" ")
            self.token("_REPEAT")
        if node.priority is not None:
            self.sep(" ")
            self.token("_PRIORITY")
            self.sep(" ")
            self.token(self.peek())         # a NUMBER or a constant's NAME
        if node.guard is not None:
            self.sep(" ")
            self.token("_IF")
            self.sep(" ")
            self.open(_Indent())
            self.expr(node.guard)
            self.close()
        self.open(_Indent())
        self.sep(LINE)
        self.token("_DO")
        self.sep(" ")
        self.body(node.body)
        self.close()

    def body(self, node: ast.ActionBody):
        self.open(_Group())
        for k, step in enumerate(node.steps):
            if k:
                self.sep(LINE)
                self.token("_THEN")
                self.sep(" ")
            self.step(step)
        self.close()

    def step(self, node: ast.Step):
        self.open(_Group())
        for k, call in enumerate(node.calls):
            if k == 1:
                self.open(_Indent())
            if k:
                self.token("_COMMA")
                self.sep(LINE)
            self.call(call)
        if len(node.calls) > 1:
            self.close()
        self.close()

    def call(self, node):
        if isinstance(node, ast.IfAction):
            self.if_action(node)
            return
        if isinstance(node, ast.Assign):
            self.token("NAME")
            if node.index is not None:
                self.token("_LBRACK")
                self.expr(node.index)
                self.token("_RBRACK")
            self.sep(" ")
            self.token(_ASSIGN_TOKENS[node.op])
            self.sep(" ")
            if isinstance(node.value, ast.ArrayLit):        # `a = [e0, e1, ...]`
                self.arguments(node.value.items, self.expr, ("_LBRACK", "_RBRACK"))
            else:
                self.expr(node.value)
            return
        if isinstance(node, (ast.CancelCall, ast.EnterCall)):
            self.token("_CANCEL" if isinstance(node, ast.CancelCall) else "_ENTER")
            self.sep(" ")
            self.token("NAME")
            return
        if self.peek() == "_ENTER":         # the event `on enter`
            self.token("_ENTER")
            return
        self.token("NAME")
        if node.args is not None:
            self.arguments(node.args, self.arg)

    def if_action(self, node: ast.IfAction):
        """`if C { A } else if D { B } else { E }` on one line when it fits,
        else each branch's actions on their own lines, one indent in, and
        each `}` at the `if`'s indent."""
        self.open(_Group())
        for k, branch in enumerate(node.branches):
            if k:
                self.sep(" ")
                self.token("_ELSE")
                self.sep(" ")
            self.token("_IF")
            self.sep(" ")
            self.open(_Indent())
            self.expr(branch.condition)
            self.close()
            self.sep(" ")
            self.branch(branch.body)
        if node.otherwise is not None:
            self.sep(" ")
            self.token("_ELSE")
            self.sep(" ")
            self.branch(node.otherwise)
        self.close()

    def branch(self, body: ast.ActionBody):
        self.token("_LBRACE")
        self.open(_Indent())
        self.sep(LINE)
        self.body(body)
        self.close()
        self.sep(LINE)
        self.token("_RBRACE")

    def arguments(self, items, each, brackets=("_LPAR", "_RPAR")):
        """`(a, b, c)` (or `[a, b, c]`), breaking after the commas when it
        does not fit."""
        self.open(_Group())
        self.token(brackets[0])
        self.open(_Indent())
        self.open(_Fill())
        for k, item in enumerate(items):
            if k:
                self.token("_COMMA")
                self.sep(LINE)
            each(item)
        self.close()
        self.close()
        self.token(brackets[1])
        self.close()

    def arg(self, node):
        if isinstance(node, ast.NamedArg):
            self.token("NAME")
            self.token("_COLON")
            self.sep(" ")
            self.expr(node.value)
        elif isinstance(node, ast.ConditionArg):
            self.token("NAME")
            self.sep(" ")
            self.token("CMP")
            self.sep(" ")
            self.value(node.value)
        else:
            self.expr(node.value)

    def expr(self, node):
        """An expression: single spaces around binary operators, none after
        a unary minus or inside parentheses."""
        cls = node.__class__
        if cls is ast.BinOp:
            self.expr(node.left)
            self.sep(" ")
            self.token(_OPERATOR_TOKENS.get(node.op, "CMP"))
            self.sep(" ")
            self.expr(node.right)
        elif cls is ast.UnaryOp:
            if node.op == "not":
                self.token("_NOT")
                self.sep(" ")
            else:
                self.token("_TILDE" if node.op == "~" else "MINUS")
            self.expr(node.operand)
        elif cls is ast.Paren:
            self.token("_LPAR")
            self.expr(node.expr)
            self.token("_RPAR")
        elif cls is ast.FuncCall:
            self.token("NAME")
            self.arguments(node.args or (), self.arg)
        elif cls is ast.Index:
            self.token("NAME")
            self.token("_LBRACK")
            self.expr(node.index)
            self.token("_RBRACK")
        elif cls is ast.Slice:          # `a[1:4]`, `a[:4]`, `a[1:]`
            self.token("NAME")
            self.token("_LBRACK")
            if node.lo is not None:
                self.expr(node.lo)
            self.token("_COLON")
            if node.hi is not None:
                self.expr(node.hi)
            self.token("_RBRACK")
        else:
            self.value(node)

    def value(self, node):
        if isinstance(node, ast.ArrayLit):
            self.arguments(node.items, self.value, ("_LBRACK", "_RBRACK"))
            return
        if isinstance(node, ast.Number):
            if node.text.startswith("-"):
                self.token("MINUS")
            self.token("NUMBER")
            if node.unit is not None:
                self.sep(" ")
                self.token("NAME")
                if "/" in node.unit:
                    self.token("_SLASH")
                    self.token("NAME")
        else:
            if node.negative:
                self.token("MINUS")
            self.token("NAME")

    def extern(self, node: ast.ExternDef):
        self.token("_EXTERN")
        self.sep(" ")
        self.token("_ACTION" if node.kind == "action" else "_EVENT")
        self.sep(" ")
        self.token("NAME")
        self.arguments(node.params, self.param)
        self.sep(" ")
        self.token("_FROM")
        self.sep(" ")
        self.token("STRING")

    def param(self, node: ast.ParamDecl):
        self.token("NAME")
        self.token("_COLON")
        self.sep(" ")
        self.token("NAME")

    def robot(self, node: ast.RobotBlock):
        group = _Group()
        self.open(group)
        self.token("_ROBOT")
        self.sep(" ")
        self.token("_LBRACE")
        if node.settings:
            self.open(_Indent())
            for k, setting in enumerate(node.settings):
                if k:
                    self.token("_COMMA")
                self.sep(LINE)
                self.token("NAME")
                self.token("_COLON")
                self.sep(" ")
                self.value(setting.value)
            if self.peek() == "_COMMA":
                group.broken = True         # a trailing comma keeps one setting per line
                self.token("_COMMA", if_break=True)
            else:
                self.stack[-1].append(_IfBreak(","))
            self.close()
            self.sep(LINE)
        self.token("_RBRACE")
        self.close()


# ---- the whole file ---------------------------------------------------------------------

def _parse(text: str, filename: str):
    source = SourceFile(filename, text)
    diags = Collector(source)
    program = parse(source, diags)
    if diags.has_errors:
        raise FormatError(diags.items)
    tokens = list(iter_tokens(source, Collector(source)))
    chunks = list(iter_statements(iter(tokens)))
    if len(chunks) != len(program.statements):     # pragma: no cover - parse() agrees
        raise AssertionError("statements and token chunks disagree")
    return tokens, chunks, program.statements


def format_text(text: str, filename: str = "<stdin>") -> str:
    """The canonical layout of a rule file's text. Raises FormatError (with
    the parser's diagnostics) when the text has syntax errors."""
    if text.startswith("\ufeff"):
        text = text[1:]
    newline = "\r\n" if "\r\n" in text[: text.find("\n") + 1] else "\n"
    # Lines end as SourceFile reads them (a lone CR too), so that the
    # tokens' offsets are offsets into this text.
    text = text.replace("\r\n", "\n").replace("\r", "\n")
    tokens, chunks, statements = _parse(text, filename)
    comments = _collect_comments(text, tokens)
    lines: list = []

    def blank():
        if lines and lines[-1] != "":
            lines.append("")

    depth = 0               # the statements of a mode block are indented
    for chunk, statement in zip(chunks, statements):
        if isinstance(statement, ast.ModeEnd):
            depth -= 1
        margin = " " * (INDENT * depth)
        first = chunk[0].start_pos
        for blank_before, comment in comments.leading.get(first, ()):
            if blank_before:
                blank()
            lines.append(margin + comment)
        if comments.blank_before.get(first) and not isinstance(statement, ast.ModeEnd):
            blank()
        builder = _Builder(chunk, comments)
        builder.statement(statement)
        text = _render(builder.finish(), WIDTH - len(margin))
        lines.append(margin + text.replace("\n", "\n" + margin) if depth else text)
        if isinstance(statement, ast.ModeDef):
            depth += 1
    for blank_before, comment in comments.at_end:
        if blank_before:
            blank()
        lines.append(comment)
    while lines and lines[-1] == "":
        lines.pop()
    if not lines:
        return ""
    return ("\n".join(lines) + "\n").replace("\n", newline)


# ---- the command line ------------------------------------------------------------------


def line_edits(old: str, new: str) -> list:
    """(start offset, end offset, new text) that turn `old` into `new`,
    whole lines at a time, so that an editor keeps the cursor and the
    folds of the lines that did not change."""
    import difflib

    def split(text):
        return [line for line in re.split(r"(?<=\n)", text) if line]
    old_lines, new_lines = split(old), split(new)
    offsets = [0]
    for line in old_lines:
        offsets.append(offsets[-1] + len(line))
    edits = []
    matcher = difflib.SequenceMatcher(None, old_lines, new_lines, autojunk=False)
    for tag, i1, i2, j1, j2 in matcher.get_opcodes():
        if tag != "equal":
            edits.append((offsets[i1], offsets[i2], "".join(new_lines[j1:j2])))
    return edits
