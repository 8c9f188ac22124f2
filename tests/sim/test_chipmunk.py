"""The world runner's second physics, Chipmunk 7 (`physics chipmunk`, issue
45): the same programs in the same worlds on Enki, the reference, and on
Chipmunk, read the same IR values at set distances, touch things in the
same steps and cover the same floor, within the tolerances stated here (and
in docs/world.md, "Large worlds"); the `physics` line, the automatic choice
above CHIPMUNK_ABOVE robots, and runs that do not depend on the threads."""
import json
import math
import statistics

import pytest

from conftest import require_physics
from epuckc.sim.physics import CHIPMUNK_ABOVE, MAX_ENKI_ROBOTS
from epuckc.sim.world import WorldError, parse_world
from tests.support.world import EXAMPLES, epuckc, final_pose, run, same_run_both_ways

BOTH = ("enki", "chipmunk")


@pytest.fixture(autouse=True)
def _providers():
    for name in BOTH:
        require_physics(name)


def on(physics, text):
    return text + f"physics {physics}\n"


def runs_on_both(tmp_path, program, world_text, *extra, expect=0):
    """{physics: records} of `program` in the world on each provider."""
    out = {}
    for physics in BOTH:
        w = tmp_path / f"{physics}.world"
        w.write_text(on(physics, world_text))
        records, _, _ = run(program, tmp_path, "--world", w, *extra, name=physics, expect=expect)
        assert records[0]["physics"] == physics
        out[physics] = records
    return out


# ---- IR readings at set distances ---------------------------------------------------

IR_PROGRAM = """var f0 = 0
var f7 = 0
var s2 = 0
every 50 ms do f0 = ir0, f7 = ir7, s2 = ir2
after 3 s do exit_main
"""
WALL_GAPS_CM = [0.5, 1, 2, 3, 4, 6, 8, 11]
ROBOT_GAPS_CM = [1, 3, 6]


def ir_world():
    """Robots standing still: facing the east wall at WALL_GAPS_CM, in
    pairs facing each other at ROBOT_GAPS_CM, before a cylinder and a box."""
    lines = ["arena 100 cm x 200 cm", "noise 0 %"]
    for i, gap in enumerate(WALL_GAPS_CM):
        lines.append(f"robot w{i} at {100 - 3.7 - gap:.2f} cm, {10 + i * 12} cm heading 0 deg")
    for i, gap in enumerate(ROBOT_GAPS_CM):
        lines.append(f"robot a{i} at 20 cm, {120 + i * 15} cm heading 0 deg")
        lines.append(f"robot b{i} at {20 + 7.4 + gap} cm, {120 + i * 15} cm heading 180 deg")
    lines += ["cylinder at 50 cm, 180 cm radius 5 cm", "robot c0 at 41 cm, 180 cm heading 0 deg",
              "box at 60 cm, 30 cm size 10 cm x 10 cm", "robot x0 at 60 cm, 20.3 cm heading 90 deg"]
    return "\n".join(lines) + "\n"


def readings(records):
    """(robot, variable) -> the values it was set to."""
    out = {}
    for r in records:
        if r["kind"] == "set":
            out.setdefault((r["robot"], r["var"]), []).append(r["value"])
    return out


# Enki's IR noise is Gaussian, sd 10, on each reading: the mean of about 60
# readings is within 1.3 of the sensor's value (one sd), the difference of
# two such means within 8 nearly always (4.3 sd); 1 % for the model's own
# rounding near the body, where readings reach 2,300.
IR_TOLERANCE = 8
IR_RELATIVE = 0.01


