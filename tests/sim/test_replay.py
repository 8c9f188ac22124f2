"""`epuckc run ... --html replay.html` (epuckc/sim/replay.py): one page with
no network that replays the run, tested in headless Chromium: it loads
without errors, and the robots move, the cursor and the clock advance as
time runs; the rules fired and the variables at the cursor are listed."""
from __future__ import annotations

import html
import json
import re
import subprocess
from pathlib import Path

import pytest

from epuckc.sim.replay import replay_html
from tests.conftest import require_enki, require_tool
from tests.support.world import EXAMPLES, epuckc


def browse(page: Path, tmp_path: Path, play: bool, budget_ms: int = 0) -> str:
    """The page's DOM after it loaded (and played `budget_ms` of virtual time)."""
    chromium = require_tool("chromium")
    url = page.as_uri() + ("#play" if play else "")
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
