"""Runs in Enki worlds: the second provider of the e-puck library on the
host. Skipped without Enki, except in CI (require_enki)."""
import itertools
import math
import re

import pytest

from epuckc.base.source import SourceFile
from epuckc.diagnostics import Collector
from epuckc.syntax import ast
from epuckc.syntax.parser import parse

from tests.support.world import EXAMPLES, by_class, epuckc, final_pose, run, svg


pytestmark = pytest.mark.usefixtures("enki")


def world(tmp_path, text, name="w.world"):
    path = tmp_path / name
    path.write_text(text)
    return path


def contacts(records):
    return {r["robot"]: r for r in records if r["kind"] == "contacts"}


# ---- the same program on the stub and in Enki ----------------------------------

NOISY_MM, NOISY_DEG = 5.0, 2.0         # Enki's default 5 % wheel noise, runs up to 25 s
EXACT_MM, EXACT_DEG = 0.5, 0.2          # noise 0 %
ALL_EXAMPLES = sorted(p.stem for p in EXAMPLES.glob("*.epk"))


def compare_with_stub(tmp_path, example, world_text, mm, deg):
    open_ground = world(tmp_path, world_text)
    stub, _, _ = run(EXAMPLES / f"{example}.epk", tmp_path, name="stub", expect=None)
    enki, _, _ = run(EXAMPLES / f"{example}.epk", tmp_path, "--world", open_ground, name="enki",
                     expect=None)
    s, e = final_pose(stub), final_pose(enki)
    assert (e["kind"], e["t_ms"]) == (s["kind"], s["t_ms"])
    assert (e["left_steps"], e["right_steps"]) == (s["left_steps"], s["right_steps"])
    assert math.hypot(e["x_mm"] - s["x_mm"], e["y_mm"] - s["y_mm"]) <= mm
    dh = (e["heading_deg"] - s["heading_deg"] + 180) % 360 - 180
    assert abs(dh) <= deg

    # the same rules fired at the same times (nothing near: no sensor event)
    def fired(records):
        return [(r["t_ms"], r["name"]) for r in records if r["kind"] in ("event", "action")]
    assert fired(enki) == fired(stub)


@pytest.mark.parametrize("example", ["paper_fig2", "square", "obstacle_avoidance",
                                     "timed_patrol", "extern_spin"])
def test_on_open_ground_enki_ends_where_the_stub_does(tmp_path, example):
    """Same program, same steps: on open ground (no walls, nothing to see)
    Enki's body ends within NOISY_MM and NOISY_DEG of the stub's odometry,
    with Enki's 5 % wheel noise on (seed 1)."""
    compare_with_stub(tmp_path, example, "arena none\n", NOISY_MM, NOISY_DEG)


# A program whose actions read the proximity sensors (its wheel speeds follow
# every reading) differs by design: Enki's IR sensors read a little noise on
# open ground where the stub reads 0. Programs that only read them in an
# event's threshold (above that noise) must end where the stub does. Which
# is which comes from the parsed program, so that a new example is sorted
# without a list to keep.
PROXIMITY = re.compile(r"ir[0-7]?")


def reads_proximity_in_actions(example):
    source = SourceFile(f"{example}.epk", (EXAMPLES / f"{example}.epk").read_text())
    program = parse(source, Collector(source))
    todo = [rule.body for rule in program.of_type(ast.Rule)]
    todo += [d for d in program.statements if isinstance(d, ast.ActionDef)]
    while todo:
        x = todo.pop()
        if isinstance(x, ast.Ident) and PROXIMITY.fullmatch(x.name):
            return True
        if isinstance(x, ast.Node):
            todo.extend(getattr(x, f) for f in x._fields)
        elif isinstance(x, (tuple, list)):
            todo.extend(x)
    return False


CONTINUOUS = {e for e in ALL_EXAMPLES if reads_proximity_in_actions(e)}


def test_the_continuous_examples_are_found_from_their_rules():
    assert {"braitenberg", "weights", "avoider"} <= CONTINUOUS
    assert not {"obstacle_avoidance", "wall_follow", "paper_fig2"} & CONTINUOUS


@pytest.mark.parametrize("example", [e for e in ALL_EXAMPLES if e not in CONTINUOUS])
def test_without_noise_every_example_ends_where_the_stub_does(tmp_path, example):
    compare_with_stub(tmp_path, example, "arena none\nnoise 0 %\n", EXACT_MM, EXACT_DEG)


# ---- determinism -----------------------------------------------------------------

