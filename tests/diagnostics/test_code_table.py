"""docs/language.md's table of diagnostic codes lists exactly the codes
`epuckc explain` knows, each once (issue 41: it lacked six and listed W020
twice)."""
from __future__ import annotations

import re
from pathlib import Path

from epuckc.diagnostics.codes import CODES, explanation

REPO = Path(__file__).resolve().parents[2]


def _table_codes() -> list:
    doc = (REPO / "docs" / "language.md").read_text(encoding="utf-8")
    section = doc[doc.index("## 8. Diagnostics"):]
    return re.findall(r"^\| ([EW]\d{3}) \|", section, re.M)


def test_the_table_lists_every_code_explain_knows_once():
    listed = _table_codes()
    twice = sorted({c for c in listed if listed.count(c) > 1})
    assert not twice, f"listed more than once: {twice}"
    known = {code for code in CODES if explanation(code)}
    assert known == set(CODES), "a code without an explanation file"
    assert sorted(set(CODES) - set(listed)) == [], "codes missing from the table"
    assert sorted(set(listed) - set(CODES)) == [], "codes in the table that explain does not know"
    assert listed == sorted(listed, key=lambda c: (c[0] != "E", c)), "the table is out of order"
