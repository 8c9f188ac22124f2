"""The SVG pictures measured in a real browser (Debian's headless Chromium):
no text outside the picture and no two texts overlapping, the robots'
names included; rule names in the map's labels; a scale bar; modes, LEDs
and contacts on the paths and the timeline; per-robot programs in the
title of a world whose robots run different programs."""
from __future__ import annotations

import html
import json
import re
import subprocess
import xml.etree.ElementTree as ET
from pathlib import Path

import pytest

from epuckc.cli.world import picture_title
from epuckc.sim.plot import plot_trace, shown_label
from epuckc.sim.world import parse_world
from tests.conftest import require_enki, require_tool
from tests.support.world import EXAMPLES, epuckc

SVG = "{http://www.w3.org/2000/svg}"
MEASURE = """
<pre id="out"></pre><script>
const svg = document.querySelector('svg');
const vb = svg.viewBox.baseVal;
const boxes = [...svg.querySelectorAll('text')].map(t => { const b = t.getBBox();
  return {text: t.textContent, x: b.x, y: b.y, w: b.width, h: b.height}; });
document.getElementById('out').textContent =
  JSON.stringify({vb: [vb.x, vb.y, vb.width, vb.height], boxes});
</script>"""


def measured(svg_text: str, tmp_path: Path) -> dict:
    """Every text's box as the browser lays it out, and the viewBox."""
    chromium = require_tool("chromium")
    page = tmp_path / "page.html"
    page.write_text("<!doctype html><html><body style='margin:0'>" + svg_text + MEASURE
                    + "</body></html>", encoding="utf-8")
    out = subprocess.run([chromium, "--headless", "--no-sandbox", "--disable-gpu",
                          "--dump-dom", page.as_uri()], capture_output=True, text=True,
                         timeout=120).stdout
    start = out.index('<pre id="out">') + len('<pre id="out">')
    return json.loads(html.unescape(out[start:out.index("</pre>", start)]))


def overlaps(boxes: list) -> list:
    found = []
    for i, a in enumerate(boxes):
        for b in boxes[i + 1:]:
            if (a["x"] < b["x"] + b["w"] - 0.5 and b["x"] < a["x"] + a["w"] - 0.5
                    and a["y"] < b["y"] + b["h"] - 0.5 and b["y"] < a["y"] + a["h"] - 0.5):
                found.append((a["text"], b["text"]))
    return found


def outside(data: dict) -> list:
    x0, y0, w, h = data["vb"]
    return [b["text"] for b in data["boxes"]
            if b["x"] < x0 or b["y"] < y0 or b["x"] + b["w"] > x0 + w or b["y"] + b["h"] > y0 + h]


@pytest.fixture(scope="module")
def crowd(tmp_path_factory):
    """Ten robots of examples/dispersion in their arena, 4 s: a crowded map."""
    require_enki()
    tmp = tmp_path_factory.mktemp("crowd")
    trace = tmp / "t.jsonl"
    epuckc("run", EXAMPLES / "dispersion.epk", "--world", EXAMPLES / "dispersion.world",
           "--time-limit", "4s", "--trace", trace, "--svg", tmp / "p.svg", cwd=tmp)
    return trace.read_text(), (tmp / "p.svg").read_text()


def test_no_text_outside_the_picture_and_none_over_another(crowd, tmp_path):
    _, svg = crowd
    data = measured(svg, tmp_path)
    assert len(data["boxes"]) > 30
    assert outside(data) == []
    assert overlaps(data["boxes"]) == []


def test_labels_name_the_rules_and_keep_their_place_as_data(crowd):
    trace, svg = crowd
    root = ET.fromstring(svg)
    labels = [t for t in root.iter(f"{SVG}text") if t.get("class") == "firing-label"]
    assert labels
    names = {"front_right", "front_left", "right", "left", "behind", "on immediate"}
    assert {t.text for t in labels} <= names
    assert all(re.fullmatch(r"dispersion\.epk:\d+", t.get("data-label")) for t in labels)


