"""The set-ups of editors/README.md read what epuckc prints: the VS Code
problem matcher and the regular expression for other editors find file,
line, column, severity and message in `check --format gcc` (the Vim
errorformat is run in Vim by test_vim.py); the Helix configuration is valid
TOML."""
from __future__ import annotations

import json
import re
import sys
from pathlib import Path

import pytest

from tests.support.cli import run_cli

REPO = Path(__file__).resolve().parents[2]
README = (REPO / "editors" / "README.md").read_text(encoding="utf-8")
PACKAGE = json.loads((REPO / "editors" / "vscode" / "package.json").read_text(encoding="utf-8"))

# A warning that an error elsewhere does not silence (W008; W007 would be,
# as a possible cascade), and an error.
PROGRAM = "on timer(2) do set_timer\non immediate do strat_straight(300, 10 cm)\n"
EXPECTED = [("prog.epk", 1, 10, "warning", "`2` without a unit is 2 ms: did you mean 2 s?"),
            ("prog.epk", 2, 17, "error", "unknown action `strat_straight`")]


def code_blocks(language: str) -> list:
    return re.findall(rf"```{language}\n(.*?)```", README, re.S)


@pytest.fixture
def gcc_output(tmp_path, monkeypatch, capsys) -> str:
    monkeypatch.chdir(tmp_path)
    (tmp_path / "prog.epk").write_text(PROGRAM)
    status, out, err = run_cli(["check", "--format", "gcc", "prog.epk"], capsys)
    assert status == 1 and len(err.splitlines()) == 2
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
