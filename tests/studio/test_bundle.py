"""The studio's page is built from studio/ (TypeScript, CodeMirror 6 from
npm, esbuild) and the built files are committed in epuckc/studio/static,
as the parse tables are: rebuilding them from the sources with the locked
packages (`npm ci`, .ci/run) gives the committed bytes, and the sources
type-check. docs/studio.md says how to rebuild."""
from __future__ import annotations

import json
import os
import subprocess
from pathlib import Path

import pytest

from tests.conftest import require_tool

REPO = Path(__file__).resolve().parents[2]
STUDIO = REPO / "studio"
STATIC = REPO / "epuckc" / "studio" / "static"


def _packages():
    node = require_tool("node")
    if not (STUDIO / "node_modules" / "esbuild").is_dir():
        reason = "studio/node_modules is missing: run `npm ci` in studio/ (.ci/run does)"
        if os.environ.get("EPUCKC_REQUIRE_ALL_TOOLS"):
            pytest.fail(reason)
        pytest.skip(reason)
    return node


def test_rebuilding_the_page_gives_the_committed_bytes(tmp_path):
    node = _packages()
    subprocess.run([node, "build.mjs", "--outdir", str(tmp_path)], cwd=STUDIO, check=True,
                   capture_output=True, timeout=300)
    built = sorted(p.name for p in tmp_path.iterdir())
    assert built == sorted(p.name for p in STATIC.iterdir()) == ["index.html", "studio.css",
                                                                  "studio.js"]
    stale = [name for name in built if (tmp_path / name).read_bytes() != (STATIC / name).read_bytes()]
    assert not stale, (f"{stale} differ from a rebuild: run `npm ci && node build.mjs` in studio/ "
                       "and commit epuckc/studio/static")


def test_the_sources_type_check():
    node = _packages()
    tsc = STUDIO / "node_modules" / "typescript" / "bin" / "tsc"
    result = subprocess.run([node, str(tsc), "--noEmit", "-p", "."], cwd=STUDIO,
                            capture_output=True, text=True, timeout=300)
    assert result.returncode == 0, result.stdout + result.stderr


def test_the_lock_file_pins_every_package_the_build_reads():
    lock = json.loads((STUDIO / "package-lock.json").read_text())
    wanted = json.loads((STUDIO / "package.json").read_text())["devDependencies"]
    for name, version in wanted.items():
        assert lock["packages"][f"node_modules/{name}"]["version"] == version


def test_the_highlighting_reads_the_editor_packages_word_lists():
    """The page's highlighting is compiled from editors/vscode's TextMate
    grammar (not a copy): every standard action's pattern is in the bundle."""
    grammar = json.loads((REPO / "editors" / "vscode" / "syntaxes" /
                          "epuck.tmLanguage.json").read_text())
    bundle = (STATIC / "studio.js").read_text(encoding="utf-8")
    builtin = grammar["repository"]["builtin"]["match"]
    assert json.dumps(builtin)[1:-1] in bundle or builtin in bundle
    source = (STUDIO / "src" / "highlight.ts").read_text()
    assert "editors/vscode/syntaxes/epuck.tmLanguage.json" in source