def test_a_scale_bar_with_or_without_walls(tmp_path):
    for world in ('{"kind": "world", "arena": {"width_mm": 1000.0, "height_mm": 600.0}, '
                  '"boxes": [], "cylinders": [], "robot_radius_mm": 37.0}\n', ""):
        trace = world + ('{"t_ms": 0, "kind": "pose", "name": "pose", "x_mm": 100.0, "y_mm": 100.0, '
                         '"heading_deg": 0.0}\n{"t_ms": 900, "kind": "pose", "name": "pose", '
                         '"x_mm": 400.0, "y_mm": 100.0, "heading_deg": 0.0}\n')
        root = ET.fromstring(plot_trace(trace, title="t"))
        [bar] = [g for g in root.iter(f"{SVG}g") if g.get("class") == "scale-bar"]
        length_mm = float(bar.get("data-mm"))
        x1, x2 = (float(bar.find(f"{SVG}line").get(k)) for k in ("x1", "x2"))
        [label] = [t.text for t in bar.iter(f"{SVG}text")]
        assert label == (f"{length_mm / 10:g} cm" if length_mm < 1000 else f"{length_mm / 1000:g} m")
        assert 40 <= x2 - x1 <= 200


def test_modes_leds_and_contacts_are_drawn(tmp_path):
    lines = [
        {"t_ms": 0, "kind": "mode", "name": "explore", "x_mm": 0.0, "y_mm": 0.0, "heading_deg": 0.0},
        {"t_ms": 5, "kind": "event", "name": "p.epk:3 rule go: on immediate", "x_mm": 0.0,
         "y_mm": 0.0, "heading_deg": 0.0},
        {"t_ms": 200, "kind": "led", "name": "body", "state": 1, "x_mm": 50.0, "y_mm": 0.0,
         "heading_deg": 0.0},
        {"t_ms": 400, "kind": "pose", "name": "pose", "x_mm": 100.0, "y_mm": 0.0,
         "heading_deg": 0.0},
        {"t_ms": 500, "kind": "mode", "name": "home", "x_mm": 120.0, "y_mm": 0.0,
         "heading_deg": 0.0},
        {"t_ms": 900, "kind": "contacts", "walls": 1, "objects": 0, "robots": 0, "first_ms": 450},
    ]
    svg = plot_trace("\n".join(json.dumps(x) for x in lines) + "\n", title="p.epk")
    root = ET.fromstring(svg)
    by_class = {}
    for e in root.iter():
        by_class.setdefault(e.get("class"), []).append(e)
    assert [e.get("data-t-ms") for e in by_class["mode-change"]] == ["0", "500"]
    assert [t.text for t in by_class["mode-label"]] == ["mode explore", "mode home"]
    assert [e.get("data-t-ms") for e in by_class["led-change"]] == ["200"]
    assert [e.get("data-t-ms") for e in by_class["contact"]] == ["450"]
    rows = {g.get("data-label"): [t.get("data-t-ms") for t in g.iter() if t.get("class") == "tick"]
            for g in by_class["timeline-row"]}
    assert rows == {"p.epk:3": ["5"], "mode": ["0", "500"], "led": ["200"], "contact": ["450"]}
    assert [t.text for t in by_class["firing-label"]] == ["go"]
    data = measured(svg, tmp_path)
    assert outside(data) == [] and overlaps(data["boxes"]) == []


def test_shown_labels():
    assert shown_label("a.epk:3 rule avoid: on sensor(ir0 > 300) repeat") == "avoid"
    assert shown_label("a.epk:9 on timer(2 s)") == "on timer(2 s)"
    assert shown_label("a.epk:9 on sensor(ir0 > 300, ir1 > 300, ir2 > 300)").endswith("\u2026")
    assert shown_label("event_timer") == "event_timer"          # hand-written C


def test_the_title_names_each_robot_s_program(tmp_path):
    (tmp_path / "fast.epk").write_text("on immediate do exit_main\n")
    (tmp_path / "slow.epk").write_text("on immediate do exit_main\n")
    (tmp_path / "w.world").write_text("arena 100 cm x 100 cm\nrobot a at 20 cm, 20 cm\n"
                                      "robot b at 50 cm, 50 cm program slow.epk\n"
                                      "robot c at 80 cm, 80 cm\n")
    world = parse_world(tmp_path / "w.world")
    assert picture_title(str(tmp_path / "fast.epk"), world) == "fast.epk: a, c; slow.epk: b"
    (tmp_path / "same.world").write_text("arena 100 cm x 100 cm\nrobot a at 20 cm, 20 cm\n")
    assert picture_title("x/fast.epk", parse_world(tmp_path / "same.world")) == "fast.epk"
    assert picture_title("x/fast.epk", None) == "fast.epk"