def test_same_world_same_trace_byte_for_byte(tmp_path):
    outs = []
    for i in range(2):
        records, out, text = run(EXAMPLES / "dispersion.epk", tmp_path, "--world",
                                 EXAMPLES / "dispersion.world", "--time-limit", "5s",
                                 "--pose-interval", "50ms", name=f"run{i}", expect=3)
        outs.append((out, text))
    assert outs[0] == outs[1]
    # another seed is another run
    seeded = world(tmp_path, EXAMPLES.joinpath("dispersion.world").read_text() + "seed 2\n")
    _, _, other = run(EXAMPLES / "dispersion.epk", tmp_path, "--world", seeded, "--time-limit",
                      "5s", "--pose-interval", "50ms", name="seed2", expect=3)
    assert other != outs[0][1]


# ---- sensing and collisions ------------------------------------------------------

def test_a_wall_ahead_is_seen_and_a_blind_robot_hits_it(tmp_path):
    """Enki's IR readings reach the program through e_get_prox: a robot
    driving at a wall sees it (sensor event) and stops before it; a robot
    that never starts its sensors drives into it, and Enki's collision
    state says so."""
    prog = tmp_path / "stop.epk"
    prog.write_text("on immediate do start_sensor, start_straight(400 steps/s, 1 m)\n"
                    "on sensor(ir0 > 1000, ir7 > 1000) do stop_motor, exit_main\n")
    blind = tmp_path / "blind.epk"
    blind.write_text("on immediate do start_straight(400 steps/s, 1 m)\n"
                     "on stop_motor do exit_main\n")
    arena = world(tmp_path, "arena 40 cm x 20 cm\nrobot at 10 cm, 10 cm heading 0 deg\n")
    records, out, _ = run(prog, tmp_path, "--world", arena)
    [seen] = [r for r in records if r["kind"] == "event" and "sensor" in r["name"]]
    # IR0/IR7 read 1000 about 1.5 cm in front of the body (37 mm radius)
    assert 400 - 37 - 25 < seen["x_mm"] < 400 - 37 - 5
    assert contacts(records)["r1"]["walls"] == 0 and "r1: no collision" in out
    records, out, _ = run(blind, tmp_path, "--world", arena, "--time-limit", "8s", expect=3)
    c = contacts(records)["r1"]
    assert c["walls"] > 0 and c["first_ms"] > 0 and "with walls" in out
    assert final_pose(records)["x_mm"] < 400 - 37 + 2     # the wall held it


def test_wander_touches_nothing_for_60_seconds(tmp_path):
    records, out, _ = run(EXAMPLES / "wander.epk", tmp_path, "--world", EXAMPLES / "arena.world",
                          expect=3)
    assert final_pose(records)["t_ms"] == 60000
    c = contacts(records)["r1"]
    assert (c["walls"], c["objects"], c["robots"]) == (0, 0, 0)
    # and it did wander: it turned away from things many times and crossed the arena
    turns = [r for r in records if r["kind"] == "event" and "_side" in r["name"]]
    assert len(turns) >= 10
    xs = [r["x_mm"] for r in records if "x_mm" in r]
    assert max(xs) - min(xs) > 500


def test_wall_following_goes_round_the_arena_near_the_walls(tmp_path):
    records, _, _ = run(EXAMPLES / "wall_follow.epk", tmp_path, "--world",
                        EXAMPLES / "wall_follow.world", "--pose-interval", "100ms", expect=3)
    poses = [r for r in records if r["kind"] == "pose"]
    w, h = 800, 600

    def wall_distance(r):
        return min(r["x_mm"], w - r["x_mm"], r["y_mm"], h - r["y_mm"])
    near = [r for r in poses if wall_distance(r) < 150]
    assert len(near) >= 0.9 * len(poses)
    # it passes along all four walls
    sides = {min((r["x_mm"], "left"), (w - r["x_mm"], "right"), (r["y_mm"], "bottom"),
                 (h - r["y_mm"], "top"))[1] for r in near}
    assert sides == {"left", "right", "bottom", "top"}
    assert contacts(records)["r1"]["walls"] == 0


def _travelled(records, robot="r1") -> float:
    """mm along the path of the pose records."""
    poses = [r for r in records if r["kind"] == "pose" and r.get("robot", "r1") == robot]
    return sum(math.hypot(b["x_mm"] - a["x_mm"], b["y_mm"] - a["y_mm"])
               for a, b in zip(poses, poses[1:]))


