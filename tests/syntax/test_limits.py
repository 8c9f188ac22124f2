"""One depth limit for every nesting (syntax/limits.py), and every stage
within it: at exactly MAX_DEPTH, each way of nesting (operators, calls,
parentheses, indexes, conditions, `if`s inside `if`s, named actions
spliced into branches, and mixtures) is checked, compiled, built with gcc
and 16-bit avr-gcc under -Werror, formatted, and answered by the editor at
every 13th position, all with a stack already 150 frames deep (a margin
for callers); one level more is E056, the same in `check`, `compile` and
the language server, from either front end, and `compile` writes nothing.
tests/syntax/test_depth_property.py draws mixtures at random."""
from __future__ import annotations

import random
from functools import lru_cache
import subprocess
from pathlib import Path

import pytest

from conftest import require_tool
from epuckc.base.source import SourceFile
from epuckc.check.frontend import check_file
from epuckc.diagnostics import Collector, Report
from epuckc.emit.program import emit_program
from epuckc.ide.fmt import format_text
from epuckc.ide.incremental import Analyzer
from epuckc.syntax import accel
from epuckc.syntax.limits import MAX_DEPTH, SLACK, measure
from epuckc.syntax.parser import _c_driver, parse_c, parse_python

from tests.support.cli import run_cli
from tests.support.ide_walk import answer_everywhere
from tests.support.language import RandomChoices
from tests.support.nesting import CLOSE_ACTION, CLOSE_COND, HEAD, layer, nested, repeated

REPO = Path(__file__).resolve().parents[2]
RUNTIME = REPO / "runtime_c"
STRICT = ["-std=c99", "-Wall", "-Wextra", "-Werror", "-pedantic"]

A, C = CLOSE_ACTION, CLOSE_COND     # `v = {}`, `{} > 3`
NE = layer("{} != v")


@lru_cache(maxsize=None)
def shapes(n: int) -> dict:
    """Statements exactly `n` levels deep, one per way of nesting."""
    every = "every 10 ms do {}"
    out = {
        "calls": repeated(every, [A], "abs({})", [], n),
        "clamp": repeated("every 11 ms do {}", [A], "clamp({}, -5, 5)", [], n),
        "parentheses": repeated("every 12 ms do {}", [A], "({})", [], n),
        "sum": repeated("every 13 ms do {}", [A], "{} + 1", [], n),
        "right sum": repeated("every 14 ms do {}", [A], "1 - {}", [], n),
        "product": repeated("every 15 ms do {}", [A], "{} * 2", [], n),
        "minus": repeated("every 16 ms do {}", [A], "-({})", [], n),
        "unary minus": repeated("every 17 ms do {}", [A], "- {}", [], n),
        "indexes": repeated("every 18 ms do {}", [A], "a[{}]", [], n),
        "index assigned": repeated("every 19 ms do {}", [layer("a[{}] = 1")], "a[{}]", [], n),
        "speed": repeated("every 20 ms priority 3 do {}",
                          [layer("set_speed(({}) * 1 steps/s, 0 steps/s)")], "({})", [], n),
        "not": repeated("when {} priority 1 do stop_motor", [], "not {}", [C], n),
        "and": repeated("when {} priority 2 do stop_motor", [], "{} and v > 1", [C], n),
        "or": repeated("when {} priority 4 do stop_motor", [], "v < 9 or {}", [C], n),
        "guard": repeated("every 21 ms if {} do v = v + 1", [], "({})", [C], n),
        "ifs": repeated("every 22 ms do {}", [], "if v > 0 {{ {} }}", [A], n),
        "else": repeated("every 23 ms do {}", [], "if v > 0 {{ v = 1 }} else {{ {} }}", [A], n),
        # deep sides of a comparison the intervals do not decide (the checker
        # compares their forms, `v - 200 <= v`: test_deep_sides_of_a_comparison)
        "compared": repeated("when {} priority 5 do stop_motor", [NE], "min({}, 7)", [], n),
        "compared sum": repeated("every 26 ms if {} do v = 2", [NE], "1 - {}", [], n),
        "conditions": repeated("every 24 ms do {}", [layer("if {} {{ v = 1 }}")], "not ({})",
                               [C], n),
        # issue 46's forms: the bitwise operators, slices beside, whole arrays assigned
        "bit not": repeated("every 27 ms do {}", [A], "~{}", [], n),
        "shifts": repeated("every 28 ms do {}", [A], "{} << 1", [], n),
        "shift counts": repeated("every 29 ms do {}", [A], "v << {}", [], n),
        "masks": repeated("every 30 ms do {}", [A], "0b1011 & {}", [], n),
        "ors": repeated("every 31 ms do {}", [A], "v | {}", [], n),
        "slices beside": repeated("every 32 ms do {}", [A], "max(a[:2]) - {}", [], n),
        "array assigned": repeated("every 33 ms do {}", [layer("a = [0, 1, {}]")], "a[{}]", [], n),
        "fill": repeated("every 34 ms do {}", [layer("fill(a, {})")], "~({})", [], n),
        # `else if` does not nest: a long chain is flat
        "chain": repeated("every 25 ms do {}", [], "if v > 0 {{ v = 1 }} else if v > 1 {{ {} }} "
                          "else {{ v = 2 }}", [A], n),
    }
    r = RandomChoices(random.Random(42))
    for k in range(6):              # (each statement form once, the named action's too)
        out[f"mixture {k}"] = nested(r, n, k)
    return out


