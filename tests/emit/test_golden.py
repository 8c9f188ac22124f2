"""Golden tests: for each rule file under tests/golden/, the generated C, its
externs header and the diagnostics are compared with
tests/golden/expected/NAME.c, NAME_externs.h and NAME.stderr. `pytest --update-goldens` rewrites them for review in git."""
from pathlib import Path

import pytest

from tests.support.programs import REPO, epuckc

GOLDEN = REPO / "tests" / "golden"
CASES = sorted(p.stem for p in GOLDEN.glob("*.epk"))


def _compare(path: Path, actual: str, update: bool):
    if update:
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(actual, encoding="utf-8")
        return
    assert path.is_file(), f"{path} is missing: run pytest --update-goldens"
    assert actual == path.read_text(encoding="utf-8"), f"{path.name} differs from the golden file"


@pytest.mark.parametrize("case", CASES)
def test_generated_c_and_diagnostics(case, tmp_path, update_goldens):
    out = tmp_path / f"{case}.c"
    result = epuckc("compile", f"{case}.epk", "-o", out, cwd=GOLDEN,
                    env={"NO_COLOR": "1"})
    expected_c = GOLDEN / "expected" / f"{case}.c"
    _compare(GOLDEN / "expected" / f"{case}.stderr", result.stderr, update_goldens)
    header = tmp_path / f"{case}_externs.h"
    expected_h = GOLDEN / "expected" / header.name
    if result.returncode == 0:
        _compare(expected_c, out.read_text(encoding="utf-8"), update_goldens)
        if header.exists():
            _compare(expected_h, header.read_text(encoding="utf-8"), update_goldens)
        else:
            assert not expected_h.exists(), f"{case} writes no header but has a golden one"
    else:
        assert result.returncode == 1
        assert not out.exists(), "a failed compile must write nothing"
        assert not expected_c.exists(), f"{case} fails now but has a golden C file"


def test_every_case_is_covered():
    stale = {p.stem.removesuffix("_externs") for p in (GOLDEN / "expected").glob("*.*")} \
        - set(CASES)
    assert not stale, f"golden files without a case: {stale}"
