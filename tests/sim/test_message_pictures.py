"""Messages in the pictures of a run (issue 27): the SVG draws a line from
sender to receiver, the replay page shows each message as a fading line,
and a run of 50 robots stays readable: labels on demand (hover, or the
robot selected), pale paths and short trails."""
from __future__ import annotations

import json
import re
import subprocess

import pytest

from epuckc.sim.plot import MESSAGE_BUCKET_MS
from epuckc.sim.replay import MESSAGE_SHOWN_MS, TRAIL_MS
from tests.conftest import require_enki, require_tool
from tests.sim.test_replay import browse
from tests.support.world import EXAMPLES, by_class, epuckc, svg

SVG_NS = "{http://www.w3.org/2000/svg}"


@pytest.fixture(scope="module")
def follow(tmp_path_factory):
    require_enki()
    tmp = tmp_path_factory.mktemp("follow")
    result = epuckc("run", EXAMPLES / "follower.epk", "--world", EXAMPLES / "follow.world",
                    "--time-limit", "5s", "--trace", tmp / "t.jsonl", "--svg", tmp / "t.svg",
                    "--html", tmp / "t.html", cwd=tmp)
    assert result.returncode == 3, result.stderr
    records = [json.loads(line) for line in (tmp / "t.jsonl").read_text().splitlines()]
    return tmp, [r for r in records if r["kind"] == "message"]


def _frame(root):
    world = next(e for e in root.iter(f"{SVG_NS}g") if e.get("id") == "world")
    x0, y1, scale, margin, top = map(float, world.get("data-frame").split())
    return lambda x, y: (round(margin + (x - x0) * scale, 1), round(top + (y1 - y) * scale, 1))


def test_the_svg_draws_a_line_from_sender_to_receiver_each_second(follow):
    tmp, deliveries = follow
    assert deliveries
    root = svg(tmp / "t.svg")
    lines = by_class(root, "message")
    px = _frame(root)
    expected = {}
    for m in deliveries:
        expected.setdefault((m["from"], m["robot"], m["t_ms"] // MESSAGE_BUCKET_MS), m)
    assert len(lines) == len(expected)
    for line in lines:
        m = expected[(line.get("data-from"), line.get("data-to"),
                      int(line.get("data-t-ms")) // MESSAGE_BUCKET_MS)]
        assert (float(line.get("x1")), float(line.get("y1"))) == px(m["from_x_mm"], m["from_y_mm"])
        assert (float(line.get("x2")), float(line.get("y2"))) == px(m["x_mm"], m["y_mm"])


def test_the_replay_shows_the_messages_of_the_last_half_second(follow, tmp_path):
    tmp, deliveries = follow
    at = deliveries[len(deliveries) // 2]["t_ms"] + 30
    dom = browse(tmp / "t.html", tmp_path, play=False, at_ms=at)
    assert 'data-errors=""' in dom
    shown = re.findall(r'<line class="replay-message"[^>]*>', dom)
    recent = [m for m in deliveries if at - MESSAGE_SHOWN_MS < m["t_ms"] <= at]
    assert len(shown) == len(recent) > 0
    opacities = [float(re.search(r'stroke-opacity="([0-9.]+)"', s).group(1)) for s in shown]
    assert opacities == sorted(opacities)           # the oldest first, the palest


@pytest.fixture(scope="module")
def swarm(tmp_path_factory):
    require_enki()
    tmp = tmp_path_factory.mktemp("swarm")
    world = tmp / "fifty.world"
    lines = ["arena 200 cm x 200 cm"]
    for k in range(50):
        lines.append(f"robot at {20 + (k % 10) * 18} cm, {20 + (k // 10) * 35} cm "
                     f"heading {(k * 37) % 360} deg")
    world.write_text("\n".join(lines) + "\n")
    result = epuckc("run", EXAMPLES / "aggregation.epk", "--world", world, "--time-limit",
                    "12s", "--svg", tmp / "s.svg", "--html", tmp / "s.html", cwd=tmp)
    assert result.returncode == 3, result.stderr
    return tmp


def test_fifty_robots_show_labels_on_demand_and_pale_paths(swarm):
    root = svg(swarm / "s.svg")
    runs = by_class(root, "robot-run")
    assert len(runs) == 50
    style = "".join(e.text or "" for e in root.iter(f"{SVG_NS}style"))
    assert "g.robot-run g.labels { display: none; }" in style and ":hover g.labels" in style
    for run in runs:
        # every label of a robot is in its own g.labels, none loose on the map
        loose = [e for e in run if e.get("class") == "firing-label"]
        assert loose == []
        [labels] = [e for e in run if e.get("class") == "labels"]
        assert all(e.get("class") in ("firing-label", "mode-label", "contact-label")
                   for e in labels)
        [path] = [e for e in run if e.get("class") == "path"]
        assert float(path.get("stroke-opacity")) < 0.5
    assert sum(len(list(e for e in run if e.get("class") == "labels")[0]) for run in runs) > 50


def test_fifty_robots_replay_trails_of_five_seconds_and_a_selected_robots_labels(swarm, tmp_path):
    dom = browse(swarm / "s.html", tmp_path, play=False, at_ms=10_000)
    assert 'data-errors=""' in dom
    trails = re.findall(r'<polyline class="trail"[^>]* points="([^"]*)"', dom)
    assert len(trails) == 50
    # each trail: the robot's poses of the last TRAIL_MS, as the page's data has them
    data = json.loads(re.search(r'<script id="run-data" type="application/json">(.*?)</script>',
                                (swarm / "s.html").read_text(), re.S).group(1))
    for trail, robot in zip(trails, data["robots"]):
        expected = [p for p in robot["poses"] if 10_000 - TRAIL_MS <= p[0] <= 10_000]
        assert len(trail.split()) == len(expected) > 0
    assert not re.search(r'<g class="robot-run selected"', dom)
    dom = _browse_selected(swarm / "s.html", tmp_path, "r7")
    assert 'data-errors=""' in dom
    assert re.search(r'<g class="robot-run selected" data-robot="r7"', dom)
    assert len(re.findall(r'class="robot-run selected"', dom)) == 1


def _browse_selected(page, tmp_path, name):
    """The page at 10 s with robot `name` selected (`#t=MS&select=NAME`)."""
    chromium = require_tool("chromium")
    url = page.as_uri() + f"#t=10000&select={name}"
    return subprocess.run([chromium, "--headless", "--no-sandbox", "--disable-gpu",
                           "--dump-dom", url], capture_output=True, text=True,
                          timeout=120).stdout
