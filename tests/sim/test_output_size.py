"""A run's output in proportion (issue 41: ten robots with a counter set
every 20 ms gave 79 MB of trace, a 16.8 MB SVG and a 33 MB page, with no
word and no way to leave a variable out): `--trace-vars` selects the
variables traced, a `set` to the value a variable has is not written, the
pictures thin dense paths, and one warning says what fills an output past
10 MB and how to narrow it."""
from __future__ import annotations

import json
import math
import random
import re

import pytest

from conftest import require_enki

from epuckc.sim.outsize import LARGE_BYTES, large_outputs_warning
from epuckc.sim.plot import plot_trace
from epuckc.sim.replay import replay_html
from epuckc.sim.thin import PATH_TOLERANCE_PX, REPLAY_POSE_MS, thin_points, thin_poses
from epuckc.sim.tracevars import traced
from tests.support.world import epuckc

COUNTER = """var count = 0
var laps = 0
var cells = [0, 0]
var fixed = 0
every 20 ms do count = (count + 1) % 1000, cells[0] = count % 7, fixed = 5
every 500 ms do laps = (laps + 1) % 100
after 2 s do exit_main
"""


def _records(path) -> list:
    return [json.loads(line) for line in path.read_text().splitlines()]


def _sets(records) -> dict:
    out: dict = {}
    for r in records:
        if r["kind"] == "set":
            out[r["var"]] = out.get(r["var"], 0) + 1
    return out


def test_trace_vars_selects_the_variables_traced(tmp_path):
    (tmp_path / "c.epk").write_text(COUNTER)
    result = epuckc("run", "c.epk", "--trace", "all.jsonl", cwd=tmp_path)
    assert result.returncode == 0, result.stderr
    every = _sets(_records(tmp_path / "all.jsonl"))
    # a set to the value the variable holds writes nothing: `fixed` once
    assert every["fixed"] == 1 and every["count"] == 100 and every["laps"] == 4
    result = epuckc("run", "c.epk", "--trace", "some.jsonl", "--trace-vars", "laps,cells",
                    cwd=tmp_path)
    assert result.returncode == 0, result.stderr
    assert _sets(_records(tmp_path / "some.jsonl")) == {"laps": 4, "cells[0]": every["cells[0]"]}
    readable = [line for line in result.stdout.splitlines() if "] set " in line]
    assert readable and all(re.search(r"set +(laps|cells\[0\]) = ", line) for line in readable)
    # none of them; a name no program declares, with the one meant
    epuckc("run", "c.epk", "--trace", "none.jsonl", "--trace-vars", "none", cwd=tmp_path)
    assert _sets(_records(tmp_path / "none.jsonl")) == {}
    result = epuckc("run", "c.epk", "--trace-vars", "cuont", cwd=tmp_path)
    assert result.returncode == 2
    assert "no program of the run declares a variable `cuont`: did you mean `count`?" \
        in result.stderr
    assert epuckc("run", "c.epk", "--trace-vars", "a b", cwd=tmp_path).returncode == 2


def test_the_replay_lists_only_the_variables_traced(tmp_path):
    (tmp_path / "c.epk").write_text(COUNTER)
    result = epuckc("run", "c.epk", "--html", "r.html", "--trace-vars", "laps", cwd=tmp_path)
    assert result.returncode == 0, result.stderr
    text = (tmp_path / "r.html").read_text()
    data = json.loads(re.search(r'<script id="run-data" type="application/json">(.*?)</script>',
                                text, re.S).group(1))
    assert {s[2] for s in data["sets"]} == {"laps"}


def test_trace_vars_reaches_every_robot_of_a_world(tmp_path):
    require_enki()
    (tmp_path / "c.epk").write_text(COUNTER)
    (tmp_path / "w.world").write_text("arena none\nrobot a at 0 cm, 0 cm\nrobot b at 50 cm, 0 cm\n")
    result = epuckc("run", "c.epk", "--world", "w.world", "--trace", "t.jsonl",
                    "--trace-vars", "laps", cwd=tmp_path)
    assert result.returncode == 0, result.stderr
    records = _records(tmp_path / "t.jsonl")
    assert {(r["robot"], r["var"]) for r in records if r["kind"] == "set"} == \
        {("a", "laps"), ("b", "laps")}


def test_the_selection_rule():
    assert traced("count", None) and traced("cells[1]", ("cells",))
    assert not traced("cells2", ("cells",)) and not traced("count", ())


