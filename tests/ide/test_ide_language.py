"""The editor's answers about variables and expressions, from epuckc/ide/
directly: hover with an expression's unit and interval, completion of
variables, readings and functions, rename of a variable, the outline; and
the formatter's layout of the language's statements."""
from epuckc.ide import completion, hover, navigate
from epuckc.ide.fmt import format_text
from epuckc.ide.incremental import Analyzer
from tests.support.ide import where

TEXT = """\
var cruise = 300 steps/s
var bumps = 0
const K = 1 steps/s
on sensor(ir0 > 500) repeat do bumps += 1
every 20 ms do set_speed(left: cruise - (ir0 + ir1) * K / 3, right: cruise)
every 500 ms do cruise = random(200, 400) * 1 steps/s
when bumps >= 3 do stop_motor
on immediate do start_sensor
"""


def analysis(text=TEXT):
    return Analyzer("lang.epk").analyse(text)


def test_hover_on_a_variable_gives_its_kind_and_interval():
    a = analysis()
    text, _ = hover.hover(a, *where(TEXT, "cruise -"))
    assert "Variable: a speed (steps/s), 300 at start" in text
    assert "200..400" in text           # from its initial value and the random assignment
    text, _ = hover.hover(a, *where(TEXT, "bumps >="))
    assert "-32768..32767" not in text or "plain number" in text


def test_hover_on_an_expression_gives_its_unit_and_interval():
    a = analysis()
    # the `-` of `cruise - (...)`: the whole difference
    text, span = hover.hover(a, *where(TEXT, "- (ir0"))
    assert "cruise - (ir0 + ir1) * K / 3" in text
    assert "A speed (steps/s), within -2530..400" in text
    text, _ = hover.hover(a, *where(TEXT, "+ ir1"))
    assert "ir0 + ir1" in text and "within 0..8190" in text
    text, _ = hover.hover(a, *where(TEXT, "ir1"))
    assert "Reading: proximity sensor 1" in text and "0..4095" in text


def test_completion_offers_variables_readings_and_functions():
    a = analysis(TEXT + "when cru")
    labels = [c.label for c in completion.completions(a, 9, 9)]
    assert {"cruise", "bumps", "K", "ir0", "heading", "x", "clamp", "random"} <= set(labels)
    a = analysis(TEXT + "on immediate do ")
    labels = [c.label for c in completion.completions(a, 9, 17)]
    assert {"start_straight", "cruise", "bumps"} <= set(labels)     # actions and assignments
    a = analysis(TEXT + "on stop_motor repeat ")
    labels = [c.label for c in completion.completions(a, 9, 22)]
    assert {"if", "priority", "do"} <= set(labels)


def test_rename_of_a_variable_renames_every_use():
    a = analysis()
    target = navigate.renameable(a, navigate.occurrence_at(a, *where(TEXT, "cruise")))
    edits = navigate.rename_edits(a, target, "speed")
    assert len(edits) == 4          # the declaration, two reads, one assignment
    lines = TEXT.split("\n")
    for span, new in edits:
        lines[span.line - 1] = (lines[span.line - 1][:span.column - 1] + "@" * (
            span.end_column - span.column) + lines[span.line - 1][span.end_column - 1:])
    assert "cruise" not in "\n".join(lines)


def test_outline_lists_variables():
    a = analysis()
    symbols = {(s.name, s.kind) for s in navigate.symbols(a)}
    assert ("cruise", "variable") in symbols and ("bumps", "variable") in symbols


def test_fmt_lays_out_the_language_and_is_idempotent():
    messy = ("var   n=0 # count\nwhen n>=3 and not(ir0<10)repeat   priority 2 if x!=3mm do "
             "n+=1,n -= -2,set_speed(left:300-(ir0+ir1)*1 steps/s/3,right:-n*1 steps/s)\n"
             "every 20 ms do n = abs( - n ) % 7\nafter 1 s do wait(2 s) then exit_main\n")
    once = format_text(messy)
    assert once == (
        "var n = 0  # count\n"
        "when n >= 3 and not (ir0 < 10) repeat priority 2 if x != 3 mm\n"
        "    do n += 1,\n"
        "        n -= -2,\n"
        "        set_speed(left: 300 - (ir0 + ir1) * 1 steps/s / 3, right: -n * 1 steps/s)\n"
        "every 20 ms do n = abs(-n) % 7\n"
        "after 1 s do wait(2 s) then exit_main\n")
    assert format_text(once) == once


def test_fmt_keeps_comments_inside_expressions():
    text = ("var n = 0  # count\nwhen n > 3 and  # many\n   ir0 > 9 do n = 0\n"
            "every 20 ms do set_speed(left: 300 -  # base\n (ir0 + ir1) * 1 steps/s / 3, right: 300)\n")
    once = format_text(text)
    assert "when n > 3 and  # many\n    ir0 > 9\n" in once
    assert "# base" in once and "# count" in once
    assert format_text(once) == once


def test_a_statement_s_definition_is_the_first_of_its_occurrences():
    """navigate.definition finds what a statement defines without a walk
    over its names (a hover in a rule with an error looks at every
    statement): it is the first occurrence when that one defines, over
    random programs of the language, with modes, named actions, externs,
    named rules and a name defined twice."""
    import random

    from tests.support.language import RandomChoices, language_program

    texts = [language_program(RandomChoices(random.Random(s))).text for s in range(40)]
    texts.append(TEXT + "mode m\n  on enter do stop_motor\nend\nconst K = 2\n"
                        "action go do stop_motor\nrule r: on immediate do go\n"
                        "extern action beep() from \"b.c\"\n")
    defined = 0
    for text in texts:
        for s in analysis(text).program.statements:
            first = next(navigate.occurrences(s), None)
            expected = first if first is not None and first.definition else None
            assert navigate.definition(s) == expected
            defined += expected is not None
    assert defined > 40


def test_an_array_is_renamed_in_its_elements_and_indices():
    """The uses of an array in `a[i]`, as an index and as an assigned
    element are references (the walk over generated programs found them
    missing: a rename left `a0[...]` behind, an unknown name)."""
    text = ("var a = [0, 0]\nconst K = [1, 2]\nvar i = 0\n"
            "every 10 ms do a[i] = K[a[1]], i = a[0], if a[i] > 0 { a[1] += 1 }\n")
    a = analysis(text)
    assert all(d.severity != "error" for d in a.diagnostics)
    for name, count in (("a", 6), ("K", 2), ("i", 4)):
        occ = navigate.occurrence_at(a, *where(text, f"{name} "))
        target = navigate.renameable(a, occ)
        edits = navigate.rename_edits(a, target, "renamed")
        assert len(edits) == count, name
