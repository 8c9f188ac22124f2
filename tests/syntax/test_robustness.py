"""No input makes epuckc crash: binary junk, bad encodings, huge lines, deep
nesting, empty files; and property tests over token soups and mutations of
the example programs. Every diagnostic must have a known code and a span
inside the file."""
from __future__ import annotations

import json
import random
import re
from pathlib import Path

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from epuckc.diagnostics.codes import CODES
from epuckc.diagnostics import Report
from epuckc.diagnostics.render import render_report
from epuckc.check.frontend import check_file
from epuckc.syntax.lexer import KEYWORDS, PUNCTUATION

from tests.support.cli import run_cli

REPO = Path(__file__).resolve().parents[2]
EXAMPLES = sorted((REPO / "examples").glob("*.epk")) + sorted(
    p for p in (REPO / "tests" / "check" / "cases").glob("ok_*.epk"))


def check_text(text: str | None = None, data: bytes | None = None, tmp_path=None) -> Report:
    """Check a text (or raw bytes, through a file) and validate every diagnostic."""
    report = Report()
    if data is not None:
        path = tmp_path / "input.epk"
        path.write_bytes(data)
        check_file(path, report, shown_name="input.epk")
    else:
        check_file(Path("input.epk"), report, shown_name="input.epk", text=text)
    source = report.sources["input.epk"]
    for d in report.diagnostics:
        assert d.code in CODES, d
        s = d.span
        assert 1 <= s.line <= source.line_count, d
        assert 1 <= s.end_line <= source.line_count, d
        assert s.column >= 1 and s.end_column >= 1, d
        assert (s.line, s.column) <= (s.end_line, s.end_column), d
        assert s.column <= len(source.line_text(s.line)) + 1, d
        assert s.end_column <= len(source.line_text(s.end_line)) + 1, d
        for note in d.notes:
            if note.span is not None:
                assert 1 <= note.span.line <= source.line_count
    for fmt in ("human", "gcc", "short", "json"):
        render_report(report, fmt)
    return report


def codes(report) -> list:
    return [d.code for d in report.sorted()]


# ---- fixed nasty inputs -------------------------------------------------------------

def test_empty_file():
    assert codes(check_text("")) == ["W006"]


def test_only_comments():
    assert codes(check_text("# nothing\n   # at all\n\n")) == ["W006"]


def test_lone_quote():
    assert "E003" in codes(check_text('"'))


def test_lone_quote_at_end_of_rule():
    assert "E003" in codes(check_text('on immediate do stop_motor "\n'))


def test_random_bytes(tmp_path):
    rnd = random.Random(1234)
    for _ in range(20):
        data = bytes(rnd.randrange(256) for _ in range(rnd.randrange(1, 3000)))
        assert check_text(data=data, tmp_path=tmp_path).error_count >= 1 or not data.strip()


def test_nul_bytes(tmp_path):
    report = check_text(data=b"on immediate do stop_motor\n\0\0\0", tmp_path=tmp_path)
    assert codes(report) == ["E004"]
    assert report.diagnostics[0].span.line == 2


def test_invalid_utf8(tmp_path):
    report = check_text(data=b"on immediate do stop_motor # caf\xe9\n", tmp_path=tmp_path)
    assert codes(report) == ["E004"]
    assert "0xe9" in report.diagnostics[0].message


def test_utf16_file(tmp_path):
    data = "on immediate do start_straight(300, 10 cm)\n".encode("utf-16")
    assert codes(check_text(data=data, tmp_path=tmp_path)) == ["E004"]


def test_utf8_bom_is_accepted(tmp_path):
    data = b"\xef\xbb\xbfon immediate do start_straight(300, 10 cm)\n"
    assert codes(check_text(data=data, tmp_path=tmp_path)) == []


def test_non_ascii_letters_are_reported_once_per_name():
    report = check_text("action d\u00e9marr\u00e9 = stop_motor\n"
                        "on immediate do d\u00e9marr\u00e9, d\u00e9marr\u00e9\n")
    assert codes(report) == ["E008"]
    [diag] = report.diagnostics
    assert "names are ASCII" in diag.message and "`demarre`" in diag.help


