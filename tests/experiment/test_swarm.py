"""Experiments as SIERRA's users run them: the robot count and the world
as grid axes, the copies placed without overlap, series over time with
their bands, and --report-only from the saved runs."""
from __future__ import annotations

import math
import statistics

import pytest

from epuckc.experiment.spec import read_experiment
from epuckc.experiment.swarm import Placement, PlacementError, check_fit, place
from epuckc.sim.world import ROBOT_RADIUS_MM, box_distance, parse_world
from tests.experiment.helpers import make, needs_enki, rows
from tests.experiment.test_spec import GOOD, _errors
from tests.support.cli import run_cli

WORLD = """arena 100 cm x 70 cm
box at 30 cm, 45 cm size 20 cm x 6 cm angle 30 deg
cylinder at 70 cm, 48 cm radius 7 cm
robot at 15 cm, 12 cm heading 20 deg colour red
"""


@pytest.mark.parametrize("text, where, words", [
    (GOOD + "[params]\nrobots = [10, 0]\n", "exp.toml:6:15:", "0 is not a robot count"),
    (GOOD + "[params]\nrobots = [0, 10]\n", "exp.toml:6:11:", "0 is not a robot count"),
    (GOOD + '[params]\nrobots = ["10 cm"]\n', "exp.toml:6:11:", "is not a robot count"),
    (GOOD + 'series = ["contacts"]\n', "exp.toml:5:11:", "`contacts` is not a metric over time"),
    (GOOD + 'series = ["speed"]\n', "exp.toml:5:11:", "unknown series `speed`"),
    (GOOD + 'series = ["coverage"]\nperiod = "10 ms"\n', "exp.toml:6:10:", "at least 100 ms"),
    (GOOD + 'period = "1 s"\n', "exp.toml:5:10:", "a period without series"),
    (GOOD + "[placement]\ndensty = 20\n", "exp.toml:6:10:", "unknown key `densty`"),
    (GOOD + "[placement]\ndensity = -2\n", "exp.toml:6:11:", "robots per square metre"),
    (GOOD + '[placement]\nmargin = "2 inch"\n', "exp.toml:6:10:", "the margin is a length"),
    (GOOD.replace('world = "arena.world"', 'world = ["arena.world", "no.world"]'),
     "exp.toml:2:25:", "no.world does not exist"),
    (GOOD + "[params]\nworld = [1, 2]\n", "exp.toml:6:9:", "`world` cannot name a constant"),
])
def test_bad_axes(tmp_path, text, where, words):
    message = _errors(tmp_path, text)
    assert message.startswith(where), message
    assert words in message
    line, col = int(where.split(":")[1]), int(where.split(":")[2])
    assert f" {line} | {text.splitlines()[line - 1]}\n" in message
    caret_line = message.split("\n")[2]
    assert caret_line.index("^") - caret_line.index("|") - 2 == col - 1


def test_the_axes_read(tmp_path):
    exp = make(tmp_path, GOOD.replace('world = "arena.world"', 'world = ["arena.world", '
                                      '"arena.world"]'))
    assert "arena.world is named twice" in _errors(tmp_path, exp.read_text())
    (tmp_path / "b.world").write_text(WORLD)
    exp = make(tmp_path, GOOD.replace('world = "arena.world"', 'world = ["arena.world", '
                                      '"b.world"]') + 'series = ["coverage", "var:left_near"]\n'
               'period = "500 ms"\n[params]\nrobots = [3, 9]\n[placement]\ndensity = 12.5\n')
    e = read_experiment(exp)
    assert [w.name for w in e.worlds] == ["arena.world", "b.world"]
    assert e.params["robots"] == ["3", "9"] and e.series == ["coverage", "var:left_near"]
    assert e.period_ms == 500 and e.placement == Placement(12.5, 5.0)
    from epuckc.experiment.plan import grid
    assert [p.values for p in grid(e)] == [{"world": w, "robots": n} for w in
                                           ("arena.world", "b.world") for n in ("3", "9")]


