"""`epuckc run ... --html replay.html` (epuckc/sim/replay.py): one page with
no network that replays the run, tested in headless Chromium: it loads
without errors, and the robots move, the cursor and the clock advance as
time runs; the rules fired and the variables at the cursor are listed."""
from __future__ import annotations

import html
import json
import re
import subprocess
import xml.etree.ElementTree as ET
from pathlib import Path

import pytest

from epuckc.sim.replay import replay_html
from tests.conftest import require_enki, require_tool
from tests.support.world import EXAMPLES, LED_PROGRAM, by_class, epuckc


def browse(page: Path, tmp_path: Path, play: bool, budget_ms: int = 0, at_ms=None) -> str:
    """The page's DOM after it loaded (and played `budget_ms` of virtual
    time; or opened at `at_ms`)."""
    chromium = require_tool("chromium")
    url = page.as_uri() + ("#play" if play else f"#t={at_ms}" if at_ms is not None else "")
    args = [chromium, "--headless", "--no-sandbox", "--disable-gpu", "--dump-dom", url]
    if budget_ms:
        args.insert(-2, f"--virtual-time-budget={budget_ms}")
    return subprocess.run(args, capture_output=True, text=True, timeout=120).stdout


def robot_transforms(dom: str) -> dict:
    return dict(re.findall(r'<g class="replay-robot" data-robot="([^"]*)" transform="([^"]*)"', dom))


@pytest.fixture(scope="module")
def page(tmp_path_factory):
    require_enki()
    tmp = tmp_path_factory.mktemp("replay")
    out = tmp / "replay.html"
    result = epuckc("run", EXAMPLES / "wander.epk", "--world", EXAMPLES / "arena.world",
                    "--time-limit", "20s", "--html", out, cwd=tmp)
    assert result.returncode == 3, result.stderr        # the time limit
    return out


def test_the_page_needs_no_network(page):
    text = page.read_text(encoding="utf-8")
    assert "<script src" not in text and "<link" not in text and "@import" not in text
    # the only addresses are XML namespaces
    assert set(re.findall(r"https?://[^\s\"')]+", text)) <= {
        "http://www.w3.org/2000/svg", "http://www.w3.org/1999/xlink", "http://www.w3.org/2001/xml-events",
        "http://www.w3.org/2000/svg\"", "http://www.w3.org/2000/svg;"}


def test_it_loads_without_errors_and_moves_the_robot_as_time_runs(page, tmp_path):
    still = browse(page, tmp_path, play=False)
    assert 'data-errors=""' in still, still[:300]
    start = robot_transforms(still)
    assert list(start) == ["r1"] and "0.000 s" in still
    played = browse(page, tmp_path, play=True, budget_ms=1500)
    assert 'data-errors=""' in played
    moved = robot_transforms(played)
    assert moved["r1"] != start["r1"]
    clock = float(re.search(r'<span id="clock">([0-9.]+) s</span>', played).group(1))
    assert clock > 5.0                      # 1.5 s of play at 10x: about 15 s of the run
    assert re.search(r'<line id="cursor"[^>]* x1="([0-9.]+)"', played).group(1) != \
        re.search(r'<line id="cursor"[^>]* x1="([0-9.]+)"', still).group(1)
    assert "<b>last rules fired</b><ul id=\"fired\"><li>" in played


def test_variables_and_firings_at_the_cursor(tmp_path):
    pose = {"x_mm": 0.0, "y_mm": 0.0, "heading_deg": 0.0}
    lines = [{"t_ms": 1, "kind": "event", "name": "p.epk:2 rule bump: on sensor(ir0 > 500)", **pose},
             {"t_ms": 1, "kind": "set", "var": "bumps", "value": 1},
             {"t_ms": 50, "kind": "pose", "name": "pose", **dict(pose, x_mm=30.0)},
             {"t_ms": 60, "kind": "set", "var": "bumps", "value": 2},
             {"t_ms": 60, "kind": "set", "var": "cruise", "value": 250},
             {"t_ms": 100, "kind": "exit", "name": "exit", **dict(pose, x_mm=60.0)}]
    page = tmp_path / "v.html"
    page.write_text(replay_html("\n".join(json.dumps(x) for x in lines) + "\n", title="p.epk"))
    played = browse(page, tmp_path, play=True, budget_ms=3000)
    assert 'data-errors=""' in played
    items = [html.unescape(i) for i in re.findall(r"<li>(.*?)</li>", played)]
    assert "bumps = 2" in items and "cruise = 250" in items
    assert any(i.endswith("bump") for i in items)
    still = browse(page, tmp_path, play=False)
    assert "bumps = 2" not in still and "<li>none</li>" in still


@pytest.fixture(scope="module")
def counting(tmp_path_factory):
    """A run that shows a count on the ring LEDs: its page and trace."""
    tmp = tmp_path_factory.mktemp("counting")
    prog = tmp / "count.epk"
    prog.write_text(LED_PROGRAM)
    result = epuckc("run", prog, "--html", tmp / "count.html", "--trace", tmp / "t.jsonl", cwd=tmp)
    assert result.returncode == 0, result.stderr
    return tmp / "count.html", [json.loads(x) for x in (tmp / "t.jsonl").read_text().splitlines()]


