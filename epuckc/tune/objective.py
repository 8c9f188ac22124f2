"""A tune's objective: an arithmetic expression over one run's metrics,
read by a small recursive-descent parser into a tree and evaluated over
floats; nothing of Python's own evaluation is involved.

    expression := term (("+" | "-") term)*
    term       := factor (("*" | "/") factor)*
    factor     := ("-" | "+") factor | atom ("^" factor)?
    atom       := NUMBER | NAME | FUNCTION "(" expression ("," expression)* ")"
                | "(" expression ")"

A NAME is a metric's column (`contacts_walls`, `distance_mm`, `var:hits`)
or a metric's own name for its one column (`coverage` is coverage_cells,
`distance` distance_mm, `still` still_s, `exit` exit_s); the functions are
abs, min, max, sqrt, log and exp. A run's value is the expression over its
swarm row (its robot's, with one robot); the candidate's, an aggregate of
its runs' values: the mean, the median or a quantile."""
from __future__ import annotations

import difflib
import math
import re
from dataclasses import dataclass, field

ALIASES = {"coverage": "coverage_cells", "distance": "distance_mm", "still": "still_s",
           "exit": "exit_s"}
COLUMNS = {"contacts": "contacts", "contacts_walls": "contacts", "contacts_objects": "contacts",
           "contacts_robots": "contacts", "distance_mm": "distance",
           "coverage_cells": "coverage", "still_s": "still", "exit_s": "exit",
           "final_x_mm": "pose", "final_y_mm": "pose", "final_heading_deg": "pose"}
FUNCTIONS = {"abs": (1, abs), "min": (2, min), "max": (2, max), "sqrt": (1, math.sqrt),
             "log": (1, math.log), "exp": (1, math.exp)}
MAX_LENGTH = 2000
MAX_DEPTH = 50
_TOKEN = re.compile(r"\s*(?:(?P<num>(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?)"
                    r"|(?P<name>(?:var|mean):[A-Za-z_][A-Za-z0-9_]*|[A-Za-z_][A-Za-z0-9_]*)"
                    r"|(?P<op>[-+*/^(),]))")


class ObjectiveError(Exception):
    """A bad expression: `column` (from 1) is where in its text."""

    def __init__(self, message: str, column: int, help: str = ""):
        super().__init__(message)
        self.column, self.help = column, help


class RunValueError(ArithmeticError):
    """A run whose value cannot be computed (a division by zero, a missing
    metric, the log of a negative number)."""


@dataclass
class Objective:
    text: str
    tree: tuple
    columns: list = field(default_factory=list)     # the columns it reads, in order

    @property
    def metrics(self) -> list:
        """The experiment metrics that measure its columns."""
        out = []
        for col in self.columns:
            m = COLUMNS.get(col, col)
            if m not in out:
                out.append(m)
        return out

    def value(self, row: dict) -> float:
        """The expression over one run's row; RunValueError when it has none."""
        try:
            v = _eval(self.tree, row)
        except (ZeroDivisionError, ValueError, OverflowError, TypeError) as exc:
            raise RunValueError(str(exc)) from None
        if not math.isfinite(v):
            raise RunValueError("the value is not finite")
        return v


def parse(text: str) -> Objective:
    if len(text) > MAX_LENGTH:
        raise ObjectiveError(f"the objective is longer than {MAX_LENGTH} characters", 1)
    tokens = []
    pos = 0
    while pos < len(text):
        if text[pos:].strip() == "":
            break
        m = _TOKEN.match(text, pos)
        if m is None:
            col = len(text) - len(text[pos:].lstrip()) + 1
            raise ObjectiveError(f"`{text[col - 1]}` has no meaning in an objective", col,
                                 "write + - * / ^, numbers, metrics and abs, min, max, sqrt, "
                                 "log, exp")
        kind = m.lastgroup
        tokens.append((kind, m.group(kind), m.start(kind) + 1))
        pos = m.end()
    if not tokens:
        raise ObjectiveError("the objective is empty", 1, 'objective = "coverage - contacts / 100"')
    parser = _Parser(text, tokens)
    tree = parser.expression(0)
    if parser.i < len(tokens):
        kind, tok, col = tokens[parser.i]
        raise ObjectiveError(f"unexpected `{tok}`", col, "an operator is missing before it?")
    return Objective(text, tree, parser.columns)


