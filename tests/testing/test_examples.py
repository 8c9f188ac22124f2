"""The examples are run by `epuckc test examples` in CI: their expected
traces (examples/NAME.trace, blessed with `epuckc test examples --bless`)
are what they do now, and their property checks hold."""
from __future__ import annotations

import os
import re
import shutil

from tests.support.programs import EXAMPLES, epuckc


def test_the_examples_pass(tmp_path):
    """The examples' expected traces (examples/*.trace) are what they do
    now; CI runs this as `epuckc test examples`."""
    copy = tmp_path / "examples"
    shutil.copytree(EXAMPLES, copy)
    r = epuckc("test", "examples", cwd=tmp_path)
    assert r.returncode == 0, r.stdout + r.stderr
    cases = len(list(EXAMPLES.glob("*.epk")))
    m = re.fullmatch(r"(\d+) passed, 0 failed(?:, (\d+) skipped)?", r.stdout.splitlines()[-1])
    assert m and int(m.group(1)) + int(m.group(2) or 0) == cases, r.stdout
    others = r.stdout.splitlines()[:-1]
    assert all(line.startswith("SKIP ") for line in others), r.stdout
    if os.environ.get("EPUCKC_REQUIRE_ALL_TOOLS"):      # CI has Enki: nothing skips
        assert not others, r.stdout


def test_every_example_is_a_golden_or_checks_properties():
    from epuckc.testing.case import discover
    for case in discover([EXAMPLES]):
        assert case.expected(".trace").is_file() or (case.expect and not case.compare_trace), \
            case.shown
