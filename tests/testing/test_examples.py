"""The examples are run by `epuckc test examples` in CI: their expected
traces (examples/NAME.trace, blessed with `epuckc test examples --bless`)
are what they do now, and their property checks hold."""
from __future__ import annotations

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
    assert re.fullmatch(rf"{cases} passed, 0 failed(, \d+ skipped)?\n", r.stdout.splitlines()[-1]
                        + "\n"), r.stdout
    assert len(list(EXAMPLES.glob("*.trace"))) >= cases - 2
