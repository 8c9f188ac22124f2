"""The checker on `if/else` actions (issue 25, point 4): every branch may
run, for the whole-program analyses (W009 races, W010 modes never entered,
E045, the variables' intervals and W017), and none must, for what they
conclude from calls that surely run (W011); conditions narrow the variables
inside their branch (W020, W013), and a variable is back to its whole
interval once a call may assign it."""
from __future__ import annotations

from epuckc.base.source import SourceFile
from epuckc.check.checker import check
from epuckc.diagnostics import Collector
from epuckc.syntax.parser import parse


def _check(text: str):
    source = SourceFile("t.epk", text)
    diags = Collector(source)
    checked = check(parse(source, diags), diags)
    return checked, diags.items


def codes(text: str) -> list:
    return [d.code for d in _check(text)[1]]


def test_a_motion_in_a_branch_races_with_another_rule():
    racing = ("var n = 0\nevery 1 s do n = clamp(n + 1, 0, 9)\n"
              "on immediate do start_sensor\n"
              "on sensor(ir0 > 300) repeat do if n > 3 { start_straight(200, 5 cm) }\n"
              "on sensor(ir7 > 300) repeat do set_speed(100, 100)\n")
    assert codes(racing).count("W009") == 1
    # the motion in the `else` branch too, and through a named action
    for branch in ("if n > 3 { led_on(body) } else { start_straight(200, 5 cm) }",
                   "if n > 3 { led_on(body) } else if n > 1 { go }"):
        text = ("action go = start_straight(200, 5 cm)\n" + racing.replace(
            "if n > 3 { start_straight(200, 5 cm) }", branch))
        assert codes(text).count("W009") == 1, branch
    # no motor command in any branch: no race
    quiet = racing.replace("start_straight(200, 5 cm)", "led_on(body)")
    assert "W009" not in codes(quiet)


def test_a_mode_entered_in_a_branch_is_entered():
    text = ("var n = 0\nevery 1 s do n = clamp(n + 1, 0, 9), if n > 5 { enter home }\n"
            "initial mode away { on enter do led_off(body) }\n"
            "mode home { on enter do led_on(body) }\n")
    assert "W010" not in codes(text)
    assert "W010" in codes(text.replace("if n > 5 { enter home }", "led_toggle(body)"))


def test_a_cancel_in_a_branch_of_another_mode_is_e045():
    text = ("var n = 0\ninitial mode a {\n"
            "    every 1 s do n = clamp(n + 1, 0, 9), if n > 5 { cancel blink } else { n = 0 }\n"
            "}\nmode b {\n    rule blink: every 2 s do led_toggle(body)\n    on enter do enter a\n}\n"
            "on immediate do enter b\n")
    assert "E045" in codes(text)


def test_an_enter_in_a_branch_may_not_run_w011_is_not_said():
    sure = ("var n = 0\nevery 1 s do n = clamp(n + 1, 0, 9)\ninitial mode a {\n"
            "    every 2 s do enter b then led_on(body)\n}\nmode b { on enter do enter a }\n")
    assert "W011" in codes(sure)
    maybe = sure.replace("enter b then", "if n > 5 { enter b } then")
    assert "W011" not in codes(maybe)


def test_an_assignment_in_a_branch_counts_for_the_variable():
    text = ("var n = 0\nvar m = 5\nevery 1 s do n = clamp(n + 1, 0, 9), "
            "if n > 5 { m = 40 } else if n > 2 { m = -3 }\nwhen m > 10 do stop_motor\n")
    checked, items = _check(text)
    assert "W017" not in [d.code for d in items]           # m is assigned, in a branch
    m = checked.variables["m"]
    assert (m.lo, m.hi) == (-3, 40)                         # every branch's value may happen


