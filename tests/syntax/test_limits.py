"""One depth limit for expressions (syntax/limits.py), and every stage
within it: at exactly MAX_DEPTH, each nesting shape is checked, compiled,
built with gcc and 16-bit avr-gcc under -Werror, formatted, and answered by
the editor at every 13th position, all with a stack already 150 frames deep
(a margin for callers); one level more is E056, the same in `check`,
`compile` and the language server, and `compile` writes nothing."""
from __future__ import annotations

import subprocess
from pathlib import Path

import pytest

from conftest import require_tool
from epuckc.check.frontend import check_file
from epuckc.diagnostics import Report
from epuckc.emit.program import emit_program
from epuckc.ide.fmt import format_text
from epuckc.ide.incremental import Analyzer
from epuckc.syntax.limits import IF_LEVELS, MAX_DEPTH

from tests.support.cli import run_cli
from tests.support.ide_walk import answer_everywhere

REPO = Path(__file__).resolve().parents[2]
RUNTIME = REPO / "runtime_c"
STRICT = ["-std=c99", "-Wall", "-Wextra", "-Werror", "-pedantic"]


def pairs(opening: str, n: int, inside: str) -> str:
    """`-(-((v)))`: n levels of an operator and its parentheses (2 each),
    and one more parenthesis when n is odd."""
    head = opening * (n // 2) + "(" * (n % 2)
    return head + inside + ")" * (n // 2 + n % 2)


def shapes(n: int) -> dict:
    """Rules whose one expression is `n` deep, one per way of nesting."""
    return {
        "calls": "every 10 ms do v = " + "abs(" * n + "v" + ")" * n,
        "clamp": "every 20 ms do v = " + "clamp(" * n + "v" + ", -5, 5)" * n,
        "parentheses": "every 30 ms do v = " + "(" * n + "v" + ")" * n,
        "sum": "every 40 ms do v = v" + " + 1" * n,
        "product": "every 50 ms do v = v" + " * 1" * n,
        "minus": "every 60 ms do v = " + pairs("-(", n, "v"),
        "not": "when " + pairs("not (", n - 1, "v > 3") + " priority 1 do stop_motor",
        "and": "when v > 0" + " and v > 1" * (n - 1) + " priority 2 do stop_motor",
        "guard": "every 70 ms if " + "(" * (n - 1) + "v > 2" + ")" * (n - 1) + " do v = v + 1",
        "speed": "every 80 ms priority 3 do set_speed(" + "(" * (n - 1) + "v * 1 steps/s"
                 + ")" * (n - 1) + ", 0 steps/s)",
        # `if`s inside `if`s: IF_LEVELS each, then parentheses to make n
        "ifs": "every 90 ms do " + "if v > 0 { " * ((n - 1) // IF_LEVELS) + "v = "
               + "(" * ((n - 1) % IF_LEVELS) + "v + 1" + ")" * ((n - 1) % IF_LEVELS)
               + " }" * ((n - 1) // IF_LEVELS),
        # `else if` does not nest: a long chain is flat
        "chain": "every 100 ms do if v > 0 { v = 0 }" + " else if v > 1 { v = 1 }" * 300
                 + " else { v = " + "(" * (n - IF_LEVELS) + "v" + ")" * (n - IF_LEVELS) + " }",
    }


def program(n: int) -> str:
    return "var v = 0\non immediate do v = 1\n" + "\n".join(shapes(n).values()) + "\n"


def with_stack_used(frames: int, f, *args):
    """f(*args) called `frames` Python frames deeper than here."""
    if frames == 0:
        return f(*args)
    return with_stack_used(frames - 1, f, *args)


def _check(text):
    report = Report()
    result = check_file(Path("deep.epk"), report, shown_name="deep.epk", text=text)
    return report, result


def test_every_shape_is_exactly_max_depth_deep():
    from epuckc.syntax.limits import too_deep
    from epuckc.syntax.parser import parse_python
    from epuckc.base.source import SourceFile
    from epuckc.diagnostics import Collector
    for n, over in ((MAX_DEPTH, False), (MAX_DEPTH + 1, True)):
        for name, rule in shapes(n).items():
            source = SourceFile("x.epk", rule + "\n")
            diags = Collector(source)
            statements = parse_python(source, diags).statements
            assert [d.code for d in diags.items] == (["E056"] if over else []), (name, n)
            assert len(statements) == (0 if over else 1), (name, n)


def test_every_stage_takes_expressions_at_the_limit(tmp_path):
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
    status, _, err = run_cli(["check", str(path)], capsys)
    assert status == 1 and err.count("error[E056]") == len(shapes(1))
    out = tmp_path / "deeper.c"
    status, _, err = run_cli(["compile", str(path), "-o", str(out)], capsys)
    assert status == 1 and "E056" in err and not out.exists()
    analysis = Analyzer("deeper.epk").analyse(path.read_text())
    assert [d.code for d in analysis.diagnostics].count("E056") == len(shapes(1))
    answer_everywhere(path.read_text(), "deeper.epk", 13)