class _Parser:
    def __init__(self, text: str, tokens: list):
        self.text, self.tokens, self.i = text, tokens, 0
        self.columns = []

    def peek(self):
        return self.tokens[self.i] if self.i < len(self.tokens) else (None, None,
                                                                        len(self.text) + 1)

    def take(self, op: str) -> bool:
        kind, tok, _ = self.peek()
        if kind == "op" and tok == op:
            self.i += 1
            return True
        return False

    def expression(self, depth: int):
        if depth > MAX_DEPTH:
            raise ObjectiveError("the objective nests too deep", self.peek()[2])
        tree = self.term(depth)
        while True:
            kind, tok, _ = self.peek()
            if kind == "op" and tok in "+-":
                self.i += 1
                tree = (tok, tree, self.term(depth))
            else:
                return tree

    def term(self, depth: int):
        tree = self.factor(depth)
        while True:
            kind, tok, _ = self.peek()
            if kind == "op" and tok in "*/":
                self.i += 1
                tree = (tok, tree, self.factor(depth))
            else:
                return tree

    def factor(self, depth: int):
        if depth > MAX_DEPTH:
            raise ObjectiveError("the objective nests too deep", self.peek()[2])
        if self.take("-"):
            return ("neg", self.factor(depth + 1))
        if self.take("+"):
            return self.factor(depth + 1)
        base = self.atom(depth)
        if self.take("^"):
            return ("^", base, self.factor(depth + 1))
        return base

    def atom(self, depth: int):
        kind, tok, col = self.peek()
        if kind is None:
            raise ObjectiveError("the objective ends too soon", col, "a value is missing here")
        self.i += 1
        if kind == "num":
            return ("num", float(tok))
        if kind == "op" and tok == "(":
            tree = self.expression(depth + 1)
            if not self.take(")"):
                raise ObjectiveError("a `(` is not closed", col, "add a `)`")
            return tree
        if kind == "name" and tok in FUNCTIONS:
            return self.call(tok, col, depth)
        if kind == "name":
            return ("col", self.column(tok, col))
        raise ObjectiveError(f"unexpected `{tok}`", col, "a value is missing before it?")

    def call(self, name: str, col: int, depth: int):
        count, _ = FUNCTIONS[name]
        if not self.take("("):
            raise ObjectiveError(f"{name} is a function: {name}(...)", col)
        args = [self.expression(depth + 1)]
        while self.take(","):
            args.append(self.expression(depth + 1))
        if not self.take(")"):
            raise ObjectiveError(f"the call of {name} is not closed", col, "add a `)`")
        if len(args) != count:
            raise ObjectiveError(f"{name} takes {count} argument{'s' if count > 1 else ''}, "
                                 f"not {len(args)}", col)
        return ("call", name, args)

    def column(self, name: str, col: int) -> str:
        name = ALIASES.get(name, name)
        if name not in COLUMNS and not name.startswith(("var:", "mean:")):
            known = sorted(set(COLUMNS) | set(ALIASES))
            close = difflib.get_close_matches(name, known, n=1)
            raise ObjectiveError(f"`{name}` is not a metric", col,
                                 (f"did you mean `{close[0]}`? " if close else "")
                                 + "the metrics are " + ", ".join(known)
                                 + ", var:NAME and mean:NAME")
        if name not in self.columns:
            self.columns.append(name)
        return name


def _eval(tree: tuple, row: dict) -> float:
    op = tree[0]
    if op == "num":
        return tree[1]
    if op == "col":
        v = row.get(tree[1], "")
        if isinstance(v, bool) or not isinstance(v, (int, float)):
            raise ValueError(f"the run has no value of {tree[1]}")
        return float(v)
    if op == "neg":
        return -_eval(tree[1], row)
    if op == "call":
        _, fn = FUNCTIONS[tree[1]]
        return float(fn(*[_eval(a, row) for a in tree[2]]))
    a, b = _eval(tree[1], row), _eval(tree[2], row)
    if op == "+":
        return a + b
    if op == "-":
        return a - b
    if op == "*":
        return a * b
    if op == "/":
        return a / b
    return float(a ** b) if not (a < 0 and b != int(b)) else math.nan


def aggregate(values: list, how: tuple) -> float:
    """`how`: ("mean",), ("median",) or ("quantile", q); the quantile as
    numpy's default (linear between the order statistics)."""
    s = sorted(values)
    if how[0] == "mean":
        return math.fsum(s) / len(s)
    q = 0.5 if how[0] == "median" else how[1]
    at = q * (len(s) - 1)
    lo = math.floor(at)
    hi = min(lo + 1, len(s) - 1)
    return s[lo] + (s[hi] - s[lo]) * (at - lo)


def describe_aggregate(how: tuple) -> str:
    return how[0] if how[0] != "quantile" else f"quantile {how[1]:g}"