def test_braitenberg_vehicle_drives_a_minute_among_obstacles_without_touching(tmp_path):
    """The course's first exercise: wheel speeds follow the sensors
    (`set_speed` every 10 ms from an expression of the readings)."""
    records, _, _ = run(EXAMPLES / "braitenberg.epk", tmp_path, "--world",
                        EXAMPLES / "braitenberg.world", "--pose-interval", "100ms", expect=3)
    assert final_pose(records)["t_ms"] == 60000
    c = contacts(records)["r1"]
    assert (c["walls"], c["objects"], c["robots"]) == (0, 0, 0)
    assert _travelled(records) > 1200
    # and the variables' changes are in the trace
    assert any(r["kind"] == "set" and r["var"] == "right_near" and r["robot"] == "r1"
               for r in records)


def test_proportional_wall_follower_keeps_to_the_walls(tmp_path):
    records, _, _ = run(EXAMPLES / "wall_follower.epk", tmp_path, "--world",
                        EXAMPLES / "wall_follow.world", "--pose-interval", "100ms", expect=3)
    poses = [r for r in records if r["kind"] == "pose"]
    near = [r for r in poses if min(r["x_mm"], 800 - r["x_mm"], r["y_mm"], 600 - r["y_mm"]) < 120]
    assert len(near) >= 0.8 * len(poses)
    assert contacts(records)["r1"]["walls"] == 0
    assert _travelled(records) > 1500


def test_random_walk_swarm_each_robot_its_own_random_numbers(tmp_path):
    records, _, _ = run(EXAMPLES / "random_walk.epk", tmp_path, "--world",
                        EXAMPLES / "swarm.world", "--pose-interval", "500ms", expect=3)
    robots = sorted({r["robot"] for r in records if "robot" in r})
    assert len(robots) == 6
    for robot, c in contacts(records).items():
        assert (c["walls"], c["objects"], c["robots"]) == (0, 0, 0), robot
    # the same program, different turns: the headings after the first wander differ
    headings = {final_pose(records, robot)["heading_deg"] for robot in robots}
    assert len(headings) == 6
    # and a run is reproducible; another seed walks elsewhere
    again, _, _ = run(EXAMPLES / "random_walk.epk", tmp_path, "--world", EXAMPLES / "swarm.world",
                      "--pose-interval", "500ms", "--seed", "1", expect=3, name="again")
    other, _, _ = run(EXAMPLES / "random_walk.epk", tmp_path, "--world", EXAMPLES / "swarm.world",
                      "--pose-interval", "500ms", "--seed", "9", expect=3, name="other")
    assert final_pose(again, "r1") == final_pose(records, "r1")
    assert final_pose(other, "r1") != final_pose(records, "r1")


def test_random_walk_wanders_on_once_the_way_is_clear(tmp_path):
    """Issue 24: avoid (a guarded `every` of priority 1) holds the wheels only
    while something is near (and its last turn runs); the wander turns after
    a robot's first avoid are carried out, except those that come while it is
    turning away. They used to be all suppressed (246 records): the final
    `set_speed` of avoid's sequence owned the wheels for good."""
    records, _, _ = run(EXAMPLES / "random_walk.epk", tmp_path, "--world",
                        EXAMPLES / "swarm.world", expect=3)
    turn_ms = 405 + 50      # avoid's 45-degree turn (162 steps at 400 steps/s), one period
    later = refused = 0
    for robot in sorted({r["robot"] for r in records if "robot" in r}):
        mine = [r for r in records if r.get("robot") == robot]
        avoids = [r["t_ms"] for r in mine if r["kind"] == "event" and "rule avoid" in r["name"]]
        if not avoids:
            continue
        later += len([r for r in mine if r["kind"] == "event" and "rule wander" in r["name"]
                      and r["t_ms"] > avoids[0]])
        for r in (r for r in mine if r["kind"] == "suppressed"):
            refused += 1
            assert "rule wander" in r["name"] and "rule avoid" in r["owner_name"]
            # refused only while avoid was turning away
            assert min(r["t_ms"] - t for t in avoids if t <= r["t_ms"]) < turn_ms, (robot, r)
    assert later >= 50 and refused <= 0.25 * later, (later, refused)


