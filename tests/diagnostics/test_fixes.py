"""Suggestions a tool can apply (diagnostics.Fix): the help line of
`epuckc check` is the fix's own sentence, and applying a fix removes the
diagnostic it was offered for."""
from __future__ import annotations

from pathlib import Path

import pytest

from epuckc.diagnostics import Report
from epuckc.check.frontend import check_file
from epuckc.ide.statements import line_starts

CASES = Path(__file__).resolve().parents[1] / "check" / "cases"

# one mistake per line, each with a suggestion
MISTAKES = """\
action go = stop_motor
const K = 5 cm
on immediate do start_straight(300, 2 m then go
on immediate do strat_sensor, go(4), start_straight(300, Kx)
on immediate start_sensor
on immediate do start_straight(speed = 300, distance: 5 cm)
const J: 5 cm
on sensor(ir8 > 300) do stop_motr
on sensor(ir0 > 300.5) do stop_motor
on timer(2 mss) do set_timer
on stop_motor do start_curve(radius: 1 cm, degree: 90 deg, speed: 100)
on stop_motor do cancel patrl
rule patrol: on tmer(2 s) do exit_main
robot { axle: 0 mm, wheel_diam: 41 mm }
extern action blink(n: itn) from "blink.c"
on timer(5) do exit_main
on stop_motor Do exit_main
"""


def diagnostics(text: str) -> list:
    report = Report()
    check_file(Path("/nonexistent/fix.epk"), report, shown_name="fix.epk", text=text)
    return report.sorted()


def apply(text: str, fix) -> str:
    starts = line_starts(text)
    start = starts[fix.span.line - 1] + fix.span.column - 1
    end = starts[fix.span.end_line - 1] + fix.span.end_column - 1
    return text[:start] + fix.text + text[end:]


def test_help_is_the_fix_sentence():
    fixed = [d for d in diagnostics(MISTAKES) if d.fixes]
    assert {d.code for d in fixed} >= {"E001", "E010", "E011", "E012", "E013", "E014", "E016",
                                       "E020", "E022", "E031", "E037", "E038", "W008"}
    for d in fixed:
        assert d.help.startswith(d.fixes[0].help)


@pytest.mark.parametrize("path", [None] + sorted(CASES.glob("*.epk")),
                         ids=lambda p: "mistakes" if p is None else p.stem)
def test_applying_a_fix_removes_its_diagnostic(path):
    text = MISTAKES if path is None else path.read_text(encoding="utf-8", errors="replace")
    for d in diagnostics(text):
        for fix in d.fixes:
            after = apply(text, fix)
            line = d.span.line
            left = [e for e in diagnostics(after)
                    if e.code == d.code and e.span.line == line and e.message == d.message]
            assert not left, (d, fix)


@pytest.mark.parametrize("name", ["E001_repeat_after_priority", "E002_degree_sign",
                                  "E001_equals_in_call", "E001_missing_do"])
def test_applying_every_fix_leaves_no_error(name):
    """Fixes of syntax mistakes make the file check clean: a fix that trades
    one error for another (as a `)` inserted after `and` did) is worse than
    none."""
    text = (CASES / f"{name}.epk").read_text(encoding="utf-8")
    while True:
        fixable = [d for d in diagnostics(text) if d.fixes]
        if not fixable:
            break
        text = apply(text, fixable[-1].fixes[0])      # from the end: spans stay true
    assert not [d for d in diagnostics(text) if d.severity == "error"], text


def test_or_and_and_between_conditions_are_fixed():
    text = (CASES / "E001_and_in_sensor.epk").read_text(encoding="utf-8")
    found = diagnostics(text)
    ands = [d for d in found if "`and`" in d.message]
    ors = [d for d in found if "`or`" in d.message]
    assert len(ands) == 2 and len(ors) == 2
    for d in ands:      # `,` would mean or: the fix is the `when` rule that means and
        assert "when ir0 >" in d.fixes[0].text
    for d in ors + ands:
        fixed = apply(text, d.fixes[0])
        assert not [e for e in diagnostics(fixed)
                    if e.severity == "error" and e.span.line == d.span.line], fixed
