"""docs/world.md's table of what the IR sensors read against the gap to a
wall is what docs/ir_table.py measures in an Enki world today (issue 41:
a wall follower needs it, and the docs had none)."""
from __future__ import annotations

import importlib.util
import re
from pathlib import Path

from conftest import require_enki

REPO = Path(__file__).resolve().parents[2]


def test_the_committed_table_is_what_the_script_measures():
    require_enki()
    spec = importlib.util.spec_from_file_location("ir_table", REPO / "docs" / "ir_table.py")
    script = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(script)
    measured = script.measure()
    doc = (REPO / "docs" / "world.md").read_text(encoding="utf-8")
    committed = re.search(r"<!-- the IR table: [^\n]*-->\n(.*?)<!-- end of the IR table -->",
                          doc, re.S).group(1)
    assert committed == script.table(measured), \
        "docs/world.md's IR table is stale: paste `python3 docs/ir_table.py` over it"
    # and it says what a wall follower relies on: nearer reads more
    ahead = [a for a, _ in measured.values()]
    beside = [b for _, b in measured.values()]
    assert ahead[:6] == sorted(ahead[:6], reverse=True) and beside == sorted(beside, reverse=True)