def test_huge_line_of_junk():
    report = check_text("@" * 10_000_000)
    assert codes(report) == ["E002", "E002"] or codes(report) == ["E002"]
    text = render_report(report, "human")
    assert len(text) < 2000


def test_huge_line_of_many_bad_runs_stops_early():
    report = check_text("a @ " * 2_500_000)
    assert 1 <= report.error_count <= 25
    assert len(render_report(report, "human")) < 20_000


def test_huge_line_of_valid_tokens():
    # 2 MB (45,000 rules) keeps the suite fast; 10 MB takes about 15 s on a
    # slow machine, linear in the size (see docs/performance.md).
    rule = "on immediate do start_straight(300, 10 cm) "
    text = rule * (2_000_000 // len(rule))
    report = check_text(text)
    assert report.error_count == 0          # the rules are tables: no capacity to exceed
    assert len(render_report(report, "human")) < 5000


def test_huge_call_on_one_line():
    text = "on immediate do " + ", ".join(["set_timer"] * 100_000)
    report = check_text(text)
    assert report.error_count == 0
    assert len(render_report(report, "human")) < 5000


def test_deep_nesting():
    report = check_text("(" * 100_000)
    assert "E001" in codes(report)
    report = check_text("on immediate do stop_motor(" + "(" * 100_000 + ")" * 100_000)
    assert "E001" in codes(report)
    assert len(render_report(report, "human")) < 5000


def test_many_statements_each_broken():
    report = check_text("on do\n" * 5000)
    assert codes(report) == ["E001"] * 5000


@pytest.mark.parametrize("text", [
    "-", "- -", "on", "rule", "rule x", "rule x:", "robot", "robot {", "robot }",
    "extern", 'extern action', 'extern action x() from', 'extern event x(a: int) from "',
    "const", "const x =", "const x = -", "action a =", "action a = then",
    "on immediate do cancel", "on sensor(ir0 >) do stop_motor", "on timer(1 s/) do x",
    "on timer(1 steps/s/s) do stop_motor", "\r\n\r\n", "\t\f\v", "\u2028\u2029",
    "on immediate do start_straight(-x, -1 m)", "const a = b\nconst b = a\non immediate do start_straight(a, 1 cm)",
    "const a = a\non immediate do start_straight(a, 1 cm)",
    "action a = b\naction b = a\non immediate do a",
    "robot { max_speed: 2000 }\non immediate do start_straight(300, 10 cm)",
    "robot { wheel_diameter: 41 mm, wheel_circumference: 128 mm }",
    "robot { axle: 10 steps }", "robot { steps_per_rev: 0.5 }", "robot{}robot{}",
    "extern event e(a: int, a: int) from \"x.c\"\non e(1, 2) do stop_motor",
    "on stop_motor do stop_motor(1)", "on sensor(1) do stop_motor", "on sensor() do x",
    "on sensor(ir0 > 1.5) do stop_motor", "on timer(99999999999999999999 s) do set_timer",
    "on immediate do start_curve(1e5)", "on immediate do start_curve(10 cm, 100000 deg, 300)",
    "on immediate do start_straight(" + "9" * 400 + ", 1 cm)",
])
def test_odd_inputs(text):
    check_text(text)


def test_check_from_the_cli_on_binary_junk(tmp_path, monkeypatch, capsys):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "junk.epk").write_bytes(bytes(range(256)) * 50)
    status, out, err = run_cli(["check", "--format", "json", "junk.epk"], capsys)
    assert status == 1 and err == ""
    assert {d["code"] for d in json.loads(out)} == {"E004"}


# ---- property tests -------------------------------------------------------------------

