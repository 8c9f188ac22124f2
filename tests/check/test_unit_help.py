"""The unit help (issue 41, check/convert.py): a value of one kind where
another is wanted gets the conversion that fits the two kinds as a fix,
which, applied, gives a program that checks and computes the same number;
a fraction says the unit it is taken in and the finer unit to write."""
from __future__ import annotations

import itertools

import pytest

from epuckc.base.source import SourceFile
from epuckc.check.checker import check
from epuckc.diagnostics import Collector
from epuckc.syntax.parser import parse

# a variable of each kind, and a value of it
KINDS = {"distance": ("d", "0 mm"), "speed": ("v", "0 steps/s"), "angle": ("a", "0 deg"),
         "duration": ("t", "0 ms")}
UNIT = {"distance": "mm", "speed": "steps/s", "angle": "deg", "duration": "ms"}
HEAD = "".join(f"var {name} = {value}\n" for name, value in KINDS.values())


def _check(text: str) -> list:
    source = SourceFile("p.epk", text)
    diags = Collector(source)
    check(parse(source, diags), diags)
    return diags.items


def _apply(text: str, fix) -> str:
    lines = text.split("\n")
    line = lines[fix.span.line - 1]
    lines[fix.span.line - 1] = line[:fix.span.column - 1] + fix.text + line[fix.span.end_column - 1:]
    return "\n".join(lines)


def test_an_angle_into_a_speed_gets_the_docs_idiom():
    """`turn = err * 6`: the factor takes the unit wanted."""
    text = "var err = 0 deg\nvar turn = 0 steps/s\nevery 20 ms do err = 90 deg - heading, " \
           "turn = err * 6\n"
    [d] = _check(text)
    assert d.code == "E048"
    [fix] = d.fixes
    assert fix.text == "err / 1 deg * 6 steps/s"
    assert "an angle does not become a speed by itself" in d.help
    assert [x for x in _check(_apply(text, fix)) if x.severity == "error"] == []


@pytest.mark.parametrize("have,want", list(itertools.permutations(KINDS, 2)))
def test_every_pair_of_kinds_has_a_conversion_that_checks(have, want):
    src, _ = KINDS[have]
    dst, _ = KINDS[want]
    for value, fixed in ((f"{src} * 3", f"{src} / 1 {UNIT[have]} * 3 {UNIT[want]}"),
                         (f"{src} + {src}", f"({src} + {src}) / 1 {UNIT[have]} * 1 {UNIT[want]}")):
        text = HEAD + f"every 20 ms do {dst} = {value}\n"
        errors = [d for d in _check(text) if d.severity == "error"]
        assert [d.code for d in errors] == ["E048"]
        [fix] = errors[0].fixes
        assert fix.text == fixed
        assert [d for d in _check(_apply(text, fix)) if d.severity == "error"] == [], fixed


def test_an_argument_of_the_wrong_kind_gets_the_conversion():
    text = "var err = 0 deg\nevery 20 ms do set_speed(err * 3, 200 steps/s)\n"
    [d] = [x for x in _check(text) if x.severity == "error"]
    assert d.code == "E019" and d.fixes[0].text == "err / 1 deg * 3 steps/s"
    assert not [x for x in _check(_apply(text, d.fixes[0])) if x.severity == "error"]


@pytest.mark.parametrize("condition,words", [
    ("abs(a) > 0.8", "angles are whole degrees, not radians: `0.8` is 0.8 deg"),
    ("abs(a) > 0.8", "0.8 rad is `46 deg`"),
    ("0.5 < d", "distances are whole millimetres: `0.5` is 0.5 mm"),
    ("d > 0.5", "`0.5 cm` is 5 mm"),
    ("t > 1.5", "`1.5 s`, which is 1500 ms"),
])
def test_a_fraction_says_its_unit_and_the_finer_one(condition, words):
    [d] = _check(HEAD + f"every 20 ms if {condition} do stop_motor\n")
    assert d.code == "E038" and words in d.help, d.help


def test_a_fraction_assigned_says_the_variable_s_unit():
    [d] = _check(HEAD + "every 20 ms do a = 0.5\n")
    assert d.code == "E038" and "angles are whole degrees" in d.help
    # a plain number keeps the plain help
    [d] = _check("var n = 0\nevery 20 ms do n = 0.5\n")
    assert d.code == "E038" and d.help == "write 1"
