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


def test_the_neovim_07_recipe_runs_in_neovim(tmp_path):
    """The README's recipe for Neovim 0.7 to 0.9, run as it is in the Neovim
    this machine has (Debian 12: 0.7.2): a rule file opens, the client
    starts `epuckc lsp`, attaches, and the server's diagnostics arrive."""
    import os
    import subprocess

    from tests.conftest import require_tool
    nvim = require_tool("nvim")
    require_tool("epuckc")
    [recipe] = [block for block in code_blocks("lua") if "vim.lsp.start_client" in block]
    (tmp_path / "prog.epk").write_text(PROGRAM)
    (tmp_path / "test.lua").write_text(
        f'vim.opt.runtimepath:append("{REPO / "editors" / "vim"}")\n'
        "vim.cmd('filetype plugin on')\n" + recipe +
        "vim.cmd('edit prog.epk')\n"
        "vim.wait(20000, function() return #vim.diagnostic.get(0) >= 2 end, 50)\n"
        "local out = {}\n"
        "for _, d in ipairs(vim.diagnostic.get(0)) do\n"
        "  table.insert(out, (d.lnum + 1) .. ':' .. (d.col + 1) .. ':' .. d.message)\n"
        "end\n"
        "table.sort(out)\n"
        "vim.fn.writefile(out, 'diagnostics.txt')\n"
        "vim.cmd('qa!')\n")
    env = dict(os.environ, PYTHONPATH=str(REPO) + os.pathsep + os.environ.get("PYTHONPATH", ""))
    subprocess.run([nvim, "--headless", "-u", "NONE", "-c", "luafile test.lua"], cwd=tmp_path,
                   env=env, capture_output=True, timeout=60, stdin=subprocess.DEVNULL)
    shown = (tmp_path / "diagnostics.txt").read_text().splitlines()
    assert [line.split(":", 2)[:2] for line in shown] == [["1", "10"], ["2", "17"]], shown
    assert "unknown action `strat_straight`" in shown[1]