def test_ir_readings_at_set_distances_agree(tmp_path):
    (tmp_path / "ir.epk").write_text(IR_PROGRAM)
    got = runs_on_both(tmp_path, tmp_path / "ir.epk", ir_world())
    enki, chipmunk = readings(got["enki"]), readings(got["chipmunk"])
    assert set(enki) == set(chipmunk) and len(enki) == 3 * (len(WALL_GAPS_CM) + 2 * 3 + 2)
    means = {}
    for key, values in enki.items():
        e, c = statistics.mean(values), statistics.mean(chipmunk[key])
        assert len(values) >= 30 and len(chipmunk[key]) >= 30, key
        assert abs(c - e) <= IR_TOLERANCE + IR_RELATIVE * e, (key, e, c)
        means[key] = e
    # what is compared is the curve: strong near, falling with the gap
    front = [means[(f"w{i}", "f0")] for i in range(len(WALL_GAPS_CM))]
    assert front[0] > 2000 and front[3] < 300
    assert all(a > b for a, b in zip(front, front[1:6]))
    assert means[("a0", "f0")] > means[("a1", "f0")] > means[("a2", "f0")]
    assert means[("c0", "f0")] > 2000 and means[("x0", "f0")] > 1000


@pytest.mark.parametrize("world, expected_mm", [
    ("arena 100 cm x 100 cm\nrobot at 60 cm, 50 cm heading 0 deg\n", 400 - 37),
    ("arena 200 cm x 200 cm\nrobot at 50 cm, 50 cm heading 90 deg\n"
     "box at 50 cm, 75 cm size 20 cm x 10 cm\n", 200 - 37),
    ("arena 200 cm x 200 cm\nrobot at 50 cm, 50 cm heading 180 deg\n"
     "robot other at 27.6 cm, 50 cm\ncylinder at 50 cm, 100 cm radius 5 cm\n", 224 - 2 * 37),
    ("arena none\nrobot at 0 cm, 0 cm\n", 2000),
])
def test_the_tof_ray_agrees(tmp_path, world, expected_mm):
    (tmp_path / "tof.epk").write_text("var d = 0 mm\nafter 50 ms do d = distance\n"
                                      "after 100 ms do exit_main\n")
    got = runs_on_both(tmp_path, tmp_path / "tof.epk", world)
    for records in got.values():
        first = next(r for r in records if r["kind"] == "set" and r["var"] == "d")
        assert abs(first["value"] - expected_mm) <= 1


CAMERA_PROGRAM = """var red = 0
var red_at = 0 deg
var green = 0
var green_at = 0 deg
every 100 ms do red = seen(red), red_at = bearing(red), green = seen(green),
    green_at = bearing(green)
after 1 s do exit_main
"""
# every 100 ms: the camera's first frame, in colour, is ready some 230 ms
# after the first reading started it (runtime_c/host/camera.c), as on the
# robot; the values compared are the last ones


def test_the_camera_sees_the_same_pixels(tmp_path):
    """A red cylinder, a green box and a blue robot at set bearings: the same
    widths and bearings on both (the camera has no noise)."""
    world = ("arena 200 cm x 200 cm colour white\nrobot at 50 cm, 50 cm heading 0 deg\n"
             "cylinder at 90 cm, 60 cm radius 5 cm colour red\n"
             "box at 110 cm, 30 cm size 10 cm x 20 cm angle 20 deg colour green\n"
             "robot other at 80 cm, 45 cm heading 90 deg colour blue\n")
    (tmp_path / "cam.epk").write_text(CAMERA_PROGRAM)
    got = runs_on_both(tmp_path, tmp_path / "cam.epk", world)
    seen = {p: {k: v[-1] for k, v in readings(r).items() if k[0] == "r1"} for p, r in got.items()}
    assert seen["enki"] == seen["chipmunk"]
    assert seen["enki"][("r1", "red")] > 0 and seen["enki"][("r1", "green")] > 0


# ---- contacts and coverage ------------------------------------------------------------

