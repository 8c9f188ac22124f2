"""The VS Code extension builds into a .vsix with the usual tool (@vscode/vsce,
offline, from editors/vscode/node_modules) holding the client, the grammar,
the language configuration and the language client library."""
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