def test_a_condition_narrows_the_variables_in_its_branch():
    # n is -32768..32767 in general; in the branch, 0..100: no overflow
    text = ("var n = 0\nevery 1 s do n += 1\n"
            "every 2 s priority 1 do if n >= 0 and n <= 100 { n = n * 300 } "
            "else if n > 100 { n = 0 } else { n = n * 2 }\n")
    items = _check(text)[1]
    overflow = [d for d in items if d.code == "W020"]
    lines = {(d.span.line, d.span.column) for d in overflow}
    # `n += 1` (line 2) and `n * 2` in the else branch (n < 0) can saturate; `n * 300` not
    assert (3, text.split("\n")[2].index("n * 2") + 1) in lines
    assert (3, text.split("\n")[2].index("n * 300") + 1) not in lines


def test_after_an_assignment_in_a_branch_the_whole_interval_is_back():
    # n narrowed to 0..10 by the outer branch; `n = 20000` inside the inner
    # branch, then `n * 4` may overflow: the checker must say so
    text = ("var n = 0\nevery 1 s do n = clamp(n + 1, -30000, 30000)\n"
            "every 2 s priority 1 do if n >= 0 and n <= 10 { "
            "if n > 5 { n = 20000 }, n = n * 4 }\n")
    items = _check(text)[1]
    assert any(d.code == "W020" and "n * 4" in d.message for d in items)
    # without the inner assignment the product stays within 0..40
    quiet = text.replace("if n > 5 { n = 20000 }, ", "")
    assert not any(d.code == "W020" and "n * 4" in d.message for d in _check(quiet)[1])


def test_the_guard_and_a_branch_narrow_together():
    text = ("var n = 0\nevery 1 s do n += 1\n"
            "every 2 s priority 1 if n > 0 do if n < 100 { n = n * 300 }\n")
    assert not any(d.code == "W020" and "n * 300" in d.message for d in _check(text)[1])


def test_resolved_if_keeps_its_branches_in_order():
    text = ("var n = 0\nevery 1 s do n = clamp(n + 1, 0, 9), if n > 5 { led_on(body) } "
            "else if n > 2 { led_off(body), n = 1 } else { led_toggle(body) }\n")
    checked, items = _check(text)
    assert [d.code for d in items] == []
    (step,) = checked.rules[0].body
    assign, if_call = step
    assert if_call.kind == "if"
    branches = if_call.values["branches"]
    assert [len(calls) for _, calls in branches] == [1, 2]
    assert [c.name for c in if_call.values["otherwise"]] == ["led_toggle"]
    assert branches[0][0].op == ">" and branches[0][0].args[1].value == 5


def test_a_cycle_through_a_branch_is_e023():
    text = ("var n = 0\naction a = if n > 0 { b }\naction b = n = 0, a\n"
            "every 1 s do a\n")
    assert "E023" in codes(text)


def _interval(text, name):
    v = _check(text)[0].variables[name]
    return v.lo, v.hi


def test_a_capped_counter_keeps_its_cap():
    # the assignment runs only where its branch's condition (or the guard) held
    assert _interval("var n = 0\nevery 1 s do if n < 100 { n += 1 }\n"
                     "when n > 50 do stop_motor\n", "n") == (0, 100)
    assert _interval("var n = 0\nevery 1 s if n < 100 do n += 1\n"
                     "when n > 50 do stop_motor\n", "n") == (0, 100)
    # the failed conditions before an `else` hold too
    assert _interval("var n = 0\nevery 1 s do if n >= 100 { led_on(body) } else { n += 1 }\n"
                     "when n > 50 do stop_motor\n", "n") == (0, 100)


def test_a_variable_assigned_since_its_condition_is_not_narrowed():
    # n = 500 after `n < 100` was evaluated: n += 1 can give 501
    for body in ("if n < 100 { n = 500, n += 1 }",
                 "if n < 100 { n = 500, if ir0 > 3 { n += 1 } }",
                 "if n < 100 { bump, n += 1 }"):
        text = ("var n = 0\naction bump = n = 500\n"
                f"every 1 s do {body}\nwhen n > 50 do stop_motor\n")
        lo, hi = _interval(text, "n")
        assert hi >= 501, body
