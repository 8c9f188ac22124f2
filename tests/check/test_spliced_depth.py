"""Named actions are spliced where they are called (check/splice.py), so an
`if` in an action called inside an `if` nests in lowering and in the C
though no statement nests it: the depth limit (syntax/limits.py) counts
them spliced. At exactly MAX_DEPTH a rule is checked, compiled (with a
stack already in use) and built; one level more is E056 at the call, in
`check`, `compile` and the language server, also after an edit of
another action that the rule's action calls."""
from __future__ import annotations

import subprocess
from pathlib import Path

from conftest import require_tool
from epuckc.check.frontend import check_file
from epuckc.diagnostics import Report
from epuckc.emit.program import emit_program
from epuckc.ide.incremental import Analyzer
from epuckc.syntax.limits import MAX_DEPTH

from tests.support.cli import run_cli

RUNTIME = Path(__file__).resolve().parents[2] / "runtime_c"
STRICT = ["-std=c99", "-Wall", "-Wextra", "-Werror", "-pedantic"]


def ifs(n: int, inside: str, reading: str = "ir0") -> str:
    return f"if {reading} > 100 {{ " * n + inside + " }" * n


def spliced(depth: int) -> str:
    """A rule whose action, spliced in, makes it `depth` levels deep: the
    action `inner` (n `if`s, 4 levels each, around `v = ((v))`) called
    inside 10 `if`s of the rule (each `if` 4 levels, the call 1 ...)."""
    # rule: the rule, its body and step (3), 10 `if`s (40), then the call's
    # place (44), where inner's `if`s (4 each) and `v = (..(v)..)` stand:
    # the assignment, the parentheses, `v` and its name
    n, pad = divmod(depth - 43 - 4, 4)
    return ("var v = 0\non immediate do v = 1\n"
            f"action inner = {ifs(n, 'v = ' + '(' * (pad + 1) + 'v' + ')' * (pad + 1))}\n"
            f"every 10 ms do {ifs(10, 'inner', 'ir1')}\n")


def _check(text: str):
    report = Report()
    result = check_file(Path("s.epk"), report, shown_name="s.epk", text=text)
    return report, result


def _codes(report) -> list:
    return [d.code for d in report.diagnostics if d.severity == "error"]


def with_stack_used(frames: int, f, *args):
    if frames == 0:
        return f(*args)
    return with_stack_used(frames - 1, f, *args)


def test_a_rule_at_the_limit_with_its_action_spliced_in_builds(tmp_path):
    text = spliced(MAX_DEPTH)
    report, result = _check(text)
    assert _codes(report) == []
    generated = with_stack_used(150, emit_program, result.checked, text, "s")
    c_file = tmp_path / "s.c"
    c_file.write_text(generated.c_text)
    subprocess.run([require_tool("cc"), *STRICT, f"-I{RUNTIME}", "-c", str(c_file),
                    "-o", str(tmp_path / "s.o")], check=True)
    assert _codes(_check(spliced(MAX_DEPTH + 1))[0]) == ["E056"]


def test_one_level_more_is_e056_at_the_call_everywhere(tmp_path, capsys):
    text = spliced(MAX_DEPTH + 1)
    path = tmp_path / "s.epk"
    path.write_text(text)
    status, _, err = run_cli(["check", str(path)], capsys)
    assert status == 1 and err.count("error[E056]") == 1
    assert "`inner` nests too deeply here" in err and "`inner` is defined here" in err
    line = text.splitlines().index(next(s for s in text.splitlines() if s.startswith("every")))
    assert f"s.epk:{line + 1}:" in err.split("error[E056]")[0].splitlines()[-1]
    out = tmp_path / "s.c"
    status, _, err = run_cli(["compile", str(path), "-o", str(out)], capsys)
    assert status == 1 and "E056" in err and not out.exists()
    analysis = Analyzer("s.epk").analyse(text)
    assert [d.code for d in analysis.diagnostics if d.severity == "error"] == ["E056"]


def test_a_chain_of_actions_nesting_ifs_is_one_error_per_root_not_a_crash(tmp_path, capsys):
    """Each action an `if` around the one before, 30 `if`s each: compile
    crashed with a RecursionError in lowering; now each action that passes
    the limit is an E056 (an action beyond one that did is measured
    without it: one error, not a cascade)."""
    lines = ["var v = 0", "on immediate do v = 1", "action a0 = v = v + 1"]
    for i in range(1, 20):
        lines.append(f"action a{i} = {ifs(30, f'a{i - 1}')}")
    lines.append("every 10 ms do a19")
    path = tmp_path / "chain.epk"
    path.write_text("\n".join(lines) + "\n")
    status, _, err = run_cli(["compile", str(path), "-o", str(tmp_path / "chain.c")], capsys)
    assert status == 1 and "internal error" not in err
    assert 5 <= err.count("error[E056]") <= 10


def test_the_language_server_sees_an_action_grow_through_another():
    """The rule calls `outer`, which calls `inner`: deepening `inner` leaves
    the rule's and `outer`'s text alone, yet the rule is too deep."""
    def text(n):
        return ("var v = 0\non immediate do v = 1\n"
                f"action inner = {ifs(n, 'v = 2')}\n"
                "action outer = inner\n"
                f"every 10 ms do {ifs(10, 'outer', 'ir1')}\n")
    analyzer = Analyzer("e.epk")
    assert [d.code for d in analyzer.analyse(text(30)).diagnostics if d.severity == "error"] == []
    grown = analyzer.analyse(text(45))
    assert [d.code for d in grown.diagnostics if d.severity == "error"] == ["E056"]
    assert [d.code for d in analyzer.analyse(text(30)).diagnostics if d.severity == "error"] == []
