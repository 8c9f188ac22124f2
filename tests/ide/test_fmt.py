"""`epuckc fmt`: the canonical layout, its properties over the corpus and
over generated programs (idempotent, comments kept in order, layout
independent, the same compiled program), and the command line."""
from __future__ import annotations

import dataclasses
import os
import random
import re
import stat
import subprocess
import sys
from pathlib import Path

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from epuckc.diagnostics import Collector, Report
from epuckc.ide.fmt import WIDTH, FormatError, format_text
from epuckc.check.frontend import check_file
from epuckc.syntax.lexer import iter_tokens
from epuckc.lower.program import lower
from epuckc.base.source import SourceFile
from epuckc.stdlib.table import STANDARD_ACTIONS
from epuckc.stdlib.units import UNITS

from tests.support.cli import run_cli

REPO = Path(__file__).resolve().parents[2]


def _parses(path: Path) -> bool:
    source, problem = SourceFile.from_path(path)
    if problem is not None:
        return False
    try:
        format_text(source.text, path.name)
    except FormatError:
        return False
    return True


CORPUS = [p for p in sorted((REPO / "examples").glob("*.epk"))
          + sorted((REPO / "tests" / "golden").glob("*.epk"))
          + sorted((REPO / "tests" / "check" / "cases").glob("*.epk"))
          if _parses(p)]


# ---- helpers ---------------------------------------------------------------------------

def tokens_of(text: str) -> list:
    return list(iter_tokens(SourceFile("t.epk", text), Collector(SourceFile("t.epk", text))))


def comments_of(text: str) -> list:
    """The comments of a text in order (found between tokens, so a `#` inside
    a string is not one), without trailing blanks."""
    out, previous = [], 0
    for token in tokens_of(text) + [None]:
        end = token.start_pos if token is not None else len(text)
        out += [m.group().rstrip(" \t\r\f\v") for m in re.finditer(r"#[^\n]*", text[previous:end])]
        previous = token.end_pos if token is not None else end
    return out


def _strip_comments(model):
    """The lowered program without its comments and debugging labels, which
    quote the source text and its line numbers."""
    if isinstance(model, dict):
        return {k: _strip_comments(v) for k, v in model.items()
                if k not in ("comment", "action_label", "event_label", "labels")}
    if isinstance(model, (list, tuple)):
        return [_strip_comments(v) for v in model]
    return model


def _no_lines(text):
    """A message without the lines it names (W009 names a rule without a
    name by its head and line: `on enter` (line 12)), which the layout moves."""
    return re.sub(r"\blines? \d+(?:, \d+)*", "line N", text) if text else text


def compiled(text: str, path: Path = Path("generated.epk")):
    """What the front end makes of a text: its diagnostics (codes and
    messages, not positions) and, when it compiles, the lowered C model
    (registrations, parameter structs, sequences, geometry)."""
    report = Report()
    result = check_file(path, report, shown_name=path.name, text=text)
    diagnostics = sorted((d.code, d.severity, _no_lines(d.message), _no_lines(d.help))
                         for d in report.diagnostics)
    if result.checked is None:
        return diagnostics, None
    return diagnostics, _strip_comments(dataclasses.asdict(lower(result.checked, text, "test")))


SAFE_GLUE = {"(", ")", "{", "}", ",", ":", "=", "/", "-", ">", "<"}


def rejoin(tokens: list, rnd: random.Random) -> str:
    """The tokens with random layout between them (no comments, no blank lines)."""
    out = []
    for k, tok in enumerate(tokens):
        if k:
            prev = tokens[k - 1]
            glue = prev.value in SAFE_GLUE or tok.value in SAFE_GLUE or (
                prev.type == "NUMBER" and tok.type == "NAME")
            out.append(rnd.choice([" ", "   ", "\n", "\t", "\n  "] + ([""] * 2 if glue else [])))
        out.append(tok.value)
    return "".join(out)