def _free(world, robots, margin):
    for i, a in enumerate(robots):
        assert ROBOT_RADIUS_MM + margin <= a.x_mm <= world.width_mm - ROBOT_RADIUS_MM - margin
        assert ROBOT_RADIUS_MM + margin <= a.y_mm <= world.height_mm - ROBOT_RADIUS_MM - margin
        for c in world.cylinders:
            assert math.hypot(a.x_mm - c.x_mm, a.y_mm - c.y_mm) >= c.radius_mm + ROBOT_RADIUS_MM
        for b in world.boxes:
            assert box_distance(b, a.x_mm, a.y_mm) >= ROBOT_RADIUS_MM
        for b in robots[i + 1:]:
            assert math.hypot(a.x_mm - b.x_mm, a.y_mm - b.y_mm) >= 2 * ROBOT_RADIUS_MM


def test_copies_are_placed_without_overlap_by_the_seed(tmp_path):
    (tmp_path / "w.world").write_text(WORLD)
    world = parse_world(tmp_path / "w.world")
    crowd = place(world, world.robots, 60, Placement(), seed=3)
    assert [r.name for r in crowd.robots] == [f"r{k}" for k in range(1, 61)]
    assert {r.colour for r in crowd.robots} == {"red"}      # copies of the template
    _free(crowd, crowd.robots, 5.0)
    again = place(world, world.robots, 60, Placement(), seed=3)
    assert [(r.x_mm, r.y_mm, r.heading_deg) for r in again.robots] == \
        [(r.x_mm, r.y_mm, r.heading_deg) for r in crowd.robots]
    other = place(world, world.robots, 60, Placement(), seed=4)
    assert other.robots[0].x_mm != crowd.robots[0].x_mm
    # at a density the arena grows with the count, its shape and its
    # obstacles' places (relative to the walls) kept
    for n in (10, 200):
        dense = place(world, world.robots, n, Placement(density=20.0), seed=1)
        assert math.isclose(n / (dense.width_mm * dense.height_mm / 1e6), 20.0)
        assert math.isclose(dense.width_mm / dense.height_mm, 100 / 70)
        assert math.isclose(dense.cylinders[0].x_mm / dense.width_mm, 0.7)
        assert dense.cylinders[0].radius_mm == 70.0
        _free(dense, dense.robots, 5.0)
    assert "about" in check_fit(world, 120, Placement())
    with pytest.raises(PlacementError):
        place(world, world.robots, 120, Placement(margin_mm=0.0), seed=1)
    # open ground: a square at the density around the origin
    (tmp_path / "open.world").write_text("robot at 0 cm, 0 cm\n")
    open_world = parse_world(tmp_path / "open.world")
    assert "open ground" in check_fit(open_world, 10, Placement())
    spread = place(open_world, open_world.robots, 10, Placement(density=10.0), seed=1)
    assert all(abs(r.x_mm) <= 500 and abs(r.y_mm) <= 500 for r in spread.robots)


def test_too_many_robots_is_an_error_at_the_robots_line(tmp_path, capsys):
    exp = make(tmp_path, GOOD + "[params]\nrobots = [2, 40]\n")
    status, _, err = run_cli(["experiment", str(exp)], capsys)
    assert status == 2 and "exp.toml:6:10: error: 40 robots in arena.world:" in err
    assert "fewer robots, a lower density" in err


SWARM = """program = "brait.epk"
world = ["arena.world", "wide.world"]
duration = "2 s"
seeds = 3
metrics = ["distance", "coverage", "contacts"]
series = ["distance", "coverage", "var:left_near"]
period = "500 ms"

[params]
robots = [2, 6]

[placement]
density = 15
"""