BLIND = """on immediate do set_speed(left: 500 steps/s, right: 500 steps/s)
after 6 s do exit_main
"""
CONTACT_WORLD = """arena 100 cm x 100 cm
noise 0 %
cylinder at 50 cm, 80 cm radius 6 cm
box at 80 cm, 50 cm size 6 cm x 20 cm angle 0 deg
robot wall at 20 cm, 20 cm heading 180 deg
robot cyl at 50 cm, 60 cm heading 90 deg
robot box at 60 cm, 50 cm heading 0 deg
robot p1 at 20 cm, 80 cm heading 0 deg
robot p2 at 40 cm, 80 cm heading 180 deg
"""
CONTACT_STEPS = 3       # steps of 10 ms: where a body first touches, within 0.2 mm


def test_blind_robots_touch_the_same_things_in_the_same_steps(tmp_path):
    """Robots driving straight into a wall, a cylinder, a box and each
    other: contact from the same step on, every step after, and held there;
    each kind (walls, obstacles, robots, as issue 41 tells them apart) and
    the steps in contact with anything counted alike on both."""
    (tmp_path / "blind.epk").write_text(BLIND)
    got = runs_on_both(tmp_path, tmp_path / "blind.epk", CONTACT_WORLD, "--pose-interval",
                       "100ms")
    counts = {p: {r["robot"]: r for r in records if r["kind"] == "contacts"}
              for p, records in got.items()}
    touches = {"wall": "walls", "cyl": "objects", "box": "objects", "p1": "robots", "p2": "robots"}
    for name, kind in touches.items():
        e, c = counts["enki"][name], counts["chipmunk"][name]
        for physics in (e, c):
            assert physics[kind] > 0 and physics["steps"] >= physics[kind]
            assert all(physics[k] == 0 for k in ("walls", "objects", "robots") if k != kind)
        for key in ("walls", "objects", "robots", "steps"):
            assert abs(e[key] - c[key]) <= CONTACT_STEPS, (name, key, e, c)
        assert abs(e["first_ms"] - c["first_ms"]) <= 10 * CONTACT_STEPS
        pe, pc = final_pose(got["enki"], name), final_pose(got["chipmunk"], name)
        assert math.hypot(pe["x_mm"] - pc["x_mm"], pe["y_mm"] - pc["y_mm"]) <= 2.0


def test_on_open_ground_a_program_ends_where_the_stub_does(tmp_path):
    """No noise, nothing to see: the body moves by its steps exactly."""
    w = tmp_path / "open.world"
    w.write_text("arena none\nnoise 0 %\nphysics chipmunk\n")
    stub, _, _ = run(EXAMPLES / "square.epk", tmp_path, name="stub", expect=None)
    chip, _, _ = run(EXAMPLES / "square.epk", tmp_path, "--world", w, name="chip", expect=None)
    s, c = final_pose(stub), final_pose(chip)
    assert (c["t_ms"], c["left_steps"], c["right_steps"]) == (s["t_ms"], s["left_steps"],
                                                              s["right_steps"])
    assert math.hypot(c["x_mm"] - s["x_mm"], c["y_mm"] - s["y_mm"]) <= 0.5
    assert abs((c["heading_deg"] - s["heading_deg"] + 180) % 360 - 180) <= 0.2


COVERAGE_CELL_MM = 50           # as epuckc/experiment/metrics.py's coverage
COVERAGE_TOLERANCE = 0.10       # the mean over seeds, of cells of all paths


def coverage_world(seed):
    lines = ["arena 150 cm x 100 cm", "cylinder at 75 cm, 50 cm radius 8 cm",
             "box at 40 cm, 70 cm size 25 cm x 5 cm angle 30 deg",
             "box at 110 cm, 30 cm size 5 cm x 25 cm"]
    lines += [f"robot at {15 + (i % 6) * 22} cm, {12 + (i // 6) * 76} cm heading "
              f"{(i * 67) % 360} deg" for i in range(12)]
    return "\n".join(lines + [f"seed {seed}"]) + "\n"


