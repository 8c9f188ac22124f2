"""The C front end (epuckc/syntax/_front*.c) against the Python one (lexer.py,
lalr.py): for every file, either the C front end gives up (and then the
Python one has something to report) or both give the same program (same
nodes, fields and spans) and the same diagnostics. Over the corpus, over
generated programs (modes, priorities, comments, strings, every kind of
statement) and over programs with random words and characters put in, so
that a change to the grammar, the lexer or the driver that makes them
disagree fails here."""
from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from epuckc.syntax import accel

from epuckc.syntax import ast

from epuckc.syntax import parser
from epuckc.diagnostics import Collector
from epuckc.base.records import FrozenInstanceError
from epuckc.base.source import SourceFile

from .test_lalr_vs_lark import CORPUS, body, call, mutated, names
from .test_lalr_vs_lark import statement as any_statement
from .test_robustness import WORDS

REPO = Path(__file__).resolve().parents[2]


def _front():
    try:
        from epuckc.syntax import _front
    except ImportError:
        reason = "the C front end is not built (`pip install -e .` builds it; CI must have it)"
        if os.environ.get("EPUCKC_REQUIRE_ALL_TOOLS"):
            pytest.fail(reason)
        pytest.skip(reason)
    assert not accel.stale(_front.__file__), \
        "a C source of epuckc/syntax/_front*.c changed after it was built: run `pip install -e .` again"
    return _front


@pytest.fixture(scope="module")
def driver():
    return parser.make_c_driver(_front(), parser._tables(), parser._CALLBACKS)


def _diagnostics(diags: Collector):
    return [(d.code, d.severity, d.message, d.span, d.help) for d in diags.items]


def compare(driver, text: str) -> bool:
    """Parse `text` both ways; whether the C front end took it."""
    source = SourceFile("input.epk", text)
    python_diags = Collector(source)
    expected = parser.parse_python(source, python_diags)
    c_diags = Collector(source)
    got = parser.parse_c(driver, source, c_diags)
    if got is None:
        assert python_diags.has_errors, "the C front end gave up on a file with nothing wrong"
        assert not c_diags.items
        return False
    assert got == expected
    assert _diagnostics(c_diags) == _diagnostics(python_diags)
    return True


@pytest.mark.parametrize("path", CORPUS, ids=lambda p: p.name)
def test_corpus(driver, path):
    data = path.read_bytes()
    try:
        text = data.decode("utf-8")
    except UnicodeDecodeError:
        text = data.decode("utf-8", "replace")
    compare(driver, text.replace("\0", " "))


def test_the_c_front_end_takes_the_valid_corpus(driver):
    """Not vacuous: the examples are taken by the C front end, and their
    programs have statements."""
    taken = 0
    for path in sorted((REPO / "examples").glob("*.epk")):
        text = path.read_text(encoding="utf-8")
        taken += compare(driver, text)
        assert parser.parse_c(driver, SourceFile("x", text), Collector(SourceFile("x", text)))
    assert taken >= 5


def test_a_different_program_is_told_apart(driver):
    """The comparison sees a one-character change in a span or a value."""
    one = parser.parse_python(SourceFile("a", "on immediate do go(1 cm)"),
                              Collector(SourceFile("a", "")))
    two = parser.parse_c(driver, SourceFile("a", "on immediate do go(2 cm)"),
                         Collector(SourceFile("a", "")))
    three = parser.parse_c(driver, SourceFile("a", "on immediate do  go(1 cm)"),
                           Collector(SourceFile("a", "")))
    assert one != two and one != three


