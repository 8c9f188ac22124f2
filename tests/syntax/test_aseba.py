"""Aseba's constructs in a rule file (issue 41): each gets its own code
naming the construct and the epuckc way, wherever an action or a
statement may start, through the batch front end and the language
server's alike; epuckc's own uses of the same words are left alone."""
from __future__ import annotations

import pytest

from epuckc.base.source import SourceFile
from epuckc.check.checker import check
from epuckc.diagnostics import Collector
from epuckc.ide.incremental import Analyzer
from epuckc.syntax.parser import parse

# (code, the construct, what the help names)
CONSTRUCTS = [
    ("E090", "while i < 3 do\n    i += 1\nend", "`every 50 ms"),
    ("E090", "for k in 0:2 do\n    i += a[k]\nend", "`sum(a)`"),
    ("E091", "on immediate do i++", "`i += 1`"),
    ("E091", "on immediate do led_on(body), i--", "`i -= 1`"),
    ("E091", "on immediate do ++i", "`i += 1`"),
    ("E092", "sub turn\n    i = 1", "`action turn = ACTIONS`"),
    ("E092", "on immediate do callsub turn", "`action turn = ACTIONS`"),
    ("E093", "onevent prox\n    i = ir0", "`on EVENT do ACTION`"),
    ("E094", "on immediate do emit ping i", "`send(VALUE)`"),
    ("E094", "on immediate do if i > 2 { emit ping }", "`on message do"),
    ("E095", "on immediate do call math.dot(i, a, a, 0)", "`dot(a, b)`"),
    ("E095", "on immediate do call math.argbounds(a, i)", "`argmin(a)`"),
    ("E096", "on immediate do sort(a)", "`argmax(a)`"),
    ("E096", "every 1 s do i = sort(a) + 1", "`argmin(a)`"),
]
HEAD = "var i = 0\nvar a = [1, 2, 3]\n"


def _diagnostics(text: str) -> list:
    source = SourceFile("p.epk", text)
    diags = Collector(source)
    check(parse(source, diags), diags)
    return diags.items


@pytest.mark.parametrize("code,construct,fix", CONSTRUCTS)
def test_each_construct_has_its_code_and_the_epuckc_way(code, construct, fix):
    text = HEAD + construct + "\n"
    found = _diagnostics(text)
    assert [d.code for d in found] == [code], [(d.code, d.message) for d in found]
    d = found[0]
    assert fix in d.help, d.help
    word = {"E090": construct.split()[0], "E092": "sub" if construct.startswith("sub")
            else "callsub", "E093": "onevent", "E094": "emit", "E095": "call",
            "E096": "sort"}.get(code, "++" if "++" in construct else "--")
    assert f"`{word}`" in d.message
    # the language server says the same
    analysis = Analyzer("p.epk").analyse(text)
    assert [(x.code, x.span) for x in analysis.diagnostics] == [(d.code, d.span)]


def test_the_lines_before_a_loop_are_still_a_statement():
    """`var s = 0` then `while` on the next line reach the parser as one
    statement (no keyword of epuckc's starts the loop): the declaration is
    kept, so `s` is not unknown below."""
    found = _diagnostics("var s = 0\nwhile s < 3 do\n    s += 1\nend\nevery 1 s do s = 2\n")
    assert [d.code for d in found] == ["E090"]


def test_the_fix_of_plus_plus_is_an_assignment():
    text = HEAD + "on immediate do i++\n"
    [d] = _diagnostics(text)
    [fix] = d.fixes
    fixed = text.splitlines()
    line = fixed[fix.span.line - 1]
    fixed[fix.span.line - 1] = (line[:fix.span.column - 1] + fix.text
                                + line[fix.span.end_column - 1:])
    assert fixed[-1] == "on immediate do i += 1"
    assert not [d for d in _diagnostics("\n".join(fixed) + "\n") if d.severity == "error"]


@pytest.mark.parametrize("text", [
    "var call = 0\nvar emit = 1\non immediate do call = emit + 1, emit -= 1\n",
    "var for_x = 0\non immediate do for_x = --for_x\n",
    "action sub_step = stop_motor\non immediate do sub_step\n",
])
def test_epuckc_s_own_uses_of_the_words_are_left_alone(text):
    assert not [d for d in _diagnostics(text) if d.code.startswith("E09")]


def test_a_real_syntax_error_near_such_a_word_is_still_e001():
    found = _diagnostics("var call = 0\non immediate do call = call + )\n")
    assert [d.code for d in found] == ["E001"]
