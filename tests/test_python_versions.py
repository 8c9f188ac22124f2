"""The Pythons epuckc declares are those it runs on (issue 41: it said
3.9, but `epuckc experiment` imported 3.11's tomllib and nothing declared
tomli, so on Ubuntu 22.04's 3.10 it died with ModuleNotFoundError): the
lowest version declared has what each TOML reader needs, and both readers
(experiment files, golden cases' options) work in a Python without
tomllib, through tomli, as before 3.11."""
from __future__ import annotations

import re
import subprocess
import sys
import tomllib
from pathlib import Path

REPO = Path(__file__).resolve().parent.parent

# A Python without tomllib (3.10): the import fails as it does there.
WITHOUT_TOMLLIB = ("import sys; sys.modules['tomllib'] = None; "
                   "from epuckc.cli import main; sys.exit(main(sys.argv[1:]))")


def _project() -> dict:
    return tomllib.loads((REPO / "pyproject.toml").read_text(encoding="utf-8"))["project"]


def test_the_lowest_python_declared_gets_tomli():
    project = _project()
    lowest = tuple(map(int, re.fullmatch(r">=(\d+)\.(\d+)", project["requires-python"]).groups()))
    listed = sorted(tuple(map(int, c.rsplit(":: ", 1)[1].split(".")))
                    for c in project["classifiers"] if c.startswith("Programming Language"))
    assert listed[0] == lowest
    if lowest < (3, 11):
        assert any(re.fullmatch(r"tomli>=[\d.]+; python_version < '3\.11'", d)
                   for d in project["dependencies"]), project["dependencies"]
    assert any(d.startswith("tomli") for d in project["optional-dependencies"]["test"])


def _without_tomllib(tmp_path, *args):
    return subprocess.run([sys.executable, "-c", WITHOUT_TOMLLIB, *args], cwd=tmp_path,
                          capture_output=True, text=True,
                          env={"PYTHONPATH": str(REPO), "PATH": "/usr/bin:/bin"})


def test_an_experiment_file_is_read_without_tomllib(tmp_path):
    (tmp_path / "p.epk").write_text("const K = 1\non immediate do exit_main\n")
    (tmp_path / "w.world").write_text("robot at 0 cm, 0 cm\n")
    (tmp_path / "e.toml").write_text('program = "p.epk"\nworld = "w.world"\nduration = "1 s"\n'
                                     "seed = 2\n")
    result = _without_tomllib(tmp_path, "experiment", "e.toml")
    assert result.returncode == 2, result.stderr
    assert "e.toml:4:8: error: unknown key `seed`" in result.stderr
    assert "did you mean `seeds`?" in result.stderr
    assert "Error" not in result.stderr and "internal error" not in result.stderr


def test_a_golden_case_s_options_are_read_without_tomllib(tmp_path):
    (tmp_path / "p.epk").write_text("on immediate do exit_main\n")
    (tmp_path / "p.toml").write_text("tracee = false\n")
    result = _without_tomllib(tmp_path, "test", ".")
    assert result.returncode == 2, result.stderr
    assert "p.toml" in result.stderr and "tomli" not in result.stderr
