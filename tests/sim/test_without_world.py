"""Devices only a world gives, in a run without one (issue 41): a program
that sends or listens for messages, reads the camera or the ToF sensor
runs on the stub harness alone with no word that nobody hears it and
nothing is seen; now the first use of each device is W070 at `run` time
(and with `check --no-world`), never in a world. The records of `send`,
`message` and `rgb` read like the others' (no raw JSON fragment)."""
from __future__ import annotations

import json
import re

from conftest import require_enki

from tests.support.world import epuckc

PROGRAM = """var got = 0
every 300 ms do send(7)
on message do got = message
every 200 ms if seen(red) > 3 or distance < 100 mm do led_rgb(led1, 100, 0, 40)
on immediate do led_rgb(led3, 10, 20, 30)
after 1 s do exit_main
"""


def _w070(stderr: str) -> list:
    return re.findall(r"^\S+:(\d+):(\d+): warning\[W070\]: `([^`]+)` uses ([^,]+),",
                      stderr, re.M)


def test_a_run_without_a_world_says_which_devices_get_nothing(tmp_path):
    (tmp_path / "p.epk").write_text(PROGRAM)
    result = epuckc("run", "p.epk", cwd=tmp_path)
    assert result.returncode == 0, result.stderr
    # each device once, at its first use, with the fix
    assert _w070(result.stderr) == [("2", "17", "send", "IR messages"),
                                    ("4", "17", "seen(COLOUR)", "the camera"),
                                    ("4", "34", "distance", "the ToF distance sensor")]
    assert "no robot hears what it sends and no message arrives" in result.stderr
    assert result.stderr.count("`epuckc run FILE --world W.world`") == 3
    # said again when the run comes from the run cache; refused with --werror
    again = epuckc("run", "p.epk", cwd=tmp_path)
    assert _w070(again.stderr) == _w070(result.stderr)
    assert epuckc("run", "p.epk", "--werror", cwd=tmp_path).returncode == 1
    # `check` says it only when told the file runs alone; the RGB LEDs need no world
    assert _w070(epuckc("check", "p.epk", cwd=tmp_path).stderr) == []
    assert _w070(epuckc("check", "--no-world", "p.epk", cwd=tmp_path).stderr) \
        == _w070(result.stderr)


def test_send_and_rgb_lines_read_like_the_others(tmp_path):
    (tmp_path / "p.epk").write_text(PROGRAM)
    result = epuckc("run", "p.epk", "--trace", "t.jsonl", cwd=tmp_path)
    lines = result.stdout.splitlines()
    assert "[   301 ms] send      7" in lines
    assert "[     1 ms] rgb       led3 red 10 green 20 blue 30" in lines
    # no record's line is a JSON fragment
    assert not [line for line in lines if '": ' in line], lines
    records = [json.loads(line) for line in (tmp_path / "t.jsonl").read_text().splitlines()]
    [send] = [r for r in records if r["kind"] == "send" and r["t_ms"] == 301]
    assert (send["name"], send["value"]) == ("send", 7)


def test_in_a_world_messages_arrive_with_a_readable_line_and_no_warning(tmp_path):
    require_enki()
    (tmp_path / "p.epk").write_text(PROGRAM)
    (tmp_path / "w.world").write_text("arena none\nrobot a at 10 cm, 20 cm heading 0 deg\n"
                                      "robot b at 20 cm, 20 cm heading 180 deg\n")
    result = epuckc("run", "p.epk", "--world", "w.world", "--trace", "t.jsonl", cwd=tmp_path)
    assert result.returncode == 0, result.stderr
    assert "W070" not in result.stderr
    heard = [line for line in result.stdout.splitlines() if "] message " in line]
    assert heard and all(re.fullmatch(r"[ab]: \[ *\d+ ms\] message   7 from [ab], bearing "
                                      r"-?\d+\.\d deg, range \d+\.\d mm \(sensor \d\)", line)
                         for line in heard), heard
    assert not [line for line in result.stdout.splitlines() if '": ' in line]
    records = [json.loads(line) for line in (tmp_path / "t.jsonl").read_text().splitlines()]
    messages = [r for r in records if r["kind"] == "message"]
    assert len(messages) == len(heard) and {m["from"] for m in messages} == {"a", "b"}