def program(n: int) -> str:
    return HEAD + "\n".join(shapes(n).values()) + "\n"


def with_stack_used(frames: int, f, *args):
    """f(*args) called `frames` Python frames deeper than here."""
    if frames == 0:
        return f(*args)
    return with_stack_used(frames - 1, f, *args)


def _check(text):
    report = Report()
    result = check_file(Path("deep.epk"), report, shown_name="deep.epk", text=text)
    return report, result


def _statements(text: str) -> list:
    source = SourceFile("x.epk", text)
    return parse_python(source, Collector(source)).statements


def test_every_shape_is_exactly_max_depth_deep():
    for n, over in ((MAX_DEPTH, False), (MAX_DEPTH + 1, True)):
        for name, rule in shapes(n).items():
            source = SourceFile("x.epk", rule + "\n")
            diags = Collector(source)
            statements = parse_python(source, diags).statements
            assert [d.code for d in diags.items] == (["E056"] if over else []), (name, n)
            if not over:
                assert max(measure(s, None)[0] for s in statements) == n, name


def test_every_stage_takes_statements_at_the_limit(tmp_path):
    text = program(MAX_DEPTH)
    report, result = with_stack_used(150, _check, text)
    assert not [d for d in report.diagnostics if d.severity == "error"], \
        [d.message for d in report.diagnostics]
    generated = with_stack_used(150, emit_program, result.checked, text, "deep")
    c_file = tmp_path / "deep.c"
    c_file.write_text(generated.c_text)
    includes = [f"-I{RUNTIME}", f"-I{RUNTIME / 'epuck_api'}", f"-I{RUNTIME / 'host'}"]
    cc = require_tool("cc")
    subprocess.run([cc, *STRICT, *includes, "-c", str(c_file), "-o", str(tmp_path / "a.o")],
                   check=True)
    avr = require_tool("avr-gcc")
    subprocess.run([avr, "-mmcu=atmega128", *STRICT, "-Os", f"-I{RUNTIME}", "-c", str(c_file),
                    "-o", str(tmp_path / "b.o")], check=True)
    formatted = with_stack_used(150, format_text, text)
    assert with_stack_used(150, format_text, formatted) == formatted
    assert not [d for d in _check(formatted)[0].diagnostics if d.severity == "error"]
    with_stack_used(150, answer_everywhere, text, "deep.epk", 13)


def test_one_level_more_is_e056_in_check_compile_and_the_editor(tmp_path, capsys):
    path = tmp_path / "deeper.epk"
    path.write_text(program(MAX_DEPTH + 1), encoding="utf-8")
    count = len(shapes(MAX_DEPTH + 1))
    status, _, err = run_cli(["check", str(path)], capsys)
    assert status == 1 and err.count("error[E056]") == count
    out = tmp_path / "deeper.c"
    status, _, err = run_cli(["compile", str(path), "-o", str(out)], capsys)
    assert status == 1 and "E056" in err and not out.exists()
    analysis = Analyzer("deeper.epk").analyse(path.read_text())
    assert [d.code for d in analysis.diagnostics].count("E056") == count
    answer_everywhere(path.read_text(), "deeper.epk", 13)