def test_a_swarm_covers_as_much_floor(tmp_path):
    """Twelve wanderers among obstacles for 30 s, three seeds: the floor
    their paths crossed (5 cm cells) within 10 % of Enki's, on average."""
    covered = {p: [] for p in BOTH}
    for seed in (1, 2, 3):
        got = runs_on_both(tmp_path, EXAMPLES / "wander.epk", coverage_world(seed),
                           "--time-limit", "30s", "--pose-interval", "100ms", expect=3)
        for p, records in got.items():
            covered[p].append(len({(math.floor(r["x_mm"] / COVERAGE_CELL_MM),
                                    math.floor(r["y_mm"] / COVERAGE_CELL_MM))
                                   for r in records if "x_mm" in r and "robot" in r}))
    e, c = statistics.mean(covered["enki"]), statistics.mean(covered["chipmunk"])
    assert e > 150                  # they wandered: a quarter of the floor at least
    assert abs(c - e) <= COVERAGE_TOLERANCE * e, covered


# ---- the same run on any number of threads --------------------------------------------

@pytest.mark.parametrize("physics", BOTH)
def test_the_threads_do_not_change_the_run(tmp_path, physics):
    """The robots' polls spread over 1 or 3 threads (workers.h): the same
    trace and output byte for byte, messages and contacts included."""
    lines = ["arena 120 cm x 120 cm", f"physics {physics}"]
    lines += [f"robot at {12 + (i % 8) * 13} cm, {12 + (i // 8) * 13} cm heading "
              f"{(i * 47) % 360} deg" for i in range(40)]
    w = tmp_path / "crowd.world"
    w.write_text("\n".join(lines) + "\n")
    same_run_both_ways(tmp_path, {"EPUCK_WORLD_THREADS": "1"}, {"EPUCK_WORLD_THREADS": "3"},
                       EXAMPLES / "aggregation.epk", "--world", w, "--time-limit", "3s",
                       "--pose-interval", "100ms")


# ---- the `physics` line -----------------------------------------------------------------

def robots(n, spacing_cm=10):
    side = math.ceil(math.sqrt(n))
    return "".join(f"robot at {(i % side) * spacing_cm} cm, {(i // side) * spacing_cm} cm\n"
                   for i in range(n))


def test_the_physics_line_and_the_automatic_choice(tmp_path):
    def parsed(text):
        p = tmp_path / "w.world"
        p.write_text(text)
        return parse_world(p)
    assert parsed("robot at 0 cm, 0 cm\n").resolved_physics == "enki"
    assert parsed("physics Chipmunk\nrobot at 0 cm, 0 cm\n").resolved_physics == "chipmunk"
    assert parsed(robots(CHIPMUNK_ABOVE)).resolved_physics == "enki"
    assert parsed(robots(CHIPMUNK_ABOVE + 1)).resolved_physics == "chipmunk"
    big = parsed("physics enki\n" + robots(CHIPMUNK_ABOVE + 1))
    assert big.resolved_physics == "enki" and big.to_json()["physics"] == "enki"
    for text, where, what in [
            ("physics box2d\nrobot at 0 cm, 0 cm\n", "w.world:1:9:", "`box2d` is not a physics"),
            ("physics chipmunk\nphysics enki\n", "w.world:2:1:", "a second `physics` line"),
            ("physics 3\n", "w.world:1:9:", "`3` is not a physics"),
            ("physics enki\n" + robots(MAX_ENKI_ROBOTS + 1), "w.world:1:",
             f"{MAX_ENKI_ROBOTS + 1:,} robots on Enki")]:
        with pytest.raises(WorldError) as err:
            parsed(text)
        assert where in str(err.value) and what in str(err.value), str(err.value)


