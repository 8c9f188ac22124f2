"""The pytest plugin (epuckc/testing/plugin.py): `pytest DIR` runs the same
cases as `epuckc test DIR`, one item per rule file, with the same diffs,
`--bless`, and JUnit XML from pytest's `--junitxml`; a fresh virtual
environment gets it from `pip install epuckc` (the `pytest11` entry point);
the project's own test data is never collected."""
from __future__ import annotations

import os
import subprocess
import sys
import xml.etree.ElementTree as ET
from pathlib import Path

import pytest

from tests.support.programs import REPO, epuckc
from tests.testing.test_epuckc_test import PROGRAM, SCENARIO, make_case

# Whatever the installation: the plugin by its module (an editable install
# of this tree also registers it as `epuckc`, which would load it twice).
PLUGIN = ["-p", "no:epuckc", "-p", "epuckc.testing.plugin"]


def pytest_run(*args, cwd, python=sys.executable, plugin=True, env=None):
    full_env = dict(os.environ)
    if python == sys.executable:
        full_env["PYTHONPATH"] = str(REPO) + os.pathsep + full_env.get("PYTHONPATH", "")
    full_env.update(env or {})
    command = [python, "-m", "pytest", "-p", "no:cacheprovider", "-q", "-rN"] \
        + (PLUGIN if plugin else []) + [str(a) for a in args]
    return subprocess.run(command, cwd=cwd, env=full_env, capture_output=True, text=True)


def marked_case(folder: Path, **kw) -> Path:
    path = make_case(folder, **kw)
    (folder / "epuckc-test.toml").write_text("")
    return path


def junit(path: Path) -> dict:
    """{test case name: (failure text or None, skipped)}."""
    out = {}
    for case in ET.parse(path).getroot().iter("testcase"):
        failure = case.find("failure")
        out[case.get("name")] = (failure.text if failure is not None else None,
                                 case.find("skipped") is not None)
    return out


def test_pytest_runs_cases_blesses_and_reports_junit(tmp_path):
    cases = tmp_path / "cases"
    marked_case(cases)
    marked_case(cases, name="second")
    # missing expected files: failures that say how to bless
    r = pytest_run("cases", "--junitxml", tmp_path / "r1.xml", cwd=tmp_path)
    assert r.returncode == 1, r.stdout + r.stderr
    assert "2 failed" in r.stdout and "`pytest --bless` writes it" in r.stdout
    report = junit(tmp_path / "r1.xml")
    assert set(report) == {"avoid.epk", "second.epk"}
    assert "avoid.trace is missing" in report["avoid.epk"][0]
    # --bless: written, and passing
    r = pytest_run("cases", "--bless", cwd=tmp_path)
    assert r.returncode == 0, r.stdout + r.stderr
    assert (cases / "avoid.trace").read_text() == epuckc(
        "run", "avoid.epk", "--scenario", "avoid.scn", cwd=cases).stdout
    r = pytest_run("cases", "--junitxml", tmp_path / "r2.xml", cwd=tmp_path)
    assert r.returncode == 0 and "2 passed" in r.stdout, r.stdout
    assert junit(tmp_path / "r2.xml") == {"avoid.epk": (None, False), "second.epk": (None, False)}
    # a change: the same diff and divergence point as `epuckc test`
    (cases / "second.scn").write_text(SCENARIO.replace("1200 ms", "2000 ms")
                                      .replace("1300 ms", "2100 ms"))
    r = pytest_run("cases", "--junitxml", tmp_path / "r3.xml", cwd=tmp_path)
    assert r.returncode == 1 and "1 failed, 1 passed" in r.stdout, r.stdout
    failure = junit(tmp_path / "r3.xml")["second.epk"][0]
    assert "the expected trace has at 1,200 ms: rule `avoid` fired" in failure
    assert "--- second.trace (expected)" in failure
    cli = epuckc("test", "cases", cwd=tmp_path).stdout
    body = failure.split("\n", 1)[1]       # after its first line, `FAIL NAME`
    assert body in cli


def test_items_are_named_by_their_path(tmp_path):
    marked_case(tmp_path / "a" / "b")
    r = pytest_run("--collect-only", ".", cwd=tmp_path)
    assert "a/b/avoid.epk::avoid.epk" in r.stdout, r.stdout + r.stderr


def test_only_folders_with_epuckc_test_toml_are_collected(tmp_path):
    make_case(tmp_path / "plain")
    marked_case(tmp_path / "marked")
    make_case(tmp_path / "marked" / "below", name="deeper")
    r = pytest_run("--collect-only", ".", cwd=tmp_path)
    assert "marked/avoid.epk::avoid.epk" in r.stdout
    assert "marked/below/deeper.epk::deeper.epk" in r.stdout
    assert "plain/" not in r.stdout


def test_the_projects_own_suite_is_unaffected():
    """`python3 -m pytest` in this repository (its testpaths: tests/, which
    holds many .epk files: check cases, goldens, broken inputs) collects
    the same items with the plugin loaded as an installed epuckc loads it:
    none of them is a rule file."""
    with_plugin = pytest_run("--collect-only", cwd=REPO)
    without = pytest_run("--collect-only", cwd=REPO, plugin=False)
    assert with_plugin.returncode == 0, with_plugin.stdout + with_plugin.stderr
    assert ".epk::" not in with_plugin.stdout
    items = [line for line in with_plugin.stdout.splitlines() if "::" in line]
    assert len(items) > 1000
    assert items == [line for line in without.stdout.splitlines() if "::" in line]