def check_properties(text: str, path: Path = Path("generated.epk"), rnd=None):
    formatted = format_text(text, path.name)
    assert format_text(formatted, path.name) == formatted, "not idempotent"
    assert comments_of(formatted) == comments_of(text), "comments lost or moved"
    assert compiled(formatted, path) == compiled(text, path), "a different program"
    assert formatted == "" or formatted.endswith("\n") and not formatted.endswith("\n\n")
    assert "\n\n\n" not in formatted
    assert all(line == line.rstrip() for line in formatted.split("\n"))
    # A line longer than WIDTH (comments aside) could not have been broken:
    # it holds no `then`, no `do` after other words and no `, `.
    for line in formatted.split("\n"):
        if len(line) > WIDTH and "#" not in line:
            assert not re.search(r", |\S then |\S do ", line), line
    # A file with CRLF line ends formats the same, with CRLF line ends.
    if "\n" in text and "\r" not in text:
        crlf = text.replace("\n", "\r\n")
        assert format_text(crlf, path.name) == formatted.replace("\n", "\r\n")
    # Without comments, the layout of the input does not matter.
    tokens = tokens_of(text)
    canonical = format_text(" ".join(t.value for t in tokens))
    assert format_text(rejoin(tokens, rnd or random.Random(0))) == canonical
    return formatted


# ---- the corpus ------------------------------------------------------------------------

