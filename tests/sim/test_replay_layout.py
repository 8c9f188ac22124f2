"""The replay in a 1200 x 800 window, laid out by headless Chromium (issue
41: the variables panel was below the fold, each robot was drawn twice,
the world's colours were ignored, and `every 20 ms` filled "last rules
fired"): the picture and both lists inside the window, one body per robot
moving with its name, the robots and the walls in their world colours,
each rule fired listed once with its repeats."""
from __future__ import annotations

import html
import json
import re
import subprocess
from pathlib import Path

import pytest

from epuckc.sim.world import COLOURS
from tests.conftest import require_enki, require_tool
from tests.support.world import by_class, epuckc, svg

MEASURE = """<pre id="measured"></pre><script>
window.addEventListener("load", () => setTimeout(() => {
  const box = s => { const r = document.querySelector(s).getBoundingClientRect();
    return [r.left, r.top, r.right, r.bottom]; };
  document.getElementById("measured").textContent = JSON.stringify({
    window: [outerWidth, outerHeight], view: [innerWidth, innerHeight],
    svg: box("#picture svg"), fired: box("#fired"),
    vars: box("#vars"), controls: box("#controls"),
    scroll: [document.documentElement.scrollWidth, document.documentElement.scrollHeight]});
}, 200));
</script>"""

PROGRAM = """var count = 0
var laps = 0
var near = 0
var spare = 0
var other = 0
var more = 0
every 20 ms do count = (count + 1) % 1000
every 1 s do laps = (laps + 1) % 100
every 50 ms do near = ir0 + ir7
on immediate do start_straight(300 steps/s, 30 cm)
on stop_motor do start_curve(radius: 0 mm, degrees: 90 deg, speed: 200 steps/s)
"""
WORLD = """arena 120 cm x 80 cm colour blue
cylinder at 80 cm, 40 cm radius 6 cm colour red
robot a at 20 cm, 20 cm heading 0 deg colour green
robot b at 20 cm, 60 cm heading 0 deg colour yellow
robot c at 60 cm, 70 cm heading 180 deg
"""


def _hex(name: str) -> str:
    return "#%02x%02x%02x" % COLOURS[name]


@pytest.fixture(scope="module")
def page(tmp_path_factory):
    require_enki()
    tmp = tmp_path_factory.mktemp("layout")
    (tmp / "p.epk").write_text(PROGRAM)
    (tmp / "w.world").write_text(WORLD)
    result = epuckc("run", "p.epk", "--world", "w.world", "--time-limit", "12s",
                    "--html", "r.html", "--svg", "p.svg", cwd=tmp)
    assert result.returncode == 3, result.stderr
    return tmp


def _chromium(page: Path, *extra) -> str:
    chromium = require_tool("chromium")
    return subprocess.run([chromium, "--headless", "--no-sandbox", "--disable-gpu",
                           "--hide-scrollbars", "--window-size=1200,800", *extra, page.as_uri()],
                          capture_output=True, text=True, timeout=120).stdout


def test_everything_is_in_a_1200_by_800_window(page, tmp_path):
    text = (page / "r.html").read_text()
    measuring = tmp_path / "m.html"
    measuring.write_text(text.replace("</body>", MEASURE + "</body>"))
    dom = _chromium(measuring, "--virtual-time-budget=2000", "--dump-dom")
    m = json.loads(html.unescape(re.search(r'<pre id="measured">(.*?)</pre>', dom, re.S).group(1)))
    # a window of 1200 x 800, the page in what its frame leaves
    assert m["window"] == [1200, 800]
    width, height = m["view"]
    assert width == 1200 and 650 <= height <= 800
    for part in ("svg", "fired", "vars", "controls"):
        left, top, right, bottom = m[part]
        assert 0 <= left and 0 <= top and right <= width and bottom <= height, (part, m[part])
    assert m["scroll"][1] <= height, "the page scrolls"
    # the panel beside the picture, not below it
    assert m["fired"][0] >= m["svg"][2] and m["vars"][0] >= m["svg"][2]
    # and a screenshot of that window is taken (Chromium draws the page)
    shot = tmp_path / "shot.png"
    _chromium(page / "r.html", f"--screenshot={shot}")
    data = shot.read_bytes()
    assert data[:8] == b"\x89PNG\r\n\x1a\n"
    assert int.from_bytes(data[16:20], "big") == 1200


def test_each_robot_is_drawn_once_in_its_world_colour_with_its_name(page):
    dom = _chromium(page / "r.html", "--dump-dom")
    assert 'data-errors=""' in dom
    robots = re.findall(r'<g class="replay-robot" data-robot="(\w+)"', dom)
    assert robots == ["a", "b", "c"]
    # the picture's final poses give way to the moving robots
    finals = re.findall(r'<g class="final-pose"[^>]*>', dom)
    assert len(finals) == 3 and all('display="none"' in f for f in finals)
    assert re.findall(r'<text class="replay-name"[^>]*>(\w+)</text>', dom) == ["a", "b", "c"]
    data = json.loads(re.search(r'<script id="run-data" type="application/json">(.*?)</script>',
                                (page / "r.html").read_text(), re.S).group(1))
    colours = {r["name"]: r["colour"] for r in data["robots"]}
    assert colours["a"] == _hex("green")
    assert colours["b"] != _hex("yellow") and colours["b"].startswith("#")    # darkened
    assert colours["c"] not in (_hex("green"), colours["b"])                 # the palette's


def test_the_picture_uses_the_world_s_colours(page):
    root = svg(page / "p.svg")
    [arena] = by_class(root, "arena")
    assert arena.get("stroke") == _hex("blue")
    [cylinder] = by_class(root, "cylinder")
    assert cylinder.get("fill") == _hex("red")
    runs = {g.get("data-robot"): g for g in by_class(root, "robot-run")}
    [path] = by_class(runs["a"], "path")
    assert path.get("stroke") == _hex("green")
    [body] = [c for c in by_class(runs["a"], "final-pose")[0] if c.tag.endswith("circle")][:1]
    assert body.get("fill") == _hex("green")


def test_last_rules_fired_lists_each_rule_once_with_its_repeats(page, tmp_path):
    """At the end of the run (`#t=END`): `every 20 ms` is one line with
    how often it fired, not the whole list."""
    end = json.loads(re.search(r'<script id="run-data" type="application/json">(.*?)</script>',
                               (page / "r.html").read_text(), re.S).group(1))["end"]
    at_end = tmp_path / "end.html"          # (a page's address with #t=MS)
    at_end.write_text((page / "r.html").read_text().replace(
        "const at = /^#t=", f"location.hash = location.hash || '#t={end}';\n  const at = /^#t="))
    dom = _chromium(at_end, "--dump-dom")
    assert 'data-errors=""' in dom
    fired = [html.unescape(re.sub(r"<[^>]+>", "", i))
             for i in re.findall(r"<li>(.*?)</li>",
                                 re.search(r'<ul id="fired">(.*?)</ul>', dom).group(1))]
    assert 3 <= len(fired) <= 8, fired
    keys = [re.sub(r"^[0-9.]+ s |\s*\u00d7.*$", "", f) for f in fired]
    assert len(keys) == len(set(keys)), fired            # each rule once
    every20 = [f for f in fired if "every 20 ms" in f]
    assert every20 and all(re.search(r"\u00d7\d+\+? since [0-9.]+ s", f) for f in every20), fired
