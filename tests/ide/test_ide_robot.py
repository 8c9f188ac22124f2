"""The editor's answers about priorities, modes and the rest of the robot,
from epuckc/ide/ (hover.py, completion.py, navigate.py) directly: hover on an enumerated argument, completion
of LED names and modes, document symbols and definitions of modes."""
from epuckc.ide import completion, hover, navigate
from epuckc.ide.incremental import Analyzer
from tests.support.ide import where

TEXT = """\
const urgent = 3
initial mode explore {
    on enter do led_on(led0), start_straight(300, 10 cm)
    rule bump: on tap(600) repeat priority urgent do play_sound(haa)
    on remote(5) do enter home
}
mode home {
    on enter do led_off(all)
}
"""


def analysis(text=TEXT):
    return Analyzer("robot.epk").analyse(text)


def test_the_example_checks_clean():
    a = analysis()
    assert [d.code for d in a.diagnostics] == []


def test_hover_on_an_enumerated_argument_and_a_standard_event():
    a = analysis()
    text, _ = hover.hover(a, *where(TEXT, "led0"))
    assert "`led`: LED, one of `led0`" in text and "`front`" in text
    text, _ = hover.hover(a, *where(TEXT, "tap("))
    assert "tap(threshold: int)" in text and "0..4095" in text


def test_hover_and_definition_of_a_mode():
    a = analysis()
    occ = navigate.occurrence_at(a, *where(TEXT, "enter home", 6))
    assert occ is not None and occ.namespace == "mode"
    target = navigate.resolve(a, occ)
    assert target is not None and a.real(target.ident.span).line == 7
    text, _ = hover.hover(a, *where(TEXT, "mode home", 5))
    assert "Mode `home`" in text
    text, _ = hover.hover(a, *where(TEXT, "mode explore", 5))
    assert "the initial mode" in text


def test_symbols_list_the_modes():
    symbols = {(s.name, s.kind, s.detail) for s in navigate.symbols(analysis())}
    assert ("explore", "mode", "initial") in symbols and ("home", "mode", "") in symbols


def test_completion_offers_the_values_of_an_enumerated_parameter_and_the_modes():
    text = TEXT.replace("led_off(all)", "led_off(")
    labels = {c.label for c in completion.completions(analysis(text), *where(text, "led_off(", 8))}
    assert {"led0", "led7", "all", "body", "front"} <= labels
    text = TEXT.replace("enter home", "enter ")
    labels = {c.label for c in completion.completions(analysis(text), *where(text, "do enter ", 9))}
    assert {"explore", "home"} <= labels