def test_both_front_ends_measure_the_same():
    """The C front end's trees go through the same gate: the same
    statements and the same E056 as the Python front end's."""
    if accel.front() is None:
        pytest.skip("the C front end is not built (python3 setup.py build_ext --inplace)")
    for n in (MAX_DEPTH, MAX_DEPTH + 1):
        text = program(n)
        source = SourceFile("x.epk", text)
        by_python, by_c = Collector(source), Collector(source)
        python = parse_python(source, by_python)
        c = parse_c(_c_driver(), source, by_c)
        assert c is not None
        assert c.statements == python.statements
        assert [(d.code, d.span, d.message) for d in by_c.items] == \
            [(d.code, d.span, d.message) for d in by_python.items]


def test_nested_indexes_of_the_campaign_are_e056_not_an_internal_error(tmp_path, capsys):
    """The campaign's input: `s = a[a[...a[0]...]]` with 329 indexes ended in a
    RecursionError of check/arrays.py (exit 4), and 328 were accepted, since
    the depth counted no index."""
    for n in (328, 329, 2000):
        path = tmp_path / f"index{n}.epk"
        path.write_text("const a = [0, 0, 0]\nvar s = 0\nevery 10 ms do s = "
                        + "a[" * n + "0" + "]" * n + "\n")
        status, _, err = run_cli(["check", str(path)], capsys)
        assert status == 1 and err.count("error[E056]") == 1, err[-2000:]
        assert "internal error" not in err


def test_a_narrow_statement_is_never_deeper_than_its_width_allows():
    """limits.narrow skips the walk of a one-line statement whose width
    bounds its depth (width + SLACK): held on every shape, even the
    tightest (a minus per character)."""
    for n in (40, MAX_DEPTH):
        for name, text in shapes(n).items():
            for statement in _statements(HEAD + text + "\n"):
                span = statement.span
                if span.line == span.end_line:
                    width = span.end_column - span.column
                    assert measure(statement, None)[0] <= width + SLACK, name
    tight = "every 1 ms do v = " + "-" * 500 + "(v)"
    statement = _statements(HEAD + tight + "\n")[-1]
    assert measure(statement, None)[0] <= statement.span.end_column - statement.span.column + SLACK


def test_deep_sides_of_a_comparison_fit_in_memory():
    """The checker compares the sides of a comparison by their forms (a sum
    of parts times factors, check/exprs.py `_linear`); a part's key held
    its operands' keys, their quotes escaped again at each level, so that
    it grew twice as long per level: a comparison 200 deep did not fit in
    memory. Checked in a process allowed 1 GB."""
    import subprocess
    import sys
    text = HEAD + shapes(MAX_DEPTH)["compared"] + "\n" + shapes(MAX_DEPTH)["compared sum"] + "\n"
    code = ("import resource, sys\n"
            "resource.setrlimit(resource.RLIMIT_AS, (1 << 30, 1 << 30))\n"
            "from pathlib import Path\n"
            "from epuckc.check.frontend import check_file\n"
            "from epuckc.diagnostics import Report\n"
            "report = Report()\n"
            "check_file(Path('c.epk'), report, shown_name='c.epk', text=sys.stdin.read())\n"
            "print(sorted({d.code for d in report.diagnostics}))\n")
    done = subprocess.run([sys.executable, "-c", code], input=text, capture_output=True,
                          text=True, timeout=300, cwd=REPO)
    assert done.returncode == 0, done.stderr[-3000:]
    assert "E" not in done.stdout, done.stdout


def test_the_figures_the_docs_give():
    """docs/language.md 2.9 and E056.md: in a rule, 195 terms of a sum (or
    of a chain of shifts or masks), 97 nested calls, 195 nested indexes, 194
    `~`s, 48 nested `if`s fit (one more does not), and the weighted sum of
    the IR readings is 14 deep."""
    from tests.support.nesting import depth_of

    def rule(body):
        return depth_of(f"every 10 ms do {body}\n")
    for n, body in ((195, lambda n: "v = v" + " + 1" * (n - 1)),
                    (97, lambda n: "v = " + "abs(" * n + "v" + ")" * n),
                    (195, lambda n: "v = " + "a[" * n + "0" + "]" * n),
                    (195, lambda n: "v = v" + " >> 1" * (n - 1)),
                    (195, lambda n: "v = v" + " & 1" * (n - 1)),
                    (194, lambda n: "v = " + "~" * n + "v"),
                    (48, lambda n: "if v > 0 { " * n + "v = 1" + " }" * n)):
        assert rule(body(n)) <= MAX_DEPTH < rule(body(n + 1)), body(2)
    weighted = "t = 8 * ir0 + 4 * ir1 + 4 * ir2 + 4 * ir3 + 4 * ir4 + 4 * ir5 + 4 * ir6 + 16 * ir7"
    assert rule(weighted) == 14
