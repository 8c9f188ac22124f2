"""Running epuckc with worlds and pictures, for the tests of issue 10."""
from __future__ import annotations

import json
import xml.etree.ElementTree as ET
from pathlib import Path

from .programs import epuckc  # noqa: F401  (the sim tests take it from here)

REPO = Path(__file__).resolve().parents[2]
EXAMPLES = REPO / "examples"
SVG = "{http://www.w3.org/2000/svg}"

# LEDs switched at known times, three variables (pictures of a run)
LED_PROGRAM = """# a count shown on the ring LEDs
var count = 0
var speed = 300 steps/s
var shown = -4
on immediate do led_on(front), start_curve(radius: 0 mm, degrees: 120 deg, speed: speed)
after 1 s do count += 1, led_on(led0)
after 2 s do count += 1, led_on(led1), led_on(body)
after 3 s do count += 1, led_on(led2), led_off(front), led_toggle(led0)
after 4 s do shown = count, exit_main
"""


def pose_records(records) -> list:
    """The pose records of a trace."""
    return [r for r in records if r["kind"] == "pose"]


def same_run_both_ways(tmp_path, env_a: dict, env_b: dict, *args):
    """`epuckc run ARGS --trace` in two environments: the same merged trace,
    stdout and exit status (0 or 3) both times; returns them."""
    results = []
    for env in (env_a, env_b):
        trace = tmp_path / "t.jsonl"
        r = epuckc("run", *args, "--trace", trace, env=env)
        assert r.returncode in (0, 3), r.stderr
        results.append((trace.read_bytes(), r.stdout, r.returncode))
    assert results[0][0], "no trace"
    assert results[0] == results[1]
    return results[0]


def three_robots_world(seed: int) -> str:
    """A small arena with a box, a cylinder and three robots (a, b, c)."""
    return ("arena 90 cm x 70 cm\n"
            "box at 30 cm, 40 cm size 20 cm x 6 cm angle 30 deg\n"
            "cylinder at 65 cm, 45 cm radius 6 cm colour red\n"
            "robot a at 15 cm, 12 cm heading 20 deg\n"
            "robot b at 60 cm, 15 cm heading 120 deg colour green\n"
            "robot c at 45 cm, 58 cm heading 250 deg\n"
            f"seed {seed}\n")


def run(program, tmp_path, *extra, expect=0, name="trace"):
    """`epuckc run` with a trace; returns (records, stdout, the trace's text).
    `expect`: the exit status (None: any)."""
    trace = tmp_path / f"{name}.jsonl"
    result = epuckc("run", program, "--trace", trace, *extra)
    if expect is not None:
        assert result.returncode == expect, result.stdout + result.stderr
    text = trace.read_text()
    return [json.loads(line) for line in text.splitlines()], result.stdout, text


def svg(path):
    return ET.parse(path).getroot()


def by_class(root, cls):
    return [e for e in root.iter() if cls in e.get("class", "").split()]


def final_pose(records, robot=None):
    """The last record with a pose (of one robot)."""
    posed = [r for r in records if "x_mm" in r and (robot is None or r.get("robot") == robot)]
    return posed[-1]
