"""The set-ups of editors/README.md read what epuckc prints: the VS Code
problem matcher, the Vim errorformat (run in Vim) and the regular expression
for other editors all find file, line, column, severity and message in
`check --format gcc`; the Helix configuration is valid TOML."""
from __future__ import annotations

import json
import re
import subprocess
import sys
from pathlib import Path

import pytest

from tests.conftest import require_tool
from tests.frontend.helpers import run_cli

REPO = Path(__file__).resolve().parents[2]
README = (REPO / "editors" / "README.md").read_text(encoding="utf-8")
PACKAGE = json.loads((REPO / "editors" / "vscode" / "package.json").read_text(encoding="utf-8"))

PROGRAM = "const unused = 1\non immediate do strat_straight(300, 10 cm)\n"
EXPECTED = [("prog.epk", 1, 7, "warning", "constant `unused` is never used"),
            ("prog.epk", 2, 17, "error", "unknown action `strat_straight`")]


def code_blocks(language: str) -> list:
    return re.findall(rf"```{language}\n(.*?)```", README, re.S)


@pytest.fixture
def gcc_output(tmp_path, monkeypatch, capsys) -> str:
    monkeypatch.chdir(tmp_path)
    (tmp_path / "prog.epk").write_text(PROGRAM)
    status, out, err = run_cli(["check", "--format", "gcc", "prog.epk"], capsys)
    assert status == 1 and len(err.splitlines()) == 2
    (tmp_path / "out.txt").write_text(err)
    return err


def test_the_vscode_problem_matcher(gcc_output):
    [matcher] = PACKAGE["contributes"]["problemMatchers"]
    pattern = matcher["pattern"]
    found = []
    for line in gcc_output.splitlines():
        m = re.match(pattern["regexp"], line)
        assert m, line
        found.append((m.group(pattern["file"]), int(m.group(pattern["line"])),
                      int(m.group(pattern["column"])), m.group(pattern["severity"]),
                      m.group(pattern["message"])))
        assert re.fullmatch(r"[EW]\d{3}", m.group(pattern["code"]))
    assert found == EXPECTED


def test_the_regular_expression_for_other_editors(gcc_output):
    [regex] = re.findall(r"`(\^\(\.\+\?\).*?\$)`", README)
    found = []
    for line in gcc_output.splitlines():
        m = re.match(regex, line)
        assert m, line
        found.append((m.group(1), int(m.group(2)), int(m.group(3)), m.group(4)))
    assert [(f, l, c) for f, l, c, _ in found] == [e[:3] for e in EXPECTED]
    assert all(message.startswith(e[4]) for (*_, message), e in zip(found, EXPECTED))


def test_the_vim_errorformat_in_vim(gcc_output, tmp_path):
    vim = require_tool("vim")
    [block] = code_blocks("vim")
    errorformat = re.search(r"(errorformat=(?:\\ |\S)+)", block).group(1)
    script = tmp_path / "qf.vim"
    script.write_text(
        f"set {errorformat}\n"
        "cgetfile out.txt\n"
        "call writefile(map(getqflist(), {_, e -> bufname(e.bufnr) . '|' . e.lnum . '|' . e.col"
        " . '|' . e.type . '|' . e.text}), 'qf.txt')\n"
        "qa!\n")
    subprocess.run([vim, "-Es", "-u", "NONE", "-N", "-S", str(script)], cwd=tmp_path,
                   timeout=60, check=False, stdin=subprocess.DEVNULL)
    rows = [line.split("|", 4) for line in (tmp_path / "qf.txt").read_text().splitlines()]
    assert [(f, int(l), int(c), t) for f, l, c, t, _ in rows] == [
        (f, l, c, s[0]) for f, l, c, s, _ in EXPECTED]
    assert all(text.startswith(e[4]) for (*_, text), e in zip(rows, EXPECTED))


@pytest.mark.skipif(sys.version_info < (3, 11), reason="tomllib is Python 3.11+")
def test_the_helix_configuration_is_valid_toml():
    import tomllib
    [block] = code_blocks("toml")
    config = tomllib.loads(block)
    [language] = config["language"]
    assert language["file-types"] == ["epk"] and language["language-servers"] == ["epuckc"]
    assert config["language-server"]["epuckc"] == {"command": "epuckc", "args": ["lsp"]}


def test_every_setup_starts_the_same_server():
    for block in code_blocks("lua") + code_blocks("elisp"):
        if "lsp" in block and ("cmd" in block or "eglot-server-programs" in block):
            assert re.search(r'"epuckc",?\s*"lsp"', block), block
    assert PACKAGE["contributes"]["configuration"]["properties"]["epuckc.args"]["default"] == ["lsp"]