def test_a_large_world_runs_on_chipmunk_and_says_so(tmp_path):
    """Above CHIPMUNK_ABOVE robots without a `physics` line: Chipmunk, one
    line on stderr, and the trace's world record names it."""
    w = tmp_path / "big.world"
    w.write_text("arena 400 cm x 400 cm\n" + "".join(
        f"robot at {10 + (i % 25) * 15} cm, {10 + (i // 25) * 15} cm\n"
        for i in range(CHIPMUNK_ABOVE + 25)))
    trace = tmp_path / "t.jsonl"
    result = epuckc("run", EXAMPLES / "wander.epk", "--world", w, "--time-limit", "500ms",
                    "--trace", trace)
    assert result.returncode == 3, result.stderr
    assert "runs on Chipmunk" in result.stderr and "physics enki" in result.stderr
    first = json.loads(trace.read_text().splitlines()[0])
    assert first["kind"] == "world" and first["physics"] == "chipmunk"


# ---- the floor and sound (issue 46) on both ------------------------------------------

GROUND_PROGRAM = """var g0 = 0
var g1 = 0
var g2 = 0
var m0 = 0
var m1 = 0
var m2 = 0
every 50 ms do g0 = ground0, g1 = ground[1], g2 = ground2
every 10 ms do m0 = mic0, m1 = mic[1], m2 = mic2
after 1 s do play_sound(haa)
after 3 s do exit_main
"""
# Enki's ground noise is Gaussian, sd 5: the difference of two means of
# about 60 readings is within 4 nearly always (4.3 sd).
GROUND_TOLERANCE = 4


def test_ground_sensors_and_microphones_agree(tmp_path):
    """Robots standing on black, white and grey floor, one astride the
    edge, near a source that plays from 0.5 s to 2 s while one robot plays
    a sample: the ground sensors read the same within their noise, the
    microphones exactly the same at each change."""
    Image = pytest.importorskip("PIL.Image")
    picture = Image.new("RGB", (100, 50), "white")
    for x in range(100):
        for y in range(50):
            if x < 50 or y < 10:
                picture.putpixel((x, y), (0, 0, 0) if x < 50 else (128, 128, 128))
    picture.save(tmp_path / "halves.png")
    (tmp_path / "probe.epk").write_text(GROUND_PROGRAM.replace("after 1 s do play_sound(haa)\n",
                                                               ""))
    (tmp_path / "player.epk").write_text(GROUND_PROGRAM)
    world = ("arena 100 cm x 50 cm\nfloor halves.png\nnoise 0 %\n"
             "sound at 60 cm, 40 cm level 80 dB from 500 ms to 2 s\n"
             "robot black at 20 cm, 25 cm\nrobot white at 80 cm, 35 cm heading 30 deg\n"
             "robot grey at 80 cm, 45 cm heading 180 deg\n"
             f"robot edge at 50 cm, 25 cm heading 90 deg program {tmp_path / 'player.epk'}\n")
    got = runs_on_both(tmp_path, tmp_path / "probe.epk", world)
    enki, chipmunk = readings(got["enki"]), readings(got["chipmunk"])
    for robot in ("black", "white", "grey", "edge"):
        for n in ("g0", "g1", "g2"):
            e, c = (statistics.mean(r.get((robot, n), [0])) for r in (enki, chipmunk))
            assert abs(c - e) <= GROUND_TOLERANCE, (robot, n, e, c)
    # what is compared: black, white and grey (the image's top rows: y near 50 cm), and
    # the edge's two sides
    assert statistics.mean(enki[("white", "g1")]) > 960
    assert statistics.mean(enki.get(("black", "g1"), [0])) < 40
    assert 300 < statistics.mean(enki[("grey", "g1")]) < 700
    assert statistics.mean(enki[("edge", "g2")]) > 900
    heard = {p: [(r["t_ms"], r["robot"], r["var"], r["value"]) for r in records
                 if r["kind"] == "set" and r["var"] in ("m0", "m1", "m2")]
             for p, records in got.items()}
    assert heard["enki"] == heard["chipmunk"]
    # the source's start and end, and the sample, are among the changes
    times = sorted({t for t, robot, _, _ in heard["enki"] if robot == "black"})
    for start, end in ((500, 520), (1000, 1020), (2000, 2020)):
        assert any(start <= t <= end for t in times), (start, times)