@pytest.mark.parametrize("path", CORPUS, ids=lambda p: f"{p.parent.name}/{p.name}")
def test_corpus_properties(path):
    source, _ = SourceFile.from_path(path)
    formatted = check_properties(source.text, path, random.Random(path.name))
    # (a line may be long where its indentation alone takes half the width:
    # branches nested as deep as E056's cases, where no layout fits)
    long = [line for line in formatted.split("\n") if len(line) > WIDTH and "#" not in line
            and len(line) - len(line.lstrip(" ")) < WIDTH // 2]
    assert long == []


def test_the_examples_are_in_the_formatters_layout(capsys):
    """What users copy from is what `epuckc fmt` writes."""
    status, out, err = run_cli(["fmt", "--check", str(REPO / "examples")], capsys)
    assert status == 0, out + err


def test_corpus_is_not_empty():
    assert len(CORPUS) >= 40
    assert {p.name for p in CORPUS} >= {"paper_fig2.epk", "extern.epk", "units.epk"}


# ---- generated programs ----------------------------------------------------------------

NAMES = st.sampled_from(["go", "turn", "x", "speed", "CRUISE", "a_1", "tick", "near",
                         "a_name_so_long_that_a_few_of_them_fill_a_whole_line_of_the_file"])
CALLEES = st.sampled_from(sorted(STANDARD_ACTIONS) + ["go", "turn", "spin", "action_stop_motor"])
NUMBERS = st.sampled_from(["0", "1", "10", "300", "2.5", "1000", "0.01", "4095"])
UNIT_TOKENS = st.sampled_from([[]] + [u.replace("/", " / ").split() for u in sorted(UNITS)])
MINUS = st.sampled_from([[], ["-"]])


def _join(parts: list, sep: str) -> list:
    out = []
    for k, part in enumerate(parts):
        out += ([sep] if k else []) + part
    return out


values = st.one_of(
    st.tuples(MINUS, NUMBERS, UNIT_TOKENS).map(lambda t: t[0] + [t[1]] + t[2]),
    st.tuples(MINUS, NAMES).map(lambda t: t[0] + [t[1]]))
args = st.one_of(
    values,
    st.tuples(st.sampled_from(["speed", "distance", "radius", "degrees", "time", "x"]), values)
    .map(lambda t: [t[0], ":"] + t[1]),
    st.tuples(st.sampled_from(["ir0", "ir3", "ir7", "ir8"]), st.sampled_from([">", "<"]), values)
    .map(lambda t: [t[0], t[1]] + t[2]))
arg_lists = st.lists(args, max_size=4).map(lambda a: ["("] + _join(a, ",") + [")"])
calls = st.one_of(
    st.tuples(CALLEES, st.one_of(st.just([]), arg_lists)).map(lambda t: [t[0]] + t[1]),
    NAMES.map(lambda n: ["cancel", n]), NAMES.map(lambda n: ["enter", n]))
bodies = st.lists(st.lists(calls, min_size=1, max_size=3).map(lambda c: _join(c, ",")),
                  min_size=1, max_size=4).map(lambda s: _join(s, "then"))
events = st.one_of(
    st.sampled_from([["immediate"], ["stop_motor"], ["event_stop_motor"], ["enter"]]),
    values.map(lambda v: ["timer", "("] + v + [")"]),
    st.lists(st.tuples(st.sampled_from(["ir0", "ir1", "ir7"]), st.sampled_from([">", "<"]),
                       NUMBERS), min_size=1, max_size=3)
    .map(lambda cs: ["sensor", "("] + _join([list(c) for c in cs], ",") + [")"]),
    st.tuples(NAMES, st.one_of(st.just([]), arg_lists)).map(lambda t: [t[0]] + t[1]))
PRIORITIES = st.one_of(st.just([]), st.sampled_from(["0", "2", "300", "2.5", "P"])
                       .map(lambda p: ["priority", p]))
rules = st.tuples(st.one_of(st.just([]), NAMES.map(lambda n: ["rule", n, ":"])), events,
                  st.booleans(), PRIORITIES, bodies).map(
    lambda t: t[0] + ["on"] + t[1] + (["repeat"] if t[2] else []) + t[3] + ["do"] + t[4])
modes = st.tuples(st.booleans(), NAMES, st.lists(rules, max_size=3)).map(
    lambda t: (["initial"] if t[0] else []) + ["mode", t[1], "{"] + _join(t[2], None) + ["}"])
statements = st.one_of(
    rules, rules, modes,
    st.tuples(NAMES, bodies).map(lambda t: ["action", t[0], "="] + t[1]),
    st.tuples(NAMES, values).map(lambda t: ["const", t[0], "="] + t[1]),
    st.tuples(st.lists(st.tuples(st.sampled_from(["axle", "wheel_diameter", "max_speed",
                                                  "steps_per_rev", "x"]), values)
                       .map(lambda t: [t[0], ":"] + t[1]), max_size=4),
              st.booleans()).map(
        lambda t: ["robot", "{"] + _join(t[0], ",") + (["," ] if t[1] and t[0] else []) + ["}"]),
    st.tuples(st.sampled_from(["action", "event"]), NAMES,
              st.lists(st.tuples(NAMES, st.sampled_from(["int", "distance", "speed", "bogus"])),
                       max_size=5)).map(
        lambda t: ["extern", t[0], t[1], "("] + _join([[n, ":", k] for n, k in t[2]], ",")
        + [")", "from", '"x.c"']))
SEPARATORS = [" ", " ", " ", "  ", "\n", "\n", "\t", "\n\n", "\n\n\n", " #C\n", "\n#C\n",
              "\n\n#C\n\n", "#C\n#C\n", "  #C  \n"]


def _layout(draw, words: list) -> str:
    """The words with random spaces, line breaks, blank lines and comments."""
    seps = draw(st.lists(st.sampled_from(SEPARATORS), min_size=len(words) + 1,
                         max_size=len(words) + 1))
    counter = iter(range(10_000))
    seps = [re.sub("#C", lambda _: f"# note {next(counter)}", s) for s in seps]
    return seps[0].lstrip(" ") + "".join(w + s for w, s in zip(words, seps[1:]))


@st.composite
def programs(draw):
    """Any statements the grammar accepts (most do not compile)."""
    words = _join(draw(st.lists(statements, max_size=8)), None)
    return _layout(draw, [w for w in words if w is not None])


VALID_CALLS = ["start_straight(300, 10 cm)", "start_straight(speed: 200 steps/s, distance: -5 cm)",
               "start_curve(radius: 0 mm, degrees: 90 deg, speed: 300)",
               "start_curve(5 cm, -45 deg, 100 mm/s)", "stop_motor", "set_timer", "reset_timer",
               "start_sensor", "stop_sensor", "exit_main", "start_straight(CRUISE, -D)", "turn",
               "action_start_straight(distance: 2 m, speed: 1000)", "led_on(led3)",
               "led_toggle(all)", "led_off(body)", "play_sound(haa)"]
VALID_EVENTS = ["immediate", "stop_motor", "timer(2 s)", "timer(500 ms)",
                "sensor(ir0 > 300, ir7 < 20)", "sensor(ir3 > 1000)", "event_timer(time: 1)",
                "selector(3)", "remote(mute)", "remote(7)", "clap(2000)", "tap(500)",
                "tilt(300)", "ambient(ir2 < 100)"]


@st.composite
def valid_programs(draw):
    """Programs that compile: standard calls, constants, a named action,
    named rules that cancel each other, a robot block."""
    n = draw(st.integers(1, 6))
    parts = ["robot { axle: 50 mm, wheel_diameter: 4 cm }"] if draw(st.booleans()) else []
    parts += ["const CRUISE = 300 steps/s", "const D = 10 cm",
              "action turn = start_curve(0 mm, 90 deg, CRUISE) then set_timer"]
    for k in range(n):
        steps = draw(st.lists(st.lists(st.sampled_from(VALID_CALLS + [f"cancel r{n - 1}"]),
                                       min_size=1, max_size=3), min_size=1, max_size=3))
        body = " then ".join(", ".join(step) for step in steps)
        repeat = " repeat" if draw(st.booleans()) else ""
        repeat += draw(st.sampled_from(["", "", " priority 1", " priority 255"]))
        parts.append(f"rule r{k}: on {draw(st.sampled_from(VALID_EVENTS))}{repeat} do {body}")
    draw(st.randoms(use_true_random=False)).shuffle(parts)
    return _layout(draw, [t.value for t in tokens_of(" ".join(parts))])


@settings(max_examples=200, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(programs(), st.randoms(use_true_random=False))
def test_generated_programs(text, rnd):
    check_properties(text, rnd=rnd)


@settings(max_examples=120, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(valid_programs(), st.randoms(use_true_random=False))
def test_generated_programs_that_compile(text, rnd):
    assert compiled(text)[1] is not None, text
    check_properties(text, rnd=rnd)


# ---- the layout ------------------------------------------------------------------------

@pytest.mark.parametrize("before, after", [
    ("const  X=300steps/s", "const X = 300 steps/s\n"),
    ("on timer( 2 s )repeat do start_straight( speed :300 , distance:- 5cm )",
     "on timer(2 s) repeat do start_straight(speed: 300, distance: -5 cm)\n"),
    ("on sensor(ir0>300,ir7 <  2)do stop_motor,cancel   go",
     "on sensor(ir0 > 300, ir7 < 2) do stop_motor, cancel go\n"),
    ("on immediate do go on stop_motor do quit action go = x const c = - y",
     "on immediate do go\non stop_motor do quit\naction go = x\nconst c = -y\n"),
    ("rule  go :on\nimmediate\ndo\nx\nthen\ny",
     "rule go: on immediate do x then y\n"),
    ('extern   event e ( a:int,b : speed )from"e.c"',
     'extern event e(a: int, b: speed) from "e.c"\n'),
    ("extern action nothing() from 'x'".replace("'", '"'),
     'extern action nothing() from "x"\n'),
    ("robot{axle:53mm,steps_per_rev:1000}", "robot { axle: 53 mm, steps_per_rev: 1000 }\n"),
    ("robot{}", "robot {}\n"),
    ("robot{axle:53mm,}", "robot {\n    axle: 53 mm,\n}\n"),
    ("", ""),
    ("\n\n  \n", ""),
])
def test_spacing(before, after):
    assert format_text(before) == after


def test_long_rules_wrap_at_do_then_then_then_commas():
    steps = "start_curve(radius: 0 mm, degrees: 180 deg, speed: SPEED)"
    assert format_text(f"on timer(3 s) repeat do {steps}") == (
        f"on timer(3 s) repeat do {steps}\n")
    assert format_text(f"rule turn_back: on timer(3 s) repeat do {steps} then exit_main") == (
        f"rule turn_back: on timer(3 s) repeat\n    do {steps} then exit_main\n")
    text = f"rule turn_back: on timer(3 s) repeat do {steps} then start_straight(SPEED, 20 cm)"
    assert format_text(text) == (
        "rule turn_back: on timer(3 s) repeat\n"
        f"    do {steps}\n"
        "    then start_straight(SPEED, 20 cm)\n")
    many = ", ".join(["start_sensor", "set_timer", "reset_timer", "stop_sensor"] * 3)
    assert format_text(f"on immediate do {many} then exit_main") == (
        "on immediate\n    do start_sensor,\n"
        + "".join(f"        {c},\n" for c in many.split(", ")[1:-1])
        + "        stop_sensor\n    then exit_main\n")


def test_named_actions_wrap_at_then():
    text = ("action side = start_straight(speed: SPEED, distance: 20 cm) "
            "then start_curve(radius: 0 mm, degrees: 90 deg, speed: SPEED)")
    assert format_text(text) == (
        "action side = start_straight(speed: SPEED, distance: 20 cm)\n"
        "    then start_curve(radius: 0 mm, degrees: 90 deg, speed: SPEED)\n")


def test_argument_lists_fill_their_lines():
    params = ", ".join(f"p{k}: distance" for k in range(12))
    out = format_text(f'extern action a_long_name({params}) from "a.c"')
    lines = out.splitlines()
    assert lines[0].startswith("extern action a_long_name(p0: distance, p1: distance,")
    assert all(len(line) <= WIDTH for line in lines)
    assert all(line.startswith("    p") for line in lines[1:])
    assert lines[-1].endswith(') from "a.c"')


def test_long_robot_block_has_one_setting_per_line():
    text = ("robot { wheel_diameter: 41 mm, axle: 53 mm, steps_per_rev: 1000, "
            "max_speed: 1000 steps/s, x: 1 }")
    assert format_text(text) == (
        "robot {\n    wheel_diameter: 41 mm,\n    axle: 53 mm,\n    steps_per_rev: 1000,\n"
        "    max_speed: 1000 steps/s,\n    x: 1,\n}\n")


def test_comments_stay_where_they_were():
    text = ("# head\n\n\n# about c\nconst c = 1   # one   \n"
            "rule r: on timer(3 s) repeat  # every 3 s\n"
            "   # turn first\n"
            "   do start_curve(0 mm, 180 deg, 300)  # around\n"
            "      then start_straight(300, 1 cm)\n"
            "# the end\n")
    assert format_text(text) == (
        "# head\n\n# about c\nconst c = 1  # one\n"
        "rule r: on timer(3 s) repeat  # every 3 s\n"
        "    # turn first\n"
        "    do start_curve(0 mm, 180 deg, 300)  # around\n"
        "    then start_straight(300, 1 cm)\n"
        "# the end\n")


def test_blank_line_groups_are_kept_and_collapsed():
    text = "\n\n\nconst a = 1\nconst b = 2\n\n\n\nconst c = 3\n\n# end\n\n\n"
    assert format_text(text) == "const a = 1\nconst b = 2\n\nconst c = 3\n\n# end\n"


def test_crlf_files_stay_crlf():
    assert format_text("const a=1\r\n\r\n\r\non immediate do x  # c\r\n") == (
        "const a = 1\r\n\r\non immediate do x  # c\r\n")


def test_a_leading_byte_order_mark_is_dropped():
    assert format_text("\ufeffconst a=1") == "const a = 1\n"


@pytest.mark.parametrize("text, code", [
    ("on immediate do", "E001"), ("on immediate do x @", "E002"),
    ('extern action a() from "x.c', "E003"), ("const = 3\nconst b = 2", "E001")])
def test_syntax_errors_are_refused(text, code):
    with pytest.raises(FormatError) as info:
        format_text(text, "bad.epk")
    assert code in [d.code for d in info.value.diagnostics]
    assert all(d.file == "bad.epk" for d in info.value.diagnostics)
    assert str(info.value).startswith("bad.epk:")


def test_semantic_errors_are_formatted():
    assert format_text("on  nonsense do  strat_straight") == "on nonsense do strat_straight\n"


# ---- the command line ------------------------------------------------------------------

MESSY = "const  X=300steps/s\non immediate do start_straight(X,10cm)\n"
TIDY = "const X = 300 steps/s\non immediate do start_straight(X, 10 cm)\n"


@pytest.fixture
def work(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "messy.epk").write_text(MESSY)
    (tmp_path / "tidy.epk").write_text(TIDY)
    (tmp_path / "bad.epk").write_text("on immediate do\n")
    return tmp_path


def test_rewrites_in_place_keeping_the_mode(work, capsys):
    (work / "messy.epk").chmod(0o640)
    tidy_inode = (work / "tidy.epk").stat().st_ino
    tidy_mtime = (work / "tidy.epk").stat().st_mtime_ns
    status, out, err = run_cli(["fmt", "messy.epk", "tidy.epk"], capsys)
    assert (status, out, err) == (0, "", "")
    assert (work / "messy.epk").read_text() == TIDY
    assert stat.S_IMODE((work / "messy.epk").stat().st_mode) == 0o640
    # unchanged files are not touched
    assert (work / "tidy.epk").stat().st_ino == tidy_inode
    assert (work / "tidy.epk").stat().st_mtime_ns == tidy_mtime
    assert sorted(p.name for p in work.iterdir()) == ["bad.epk", "messy.epk", "tidy.epk"]


def test_a_symbolic_link_keeps_pointing_at_the_formatted_file(work, capsys):
    (work / "link.epk").symlink_to("messy.epk")
    assert run_cli(["fmt", "link.epk"], capsys)[0] == 0
    assert (work / "link.epk").is_symlink()
    assert (work / "messy.epk").read_text() == TIDY


def test_a_folder_formats_its_rule_files(work, capsys):
    (work / "sub").mkdir()
    (work / "sub" / "deep.epk").write_text(MESSY)
    (work / "sub" / "notes.txt").write_text(MESSY)
    status, out, err = run_cli(["fmt", "--check", "sub"], capsys)
    assert (status, out) == (1, f"would reformat {Path('sub') / 'deep.epk'}\n")
    assert (work / "sub" / "deep.epk").read_text() == MESSY


def test_check_names_the_files_that_would_change(work, capsys):
    status, out, err = run_cli(["fmt", "--check", "messy.epk", "tidy.epk"], capsys)
    assert (status, out, err) == (1, "would reformat messy.epk\n", "")
    assert (work / "messy.epk").read_text() == MESSY
    assert run_cli(["fmt", "--check", "tidy.epk"], capsys) == (0, "", "")


def test_diff_prints_a_unified_diff(work, capsys):
    status, out, err = run_cli(["fmt", "--diff", "messy.epk", "tidy.epk"], capsys)
    assert status == 0 and err == ""
    assert out.startswith("--- messy.epk (original)\n+++ messy.epk (formatted)\n@@ ")
    assert "-const  X=300steps/s\n" in out and "+const X = 300 steps/s\n" in out
    assert "tidy.epk" not in out
    assert (work / "messy.epk").read_text() == MESSY
    status, out, _ = run_cli(["fmt", "--diff", "--check", "messy.epk"], capsys)
    assert status == 1 and "would reformat messy.epk" in out and "+const X" in out


def test_syntax_errors_are_reported_as_check_does_and_nothing_is_written(work, capsys):
    before = (work / "bad.epk").read_bytes()
    status, out, err = run_cli(["fmt", "bad.epk", "messy.epk"], capsys)
    assert status == 1 and out == ""
    _, _, check_err = run_cli(["check", "bad.epk"], capsys)
    assert err == check_err
    assert err.startswith("bad.epk:1:14: error[E001]: expected an action after `do`")
    assert (work / "bad.epk").read_bytes() == before
    assert (work / "messy.epk").read_text() == TIDY       # the other files are formatted


def test_a_file_that_is_not_utf8_is_refused(work, capsys):
    (work / "latin1.epk").write_bytes(b"const a = 1 # caf\xe9\n")
    status, out, err = run_cli(["fmt", "latin1.epk"], capsys)
    assert status == 1 and "error[E004]" in err
    assert (work / "latin1.epk").read_bytes() == b"const a = 1 # caf\xe9\n"


def test_a_missing_file_is_an_io_error(work, capsys):
    status, out, err = run_cli(["fmt", "missing.epk", "messy.epk"], capsys)
    assert status == 2
    assert err == "epuckc: error: cannot read missing.epk: No such file or directory\n"
    assert (work / "messy.epk").read_text() == TIDY


def _stdin(args, data: bytes, cwd):
    env = dict(os.environ, PYTHONPATH=str(REPO))
    return subprocess.run([sys.executable, "-m", "epuckc", "fmt", *args], input=data,
                          capture_output=True, cwd=cwd, env=env)


def test_standard_input_to_standard_output(work):
    result = _stdin(["-"], MESSY.encode(), work)
    assert (result.returncode, result.stdout, result.stderr) == (0, TIDY.encode(), b"")
    # a text with errors comes back unchanged (an editor's filter keeps
    # it), byte for byte; its diagnostics only when asked
    broken = b"on immediate do\r\n\xef\xbb\xbf  # caf\xc3\xa9\n\x00\n"
    result = _stdin(["-"], broken, work)
    assert (result.returncode, result.stdout, result.stderr) == (1, broken, b"")
    result = _stdin(["--errors", "-"], b"on immediate do\n", work)
    assert result.returncode == 1 and result.stdout == b"on immediate do\n"
    assert result.stderr.startswith(b"<stdin>:1:14: error[E001]")
    result = _stdin(["--check", "-"], MESSY.encode(), work)
    assert (result.returncode, result.stdout) == (1, b"would reformat <stdin>\n")
    result = _stdin(["--check", "-"], TIDY.encode(), work)
    assert (result.returncode, result.stdout) == (0, b"")
