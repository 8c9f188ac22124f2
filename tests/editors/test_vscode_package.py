"""The VS Code extension: its client starts exactly `epuckc lsp` (run by node
against stand-ins for the VS Code API), and it builds into a .vsix with the
usual tool (@vscode/vsce, offline, from editors/vscode/node_modules) holding
the client, the grammar, the language configuration and the language client
library."""
from __future__ import annotations

import json
import subprocess
import zipfile

from tests.conftest import require_tool

from .test_textmate import VSCODE, node_modules


def test_the_client_is_valid_javascript():
    node = require_tool("node")
    result = subprocess.run([node, "--check", str(VSCODE / "extension.js")],
                            capture_output=True, text=True)
    assert result.returncode == 0, result.stderr


def test_vsce_packages_the_extension(tmp_path):
    modules = node_modules()
    vsce = modules / ".bin" / "vsce"
    assert vsce.exists(), "@vscode/vsce is a devDependency: run `npm ci` in editors/vscode"
    out = tmp_path / "epuckc.vsix"
    result = subprocess.run([str(vsce), "package", "--allow-missing-repository", "--skip-license",
                             "-o", str(out)], cwd=VSCODE, capture_output=True, text=True,
                            timeout=300)
    assert result.returncode == 0, result.stdout + result.stderr
    with zipfile.ZipFile(out) as vsix:
        names = set(vsix.namelist())
        manifest = json.loads(vsix.read("extension/package.json"))
    assert {"extension/extension.js", "extension/syntaxes/epuck.tmLanguage.json",
            "extension/language-configuration.json", "extension.vsixmanifest"} <= names
    assert "extension/node_modules/vscode-languageclient/node.js" in names
    assert not any(n.startswith("extension/test/") for n in names)
    assert not any("vscode-textmate" in n or "@vscode/vsce" in n for n in names)
    assert manifest["contributes"]["languages"][0]["extensions"] == [".epk"]


def run_client(settings: dict) -> dict:
    node = require_tool("node")
    node_modules()
    result = subprocess.run([node, str(VSCODE / "test" / "client.js"), json.dumps(settings)],
                            capture_output=True, text=True, timeout=60)
    assert result.returncode == 0, result.stderr
    return json.loads(result.stdout)


def test_the_client_starts_epuckc_lsp_and_restarts_it():
    log = run_client({})
    first, restarted, reconfigured = log["clients"]
    # exactly `epuckc lsp` on standard input/output: no transport option,
    # which would make vscode-languageclient append `--stdio`
    assert first["serverOptions"] == {"command": "epuckc", "args": ["lsp"]}
    assert first["documentSelector"] == [{"scheme": "file", "language": "epuck"},
                                         {"scheme": "untitled", "language": "epuck"}]
    assert restarted["serverOptions"] == first["serverOptions"]
    assert reconfigured["serverOptions"] == {"command": "epuckc", "args": ["-m", "epuckc", "lsp"]}
    assert log["stopped"] == 3 and log["errors"] == []
    assert log["commands"] == ["epuckc.restartServer"]


def test_a_server_that_cannot_start_is_reported():
    log = run_client({"epuckc.path": "/nowhere/epuckc", "failStart": True})
    assert log["clients"][0]["serverOptions"]["command"] == "/nowhere/epuckc"
    assert log["stopped"] == 0
    assert len(log["errors"]) == 3
    assert "cannot start the language server with `/nowhere/epuckc`" in log["errors"][0]
    assert "epuckc.path" in log["errors"][0]
