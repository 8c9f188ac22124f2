"""`-D NAME=VALUE` on compile, build and run: a constant's value replaced
before checking, an unknown name and a value of the wrong kind refused."""
from __future__ import annotations

import pytest

from epuckc.check.defines import DefineError, apply_defines, parse_define
from tests.support.cli import run_cli

PROGRAM = """const GAIN = 2
const SPEED = 300 steps/s   # the cruise
every 10 ms do set_speed(left: SPEED * GAIN, right: SPEED)
on timer(50 ms) do exit_main
on immediate do set_timer
"""


@pytest.fixture
def prog(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "g.epk").write_text(PROGRAM, encoding="utf-8")
    return tmp_path / "g.epk"


def test_value_replaced_in_the_generated_c(prog, capsys):
    status, out, err = run_cli(["compile", "g.epk", "-o", "-"], capsys)
    assert status == 0 and "{600, 300}" in out
    status, out, err = run_cli(["compile", "g.epk", "-o", "-", "-D", "GAIN=3",
                                "-D", "SPEED=200steps/s"], capsys)
    assert status == 0, err
    assert "{600, 200}" in out and "{600, 300}" not in out


def test_wrong_unit_is_the_checkers_diagnostic(prog, capsys):
    status, out, err = run_cli(["compile", "g.epk", "-o", "-", "-D", "GAIN=3 cm"], capsys)
    assert status == 1
    assert "g.epk:3:" in err and "error[E048]" in err


def test_unknown_constant(prog, capsys):
    status, out, err = run_cli(["build", "g.epk", "-D", "GAINS=3"], capsys)
    assert status == 2
    assert "has no constant GAINS" in err and "GAIN, SPEED" in err


def test_run_takes_defines(prog, capsys):
    status, out, err = run_cli(["run", "g.epk", "-D", "GAIN=1", "--trace", "t.jsonl"], capsys)
    assert status == 0, err
    status, out2, err = run_cli(["run", "g.epk", "--trace", "t2.jsonl"], capsys)
    assert status == 0
    # the left wheel went twice as far with GAIN=2 as with GAIN=1
    import json
    last = [json.loads(line) for line in (prog.parent / "t.jsonl").read_text().splitlines()][-1]
    last2 = [json.loads(line) for line in (prog.parent / "t2.jsonl").read_text().splitlines()][-1]
    assert last["left_steps"] == last["right_steps"]
    assert last2["left_steps"] == 2 * last2["right_steps"]


def test_bad_define_text(prog, capsys):
    with pytest.raises(SystemExit) as exc:
        run_cli(["compile", "g.epk", "-D", "GAIN"], capsys)
    assert exc.value.code == 2
    assert "NAME=VALUE" in capsys.readouterr().err
    with pytest.raises(DefineError):
        parse_define("GAIN=3\non immediate do exit_main")


def test_only_the_value_changes():
    text = apply_defines(PROGRAM, {"SPEED": "-100 steps/s"})
    assert text.splitlines()[1] == "const SPEED = -100 steps/s   # the cruise"
    assert text.splitlines()[0] == "const GAIN = 2"