WORDS = sorted(KEYWORDS) + sorted(set(PUNCTUATION)) + [
    "immediate", "stop_motor", "timer", "sensor", "start_straight", "start_curve",
    "set_timer", "start_sensor", "exit_main", "ir0", "ir9", "speed", "distance", "x",
    "0", "300", "2.5", "-", "cm", "mm", "s", "ms", "deg", "steps", '"a.c"', '"', "#c\n",
    "\n", "int", "angle", "@", "é", "\0",
]
SETTINGS = settings(max_examples=150, deadline=None,
                    suppress_health_check=[HealthCheck.too_slow])


@SETTINGS
@given(st.lists(st.sampled_from(WORDS), max_size=60),
       st.lists(st.sampled_from([" ", "", "\n", "\t"]), min_size=60, max_size=60))
def test_token_soup_never_crashes(words, seps):
    check_text("".join(w + s for w, s in zip(words, seps)))


def _example_tokens():
    out = []
    for path in EXAMPLES:
        text = path.read_text(encoding="utf-8")
        out.append(re.findall(r'#[^\n]*\n|"[^"\n]*"|\w+(?:\.\w+)?|\s+|.', text))
    return out


EXAMPLE_TOKENS = _example_tokens()


@st.composite
def mutated_example(draw):
    tokens = list(draw(st.sampled_from(EXAMPLE_TOKENS)))
    for _ in range(draw(st.integers(1, 5))):
        if not tokens:
            break
        i = draw(st.integers(0, len(tokens) - 1))
        op = draw(st.sampled_from(["delete", "duplicate", "swap", "insert"]))
        if op == "delete":
            del tokens[i]
        elif op == "duplicate":
            tokens.insert(i, tokens[i])
        elif op == "swap":
            j = draw(st.integers(0, len(tokens) - 1))
            tokens[i], tokens[j] = tokens[j], tokens[i]
        else:
            tokens.insert(i, draw(st.sampled_from(WORDS)))
    return "".join(tokens)


def test_examples_are_there():
    assert EXAMPLE_TOKENS


@SETTINGS
@given(mutated_example())
def test_mutated_examples_never_crash(text):
    check_text(text)


@SETTINGS
@given(st.text(max_size=200))
def test_any_text_never_crashes(text):
    check_text(text)


def test_capitalised_keywords_are_names_where_a_name_fits():
    """`Robot` is a name (keywords are lower case): an action may be called
    that, also first on a line inside a statement."""
    report = check_text("action Robot = stop_motor\non immediate do\n    Robot\n")
    assert codes(report) == []


# One of each statement kind, as written inside a mode block.
IN_MODE = {
    "RobotBlock": "robot { axle: 53 mm }",
    "ConstDef": "const K = 1",
    "VarDef": "var count = 0",
    "ActionDef": "action go = stop_motor",
    "ExternDef": 'extern action spin() from "spin.c"',
    "Rule": "every 1 s do led_toggle(body)",
    "ModeDef": "mode inner {",
    "ModeEnd": "}",
}


def test_every_statement_kind_has_an_answer_inside_a_mode():
    """Inside a mode, each kind of statement is a rule of the mode or a
    coded error (E001) that says what it is, never a crash; outside, the
    same text is accepted. A new statement kind needs a sample here."""
    import typing
    from epuckc.syntax import ast
    kinds = {cls.__name__ for cls in typing.get_args(ast.Statement)}
    assert kinds == set(IN_MODE), "a statement kind without a sample in IN_MODE"
    for kind, text in IN_MODE.items():
        cls = getattr(ast, kind)
        assert cls.described, kind
        program = f"mode m {{\n    {text}\n}}\non immediate do enter m\n"
        if kind == "ModeDef":
            program = "mode m {\n    mode inner {\n    }\n}\non immediate do enter m\n"
        elif kind == "ModeEnd":     # the `}` that closes the mode
            program = "mode m {\n    every 1 s do stop_motor\n}\non immediate do enter m\n"
        got = codes(check_text(program))
        if kind in ("Rule", "ModeEnd"):
            assert not [c for c in got if c.startswith("E")], (kind, got)
        else:
            assert "E001" in got, (kind, got)
            report = check_text(program)
            said = "starts inside mode" if kind == "ModeDef" else cls.described
            assert any(said in d.message for d in report.diagnostics), kind
