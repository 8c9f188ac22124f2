"""The hand-written LALR driver (epuckc/syntax/lalr.py) against Lark's own LALR
parser with its tree builder, statement by statement: the same AST (same
nodes, fields and spans) where a statement parses, the same unexpected
token and the same expected terminals where it does not. Over the corpus
(examples, golden inputs, diagnostic cases) and over generated programs,
valid ones from the grammar and mutated ones, so that a change to the
grammar or to the driver that makes them disagree fails here."""
from __future__ import annotations

from pathlib import Path

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from epuckc.syntax import lalr
from epuckc.diagnostics import Collector
from epuckc.syntax.lexer import iter_statements, iter_tokens
from epuckc.syntax.parser import _CALLBACKS, _tables
from epuckc.base.source import SourceFile, Span

from tests.support.lark_reference import lark_parser, parse_with_lark
from .test_robustness import WORDS

REPO = Path(__file__).resolve().parents[2]
CORPUS = sorted(list((REPO / "examples").glob("*.epk")) + list((REPO / "tests" / "golden").glob("*.epk"))
                + list((REPO / "tests" / "check" / "cases").glob("*.epk")))
LARK = lark_parser()


def parse_with_driver(chunk):
    try:
        return "ok", lalr.parse(_tables(), chunk, _CALLBACKS, meta=Span)
    except lalr.ParseError as exc:
        tok = exc.token
        return "error", (None if tok.type == "$END" else tok.start_pos, set(exc.expected))


def compare(text: str) -> int:
    """Parse every statement of `text` both ways; the number compared."""
    source = SourceFile("input.epk", text)
    count = 0
    for chunk in iter_statements(iter_tokens(source, Collector(source))):
        ours = parse_with_driver(chunk)
        theirs = parse_with_lark(LARK, chunk)
        assert ours == theirs, f"statement {[t.value for t in chunk]}"
        count += 1
    return count


def test_the_corpus_is_there():
    assert len(CORPUS) > 40


@pytest.mark.parametrize("path", CORPUS, ids=lambda p: p.name)
def test_corpus(path):
    data = path.read_bytes()
    try:
        text = data.decode("utf-8")
    except UnicodeDecodeError:
        text = data.decode("utf-8", "replace")
    compare(text.replace("\0", " "))


def test_valid_statements_give_nodes_with_spans():
    """The comparison is not vacuous: the corpus has statements that parse."""
    text = (REPO / "examples" / "obstacle_avoidance.epk").read_text(encoding="utf-8")
    source = SourceFile("x.epk", text)
    results = [parse_with_driver(c) for c in iter_statements(iter_tokens(source, Collector(source)))]
    assert sum(kind == "ok" for kind, _ in results) >= 3


# ---- generated programs ----------------------------------------------------------------

names = st.sampled_from(["go", "x", "turn_left", "r1", "ir0", "ir7", "speed", "cruise",
                         "start_straight", "stop_motor", "timer", "sensor", "immediate"])
numbers = st.sampled_from(["0", "1", "300", "2.5", "4095", "10"])
units = st.sampled_from(["", " mm", " cm", " steps/s", " deg", " ms", " s", " m/s"])


@st.composite
def value(draw):
    minus = draw(st.sampled_from(["", "-"]))
    if draw(st.booleans()):
        return minus + draw(numbers) + draw(units)
    return minus + draw(names)


@st.composite
def arg(draw):
    kind = draw(st.integers(0, 2))
    if kind == 0:
        return draw(value())
    if kind == 1:
        return f"{draw(names)}: {draw(value())}"
    return f"{draw(names)} {draw(st.sampled_from(['>', '<']))} {draw(value())}"


@st.composite
def call(draw):
    if draw(st.integers(0, 5)) == 0:
        return f"cancel {draw(names)}"
    name = draw(names)
    if draw(st.booleans()):
        return name
    return f"{name}({', '.join(draw(st.lists(arg(), max_size=4)))})"


@st.composite
def body(draw):
    steps = draw(st.lists(st.lists(call(), min_size=1, max_size=3), min_size=1, max_size=3))
    return " then ".join(", ".join(step) for step in steps)


@st.composite
def statement(draw):
    kind = draw(st.integers(0, 5))
    if kind == 0:
        settings_ = [f"{draw(names)}: {draw(value())}" for _ in range(draw(st.integers(0, 3)))]
        trailing = "," if settings_ and draw(st.booleans()) else ""
        return f"robot {{ {', '.join(settings_)}{trailing} }}"
    if kind == 1:
        return f"const {draw(names)} = {draw(value())}"
    if kind == 2:
        return f"action {draw(names)} = {draw(body())}"
    if kind == 3:
        params = ", ".join(f"{draw(names)}: {draw(names)}"
                           for _ in range(draw(st.integers(0, 3))))
        kind_ = draw(st.sampled_from(["action", "event"]))
        return f'extern {kind_} {draw(names)}({params}) from "{draw(names)}.c"'
    head = f"rule {draw(names)}: " if draw(st.booleans()) else ""
    event = draw(call()).replace("cancel ", "")
    repeat = " repeat" if draw(st.booleans()) else ""
    return f"{head}on {event}{repeat} do {draw(body())}"


programs = st.lists(statement(), min_size=1, max_size=6).map("\n".join)
SETTINGS = settings(max_examples=200, deadline=None, suppress_health_check=[HealthCheck.too_slow])


@SETTINGS
@given(programs)
def test_generated_programs(text):
    compare(text)


@st.composite
def mutated(draw):
    """A generated program with a few words deleted, repeated or inserted:
    mostly syntax errors, at every place of the grammar."""
    words = draw(programs).split(" ")
    for _ in range(draw(st.integers(1, 4))):
        i = draw(st.integers(0, len(words) - 1))
        op = draw(st.sampled_from(["delete", "duplicate", "insert"]))
        if op == "delete" and len(words) > 1:
            del words[i]
        elif op == "duplicate":
            words.insert(i, words[i])
        else:
            words.insert(i, draw(st.sampled_from(WORDS)))
    return " ".join(words)


@SETTINGS
@given(mutated())
def test_mutated_programs(text):
    compare(text)


def test_the_shipped_tables_are_the_grammars():
    """epuckc/syntax/_parse_tables.py is what `python3 -m epuckc.syntax.lalr` writes from
    grammar/epuck.lark now (Lark's tables, numbered the same way whatever
    the hash seed), and the parser uses it: after editing the grammar, run
    that command."""
    from epuckc.base.resources import grammar_path
    grammar = grammar_path().read_text(encoding="utf-8")
    shipped = Path(lalr.__file__).with_name(lalr.SHIPPED)
    assert shipped.read_text(encoding="utf-8") == lalr.tables_module(grammar, "statement"), \
        "grammar/epuck.lark changed: run `python3 -m epuckc.syntax.lalr`"
    tables = lalr._shipped(grammar, "statement")
    assert tables is not None and _tables().packed == tables.packed


def test_tables_do_not_depend_on_the_hash_seed():
    import os
    import subprocess
    import sys
    probe = ("from epuckc.syntax import lalr; from epuckc.base.resources import grammar_path; "
             "import sys; sys.stdout.write(lalr.tables_module("
             "grammar_path().read_text(encoding='utf-8'), 'statement'))")
    outputs = {subprocess.run([sys.executable, "-c", probe], capture_output=True, text=True,
                              env=dict(os.environ, PYTHONHASHSEED=seed),
                              check=True).stdout for seed in ("1", "2")}
    assert len(outputs) == 1
