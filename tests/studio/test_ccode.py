"""Show C (epuckc/studio/ccode.py): the C `epuckc compile` writes for the
editor's text, and the parts of it that the statement at the cursor
becomes."""
from __future__ import annotations

import pytest

from epuckc.studio.ccode import NoC, generated_c
from tests.support.world import EXAMPLES, epuckc


def test_the_parts_of_a_statement_over_several_lines(tmp_path):
    text = (EXAMPLES / "braitenberg.epk").read_text()
    path = tmp_path / "braitenberg.epk"
    shown = generated_c(path, text, 14)         # inside the rule that starts on line 11
    assert shown["line"] == 11
    # the whole file is what `epuckc compile` writes
    path.write_text(text)
    assert epuckc("compile", path, "-o", tmp_path / "out.c").returncode == 0
    assert shown["c"] == (tmp_path / "out.c").read_text()
    joined = "\n".join(shown["parts"])
    assert "static void epk_do_r1(void *epk_param)" in joined
    assert "epk_when_r1 = {10L}" in joined
    assert "braitenberg.epk:8" not in joined and "epk_v_right_near = 0;" not in joined


def test_a_declaration_has_its_own_part(tmp_path):
    text = (EXAMPLES / "braitenberg.epk").read_text()
    for line, name in ((8, "right_near"), (9, "left_near")):
        shown = generated_c(tmp_path / "braitenberg.epk", text, line)
        assert [p for p in shown["parts"] if f"static int epk_v_{name} = 0;" in p], shown["parts"]
        assert "epk_do_r1" not in "\n".join(shown["parts"])


def test_a_text_with_errors_has_no_c_and_says_why(tmp_path):
    with pytest.raises(NoC) as exc:
        generated_c(tmp_path / "x.epk", "on immediate do set_sped(1 steps/s, 1 steps/s)\n", 1)
    assert "set_speed" in str(exc.value)