def test_ten_robots_disperse(tmp_path):
    records, out, _ = run(EXAMPLES / "dispersion.epk", tmp_path, "--world",
                          EXAMPLES / "dispersion.world", "--time-limit", "30s", expect=3)
    names = [f"r{i}" for i in range(1, 11)]
    start = {r["robot"]: (r["x_mm"], r["y_mm"]) for r in reversed(records) if "x_mm" in r}
    end = {n: (final_pose(records, n)["x_mm"], final_pose(records, n)["y_mm"]) for n in names}
    assert sorted(start) == sorted(names)

    def mean_distance(p):
        d = [math.dist(a, b) for a, b in itertools.combinations(p.values(), 2)]
        return sum(d) / len(d)

    def min_distance(p):
        return min(math.dist(a, b) for a, b in itertools.combinations(p.values(), 2))
    assert mean_distance(end) > 2.5 * mean_distance(start)
    assert min_distance(end) > min_distance(start) + 20
    # and then they stay put: nothing fires in the last 10 s
    assert not [r for r in records if r["kind"] == "event" and r["t_ms"] > 20000]
    # each robot's readable lines carry its name
    assert all(any(line.startswith(f"{n}: [") for line in out.splitlines()) for n in names)


# ---- several robots, several programs --------------------------------------------

def test_each_robot_has_its_own_program_and_runtime_state(tmp_path):
    """Two robots run the same program and a third another one: each has
    its own timer, motion and registration arrays (the runtime's globals)."""
    (tmp_path / "fast.epk").write_text("on immediate do set_timer, start_straight(800 steps/s, 10 cm)\n"
                                       "on timer(1500 ms) do exit_main\n")
    slow = tmp_path / "slow.epk"
    slow.write_text("on immediate do set_timer, start_straight(200 steps/s, 10 cm)\n"
                    "on timer(3 s) do exit_main\n")
    w = world(tmp_path, "robot a at 0 cm, 0 cm\nrobot b at 0 cm, 20 cm\n"
                        "robot c at 0 cm, 40 cm program fast.epk\n")
    records, out, _ = run(slow, tmp_path, "--world", w)
    exits = {r["robot"]: r for r in records if r["kind"] == "exit"}
    assert exits["a"]["t_ms"] == exits["b"]["t_ms"] == 3001
    assert exits["c"]["t_ms"] == 1501
    assert exits["a"]["x_mm"] == pytest.approx(77.3, abs=2)    # 3 s at 200 steps/s
    assert exits["c"]["x_mm"] == pytest.approx(100, abs=2)     # 10 cm at 800 steps/s
    assert exits["a"]["y_mm"] == pytest.approx(0, abs=2) and exits["c"]["y_mm"] == pytest.approx(400, abs=2)
    # ids are per robot: each has its own event #0
    firsts = [r for r in records if r["kind"] == "event" and r["id"] == 0]
    assert sorted(r["robot"] for r in firsts) == ["a", "b", "c"]
    assert "c: exit at 1501 ms" in out


def test_exit_status_is_the_highest_of_the_robots(tmp_path):
    quick = tmp_path / "quick.epk"
    quick.write_text("on immediate do exit_main\n")
    (tmp_path / "never.epk").write_text("on immediate do start_straight(100 steps/s, 1 m)\n")
    w = world(tmp_path, "robot a at 0 cm, 0 cm\nrobot b at 0 cm, 20 cm program never.epk\n")
    result = epuckc("run", quick, "--world", w, "--time-limit", "2s")
    assert result.returncode == 3, result.stderr
    assert "a: exit at 1 ms" in result.stdout and "b: timeout at 2000 ms" in result.stdout


def test_a_robot_program_with_errors_is_reported(tmp_path):
    (tmp_path / "bad.epk").write_text("on immediate do strat_straight(100, 1 m)\n")
    w = world(tmp_path, "robot a at 0 cm, 0 cm program bad.epk\n")
    result = epuckc("run", "--world", w)       # the world names every robot's program
    assert result.returncode == 1
    assert "bad.epk:1:" in result.stderr and "E011" in result.stderr


# ---- pictures of a world run -----------------------------------------------------