def test_a_bad_options_file_fails_its_case(tmp_path):
    marked_case(tmp_path, toml='seed = "three"\n')
    r = pytest_run(".", cwd=tmp_path)
    assert r.returncode == 1
    assert "avoid.toml:1:1: error: `seed` must be" in r.stdout, r.stdout


def _venv(tmp_path) -> Path:
    """A fresh virtual environment with epuckc installed from this tree as a
    user installs it (pip, the wheel built in isolation; the other
    packages are the system's)."""
    venv = tmp_path / "venv"
    subprocess.run([sys.executable, "-m", "venv", "--system-site-packages", "--without-pip",
                    str(venv)], check=True)
    python = venv / "bin" / "python"
    r = subprocess.run([str(python), "-m", "pip", "install", "-q", "--no-deps", str(REPO)],
                       capture_output=True, text=True, cwd=tmp_path)
    if r.returncode != 0:
        reason = f"pip could not install epuckc into a fresh venv:\n{r.stdout}{r.stderr}"
        if os.environ.get("EPUCKC_REQUIRE_ALL_TOOLS"):
            pytest.fail(reason)
        pytest.skip(reason)
    return venv


def test_a_fresh_venv_gets_the_command_and_the_plugin(tmp_path):
    venv = _venv(tmp_path)
    python = str(venv / "bin" / "python")
    probe = subprocess.run([python, "-c", "import importlib.metadata as m, epuckc; print("
                            "[e.value for e in m.entry_points(group='pytest11') "
                            "if e.name == 'epuckc']); print(epuckc.__file__)"],
                           capture_output=True, text=True, cwd=tmp_path, check=True)
    assert probe.stdout.splitlines()[0] == "['epuckc.testing.plugin']"
    assert probe.stdout.splitlines()[1].startswith(str(venv))       # the installed copy
    env = {k: v for k, v in os.environ.items() if k != "PYTHONPATH"}
    cases = tmp_path / "cases"
    marked_case(cases)
    installed = str(venv / "bin" / "epuckc")
    r = subprocess.run([installed, "test", "--bless", "cases"], cwd=tmp_path, env=env,
                       capture_output=True, text=True)
    assert r.returncode == 0 and "avoid.trace (new)" in r.stdout, r.stdout + r.stderr
    r = subprocess.run([installed, "test", "cases"], cwd=tmp_path, env=env,
                       capture_output=True, text=True)
    assert (r.returncode, r.stdout) == (0, "1 passed, 0 failed\n"), r.stderr
    # pytest finds the plugin by itself (no -p): pass, then a change fails
    r = pytest_run("cases", "--junitxml", tmp_path / "ok.xml", cwd=tmp_path, python=python,
                   plugin=False, env={"PYTHONPATH": ""})
    assert r.returncode == 0 and "1 passed" in r.stdout, r.stdout + r.stderr
    (cases / "avoid.epk").write_text((cases / "avoid.epk").read_text()
                                     .replace("timer(4 s)", "timer(3 s)"))
    r = pytest_run("cases", "--junitxml", tmp_path / "bad.xml", cwd=tmp_path, python=python,
                   plugin=False, env={"PYTHONPATH": ""})
    assert r.returncode == 1
    failure = junit(tmp_path / "bad.xml")["avoid.epk"][0]
    assert "this one at 3,001 ms: the rule at avoid.epk:6" in failure and "--- avoid.trace (expected)" in failure, failure


def test_a_teachers_folder_of_submissions(tmp_path):
    """docs/testing.md: the lab's checks in one epuckc-test.toml, the
    students' files below it, one JUnit test case per student."""
    lab = tmp_path / "lab3"
    (lab / "submissions").mkdir(parents=True)
    (lab / "course.scn").write_text(SCENARIO)
    (lab / "epuckc-test.toml").write_text(
        'scenario = "course.scn"\ntime_limit = "10s"\n'
        'expect = ["exit within 5 s", "rule avoid fires", "y > 20 mm at exit"]\n')
    good = PROGRAM
    (lab / "submissions" / "alice.epk").write_text(good)
    (lab / "submissions" / "bob.epk").write_text(good.replace("timer(4 s)", "timer(7 s)"))
    (lab / "submissions" / "carol.epk").write_text(good.replace("start_curve", "start_curv"))
    # a warning (an unused constant) is no failure: the checks are the lab's
    (lab / "submissions" / "dave.epk").write_text("const UNUSED = 3\n" + good)
    r = pytest_run("lab3", "--junitxml", tmp_path / "lab3.xml", cwd=tmp_path)
    assert r.returncode == 1, r.stdout + r.stderr
    report = junit(tmp_path / "lab3.xml")
    assert set(report) == {"alice.epk", "bob.epk", "carol.epk", "dave.epk"}
    assert report["alice.epk"] == (None, False) and report["dave.epk"] == (None, False)
    assert "expect `exit within 5 s`: the program exited at 7001 ms, after 5000 ms" \
        in report["bob.epk"][0]
    assert "the program has errors" in report["carol.epk"][0]
    assert "carol.epk:4:8: error[E011]: unknown action `start_curv`" in report["carol.epk"][0]
    cli = epuckc("test", "lab3", cwd=tmp_path)
    assert cli.returncode == 1 and cli.stdout.endswith("2 passed, 2 failed\n"), cli.stdout
    assert not list(lab.rglob("*.trace")) and not list(lab.rglob("*.diag"))
    # one submission, or the folder of submissions: the lab's options above still hold
    one = epuckc("test", "lab3/submissions/bob.epk", cwd=tmp_path)
    assert one.returncode == 1 and "exited at 7001 ms, after 5000 ms" in one.stdout, one.stdout
    assert epuckc("test", "submissions", cwd=lab).stdout.endswith("2 passed, 2 failed\n")
