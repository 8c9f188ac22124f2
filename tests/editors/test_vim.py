"""The Vim runtime files (editors/vim): the syntax file's word lists equal
epuckc's tables; Vim, run on the corpus, puts every keyword, number, unit,
string, comment, standard name and defined name in its group; the ftplugin
sets comments, `gq` (epuckc fmt) and `:make` (epuckc check), whose
errorformat reads the gcc format into the quickfix list."""
from __future__ import annotations

import re
import subprocess
from pathlib import Path

import pytest

from epuckc.diagnostics import Collector
from epuckc.syntax.lexer import KEYWORDS, iter_tokens
from epuckc.base.source import SourceFile
from epuckc.stdlib.table import ACTION_ALIASES, EVENT_ALIASES, STANDARD_ACTIONS, STANDARD_EVENTS
from epuckc.stdlib.units import UNITS
from tests.conftest import require_tool
from tests.support.cli import run_cli

from .test_textmate import CORPUS, _parses, _units

REPO = Path(__file__).resolve().parents[2]
VIM_DIR = REPO / "editors" / "vim"
SYNTAX = (VIM_DIR / "syntax" / "epuck.vim").read_text(encoding="utf-8")
# the standard names written as names (the `enter` event is a keyword)
STANDARD = (set(STANDARD_ACTIONS) | set(STANDARD_EVENTS) | set(ACTION_ALIASES)
            | set(EVENT_ALIASES)) - set(KEYWORDS)


def keywords(group: str) -> set:
    return {w for line in re.findall(rf"^syntax keyword {group} (.*)$", SYNTAX, re.M)
            for w in line.split()}


def test_keywords_are_the_lexers():
    assert keywords("epuckDeclaration") | keywords("epuckKeyword") == set(KEYWORDS)
    assert not keywords("epuckDeclaration") & keywords("epuckKeyword")


def test_builtins_are_the_standard_actions_and_events():
    assert keywords("epuckBuiltin") == STANDARD


def test_units_are_the_unit_tables():
    found = re.findall(r'^syntax match epuckUnit contained "\\<(.*)\\>"$', SYNTAX, re.M)
    assert {u.replace("\\s*", "") for u in found} == set(UNITS)


def vim(*args, cwd=None, timeout=120):
    exe = require_tool("vim")
    return subprocess.run([exe, "-Es", "-u", "NONE", "-N", "--cmd", f"set rtp^={VIM_DIR}",
                           "--cmd", "filetype plugin on", "--cmd", "syntax on", *args],
                          cwd=cwd, capture_output=True, text=True, timeout=timeout,
                          stdin=subprocess.DEVNULL)


@pytest.fixture(scope="module")
def groups(tmp_path_factory):
    """Vim's syntax group at each token and comment of the corpus."""
    tmp = tmp_path_factory.mktemp("vim")
    wanted, rows = [], []
    for path in CORPUS:
        source, program = _parses(path)
        for line, column, kind in expectations(source, program):
            text = source.line_text(line)
            byte = len(text[: column - 1].encode("utf-8")) + 1
            rows.append(f"{path}\t{line}\t{byte}")
            wanted.append((path, line, column, kind))
    (tmp / "positions.txt").write_text("\n".join(rows) + "\n", encoding="utf-8")
    script = tmp / "groups.vim"
    script.write_text(
        "let out = []\nlet current = ''\n"
        "for row in readfile('positions.txt')\n"
        "  let [file, l, c] = split(row, \"\\t\")\n"
        "  if file !=# current\n"
        "    execute 'edit ' . fnameescape(file)\n"
        "    let current = file\n"
        "  endif\n"
        "  call add(out, synIDattr(synID(str2nr(l), str2nr(c), 1), 'name'))\n"
        "endfor\n"
        "call writefile(out, 'groups.txt')\nqa!\n", encoding="utf-8")
    vim("-S", str(script), cwd=tmp)
    found = (tmp / "groups.txt").read_text(encoding="utf-8").splitlines()
    assert len(found) == len(wanted)
    return list(zip(wanted, found))


def expectations(source, program):
    """(line, column, expected kind) for each token and comment."""
    tokens = list(iter_tokens(source, Collector(source)))
    unit_starts = {(s.line, s.column) for s in _units(program)}
    for k, tok in enumerate(tokens):
        prev = tokens[k - 1] if k else None
        if tok.type.startswith("_") and tok.value in KEYWORDS:
            yield tok.line, tok.column, "keyword"
        elif tok.type == "NUMBER":
            yield tok.line, tok.column, "number"
        elif (tok.line, tok.column) in unit_starts:
            slash = k + 2 < len(tokens) and tokens[k + 1].type == "_SLASH"
            text = tok.value + ("/" + tokens[k + 2].value if slash else "")
            if text in UNITS and prev.line == tok.line:
                yield tok.line, tok.column, "unit"
        elif tok.type == "STRING":
            yield tok.line, tok.column, "string"
        elif tok.type == "NAME":
            if prev is not None and prev.line == tok.line and prev.type in (
                    "_RULE", "_ACTION", "_EVENT", "_CONST"):
                yield tok.line, tok.column, "definition"
            elif tok.value in STANDARD:
                yield tok.line, tok.column, "builtin"
            elif re.fullmatch(r"ir[0-9]+", tok.value):
                yield tok.line, tok.column, "sensor"
    previous = 0
    for tok in tokens + [None]:
        end = tok.start_pos if tok is not None else len(source.text)
        for m in re.finditer(r"#[^\n]*", source.text[previous:end]):
            yield (*source.position(previous + m.start()), "comment")
            yield (*source.position(previous + m.end() - 1), "comment")
        previous = tok.end_pos if tok is not None else end