def replay_leds(dom: str) -> dict:
    """The moving robot's LEDs in the page: {"ring": "0110...", "body": "1", "front": "0"}."""
    group = re.search(r'<g class="replay-robot".*?</g>', dom, re.S).group(0)
    found = {}
    for tag in re.findall(r"<circle [^>]*>", group):
        kind = re.search(r'class="led (ring|body|front)-led"', tag)
        if kind:
            on = re.search(r'data-on="([01])"', tag).group(1)
            led = re.search(r'data-led="(\d)"', tag)
            found[kind.group(1) + (led.group(1) if led else "")] = on
    return {"ring": "".join(found[f"ring{i}"] for i in range(8)), "body": found["body"],
            "front": found["front"]}


def test_the_leds_are_lit_as_the_trace_says_at_the_cursor(counting, tmp_path):
    page, records = counting
    switched = [r for r in records if r["kind"] == "led"]
    times = sorted({0, records[-1]["t_ms"]} | {r["t_ms"] for r in switched}
                   | {r["t_ms"] - 1 for r in switched[1:]})
    for t in times:
        dom = browse(page, tmp_path, play=False, at_ms=t)
        assert 'data-errors=""' in dom
        before = [r for r in switched if r["t_ms"] <= t]
        state = before[-1] if before else {"ring": "00000000", "body": 0, "front": 0}
        assert replay_leds(dom) == {"ring": state["ring"], "body": str(state["body"]),
                                    "front": str(state["front"])}, t
        # the final pose's LEDs (the end's) give way to the moving robot's
        assert re.search(r'<g class="leds"[^>]*display="none"', dom)
    # the count was shown: three LEDs of the ring lit one after another
    assert len({r["ring"] for r in switched}) >= 3


def test_the_variables_panel_lists_every_declared_variable_from_0_s(counting, tmp_path):
    page, records = counting
    declared = re.findall(r"^var (\w+) = (-?\d+)", LED_PROGRAM, re.M)
    assert len(declared) == 3
    panel = lambda dom: [html.unescape(i) for i in re.findall(  # noqa: E731
        r"<li>(.*?)</li>", re.search(r'<ul id="vars">(.*?)</ul>', dom).group(1))]
    assert panel(browse(page, tmp_path, play=False, at_ms=0)) == [
        f"{name} = {value}" for name, value in declared]
    # later, the values the trace's set records gave them, in the same order
    t = records[-1]["t_ms"]
    values = dict(declared)
    values.update({r["var"]: str(r["value"]) for r in records if r["kind"] == "set"})
    assert panel(browse(page, tmp_path, play=False, at_ms=t)) == [
        f"{name} = {values[name]}" for name, _ in declared]
    assert values != dict(declared)


def test_a_robot_pushing_a_wall_is_still_and_each_robot_lists_its_own_variables(tmp_path):
    """A robot that drives into a wall and pushes it to the end of the run
    (its wheels turning) gets a still band from about its first contact to
    the end; in a world whose robots run different programs, the panel
    lists each robot's own variables from 0 s."""
    require_enki()
    (tmp_path / "push.epk").write_text("var pushes = 1\n"
                                       "on immediate do pushes += 1, start_straight(300 steps/s, 1 m)\n")
    (tmp_path / "idle.epk").write_text("var idle = 7\nvar spare = -1\n"
                                       "after 5 s do idle = 8, spare = 0\n")
    (tmp_path / "w.world").write_text("arena 40 cm x 40 cm\nrobot a at 20 cm, 20 cm\n"
                                      "robot b at 10 cm, 30 cm heading 90 deg program idle.epk\n")
    out, trace = tmp_path / "w.html", tmp_path / "t.jsonl"
    result = epuckc("run", tmp_path / "push.epk", "--world", tmp_path / "w.world",
                    "--time-limit", "8s", "--html", out, "--trace", trace, cwd=tmp_path)
    assert result.returncode == 3, result.stderr
    records = [json.loads(x) for x in trace.read_text().splitlines()]
    [contact] = [r for r in records if r["kind"] == "contacts" and r["robot"] == "a"]
    end = max(r["t_ms"] for r in records if "t_ms" in r)
    assert 0 < contact["first_ms"] < end - 3000
    text = out.read_text()
    picture = ET.fromstring(text[text.index("<svg"):text.index("</svg>") + 6])
    spans = {r.get("data-robot"): (int(r.get("data-from-ms")), int(r.get("data-to-ms")))
             for r in by_class(picture, "still")}
    assert len(spans) == len(by_class(picture, "still")) == 2       # one band each
    assert spans["b"] == (0, end)                   # b never moves
    first, last = spans["a"]
    # the last 5 mm before the wall take 130 ms at 38.6 mm/s
    assert contact["first_ms"] - 300 <= first <= contact["first_ms"] + 50 and last == end
    dom = browse(out, tmp_path, play=False, at_ms=0)
    items = [html.unescape(i) for i in re.findall(
        r"<li>(.*?)</li>", re.search(r'<ul id="vars">(.*?)</ul>', dom).group(1))]
    assert items == ["a: pushes = 1", "b: idle = 7", "b: spare = -1"]
