"""What the docs tell a user about the command line and experiments is
true of them (issue 41): the README's `--seed` says that a world's noise
comes from its own `seed` line (a new user changed --seed and expected
other wheel noise), and docs/experiments.md does not say that the language
has no messages."""
from __future__ import annotations

import re
from pathlib import Path

REPO = Path(__file__).resolve().parents[2]


def test_the_readme_s_seed_says_where_a_world_s_noise_comes_from():
    readme = (REPO / "README.md").read_text(encoding="utf-8")
    [row] = [line for line in readme.splitlines() if line.startswith("| `epuckc run FILE [")]
    assert re.search(r"`--seed`[^|]*world file's own `seed` line", row), row


def test_the_experiments_doc_knows_the_language_has_messages():
    doc = (REPO / "docs" / "experiments.md").read_text(encoding="utf-8")
    assert "no messages" not in doc
    assert "`on message" in doc
