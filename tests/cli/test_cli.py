"""Output formats, exit statuses, colour, several files, capacity options,
and `epuckc explain`."""
from __future__ import annotations

import json
import os
import re
import subprocess
import sys
from pathlib import Path

import pytest

from epuckc.diagnostics.codes import CODES, explanation
from epuckc.diagnostics import Report
from epuckc.diagnostics.render import render_report
from epuckc.check.frontend import check_file

from tests.support.cli import CASES, run_cli

REPO = Path(__file__).resolve().parents[2]
ANSI = re.compile(r"\033\[[0-9;]*m")

TWO_PROBLEMS = """const pause = 3
on immediate do start_straight(300, 10 cm), set_timer
on timr(2 s) do stop_motor
on timer(pause) do exit_main
"""


@pytest.fixture
def work(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    monkeypatch.delenv("NO_COLOR", raising=False)
    (tmp_path / "two.epk").write_text(TWO_PROBLEMS, encoding="utf-8")
    (tmp_path / "good.epk").write_text("on immediate do start_straight(300, 10 cm)\n",
                                       encoding="utf-8")
    (tmp_path / "warn.epk").write_text("const c = 1\non immediate do set_timer\n",
                                       encoding="utf-8")
    return tmp_path


def test_gcc_format(work, capsys):
    status, out, err = run_cli(["check", "--format", "gcc", "two.epk"], capsys)
    assert status == 1 and out == ""
    lines = err.splitlines()
    assert len(lines) == 2
    assert lines[0] == ("two.epk:1:15: warning: `3` without a unit is 3 ms: did you mean 3 s? [W008] "
                        "(help: write `3 s`, or `3 ms` if milliseconds are meant)")
    assert re.fullmatch(r"two\.epk:3:4: error: unknown event `timr` \[E010\].*", lines[1])
    for line in lines:      # what editors' problem matchers read
        assert re.match(r"^[^:]+:\d+:\d+: (error|warning): .* \[[EW]\d{3}\]", line)


def test_short_format(work, capsys):
    status, out, err = run_cli(["check", "--format", "short", "two.epk"], capsys)
    assert status == 1
    assert err.splitlines() == [
        "two.epk:1:15: warning[W008]: `3` without a unit is 3 ms: did you mean 3 s?",
        "two.epk:3:4: error[E010]: unknown event `timr`",
    ]


def test_json_format(work, capsys):
    status, out, err = run_cli(["check", "--format", "json", "two.epk"], capsys)
    assert status == 1 and err == ""
    diags = json.loads(out)
    assert [d["code"] for d in diags] == ["W008", "E010"]
    for d in diags:
        assert {"code", "severity", "message", "file", "line", "column", "end_line",
                "end_column", "help"} <= set(d)
        assert d["file"] == "two.epk"
        assert d["line"] >= 1 and d["column"] >= 1
    assert diags[1]["line"] == 3 and diags[1]["column"] == 4
    assert diags[1]["end_line"] == 3 and diags[1]["end_column"] == 8


def test_json_fixes_are_edits_that_repair_the_file(tmp_path, monkeypatch, capsys):
    """Applied as a tool would apply them, the JSON's quick fixes turn the
    misspellings into the names meant, and the file checks clean."""
    monkeypatch.chdir(tmp_path)
    text = "on immediat do start_straigt(300, 10 cm)\non stop_motor do exit_main\n"
    (tmp_path / "typo.epk").write_text(text)
    status, out, _ = run_cli(["check", "--format", "json", "typo.epk"], capsys)
    diags = json.loads(out)
    fixes = [f for d in diags for f in d["fixes"]]
    assert status == 1 and len(fixes) == 2
    assert all(f["help"] and f["help"] in d["help"] for d in diags for f in d["fixes"])
    lines = text.split("\n")
    for f in sorted(fixes, key=lambda f: (f["line"], f["column"]), reverse=True):
        assert f["line"] == f["end_line"]
        line = lines[f["line"] - 1]
        lines[f["line"] - 1] = line[:f["column"] - 1] + f["text"] + line[f["end_column"] - 1:]
    (tmp_path / "typo.epk").write_text("\n".join(lines))
    status, out, _ = run_cli(["check", "--format", "json", "typo.epk"], capsys)
    assert (status, json.loads(out)) == (0, [])


def test_json_of_a_clean_file_is_an_empty_array(work, capsys):
    status, out, err = run_cli(["check", "--format", "json", "good.epk"], capsys)
    assert (status, json.loads(out), err) == (0, [], "")


def test_clean_file_prints_nothing(work, capsys):
    assert run_cli(["check", "good.epk"], capsys) == (0, "", "")


def test_warnings_pass_unless_werror(work, capsys):
    status, _, err = run_cli(["check", "warn.epk"], capsys)
    assert status == 0 and "W007" in err
    status, _, err = run_cli(["check", "--werror", "warn.epk"], capsys)
    assert status == 1 and "W007" in err


def test_missing_file_is_a_usage_error(work, capsys):
    status, out, err = run_cli(["check", "nowhere.epk"], capsys)
    assert status == 2
    assert "nowhere.epk" in err and "Traceback" not in err


@pytest.mark.parametrize("fmt", ["human", "gcc", "short", "json"])
def test_a_missing_file_is_a_diagnostic_and_the_rest_is_checked(work, capsys, fmt):
    status, out, err = run_cli(["check", "--format", fmt, "two.epk", "missing.epk",
                                "warn.epk"], capsys)
    assert status == 2
    text = out if fmt == "json" else err
    assert "E005" in text and "missing.epk" in text
    assert "E010" in text and "W007" in text          # the other files are checked
    if fmt == "json":
        diags = json.loads(out)
        [missing] = [d for d in diags if d["file"] == "missing.epk"]
        assert missing["code"] == "E005" and missing["severity"] == "error"
        assert "No such file" in missing["message"]


@pytest.mark.parametrize("fmt", ["human", "json"])
def test_a_c_file_is_named_as_c(work, capsys, fmt):
    (work / "fig2.c").write_text('#include "utility.h"\nint main(void) { return 0; }\n')
    status, out, err = run_cli(["check", "--format", fmt, "fig2.c"], capsys)
    assert status == 1
    text = out if fmt == "json" else err
    assert "E006" in text and "epuckc run fig2.c" in text
    assert "E001" not in text and "E002" not in text


def test_directory_is_a_usage_error(work, capsys):
    (work / "folder.epk").mkdir()
    status, _, err = run_cli(["check", "folder.epk"], capsys)
    assert status == 2 and "folder.epk" in err


def test_missing_file_in_a_subprocess_has_no_traceback(work):
    proc = subprocess.run([sys.executable, "-m", "epuckc", "check", "nowhere.epk"],
                          capture_output=True, text=True, env=_env())
    assert proc.returncode == 2
    assert "nowhere.epk" in proc.stderr and "Traceback" not in proc.stderr


def test_several_files_in_one_run(work, capsys):
    status, out, err = run_cli(["check", "--format", "short", "good.epk", "two.epk",
                                "warn.epk"], capsys)
    assert status == 1
    files = [line.split(":")[0] for line in err.splitlines()]
    assert files == ["two.epk", "two.epk", "warn.epk"]
    status, out, _ = run_cli(["check", "--format", "json", "good.epk", "warn.epk"], capsys)
    assert status == 0 and [d["file"] for d in json.loads(out)] == ["warn.epk"]


def test_human_summary_counts_all_files(work, capsys):
    _, _, err = run_cli(["check", "two.epk", "warn.epk"], capsys)
    assert err.rstrip().endswith("1 error and 2 warnings found")


def test_capacity_options_do_not_limit_a_rule_files_rules(work, capsys):
    """The rules are tables: the capacities only size the dynamic arrays
    (for register_action/register_event from the user's C)."""
    rules = "".join(f"rule r{i}: on immediate do led_on(led{i})\n"
                    for i in range(5))
    (work / "five.epk").write_text(rules, encoding="utf-8")
    assert run_cli(["check", "five.epk"], capsys)[0] == 0
    status, out, _ = run_cli(["check", "--format", "json", "--max-events", "1",
                              "--max-actions", "1", "five.epk"], capsys)
    assert status == 0 and json.loads(out) == []


def test_capacity_must_be_positive(work, capsys):
    with pytest.raises(SystemExit) as exit_:
        run_cli(["check", "--max-actions", "0", "good.epk"], capsys)
    assert exit_.value.code == 2


def test_colour_only_when_asked(work):
    report = Report()
    check_file(Path("two.epk"), report, shown_name="two.epk")
    coloured = render_report(report, "human", colour=True)
    plain = render_report(report, "human", colour=False)
    assert ANSI.search(coloured)
    assert not ANSI.search(plain)
    assert ANSI.sub("", coloured) == plain


def test_no_colour_on_a_pipe(work):
    proc = subprocess.run([sys.executable, "-m", "epuckc", "check", "two.epk"],
                          capture_output=True, text=True, env=_env())
    assert proc.returncode == 1
    assert "E010" in proc.stderr and "\033[" not in proc.stderr


def test_no_colour_with_no_color_even_on_a_terminal(work, monkeypatch, capsys):
    from epuckc.cli import commands
    monkeypatch.setattr(sys.stderr, "isatty", lambda: True, raising=False)
    monkeypatch.setenv("NO_COLOR", "1")
    assert not commands._colour_wanted(sys.stderr)
    monkeypatch.delenv("NO_COLOR")
    assert commands._colour_wanted(sys.stderr)


# ---- explain ----------------------------------------------------------------------

def test_explain_prints_the_explanation(capsys):
    status, out, err = run_cli(["explain", "E012"], capsys)
    assert status == 0 and out.startswith("# E012: unknown rule")
    assert out == explanation("E012") and err == ""


@pytest.mark.parametrize("spelling", ["e12", "E12", " e012 ", "E0012"])
def test_explain_normalises_the_code(spelling, capsys):
    status, out, _ = run_cli(["explain", spelling], capsys)
    assert status == 0 and out.startswith("# E012:")


@pytest.mark.parametrize("code", ["E999", "X1", "hello", "W", "E\u00b2"])
def test_explain_unknown_code(code, capsys):
    status, out, err = run_cli(["explain", code], capsys)
    assert status == 2 and out == ""
    assert "no diagnostic has the code" in err


def _blocks(text: str) -> list:
    return re.findall(r"```\n(.*?)\n```", text, re.S)


@pytest.mark.parametrize("code", sorted(CODES))
def test_explanation_examples_are_right(code, tmp_path):
    """The wrong example gives the code (where it can be written as a
    file on its own) and the right example does not."""
    text = explanation(code)
    assert re.match(rf"# {code}: \S", text)
    wrong, right = _blocks(text)[:2]
    if code in ("E004", "E005", "E006", "E039"):   # not a rule file on its own
        return
    # E070: a device the target lacks; its examples are for the e-puck
    target = "dspic" if code == "E070" else "host"
    codes_right = _codes(tmp_path / "right", right, make_c_files=True, target=target)
    assert code not in codes_right, right
    assert not any(c.startswith("E") for c in codes_right), (right, codes_right)
    # E035 cannot fire (see test_goldens.UNREACHABLE); E056's wrong example
    # is 200 levels deep, shown with `...` (its golden case is the real one)
    # W070: a device only a world gives; its wrong example is run alone
    if code not in ("E035", "E056"):
        assert code in _codes(tmp_path / "wrong", wrong, make_c_files=False, target=target,
                              world=code != "W070"), wrong


def _codes(folder: Path, text: str, make_c_files: bool, target: str = "host",
           world: bool = True) -> set:
    folder.mkdir()
    if make_c_files:        # the C files an extern names exist in the right example
        for name in re.findall(r'"([\w.]+\.c)"', text):
            (folder / name).write_text("/* C */\n", encoding="utf-8")
    path = folder / "example.epk"
    path.write_text(text + "\n", encoding="utf-8")
    report = Report()
    check_file(path, report, shown_name="example.epk", target=target, world=world)
    return {d.code for d in report.diagnostics}


def _env():
    env = dict(os.environ)
    env["PYTHONPATH"] = str(REPO) + os.pathsep + env.get("PYTHONPATH", "")
    env.pop("NO_COLOR", None)
    return env


def test_a_reader_that_goes_away_stops_epuckc_quietly(tmp_path):
    """`epuckc compile big.epk -o - | head`: when the pipe closes, epuckc
    stops like a Unix filter (SIGPIPE's status 141), with no internal error."""
    big = tmp_path / "big.epk"
    big.write_text("".join(f"on timer({i + 1} s) do start_straight(300, {i % 90 + 1} cm)\n"
                           for i in range(3000)) + "on immediate do set_timer\n")
    read_end, write_end = os.pipe()
    os.close(read_end)          # the reader has already gone
    result = subprocess.run([sys.executable, "-m", "epuckc", "compile", str(big), "-o", "-",
                             "--max-actions", "4000", "--max-events", "4000"],
                            stdout=write_end, stderr=subprocess.PIPE, text=True, timeout=120)
    os.close(write_end)
    assert result.returncode == 141, result.stderr
    assert result.stderr == ""


@pytest.mark.parametrize("argv", [
    ["check", "a.epk", "b.epk", "--format", "json", "--werror", "--max-actions", "20"],
    ["explain", "E001"], ["fmt", "--check", "x.epk"], ["lsp"],
    ["compile", "a.epk", "-o", "-"], ["build", "a.epk", "--target", "dspic", "-o", "out"],
    ["run", "a.epk", "--time-limit", "2s", "--trace", "-", "--scenario", "s.scn"],
    ["plot", "t.jsonl", "-o", "x.svg", "--title", "T"],
])
def test_a_command_alone_parses_as_with_every_command(argv):
    """main builds only the command it runs (build_parser(only=...)): the
    arguments come out the same as from the whole command line's parser."""
    from epuckc.cli import _COMMANDS, build_parser
    assert build_parser(argv[0]).parse_args(argv) == build_parser().parse_args(argv)
    whole = build_parser()
    [sub] = [a for a in whole._actions if a.dest == "command"]
    assert list(sub.choices) == list(_COMMANDS)
