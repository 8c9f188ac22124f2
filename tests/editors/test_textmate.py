"""The VS Code extension's TextMate grammar (editors/vscode/syntaxes): its
word lists equal epuckc's own tables, and, tokenised as VS Code does
(vscode-textmate and vscode-oniguruma, run by node), it gives every token of
the corpus the scope its kind calls for: keywords, numbers, units, names,
comments and strings."""
from __future__ import annotations

import json
import os
import re
import subprocess
from pathlib import Path

import pytest

from epuckc.syntax import ast
from epuckc.diagnostics import Collector
from epuckc.syntax.lexer import KEYWORDS, iter_tokens
from epuckc.syntax.parser import parse
from epuckc.base.source import SourceFile
from epuckc.stdlib.table import (ACTION_ALIASES, AGGREGATES, CHOICE_READINGS, EVENT_ALIASES,
                                 FUNCTIONS, READING_ARRAYS, STANDARD_ACTIONS, STANDARD_EVENTS,
                                 STANDARD_READINGS)
from epuckc.stdlib.units import UNITS

from tests.conftest import require_tool

REPO = Path(__file__).resolve().parents[2]
VSCODE = REPO / "editors" / "vscode"
GRAMMAR = json.loads((VSCODE / "syntaxes" / "epuck.tmLanguage.json").read_text(encoding="utf-8"))


def alternatives(regex: str) -> set:
    """The words of the first `(a|b|c)` group of a grammar regex."""
    group = re.search(r"\((?!\?)([^()]*)\)", regex).group(1)
    return {re.sub(r"\\s\*", "", w).replace("\\", "") for w in group.split("|")}


# ---- the word lists ------------------------------------------------------------------

def test_keywords_are_the_lexers():
    found = set()
    for pattern in GRAMMAR["repository"]["keyword"]["patterns"]:
        found |= alternatives(pattern["match"])
    assert found == set(KEYWORDS)


def test_definition_keywords_are_keywords():
    for pattern in GRAMMAR["repository"]["definition"]["patterns"]:
        assert alternatives(pattern["match"]) <= set(KEYWORDS)


def test_units_are_the_unit_tables():
    regex = GRAMMAR["repository"]["quantity"]["match"]
    group = re.search(r"\(\?:\\s\*\(([^()]*)\)", regex).group(1)
    units = {re.sub(r"\\s\*", "", w) for w in group.split("|")}
    assert units == set(UNITS)


def test_builtins_are_the_standard_actions_and_events():
    regex = GRAMMAR["repository"]["builtin"]["match"]
    prefixes = alternatives(regex.replace("(?:", "("))
    names = alternatives(regex.split(")?", 1)[1])
    # the standard names written as names (the `enter` event is a keyword)
    assert names == (set(STANDARD_ACTIONS) | set(STANDARD_EVENTS)) - set(KEYWORDS)
    assert {p + n for p in prefixes for n in STANDARD_ACTIONS} >= set(ACTION_ALIASES)
    assert {p + n for p in prefixes for n in STANDARD_EVENTS} >= set(EVENT_ALIASES)


def test_package_json_points_at_the_grammar_and_the_configuration():
    package = json.loads((VSCODE / "package.json").read_text(encoding="utf-8"))
    [language] = package["contributes"]["languages"]
    [grammar] = package["contributes"]["grammars"]
    assert language["extensions"] == [".epk"]
    assert grammar["scopeName"] == GRAMMAR["scopeName"]
    assert (VSCODE / grammar["path"]).is_file()
    configuration = json.loads((VSCODE / language["configuration"]).read_text(encoding="utf-8"))
    assert configuration["comments"]["lineComment"] == "#"
    assert ["(", ")"] in configuration["brackets"] and ["{", "}"] in configuration["brackets"]
    assert (VSCODE / package["main"]).is_file()
    assert package["contributes"]["configuration"]["properties"]["epuckc.args"]["default"] == ["lsp"]


# ---- tokenising the corpus ---------------------------------------------------------------

def node_modules() -> Path:
    """editors/vscode/node_modules, installed by `npm ci` (.ci/run does it)."""
    require_tool("node")
    modules = VSCODE / "node_modules"
    if not (modules / "vscode-textmate").is_dir() or not (modules / "vscode-oniguruma").is_dir():
        reason = "run `npm ci` in editors/vscode (CI does it in .ci/run)"
        if os.environ.get("EPUCKC_REQUIRE_ALL_TOOLS"):
            pytest.fail(reason)
        pytest.skip(reason)
    return modules


def _parses(path: Path):
    source, problem = SourceFile.from_path(path)
    if problem is not None:
        return None
    diags = Collector(source)
    program = parse(source, diags)
    return None if diags.has_errors else (source, program)


def _lone_cr(path: Path) -> bool:
    """Lines that end with a lone CR: epuckc reads them as lines, but the
    tokenising script here splits on LF and Vim needs 'fileformats' with
    mac, so such files are left out of the editors' corpus."""
    return b"\r" in path.read_bytes().replace(b"\r\n", b"")


CORPUS = [p for p in sorted((REPO / "examples").glob("*.epk"))
          + sorted((REPO / "tests" / "golden").glob("*.epk"))
          + sorted((REPO / "tests" / "check" / "cases").glob("*.epk"))
          if not _lone_cr(p) and _parses(p)]


@pytest.fixture(scope="module")
def scopes():
    node_modules()
    result = subprocess.run(["node", str(VSCODE / "test" / "tokenize.js"), *map(str, CORPUS)],
                            capture_output=True, text=True, timeout=120)
    assert result.returncode == 0, result.stderr
    tokenised = json.loads(result.stdout)

    def at(path: Path, line: int, column: int) -> list:
        """The scopes of the character at a 1-based line and code-point column."""
        text = SourceFile.from_path(path)[0].line_text(line)
        unit = len(text[: column - 1].encode("utf-16-le")) // 2
        for token in tokenised[str(path)][line - 1]:
            if token["start"] <= unit < token["end"]:
                return token["scopes"]
        raise AssertionError(f"{path.name}:{line}:{column}: no token")
    return at