GROUPS = {"keyword": {"epuckDeclaration", "epuckKeyword"}, "number": {"epuckNumber"},
          "unit": {"epuckUnit"}, "string": {"epuckString"}, "comment": {"epuckComment"},
          "builtin": {"epuckBuiltin"}, "sensor": {"epuckSensor"},
          # a standard name redefined (an error) stays a builtin: Vim's
          # keywords come before its patterns
          "definition": {"epuckDefinition"}}


def test_vim_groups_over_the_corpus(groups):
    kinds = set()
    for (path, line, column, kind), group in groups:
        allowed = GROUPS[kind] | ({"epuckBuiltin"} if kind == "definition" else set())
        assert group in allowed, f"{path.name}:{line}:{column}: {kind} is {group!r}"
        kinds.add(kind)
    assert kinds == set(GROUPS)


def test_the_ftplugin_and_the_compiler(tmp_path, monkeypatch, capsys):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "prog.epk").write_text("on timer(2) do set_timer\non immediate do strat_straight(1, 1 cm)\n")
    status, _, err = run_cli(["check", "--format", "gcc", "prog.epk"], capsys)
    assert status == 1
    (tmp_path / "out.txt").write_text(err)
    (tmp_path / "report.vim").write_text(
        "cgetfile out.txt\n"
        "let out = [&filetype, &commentstring, &formatprg, &makeprg]\n"
        "call extend(out, map(getqflist(), {_, e -> bufname(e.bufnr) . '|' . e.lnum . '|'"
        " . e.col . '|' . e.type . '|' . e.text}))\n"
        "call writefile(out, 'report.txt')\nqa!\n")
    vim("-S", "report.vim", "prog.epk", cwd=tmp_path)
    report = (tmp_path / "report.txt").read_text().splitlines()
    assert report[:4] == ["epuck", "# %s", "epuckc fmt -", "epuckc check --format gcc %"]
    rows = [r.split("|", 4) for r in report[4:]]
    assert [r[:4] for r in rows] == [["prog.epk", "1", "10", "w"], ["prog.epk", "2", "17", "e"]]
    assert rows[1][4].startswith("unknown action `strat_straight` [E011]")


def test_the_readme_quotes_the_compiler():
    compiler = (VIM_DIR / "compiler" / "epuckc.vim").read_text(encoding="utf-8")
    readme = " ".join((REPO / "editors" / "README.md").read_text(encoding="utf-8").split())
    makeprg = re.search(r"^CompilerSet makeprg=(.*)$", compiler, re.M).group(1)
    errorformat = re.search(r"^CompilerSet errorformat=(.*)$", compiler, re.M).group(1)
    assert f"`makeprg={makeprg.replace(chr(92) + ' ', ' ')}`" in readme
    assert f"`errorformat={errorformat}`" in readme


def test_gq_formats_with_epuckc_fmt(tmp_path):
    require_tool("epuckc")
    (tmp_path / "prog.epk").write_text("const  X=300steps/s\non immediate do start_straight(X,1cm)\n")
    vim("-c", "normal gggqG", "-c", "wq", "prog.epk", cwd=tmp_path)
    assert (tmp_path / "prog.epk").read_text() == (
        "const X = 300 steps/s\non immediate do start_straight(X, 1 cm)\n")


def nvim(*args, cwd=None, timeout=120):
    exe = require_tool("nvim")
    return subprocess.run([exe, "--headless", "-u", "NONE", "-N", "--cmd", f"set rtp^={VIM_DIR}",
                           "--cmd", "filetype plugin on", *args],
                          cwd=cwd, capture_output=True, text=True, timeout=timeout,
                          stdin=subprocess.DEVNULL)


BROKEN = ("# a rule file with a mistake in it\n"
          "const  X=300steps/s\n"
          "on immediate do start_straight(X,1cm\n"
          "on stop_motor do exit_main\n")


@pytest.mark.parametrize("editor", [vim, nvim], ids=["vim", "neovim"])
def test_gq_keeps_a_buffer_that_cannot_be_formatted(tmp_path, editor):
    """`gq` pipes the lines through `epuckc fmt -`, and the editor replaces
    them with what it prints, stderr included: a text with a syntax error
    must come back as it was, not as the error message."""
    require_tool("epuckc")
    (tmp_path / "prog.epk").write_text(BROKEN)
    editor("-c", "normal gggqG", "-c", "wq", "prog.epk", cwd=tmp_path)
    assert (tmp_path / "prog.epk").read_text() == BROKEN
    # and a good file is formatted by the same editor
    (tmp_path / "good.epk").write_text("const  X=300steps/s\non immediate do start_straight(X,1cm)\n")
    editor("-c", "normal gggqG", "-c", "wq", "good.epk", cwd=tmp_path)
    assert (tmp_path / "good.epk").read_text() == (
        "const X = 300 steps/s\non immediate do start_straight(X, 1 cm)\n")