def _walk(seed: int, n: int) -> list:
    rng = random.Random(seed)
    x = y = 0.0
    h = 0.0
    points = []
    for _ in range(n):
        h += rng.choice([0.0, 0.0, 0.0, rng.uniform(-0.3, 0.3)])
        x, y = x + math.cos(h), y + math.sin(h)
        points.append((round(x, 1), round(y, 1)))
    return points


@pytest.mark.parametrize("seed", range(6))
def test_a_thinned_path_stays_within_half_a_pixel_of_every_point(seed):
    from epuckc.sim.thin import _distance
    points = _walk(seed, 3000)
    kept = thin_points(points)
    assert kept[0] == points[0] and kept[-1] == points[-1] and len(kept) < len(points) / 3
    for p in points:
        assert min(_distance(p, a, b) for a, b in zip(kept, kept[1:])) <= PATH_TOLERANCE_PX + 1e-9


def _dense_trace(seconds: int) -> str:
    """A robot driving a slow circle with a record every 10 ms."""
    lines = []
    for t in range(0, seconds * 1000, 10):
        a = t / 20000 * 2 * math.pi
        lines.append(json.dumps({"t_ms": t, "kind": "set", "var": "count", "value": t % 1000,
                                 "x_mm": round(300 * math.cos(a), 1),
                                 "y_mm": round(300 * math.sin(a), 1),
                                 "heading_deg": round(math.degrees(a) + 90, 1) % 360}))
    return "\n".join(lines) + "\n"


def test_the_pictures_thin_a_dense_path():
    text = _dense_trace(120)            # 12,000 poses
    svg = plot_trace(text)
    [path] = re.findall(r'<polyline class="path"[^>]* points="([^"]*)"', svg)
    assert len(path.split()) < 600
    page = replay_html(text)
    data = json.loads(re.search(r'<script id="run-data" type="application/json">(.*?)</script>',
                                page, re.S).group(1))
    [robot] = data["robots"]
    assert len(robot["poses"]) <= 120000 // REPLAY_POSE_MS + 2
    gaps = [b[0] - a[0] for a, b in zip(robot["poses"], robot["poses"][1:])]
    assert max(gaps) <= REPLAY_POSE_MS + 10
    assert thin_poses([(0, 0, 0, 0), (1, 0, 0, 0)]) == [(0, 0, 0, 0), (1, 0, 0, 0)]


def test_one_warning_says_what_fills_a_large_output_and_how_to_narrow_it(tmp_path):
    """A real run past 10 MB: its firings fill it."""
    (tmp_path / "big.epk").write_text("var count = 0\nevery 5 ms do count = (count + 1) % 1000\n")
    result = epuckc("run", "big.epk", "--trace", "t.jsonl", "--time-limit", "140s",
                    cwd=tmp_path, env={"EPUCK_QUIET": "1"})
    assert result.returncode == 3, result.stderr
    assert (tmp_path / "t.jsonl").stat().st_size > LARGE_BYTES
    warnings = [line for line in result.stderr.splitlines() if "warning: the run wrote" in line]
    assert len(warnings) == 1, result.stderr
    assert "t.jsonl 1" in warnings[0] and "more than 10 MB" in warnings[0]
    assert "of `big.epk:2 every 5 ms`" in warnings[0] and "--time-limit" in warnings[0]
    # a short run: no word
    result = epuckc("run", "big.epk", "--trace", "t.jsonl", "--time-limit", "1s", cwd=tmp_path)
    assert "warning: the run wrote" not in result.stderr


def test_set_records_that_fill_a_trace_name_the_option(tmp_path):
    trace = tmp_path / "t.jsonl"
    pad = '"x_mm": 0.0, "y_mm": 0.0, "heading_deg": 0.0'
    with open(trace, "w") as f:
        for t in range(LARGE_BYTES // 60):
            f.write(f'{{"t_ms": {t}, "kind": "set", "var": "count", "value": {t % 999}, {pad}}}\n')
            if t % 100 == 0:
                f.write(f'{{"t_ms": {t}, "kind": "set", "var": "laps", "value": {t}, {pad}}}\n')
    svg = tmp_path / "p.svg"
    svg.write_bytes(b" " * (LARGE_BYTES + 1))
    text = large_outputs_warning([trace, svg], trace)
    # one warning for both outputs
    assert text.count("MB") == 3 and "t.jsonl" in text and "p.svg" in text
    assert re.search(r"the changes of `count` are (99|100) % of the trace", text), text
    assert "--trace-vars laps (the variables kept)" in text
    assert large_outputs_warning([tmp_path / "t.jsonl"], None) is not None
    small = tmp_path / "s.jsonl"
    small.write_text("{}\n")
    assert large_outputs_warning([small], small) is None