@pytest.mark.parametrize("text", [
    "on immediate do go # café",                    # not ASCII, in a comment
    'extern action f() from "dossier/é\\"t\\\\.c"',  # and in a string, with escapes
    "const x = 10cm\n\n\n  on immediate do go(x)",   # a unit glued to its number
    "robot { axle: 53 mm, }",
    "initial mode a {\non immediate priority 2 do enter b\n}\nmode b { on enter do stop_motor }",
    "rule r: on timer(1 s) repeat priority p do set_timer then cancel r",
    "on sensor(ir0 > -5, ir1 < 3.25) do start_curve(radius: 5 cm, degrees: -90 deg, speed: 2 m/s)",
    "", "   \n\n# only a comment", "}", "{",
    # the bitwise operators, hexadecimal and binary numbers, slices, arrays assigned
    "var n = 0x1F\nvar m = 0B101\nevery 1 s do n = (n + 1) & 0xfF, m = ~n << 2 | m >> 1 ^ 0b1",
    "var a = [0, 0, 0]\nwhen sum(a[1:3]) + max(a[:2]) + min(a[1:]) > 0x7 do a = [1, a[0] | 2, 3]",
])
def test_written_cases(driver, text):
    compare(driver, text)


@pytest.mark.parametrize("text", [
    "on immediate do go(2e3)",          # E007
    "on immediate do café",             # E008
    'extern action f() from "open',      # E003
    "on immediate do go $",             # E002
    "on immediate go",                  # E001
    "on immediate do go(1.)",
    'extern action f() from "a\\',
    "var n = 0x1G",                     # E009
    "var n = 0b",
    "var n = 0b2",
])
def test_the_c_front_end_leaves_mistakes_to_python(driver, text):
    assert not compare(driver, text)


# ---- generated programs ----------------------------------------------------------------

blanks = st.sampled_from([" ", "  ", "\t", " # a comment\n", "\n", "\n\n  ", " \f"])


@st.composite
def statement(draw):
    """Every statement of the driver's own test, plus what it leaves out:
    mode blocks, priorities, `enter`, and file names with escapes and
    letters that are not ASCII."""
    kind = draw(st.integers(0, 3))
    if kind == 0:
        return draw(any_statement())
    if kind == 1:
        kind_ = draw(st.sampled_from(["action", "event"]))
        file = draw(st.sampled_from(["dir/b.c", 'q\\"uote.c', "ünï.c"]))
        return f'extern {kind_} {draw(names)}() from "{file}"'
    if kind == 2:
        rules = draw(st.lists(rule(), max_size=3))
        initial = "initial " if draw(st.booleans()) else ""
        return f"{initial}mode {draw(names)} {{\n" + "\n".join(rules) + "\n}"
    return draw(rule())


@st.composite
def rule(draw):
    head = f"rule {draw(names)}: " if draw(st.booleans()) else ""
    event = "enter" if draw(st.integers(0, 6)) == 0 else draw(call()).replace("cancel ", "")
    repeat = " repeat" if draw(st.booleans()) else ""
    priority = draw(st.sampled_from(["", " priority 3", " priority high"]))
    actions = draw(body())
    if draw(st.integers(0, 4)) == 0:
        actions += f", enter {draw(names)}"
    return f"{head}on {event}{repeat}{priority} do {actions}"


@st.composite
def programs(draw):
    statements = draw(st.lists(statement(), min_size=1, max_size=6))
    text = "\n".join(statements)
    # blanks and comments between words
    words = text.split(" ")
    return "".join(w + (draw(blanks) if draw(st.integers(0, 5)) == 0 else " ") for w in words)


SETTINGS = settings(max_examples=300, deadline=None, suppress_health_check=[HealthCheck.too_slow])


@SETTINGS
@given(programs())
def test_generated_programs(driver, text):
    compare(driver, text)


@SETTINGS
@given(mutated())
def test_mutated_programs(driver, text):
    compare(driver, text)


@st.composite
def with_characters(draw):
    """A generated program with a few characters put in anywhere: bad
    characters, quotes, exponents, letters that are not ASCII, braces."""
    text = draw(programs())
    for _ in range(draw(st.integers(1, 3))):
        i = draw(st.integers(0, len(text)))
        piece = draw(st.sampled_from(['"', "\\", "$", "é", "e5", "E-3", ".", "{", "}", "#",
                                      "\n", "-", ":", "=", "٣", "_", "0", "\x0b"]
                                     + WORDS))
        text = text[:i] + piece + text[i:]
    return text


@SETTINGS
@given(with_characters())
def test_programs_with_characters_put_in(driver, text):
    compare(driver, text)


# ---- which front end runs -------------------------------------------------------------------

