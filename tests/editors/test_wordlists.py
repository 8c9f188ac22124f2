"""The editors' word lists are generated from the lexer and the standard
table (epuckc/ide/wordlists.py): the committed Vim syntax file and TextMate
grammar are byte for byte what generation gives, a new reading, action,
event, function, unit or keyword changes what it gives (so the first test
fails until `python3 -m epuckc.ide.wordlists --write`), and completion's
statement starts are the lexer's."""
from __future__ import annotations

import json
import re

import pytest

from epuckc.ide import completion, wordlists
from epuckc.ide.incremental import Analyzer
from epuckc.stdlib.table import ActionSpec, EventSpec, Reading
from epuckc.syntax.lexer import KEYWORDS, STATEMENT_STARTS


def test_the_committed_files_are_what_generation_gives():
    for rel, (now, new) in wordlists.generated().items():
        assert now == new, f"{rel} is stale: run `python3 -m epuckc.ide.wordlists --write`"


def test_the_command_says_when_files_are_stale(tmp_path, monkeypatch, capsys):
    for rel in wordlists.GENERATORS:
        (tmp_path / rel).parent.mkdir(parents=True)
        (tmp_path / rel).write_text((wordlists.REPO / rel).read_text(encoding="utf-8"),
                                    encoding="utf-8")
    monkeypatch.setattr(wordlists, "REPO", tmp_path)
    assert wordlists.main([]) == 0
    _add_a_reading(monkeypatch)
    assert wordlists.main([]) == 1
    assert "epuck.vim is stale" in capsys.readouterr().out
    assert wordlists.main(["--write"]) == 0
    assert "rebuild the studio's page" in capsys.readouterr().out
    assert wordlists.main([]) == 0
    assert "dummy_level" in (tmp_path / wordlists.VIM).read_text(encoding="utf-8")


def _add_a_reading(monkeypatch):
    extra = Reading("dummy_level", "int", 0, 10, "rt_dummy_level()", "a reading for the test")
    monkeypatch.setattr(wordlists, "READINGS", (*wordlists.READINGS, extra))


def _vim_words(text: str, group: str) -> set:
    return {w for line in re.findall(rf"^syntax keyword {group} (.*)$", text, re.M)
            for w in line.split()}


def _textmate(text: str, rule: str) -> str:
    return json.loads(text)["repository"][rule]["match"]


def _both():
    (vim_now, vim), (tm_now, tm) = (wordlists.generated()[wordlists.VIM],
                                    wordlists.generated()[wordlists.TEXTMATE])
    return vim, tm


def test_a_new_reading_reaches_both_editors(monkeypatch):
    _add_a_reading(monkeypatch)
    vim, tm = _both()
    assert "dummy_level" in _vim_words(vim, "epuckReading")
    assert re.fullmatch(_textmate(tm, "sensor"), "dummy_level")


def test_a_new_action_and_event_reach_both_editors(monkeypatch):
    action = ActionSpec("dummy_beep", (), "a beep for the test", "rt_dummy_beep")
    event = EventSpec("dummy_bump", (), "a bump for the test", "rt_dummy_bump")
    monkeypatch.setattr(wordlists, "STANDARD_ACTIONS", {**wordlists.STANDARD_ACTIONS,
                                                        "dummy_beep": action})
    monkeypatch.setattr(wordlists, "ACTION_ALIASES", {**wordlists.ACTION_ALIASES,
                                                      "action_dummy_beep": "dummy_beep"})
    monkeypatch.setattr(wordlists, "STANDARD_EVENTS", {**wordlists.STANDARD_EVENTS,
                                                       "dummy_bump": event})
    vim, tm = _both()
    assert {"dummy_beep", "action_dummy_beep", "dummy_bump"} <= _vim_words(vim, "epuckBuiltin")
    for word in ("dummy_beep", "action_dummy_beep", "dummy_bump", "event_dummy_bump"):
        assert re.fullmatch(_textmate(tm, "builtin"), word)


def test_a_new_function_unit_and_keyword_reach_both_editors(monkeypatch):
    monkeypatch.setattr(wordlists, "FUNCTIONS", {**wordlists.FUNCTIONS,
                                                 "dummy_fn": (("x",), "for the test")})
    monkeypatch.setattr(wordlists, "UNITS", {**wordlists.UNITS, "km/s": ("speed", 1)})
    monkeypatch.setattr(wordlists, "KEYWORDS", {**wordlists.KEYWORDS, "unless": "_UNLESS"})
    vim, tm = _both()
    assert "dummy_fn" in _vim_words(vim, "epuckFunction")
    assert re.match(_textmate(tm, "function"), "dummy_fn(1)")
    assert 'syntax match epuckUnit contained "\\<km\\s*/\\s*s\\>"' in vim
    found = re.match(_textmate(tm, "quantity"), "3 km / s")
    assert found and found.group(2) == "km / s"
    assert "unless" in _vim_words(vim, "epuckKeyword")
    patterns = json.loads(tm)["repository"]["keyword"]["patterns"]
    assert re.fullmatch(patterns[1]["match"], "unless")


def test_the_words_are_the_tables():
    assert set(wordlists.declarations()) | set(wordlists.control_keywords()) \
        | set(wordlists.OPERATOR_KEYWORDS) == set(KEYWORDS)
    assert len(wordlists.declarations() + wordlists.control_keywords()
               + list(wordlists.OPERATOR_KEYWORDS)) == len(KEYWORDS)
    # longest units first in TextMate (`m/s` must not stop at `m`)
    regex = json.loads(wordlists.generated()[wordlists.TEXTMATE][1])["repository"]["quantity"]
    for text, unit in (("2 m/s", "m/s"), ("2 ms", "ms"), ("2 m", "m"), ("300 steps/s", "steps/s"),
                       ("4 steps", "steps")):
        assert re.match(regex["match"], text).group(2) == unit


@pytest.mark.parametrize("text", ["", "const A = 1\n"])
def test_completion_offers_every_statement_start_of_the_lexer(text):
    analysis = Analyzer("start.epk").analyse(text)
    line = text.count("\n") + 1
    labels = {c.label for c in completion.completions(analysis, line, 1) if c.kind == "keyword"}
    starts = {k for k, t in KEYWORDS.items() if t in STATEMENT_STARTS}
    assert starts <= labels
    assert {"mode", "initial"} <= labels
