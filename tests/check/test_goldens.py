"""Golden diagnostics: every file in cases/ is checked and its output is
compared exactly with the .stderr (human form, no colour) and .json files
next to it. Run `pytest tests/check --update-goldens` to rewrite them,
then read the diff: each message must make sense to a student.

A case may ask for options on its first line: `# args: --werror`.
"""
from __future__ import annotations

import json

import pytest

from epuckc.diagnostics.codes import CODES, explanation

from tests.support.cli import CASES, case_args, run_cli

CASE_FILES = sorted(CASES.glob("*.epk"))

# Codes that no input can trigger today, and why. Their case file shows an
# input at the edge that is accepted.
UNREACHABLE = {
    "E039": "a rule file's rules are const tables (register_program), not entries of the "
            "runtime's dynamic arrays, so no number of rules overflows them",
    "E035": "start_curve's `speed` is the outer wheel's, and the inner wheel of a "
            "curve with radius >= 0 is never faster, so the check cannot fail",
}


def _compare(path, actual: str, update: bool):
    if update:
        path.write_text(actual, encoding="utf-8")
        return
    assert path.exists(), f"{path.name} is missing: run pytest with --update-goldens"
    expected = path.read_text(encoding="utf-8")
    assert actual == expected, f"output differs from {path.name}"


@pytest.mark.parametrize("case", CASE_FILES, ids=lambda p: p.stem)
def test_golden(case, capsys, monkeypatch, update_goldens):
    monkeypatch.chdir(CASES)            # relative names: no absolute paths in goldens
    monkeypatch.delenv("NO_COLOR", raising=False)
    args = case_args(case)

    status, out, err = run_cli(["check", *args, case.name], capsys)
    assert out == ""
    _compare(case.with_suffix(".stderr"), err, update_goldens)

    json_status, json_out, json_err = run_cli(["check", "--format", "json", *args, case.name],
                                             capsys)
    assert json_err == ""
    _compare(case.with_suffix(".json"), json_out, update_goldens)
    assert json_status == status

    diags = json.loads(json_out)
    errors = sum(d["severity"] == "error" for d in diags)
    warnings = sum(d["severity"] == "warning" for d in diags)
    failed = errors > 0 or ("--werror" in args and warnings > 0)
    unreadable = any(d["code"] == "E005" for d in diags)
    assert status == (2 if unreadable else 1 if failed else 0)
    assert "\033[" not in err          # captured output is not a terminal
    assert str(CASES) not in err + json_out
    if not diags:
        assert err == ""


def _codes_of(case) -> set:
    path = case.with_suffix(".json")
    return {d["code"] for d in json.loads(path.read_text(encoding="utf-8"))}


@pytest.mark.parametrize("code", sorted(CODES))
def test_every_code_has_a_case_and_an_explanation(code):
    named = [c for c in CASE_FILES if c.stem.split("_")[0] == code]
    assert named, f"no case file is named {code}_*.epk"
    if code in UNREACHABLE:
        assert not any(code in _codes_of(c) for c in named), f"{code} fires now: update UNREACHABLE"
    else:
        assert any(code in _codes_of(c) for c in named), f"{named[0].name} does not produce {code}"
    text = explanation(code)
    assert text, f"epuckc/diagnostics/explanations/{code}.md is missing"
    assert text.startswith(f"# {code}:"), "an explanation starts with `# CODE: title`"


def test_cases_only_use_known_codes():
    for case in CASE_FILES:
        assert _codes_of(case) <= set(CODES), case.name


def test_several_errors_are_all_reported():
    """One broken statement costs one error; the rest is still checked."""
    codes = [d["code"] for d in json.loads(
        (CASES / "many_three_syntax_errors.json").read_text(encoding="utf-8"))]
    assert codes == ["E001", "E001", "E001"]
    mixed = {d["code"] for d in json.loads(
        (CASES / "many_syntax_and_semantic.json").read_text(encoding="utf-8"))}
    assert "E001" in mixed and len(mixed - {"E001"}) >= 3
