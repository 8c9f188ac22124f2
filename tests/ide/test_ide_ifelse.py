"""The editor's answers inside `if/else` actions (issue 25, point 4): hover
on a branch's condition and call, completion inside a branch and after its
`}`, rename and references through the branches, the outline, every
request at every position; and the formatter's layout of an `if`."""
from epuckc.ide import completion, hover, navigate
from epuckc.ide.fmt import format_text
from epuckc.ide.incremental import Analyzer
from tests.support.ide import where

from tests.support.ide_walk import answer_everywhere

TEXT = """\
var near = 0
action back = stop_motor, near = 0
on immediate do start_sensor
every 50 ms do near = clamp(ir0 / 100, 0, 40), if near > 30 { back } else if near > 10 { set_speed(100, 100 steps/s - near * 2 steps/s) } else { set_speed(300, 300) }
mode m {
    on enter do if near < 5 { led_on(body) }
}
"""


def analysis(text=TEXT):
    return Analyzer("ifelse.epk").analyse(text)


def test_the_program_checks_clean():
    assert analysis().diagnostics == []


def test_hover_inside_branches():
    a = analysis()
    # a call of a branch: the standard action's signature
    text, _ = hover.hover(a, *where(TEXT, "set_speed(100"))
    assert "set_speed" in text and "left" in text
    # a condition's variable: its interval
    text, _ = hover.hover(a, *where(TEXT, "near > 30"))
    assert "0..40" in text
    # an expression inside a branch's argument
    text, _ = hover.hover(a, *where(TEXT, "* 2"))
    assert "near * 2" in text
    # a named action run by a branch
    text, _ = hover.hover(a, *where(TEXT, "back }"))
    assert "stop_motor" in text


def test_completion_inside_a_branch_and_after_it():
    a = analysis(TEXT + "on immediate do if near > 3 { ")
    line = TEXT.count("\n") + 1
    labels = {c.label for c in completion.completions(a, line, 31)}
    assert {"start_straight", "near", "back", "if"} <= labels
    a = analysis(TEXT + "on immediate do if near > 3 { back } ")
    labels = {c.label for c in completion.completions(a, line, 37)}
    assert "else" in labels and "then" in labels


def test_rename_and_references_reach_into_branches():
    a = analysis()
    target = navigate.renameable(a, navigate.occurrence_at(a, *where(TEXT, "near")))
    edits = navigate.rename_edits(a, target, "dist")
    # the declaration, the named action's assignment, the assignment, three
    # conditions, the argument, the mode's condition
    assert len(edits) == TEXT.count("near")
    target = navigate.resolve(a, navigate.occurrence_at(a, *where(TEXT, "back =")))
    refs = navigate.references(a, target)
    # the definition and the call inside the first branch
    assert [r.definition for r in refs] == [True, False]
    assert refs[1].statement.span == a.program.statements[3].span


def test_outline_and_every_request_everywhere():
    a = analysis()
    symbols = {(s.name, s.kind) for s in navigate.symbols(a)}
    assert ("near", "variable") in symbols and ("back", "action") in symbols
    assert answer_everywhere(TEXT, "ifelse.epk", step=3) > 0
    # and with the `if` broken while it is typed
    for cut in ("if near > 30 { back", "if near > 30 { back } else", "if near >"):
        partial = TEXT[:TEXT.index(cut) + len(cut)] + "\n"
        answer_everywhere(partial, "partial.epk", step=5)


def test_fmt_lays_out_an_if_and_is_idempotent():
    messy = ("var n=0\nevery 1 s do n+=1,if n>3{n=0,led_on(body)}else if n<0{n=1}"
             "else{led_off(body)}\n"
             "every 2 s do if n > 1 { start_straight(200, 10 cm), led_on(front) } else "
             "{ start_curve(5 cm, 90 deg, 200), led_off(front) } then led_toggle(body)\n")
    once = format_text(messy)
    assert once == (
        "var n = 0\n"
        "every 1 s\n"
        "    do n += 1,\n"
        "        if n > 3 { n = 0, led_on(body) } else if n < 0 { n = 1 } else { led_off(body) }\n"
        "every 2 s\n"
        "    do if n > 1 {\n"
        "        start_straight(200, 10 cm), led_on(front)\n"
        "    } else {\n"
        "        start_curve(5 cm, 90 deg, 200), led_off(front)\n"
        "    }\n"
        "    then led_toggle(body)\n")
    assert format_text(once) == once


def test_fmt_keeps_comments_inside_branches():
    text = ("var n = 0\nevery 1 s do if n > 3 {  # high\n  n = 0  # reset\n} else {\n"
            "  # low\n  n += 1\n}\n")
    once = format_text(text)
    assert "# high" in once and "# reset" in once and "# low" in once
    assert format_text(once) == once
    assert once.index("# high") < once.index("# reset") < once.index("# low")


def test_an_edit_elsewhere_that_changes_a_branchs_intervals_is_seen():
    """The language server reuses a rule's check while nothing it read
    changed; a branch's narrowing reads the intervals of the variables its
    conditions compare, so an edit of another rule that changes them must
    re-check it, and say what a full check says."""
    from pathlib import Path
    from epuckc.check.frontend import check_file
    from epuckc.diagnostics import Report

    def full(text):
        report = Report()
        check_file(Path("e.epk"), report, shown_name="e.epk", text=text)
        return sorted((d.code, d.span.line, d.span.column, d.message) for d in report.diagnostics)

    first = ("var n = 0\nvar m = 0\nevery 1 s do n = clamp(ir0 - 1000, -5, 5)\n"
             "every 2 s priority 1 do if n < 3 { m = n * 3000 }\nwhen m > 5 do stop_motor\n")
    second = first.replace("clamp(ir0 - 1000, -5, 5)", "clamp(ir0 - 1000, -500, 5)")
    analyzer = Analyzer("e.epk")
    for text in (first, second, first):
        got = sorted((d.code, d.span.line, d.span.column, d.message)
                     for d in analyzer.analyse(text).diagnostics)
        assert got == full(text)
    assert any(d[0] == "W020" for d in full(second)) and not any(
        d[0] == "W020" for d in full(first))