@needs_enki
def test_robot_counts_and_worlds_give_series_bands_and_a_report_only_redraw(
        tmp_path, capsys, monkeypatch):
    exp = make(tmp_path, SWARM)
    (tmp_path / "wide.world").write_text(WORLD)
    out = tmp_path / "o"
    status, _, err = run_cli(["experiment", str(exp), "-o", str(out), "--workers", "2"], capsys)
    assert status == 0, err
    runs = rows(out / "runs.csv")
    # a row per robot and one for the swarm; robots r1..rN, the count as a column
    for n in ("2", "6"):
        for world in ("arena.world", "wide.world"):
            mine = [r for r in runs if r["robots"] == n and r["world"] == world]
            assert len(mine) == 3 * (int(n) + 1)
            assert [r["robot"] for r in mine[:int(n) + 1]] == \
                [f"r{k}" for k in range(1, int(n) + 1)] + ["swarm"]
            assert all(r["error"] == "" for r in mine)
    series = rows(out / "series.csv")
    summary = {(s["world"], s["robots"]): s for s in rows(out / "summary.csv")}
    assert len(series) == 4 * 3 * 5        # points x columns x samples (0, 0.5 .. 2 s)
    for (world, n), s in summary.items():
        mine = [r for r in series if r["world"] == world and r["robots"] == n]
        for col, end in (("distance_mm", "distance_mm:mean"),
                         ("coverage_cells", "coverage_cells:mean")):
            line = [r for r in mine if r["series"] == col]
            assert [r["t_s"] for r in line] == ["0.000", "0.500", "1.000", "1.500", "2.000"]
            means = [float(r["mean"]) for r in line]
            assert means == sorted(means)            # so far: never less
            # the last sample is the end-of-run metric, measured apart
            assert math.isclose(means[-1], float(s[end]), abs_tol=0.002)
            for r in line[1:]:
                assert float(r["ci95_low"]) <= float(r["mean"]) <= float(r["ci95_high"])
        # the swarm's distance at the end: its robots' sum, averaged over the seeds
        swarm = [float(r["distance_mm"]) for r in runs if r["world"] == world
                 and r["robots"] == n and r["robot"] == "swarm"]
        assert math.isclose(statistics.mean(swarm), float(s["distance_mm:mean"]), abs_tol=0.002)
    # more robots at the same density: more of the floor covered
    assert float(summary[("arena.world", "6")]["coverage_cells:mean"]) > \
        float(summary[("arena.world", "2")]["coverage_cells:mean"])
    svg = (out / "series.svg").read_text()
    assert svg.count("<polygon") == 4 * 3 and "robots=6" in svg
    times = rows(out / "times.csv")
    assert len(times) == 12 and all(float(t["wall_s"]) > 0 for t in times)

    before = {name: (out / name).read_bytes() for name in
              ("runs.csv", "summary.csv", "summary.svg", "series.csv", "series.svg")}
    for name in before:
        (out / name).unlink()
    import epuckc.sim.enki as enki

    def no_simulation(*args, **kwargs):
        raise AssertionError("--report-only simulated")
    monkeypatch.setattr(enki, "simulate", no_simulation)
    status, _, err = run_cli(["experiment", str(exp), "-o", str(out), "--report-only"], capsys)
    assert status == 0 and "report of 12 of 12 runs" in err
    assert {name: (out / name).read_bytes() for name in before} == before
    # fewer metrics and series than were measured: the saved runs serve
    exp.write_text(SWARM.replace('"distance", "coverage", "contacts"', '"coverage"')
                   .replace(', "var:left_near"', ""))
    status, _, err = run_cli(["experiment", str(exp), "-o", str(out), "--report-only"], capsys)
    assert status == 0 and "report of 12 of 12 runs" in err
    assert rows(out / "runs.csv")[0].keys() >= {"coverage_cells"}
    assert "distance_mm" not in rows(out / "runs.csv")[0]
    status, _, err = run_cli(["experiment", str(exp), "-o", str(tmp_path / "none"),
                              "--report-only"], capsys)
    assert status == 1 and "no run of this experiment is saved" in err