def test_world_svg_shows_walls_obstacles_every_robot_and_every_firing(tmp_path):
    picture = tmp_path / "disp.svg"
    records, _, _ = run(EXAMPLES / "dispersion.epk", tmp_path, "--world",
                        EXAMPLES / "dispersion.world", "--time-limit", "10s", "--svg", picture,
                        expect=3)
    root = svg(picture)
    assert len(by_class(root, "arena")) == 1
    runs = by_class(root, "robot-run")
    assert [g.get("data-robot") for g in runs] == [f"r{i}" for i in range(1, 11)]
    from collections import Counter
    from epuckc.sim.plot import DENSE, rule_label
    for g in runs:
        name = g.get("data-robot")
        events = [r for r in records if r["kind"] == "event" and r["robot"] == name]
        # a rule that fires more than DENSE times is a band on the timeline, not marks
        counts = Counter(rule_label(r["name"]) for r in events)
        shown = [r["t_ms"] for r in events if counts[rule_label(r["name"])] <= DENSE]
        assert [int(m.get("data-t-ms")) for m in by_class(g, "firing")] == shown
        [final] = by_class(g, "final-pose")
        last = final_pose(records, name)
        assert float(final.get("data-x-mm")) == last["x_mm"]
    picture = tmp_path / "arena.svg"
    run(EXAMPLES / "wander.epk", tmp_path, "--world", EXAMPLES / "arena.world",
        "--time-limit", "5s", "--svg", picture, expect=3)
    root = svg(picture)
    assert len(by_class(root, "box")) == 2 and len(by_class(root, "cylinder")) == 2


def test_readme_picture_is_up_to_date(tmp_path):
    """docs/images/wander.svg, braitenberg.svg and line_follower.svg are what
    docs/make_pictures.py draws today."""
    import subprocess
    import sys
    from tests.support.world import REPO
    result = subprocess.run([sys.executable, str(REPO / "docs" / "make_pictures.py"), "--out", str(tmp_path)],
                            capture_output=True, text=True)
    assert result.returncode == 0, result.stderr
    for name in ("wander.svg", "braitenberg.svg", "line_follower.svg"):
        assert (tmp_path / name).read_bytes() == (REPO / "docs" / "images" / name).read_bytes(), \
            f"{name}: run python3 docs/make_pictures.py and commit docs/images/"


def test_the_portable_coroutine_switch_gives_the_same_run(tmp_path):
    """The runner switches robots with a few instructions on x86-64 and with
    swapcontext elsewhere (-DEPUCK_WORLD_UCONTEXT): the same run either way."""
    import shutil
    import subprocess
    from epuckc.sim import enki
    from epuckc.diagnostics import Report
    from epuckc.cli.driver import load_program
    from epuckc.sim.world import parse_world, runner_spec
    fast = enki.build_runner()
    portable = tmp_path / "portable"
    subprocess.run(enki.runner_command("enki", portable, ("-DEPUCK_WORLD_UCONTEXT",)), check=True)
    lib = enki.build_robot(load_program(EXAMPLES / "dispersion.epk", Report()))
    w = parse_world(EXAMPLES / "dispersion.world")
    outputs = []
    for label, runner in (("fast", fast), ("ucontext", portable)):
        d = tmp_path / label
        d.mkdir()
        robots = []
        for i in range(len(w.robots)):
            shutil.copyfile(lib, d / f"r{i}.so")
            robots.append((d / f"r{i}.so", {"EPUCK_TIME_LIMIT_MS": "3000",
                                            "EPUCK_TRACE": str(d / f"r{i}.jsonl"),
                                            "EPUCK_POSE_MS": "50"}))
        (d / "spec").write_text(runner_spec(w, robots))
        result = subprocess.run([str(runner), str(d / "spec"), str(d / "results")],
                                capture_output=True, text=True)
        assert result.returncode == 0, result.stderr
        traces = [(d / f"r{i}.jsonl").read_text() for i in range(len(w.robots))]
        outputs.append((result.stdout, (d / "results").read_text(), traces))
    assert outputs[0] == outputs[1]
    assert outputs[0][1].count(" 3 ") == 10         # every robot ran to its time limit


def test_odometry_readings_in_a_world(tmp_path):
    """`x` and `heading` are the runtime's own dead reckoning from the wheels'
    steps; in Enki (wheel noise off) they stop the robot where its body is."""
    prog = tmp_path / "odo.epk"
    prog.write_text("on immediate do set_speed(left: 300, right: 300)\n"
                    "rule far: when x >= 200 mm do set_speed(left: -200, right: 200)\n"
                    "rule turned: when heading >= 90 deg do stop_motor, exit_main\n")
    records, _, _ = run(prog, tmp_path, "--world", world(tmp_path, "arena none\nnoise 0 %\n"))
    end = final_pose(records)
    assert end["kind"] == "exit"
    start = next(r for r in records if r["kind"] == "event" and "on immediate" in r["name"])
    assert 195 <= end["x_mm"] - start["x_mm"] <= 205
    dh = (end["heading_deg"] - start["heading_deg"]) % 360
    assert 88 <= dh <= 92
