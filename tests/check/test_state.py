"""The checker's state is its records (check/state.py): what declaring
leaves is in them, so that the language server, which keeps and replays
declarations by the records' fields (ide/passes.py), cannot miss a table
a mixin adds; and every field is read and set as the checker's attribute."""
from __future__ import annotations

import copy
from pathlib import Path

import pytest

from epuckc.base.source import SourceFile
from epuckc.check.checker import Checker
from epuckc.check.state import Declarations, Facts, Memories
from epuckc.diagnostics import Collector
from epuckc.syntax.parser import parse

REPO = Path(__file__).resolve().parents[2]
EXAMPLES = sorted((REPO / "examples").glob("*.epk"))

# what the checker is given, and its records: the rest is per-check scratch
GIVEN = {"program", "target", "world", "diags", "base_dir", "decls", "facts", "memories"}


def _checker(path: Path) -> Checker:
    source = SourceFile(path.name, path.read_text())
    diags = Collector(source)
    return Checker(parse(source, diags), diags, base_dir=path.parent)


def test_the_examples_declare_every_kind_of_table():
    """(what the next test stands on: between them, the examples fill
    every table of the declarations)"""
    filled = set()
    for path in EXAMPLES:
        c = _checker(path)
        c._declarations()
        filled |= {t for t in Declarations.TABLES if getattr(c.decls, t)}
    assert filled >= set(Declarations.TABLES) - {"broken_externs"}


@pytest.mark.parametrize("path", EXAMPLES, ids=lambda p: p.stem)
def test_declaring_writes_only_into_the_records(path):
    c = _checker(path)
    before = {k: copy.copy(v) for k, v in vars(c).items() if k not in GIVEN}
    c._declarations()
    after = {k: v for k, v in vars(c).items() if k not in GIVEN}
    assert after == before, "declaring left state outside check/state.py's records"


def test_every_field_of_the_declarations_is_a_table_a_rule_reads_or_said_not_to_be():
    fields = set(Declarations.__match_args__)
    kinds = (Declarations.TABLES, Declarations.DERIVED, Declarations.NOT_LOOKED_UP)
    assert set().union(*kinds) == fields
    assert sum(map(len, kinds)) == len(fields)          # each field in one of them


def test_the_records_fields_are_the_checkers_attributes():
    c = Checker(parse(SourceFile("t.epk", ""), Collector(SourceFile("t.epk", ""))),
                Collector(SourceFile("t.epk", "")))
    for record, cls in (("decls", Declarations), ("facts", Facts), ("memories", Memories)):
        for name in cls.__match_args__:
            attr = name if hasattr(Checker, name) else f"_{name}"
            marker = object()
            setattr(c, attr, marker)
            assert getattr(getattr(c, record), name) is marker, (record, name)
            assert attr not in vars(c)


def test_a_step_apart_gives_back_what_it_said_and_found_and_leaves_the_checkers_own():
    path = REPO / "examples" / "avoider.epk"
    c = _checker(path)
    c._declarations()
    said, facts, memories = list(c.diags.items), c.facts.copy(), c.memories.copy()
    rule = next(iter(c.program.of_type(__import__("epuckc.syntax.ast").syntax.ast.Rule)))
    with c.apart() as step:
        c._rule(rule)
    assert step.facts, "a rule of avoider.epk uses names"
    assert c.diags.items == said and c.facts == facts and c.memories == memories
    # what the step found is what checking the rule alone finds
    alone = _checker(path)
    alone._declarations()
    alone.facts, alone.diags.items = Facts(), []
    alone._rule(next(iter(alone.program.of_type(type(rule)))))
    assert dict(step.facts) == dict(alone.facts.items())
    assert step.diags == alone.diags.items
