"""`epuckc run [FILE] --world W` (issue 41): FILE is optional when the world
names every robot's program, a FILE no robot would run is an error, FILE
runs where the world names none, the run says which program runs on which
robot, and the usage line shows what is optional as optional."""
from __future__ import annotations

import json

import pytest

from conftest import require_enki

from tests.support.world import epuckc

PROGRAM = "on immediate do start_straight(200 steps/s, 1 m)\n"


@pytest.fixture
def folder(tmp_path):
    (tmp_path / "mine.epk").write_text(PROGRAM)
    (tmp_path / "other.epk").write_text("# another program\n" + PROGRAM)
    (tmp_path / "all.world").write_text("arena 100 cm x 60 cm\n"
                                        "robot a at 10 cm, 20 cm program mine.epk\n"
                                        "robot b at 50 cm, 40 cm program mine.epk\n")
    (tmp_path / "half.world").write_text("arena 100 cm x 60 cm\n"
                                         "robot a at 10 cm, 20 cm program mine.epk\n"
                                         "robot b at 50 cm, 40 cm\n")
    return tmp_path


def _programs(trace) -> dict:
    """robot -> the program files its rules came from (their event names
    start with `FILE:LINE`)."""
    out: dict = {}
    for line in trace.read_text().splitlines():
        rec = json.loads(line)
        if rec["kind"] == "event":
            out.setdefault(rec["robot"], set()).add(rec["name"].split(":")[0])
    return out


def test_the_usage_line_shows_file_and_more_as_optional():
    result = epuckc("run", "--help")
    assert "[FILE] [MORE.c ...]" in " ".join(result.stdout.split())
    result = epuckc("run")
    assert result.returncode == 2
    assert "MORE.c" not in result.stderr.replace("MORE.c files", "")   # not "required: MORE.c"
    assert "needs FILE" in result.stderr and "--world" in result.stderr


def test_a_world_that_names_every_program_needs_no_file(folder):
    require_enki()
    result = epuckc("run", "--world", "all.world", "--time-limit", "300ms", "--trace", "t.jsonl",
                    cwd=folder)
    assert result.returncode == 3, result.stderr
    assert "epuckc: all.world runs mine.epk on a, b" in result.stderr
    assert _programs(folder / "t.jsonl") == {"a": {"mine.epk"}, "b": {"mine.epk"}}
    # FILE may still be given when it is the program the world names
    result = epuckc("run", "mine.epk", "--world", "all.world", "--time-limit", "300ms",
                    cwd=folder)
    assert result.returncode == 3, result.stderr


def test_a_file_no_robot_would_run_is_an_error(folder):
    result = epuckc("run", "other.epk", "--world", "all.world", "--time-limit", "300ms",
                    cwd=folder)
    assert result.returncode == 2
    assert "other.epk would not run: every robot of all.world names its own program " \
           "(mine.epk on a, b)" in result.stderr
    assert "leave FILE out" in result.stderr


def test_file_runs_where_the_world_names_no_program_and_the_run_says_so(folder):
    require_enki()
    result = epuckc("run", "other.epk", "--world", "half.world", "--time-limit", "300ms",
                    "--trace", "t.jsonl", cwd=folder)
    assert result.returncode == 3, result.stderr
    assert "epuckc: half.world runs mine.epk on a; other.epk (FILE) on b" in result.stderr
    assert _programs(folder / "t.jsonl") == {"a": {"mine.epk"}, "b": {"other.epk"}}
    # without FILE, the robot left without a program is named
    result = epuckc("run", "--world", "half.world", cwd=folder)
    assert result.returncode == 2
    assert "robot b of half.world has no `program`: give FILE" in result.stderr
