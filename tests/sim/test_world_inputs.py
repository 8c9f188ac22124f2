"""What a world gives its robots besides physics (docs/world.md, "Inputs at
set times"): a robot's selector, the world's scenario and a robot's own,
`--scenario` with `--world`; and `-D` for the programs a world names,
`--trace -` for a world."""
import json

import pytest

from conftest import require_enki
from tests.support.world import epuckc

PROGRAM = """# the selector, a clap and a key, each shown on an LED
const WAIT = 300 ms
on selector(3) do led_on(led3)
on selector(5) do led_on(led5)
on clap(800) do led_on(body)
on remote(mute) do led_on(front)
every WAIT do led_toggle(led0)
"""

WORLD = """arena 1 m x 1 m
scenario all.scn
robot a at 30 cm, 50 cm selector 3
robot b at 70 cm, 50 cm selector 5 scenario b.scn
"""


@pytest.fixture(scope="module")
def folder(tmp_path_factory):
    require_enki()
    path = tmp_path_factory.mktemp("inputs")
    (path / "p.epk").write_text(PROGRAM)
    (path / "w.world").write_text(WORLD)
    (path / "all.scn").write_text("0 ms mic=0\n400 ms mic=900\n450 ms mic=0\n")
    (path / "b.scn").write_text("200 ms key=mute\n")
    (path / "other.scn").write_text("600 ms mic=900\n650 ms mic=0\n")
    return path


def _run(folder, *extra, trace="t.jsonl"):
    result = epuckc("run", "p.epk", "--world", "w.world", "--time-limit", "700ms",
                    "--trace", trace, *extra, cwd=folder)
    assert result.returncode == 3, result.stdout + result.stderr
    text = result.stdout if trace == "-" else (folder / trace).read_text()
    return [json.loads(line) for line in text.splitlines()], result


def _firsts(records, robot):
    """When each LED of `robot` first lit."""
    firsts = {}
    for r in records:
        if r.get("robot") == robot and r["kind"] == "led" and r["state"] == 1:
            firsts.setdefault(r["name"], r["t_ms"])
    return firsts


def test_each_robot_has_its_selector_and_the_scenario_it_is_given(folder):
    records, _ = _run(folder)
    a, b = _firsts(records, "a"), _firsts(records, "b")
    # a: its selector, the world's clap; b: its selector, its own key and
    # not the world's clap (its scenario replaces the world's)
    # (the rules' first poll is at 1 ms)
    assert a["led3"] == 1 and a["body"] == 400 and "front" not in a and "led5" not in a
    assert b["led5"] == 1 and b["front"] == 200 and "body" not in b and "led3" not in b
    assert a["led0"] == b["led0"] == 301


def test_the_command_lines_scenario_replaces_the_worlds(folder):
    records, _ = _run(folder, "--scenario", "other.scn")
    a, b = _firsts(records, "a"), _firsts(records, "b")
    assert a["body"] == 600 and "body" not in b


def test_a_define_goes_to_the_programs_that_declare_it_and_the_trace_to_stdout(folder):
    on_file, _ = _run(folder, "-D", "WAIT=100 ms")
    streamed, result = _run(folder, "-D", "WAIT=100 ms", trace="-")
    assert _firsts(on_file, "a")["led0"] == _firsts(on_file, "b")["led0"] == 101
    assert streamed == on_file and "[" not in result.stdout.split("{", 1)[0]
    refused = epuckc("run", "p.epk", "--world", "w.world", "-D", "NOPE=1", cwd=folder)
    assert refused.returncode == 2
    assert "-D NOPE: no program of the run declares a constant NOPE (the rule files: p.epk)" \
        in refused.stderr