def _units(program) -> list:
    """The spans of the units written after numbers."""
    found = []

    def walk(node):
        if isinstance(node, ast.Number) and node.unit is not None:
            found.append(node.unit_span)
        elif isinstance(node, (list, tuple)):
            for item in node:
                walk(item)
        elif hasattr(node, "__dataclass_fields__"):
            for name in node.__dataclass_fields__:
                walk(getattr(node, name))
    walk(program.statements)
    return found


STANDARD = set(STANDARD_ACTIONS) | set(STANDARD_EVENTS) | set(ACTION_ALIASES) | set(EVENT_ALIASES)


def expected_name_scope(tokens, k) -> str:
    tok = tokens[k]
    prev = tokens[k - 1] if k else None
    after = tokens[k + 1] if k + 1 < len(tokens) else None
    same_line = lambda other: other is not None and other.line == tok.line
    if same_line(prev) and prev.type == "_RULE":
        return "entity.name.function.rule.epuck"
    if same_line(prev) and prev.type in ("_ACTION", "_EVENT"):
        return "entity.name.function.action.epuck"
    if same_line(prev) and prev.type in ("_CONST", "_VAR"):
        return "variable.other.constant.definition.epuck"
    if same_line(after) and after.type == "_COLON":
        return "variable.parameter.epuck"
    if tok.value in STANDARD:
        return "support.function.epuck"
    if re.fullmatch(r"ir[0-9]+", tok.value) or tok.value in STANDARD_READINGS \
            or tok.value in READING_ARRAYS or tok.value in CHOICE_READINGS:
        return "variable.language.sensor.epuck"
    if (tok.value in FUNCTIONS or tok.value in AGGREGATES) and same_line(after) \
            and after.type == "_LPAR":
        return "support.function.math.epuck"
    return "variable.other.epuck"


@pytest.mark.parametrize("path", CORPUS, ids=lambda p: f"{p.parent.name}/{p.name}")
def test_every_token_has_the_scope_of_its_kind(path, scopes):
    source, program = _parses(path)
    tokens = list(iter_tokens(source, Collector(source)))
    starts = {(s.line, s.column) for s in _units(program)}
    unit_tokens, skipped = set(), set()
    for k, tok in enumerate(tokens):
        if (tok.line, tok.column) in starts:
            # `steps/s` (or `steps / s`) is three tokens; the number is just before
            part = [k, k + 1, k + 2] if k + 2 < len(tokens) and tokens[k + 1].type == "_SLASH" else [k]
            text = "".join(tokens[i].value for i in part)
            same_line = {tokens[i].line for i in [k - 1] + part} == {tok.line}
            (unit_tokens if text in UNITS and same_line else skipped).update(part)
    checked = 0
    for k, tok in enumerate(tokens):
        got = scopes(path, tok.line, tok.column)
        if tok.type.startswith("_") and tok.value in KEYWORDS:
            assert got[-1].startswith(("storage.type.", "keyword.control.",
                                       "keyword.operator.logical.")), (tok, got)
        elif tok.type == "NUMBER":
            assert got[-1] == "constant.numeric.epuck", (tok, got)
        elif k in unit_tokens:
            assert got[-1] == "keyword.other.unit.epuck", (tok, got)
        elif k in skipped:          # an unknown unit, or one on the next line
            pass
        elif tok.type == "NAME":
            assert got[-1] == expected_name_scope(tokens, k), (tok, got)
        elif tok.type == "STRING":
            assert "string.quoted.double.epuck" in got, (tok, got)
        checked += 1
    # comments: between tokens, so a `#` inside a string is not one
    previous = 0
    for tok in tokens + [None]:
        end = tok.start_pos if tok is not None else len(source.text)
        for m in re.finditer(r"#[^\n]*", source.text[previous:end]):
            line, column = source.position(previous + m.start())
            assert "comment.line.number-sign.epuck" in scopes(path, line, column)
            last = source.position(previous + m.end() - 1)
            assert "comment.line.number-sign.epuck" in scopes(path, *last)
        previous = tok.end_pos if tok is not None else end
    assert checked == len(tokens)


def test_the_scopes_of_an_example(scopes):
    path = REPO / "examples" / "extern_spin.epk"
    lines = path.read_text(encoding="utf-8").split("\n")

    def scope_of(word: str, nth: int = 0) -> str:
        row = next(i for i, line in enumerate(lines) if word in line and not line.startswith("#"))
        column = [m.start() for m in re.finditer(re.escape(word), lines[row])][nth]
        return scopes(path, row + 1, column + 1)[-1]
    assert scopes(path, 1, 3)[-1] == "comment.line.number-sign.epuck"
    assert scope_of("extern") == "storage.type.epuck"
    assert scope_of("action") == "storage.type.action.epuck"
    assert scope_of("spin(") == "entity.name.function.action.epuck"
    assert scope_of("turns") == "variable.parameter.epuck"
    assert scope_of('"spin.c"') == "punctuation.definition.string.begin.epuck"
    assert scope_of("spin.c") == "string.quoted.double.epuck"
    assert scope_of("from") == "keyword.control.epuck"
    assert scope_of("immediate") == "support.function.epuck"
    assert scope_of("500") == "constant.numeric.epuck"
    assert scope_of("steps/s") == "keyword.other.unit.epuck"
    assert scope_of("exit_main") == "support.function.epuck"