def test_check_uses_the_c_front_end_unless_told_not_to(driver):
    """`EPUCKC_PURE_PYTHON=1` runs the Python front end, and both give the
    same output on a file with a mistake and on one without."""
    probe = ("import sys; from epuckc.syntax import parser; "
             "print(parser._c_driver() is not None)")
    env = dict(os.environ, PYTHONPATH=str(REPO))
    env.pop("EPUCKC_PURE_PYTHON", None)
    assert subprocess.run([sys.executable, "-c", probe], env=env, capture_output=True,
                          text=True).stdout.strip() == "True"
    pure = dict(env, EPUCKC_PURE_PYTHON="1")
    assert subprocess.run([sys.executable, "-c", probe], env=pure, capture_output=True,
                          text=True).stdout.strip() == "False"
    for name in ("obstacle_avoidance.epk",):
        path = REPO / "examples" / name
        outs = [subprocess.run([sys.executable, "-m", "epuckc", "check", str(path)], env=e,
                               capture_output=True, text=True, cwd=REPO) for e in (env, pure)]
        assert outs[0].returncode == outs[1].returncode == 0
        assert outs[0].stderr == outs[1].stderr


# ---- makers: the nodes the callbacks build ----------------------------------------------------

NODE_CLASSES = [c for c in vars(ast).values()
                if isinstance(c, type) and issubclass(c, ast.Node) and c._fields]


def test_every_node_class_is_covered():
    assert {ast.Ident, ast.Number, ast.Rule, ast.ExternDef} <= set(NODE_CLASSES)


@pytest.mark.parametrize("cls", NODE_CLASSES, ids=lambda c: c.__name__)
def test_makers_make_what_the_class_makes(cls, monkeypatch):
    """ast.maker(cls)(*fields) is cls(*fields), frozen, both from the C
    accelerator and from Python."""
    values = [f"field {i}" for i in range(len(cls._fields))]
    expected = cls(*values)
    c_maker = _front().maker(cls)
    monkeypatch.setattr(accel, "front", lambda: None)
    python_maker = ast.maker(cls)
    for make in (c_maker, python_maker):
        made = make(*values)
        assert type(made) is cls and made == expected
        assert [getattr(made, f) for f in cls._fields] == values
        with pytest.raises(FrozenInstanceError):
            setattr(made, cls._fields[0], "changed")
        with pytest.raises(TypeError):
            make(*values, "one too many")
    with pytest.raises(TypeError):
        c_maker(*values[:-1])


def test_the_c_maker_takes_only_classes_of_plain_slots():
    front = _front()

    class WithNew(ast.Node):
        __slots__ = ("a",)

        def __new__(cls, *args):
            return super().__new__(cls)

    class NoSlot:
        _fields = ("a",)

    for cls in (WithNew, NoSlot, int):
        with pytest.raises(TypeError):
            front.maker(cls)


def test_setup_builds_the_files_accel_checks(tmp_path):
    """setup.py compiles the C front end from the files accel.stale watches,
    so an edit to any of them (a header too) retires the built module."""
    import ast as python_ast
    setup = python_ast.parse((REPO / "setup.py").read_text())
    lists = {node.targets[0].id: python_ast.literal_eval(node.value) for node in setup.body
             if isinstance(node, python_ast.Assign) and isinstance(node.targets[0], python_ast.Name)
             and node.targets[0].id in ("SOURCES", "HEADERS")}
    assert tuple(lists["SOURCES"]) == accel.SOURCES and tuple(lists["HEADERS"]) == accel.HEADERS
    on_disk = {p.name for p in (REPO / "epuckc" / "syntax").glob("_front*.[ch]")}
    assert on_disk == set(accel.SOURCES + accel.HEADERS)
    # a header newer than the module makes it stale
    built = tmp_path / "_front.so"
    built.write_bytes(b"")
    for name in accel.SOURCES + accel.HEADERS:
        (tmp_path / name).write_text("")
    old = built.stat().st_mtime - 10
    for name in accel.SOURCES + accel.HEADERS:
        os.utime(tmp_path / name, (old, old))
    assert not accel.stale(str(built))
    os.utime(tmp_path / "_front.h", None)
    assert accel.stale(str(built))
