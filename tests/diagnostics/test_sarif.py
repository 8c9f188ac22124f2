"""`epuckc check --format sarif`: valid SARIF 2.1.0 (checked against the
official OASIS schema, vendored in tests/schemas/) that says the same as
the JSON form: codes, levels, messages, regions, and the explanations."""
from __future__ import annotations

import json
from pathlib import Path

import jsonschema           # in the test extra (pyproject.toml)
import pytest

from epuckc.diagnostics.codes import CODES, explanation

from tests.support.cli import CASES, case_args, run_cli

SCHEMA = json.loads((Path(__file__).resolve().parents[1] / "schemas" /
                     "sarif-schema-2.1.0.json").read_text(encoding="utf-8"))
VALIDATOR = jsonschema.Draft4Validator(SCHEMA, format_checker=jsonschema.FormatChecker())


def validate(log: dict):
    errors = sorted(VALIDATOR.iter_errors(log), key=lambda e: list(e.path))
    assert not errors, "\n".join(f"{list(e.path)}: {e.message}" for e in errors[:10])


def sarif_and_json(args, capsys) -> tuple:
    status, out, err = run_cli(["check", "--format", "sarif", *args], capsys)
    assert err == ""
    json_status, json_out, _ = run_cli(["check", "--format", "json", *args], capsys)
    assert status == json_status
    return status, json.loads(out), json.loads(json_out)


def test_the_schema_is_the_official_one():
    assert SCHEMA["id"].startswith("https://docs.oasis-open.org/sarif/sarif/v2.1.0/")
    jsonschema.Draft4Validator.check_schema(SCHEMA)
    # the validator does reject what is not SARIF
    assert list(VALIDATOR.iter_errors({"version": "2.1.0", "runs": [{"results": []}]}))
    assert list(VALIDATOR.iter_errors({"version": "2.0.0", "runs": []}))


@pytest.mark.parametrize("case", sorted(CASES.glob("*.epk")), ids=lambda p: p.stem)
def test_every_golden_case_gives_valid_sarif_that_matches_the_json(case, capsys, monkeypatch):
    monkeypatch.chdir(CASES)
    status, log, diags = sarif_and_json([*case_args(case), case.name], capsys)
    validate(log)
    assert log["version"] == "2.1.0"
    [run] = log["runs"]
    assert run["columnKind"] == "unicodeCodePoints"
    assert run["originalUriBaseIds"]["%SRCROOT%"]["uri"] == CASES.as_uri() + "/"
    rules = run["tool"]["driver"]["rules"]
    assert run["tool"]["driver"]["name"] == "epuckc"
    assert [r["id"] for r in rules] == sorted({d["code"] for d in diags})
    assert len(run["results"]) == len(diags)
    for result, diag in zip(run["results"], diags):
        assert result["ruleId"] == diag["code"]
        assert rules[result["ruleIndex"]]["id"] == diag["code"]
        assert result["level"] == diag["severity"]
        assert result["message"]["text"].split("\n")[0] == diag["message"]
        if diag["help"]:
            assert result["message"]["text"].endswith(f"\nhelp: {diag['help']}")
        [location] = result["locations"]
        physical = location["physicalLocation"]
        # the case's own file, or another named by its `# args:` (E005, E006)
        assert physical["artifactLocation"] == {"uri": diag["file"], "uriBaseId": "%SRCROOT%"}
        assert physical["region"] == {
            "startLine": diag["line"], "startColumn": diag["column"],
            "endLine": diag["end_line"], "endColumn": diag["end_column"]}
        # the quick fixes: the same edits as the JSON's
        fixes = [(f["description"]["text"], change["artifactLocation"]["uri"],
                  r["deletedRegion"], r["insertedContent"]["text"])
                 for f in result.get("fixes", []) for change in f["artifactChanges"]
                 for r in change["replacements"]]
        assert fixes == [(f["help"], diag["file"],
                          {"startLine": f["line"], "startColumn": f["column"],
                           "endLine": f["end_line"], "endColumn": f["end_column"]}, f["text"])
                         for f in diag["fixes"]]
    for rule in rules:
        code = rule["id"]
        assert rule["shortDescription"]["text"] == CODES[code]
        assert rule["help"]["markdown"] == explanation(code)
        assert rule["fullDescription"]["text"] in " ".join(explanation(code).split())
        levels = {r["level"] for r in run["results"] if r["ruleId"] == code}
        assert levels == {rule["defaultConfiguration"]["level"]}


def test_notes_with_a_position_are_related_locations(tmp_path, monkeypatch, capsys):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "twice.epk").write_text("const a = 1\nconst a = 2\non immediate do start_straight(a, a)\n")
    status, log, diags = sarif_and_json(["twice.epk"], capsys)
    validate(log)
    [result] = [r for r in log["runs"][0]["results"] if r["ruleId"] == "E015"]
    [related] = result["relatedLocations"]
    assert related["message"]["text"] == "first defined here"
    assert related["physicalLocation"]["region"]["startLine"] == 1


def test_several_files_one_clean_and_odd_paths(tmp_path, monkeypatch, capsys):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "sub dir").mkdir()
    (tmp_path / "sub dir" / "caf\u00e9 #1.epk").write_text("on timr(1 s) do stop_motor\n")
    (tmp_path / "clean.epk").write_text("on immediate do start_straight(300, 10 cm)\n")
    absolute = tmp_path / "abs.epk"
    absolute.write_text("const unused = 1\non immediate do exit_main\n")
    status, log, diags = sarif_and_json(
        [str(Path("sub dir") / "caf\u00e9 #1.epk"), "clean.epk", str(absolute)], capsys)
    validate(log)
    assert status == 1
    uris = [r["locations"][0]["physicalLocation"]["artifactLocation"]
            for r in log["runs"][0]["results"]]
    assert {"uri": "sub%20dir/caf%C3%A9%20%231.epk", "uriBaseId": "%SRCROOT%"} in uris
    assert {"uri": absolute.as_uri()} in uris


def test_a_clean_run_is_an_empty_valid_log(tmp_path, monkeypatch, capsys):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "clean.epk").write_text("on immediate do start_straight(300, 10 cm)\n")
    status, log, _ = sarif_and_json(["clean.epk"], capsys)
    validate(log)
    assert status == 0
    assert log["runs"][0]["results"] == [] and log["runs"][0]["tool"]["driver"]["rules"] == []
