"""The world file format (epuckc/sim/world.py): what it accepts, what it
rejects and how it says so."""
import math

import pytest

from epuckc.sim.world import WorldError, parse_world, runner_spec

from tests.support.world import EXAMPLES, epuckc


def parse(tmp_path, text, name="w.world"):
    path = tmp_path / name
    path.write_text(text)
    return parse_world(path, shown=name)


def error(tmp_path, text):
    with pytest.raises(WorldError) as info:
        parse(tmp_path, text)
    return str(info.value)


def test_every_item_with_units(tmp_path):
    (tmp_path / "other.epk").write_text("on immediate do exit_main\n")
    w = parse(tmp_path, """
        # a comment
        arena 1.2 m x 800 mm
        box at 40 cm, 30 cm size 20 cm x 5 cm angle 30 deg height 4 cm
        cylinder at 900mm 500mm radius 6cm     # no comma, units attached
        robot at 20 cm, 20 cm heading 45 deg
        robot bob at 60 cm, 60 cm heading -90 deg program other.epk
        seed 7
        noise 2.5 %
        step 20 ms
    """)
    assert (w.width_mm, w.height_mm) == (1200, 800)
    [b] = w.boxes
    assert (b.x_mm, b.y_mm, b.length_mm, b.width_mm, b.angle_deg, b.height_mm) == (400, 300, 200, 50, 30, 40)
    [c] = w.cylinders
    assert (c.x_mm, c.y_mm, c.radius_mm) == (900, 500, 60)
    r1, bob = w.robots
    assert (r1.name, r1.x_mm, r1.y_mm, r1.heading_deg, r1.program) == ("r1", 200, 200, 45, None)
    assert (bob.name, bob.heading_deg, bob.program) == ("bob", -90, tmp_path / "other.epk")
    assert (w.seed, w.noise_percent, w.step_ms) == (7, 2.5, 20)


def test_defaults_one_robot_in_the_middle_or_at_the_origin(tmp_path):
    w = parse(tmp_path, "arena 100 cm x 60 cm\n")
    [r] = w.robots
    assert (r.name, r.x_mm, r.y_mm, r.heading_deg) == ("r1", 500, 300, 0)
    assert (w.seed, w.noise_percent, w.step_ms) == (1, 5.0, 10)
    w = parse(tmp_path, "# open ground\n")
    assert not w.walled and (w.robots[0].x_mm, w.robots[0].y_mm) == (0, 0)


def test_runner_spec_is_in_cm_and_radians(tmp_path):
    w = parse(tmp_path, "arena 100 cm x 60 cm\nbox at 50 cm, 30 cm size 10 cm x 4 cm angle 90 deg\n"
                        "robot a at 20 cm, 20 cm heading 180 deg\n")
    spec = runner_spec(w, [("/x/a.so", {"EPUCK_TRACE": "/x/a.jsonl"})]).splitlines()
    assert spec[0] == "arena square 100.0 60.0 0.501961 0.501961 0.501961"     # grey walls
    # the message channel's defaults: 22.5 cm, 5 %, 60 deg cones, 10 %, 100 ms
    messages = spec[4].split()
    assert messages[0] == "messages" and messages[1:3] == ["22.5", "0.05"]
    assert [round(float(v), 6) for v in messages[3:5]] == [round(math.pi / 3, 6)] * 2
    assert messages[5:] == ["0.1", "100"]
    box = spec[5].split()
    assert box[:5] == ["box", "50.0", "30.0", "10.0", "4.0"] and math.isclose(float(box[5]), math.pi / 2)
    robot = spec[6].split()
    assert robot[:4] == ["robot", "a", "20.0", "20.0"] and math.isclose(float(robot[4]), math.pi)
    # devices not known (hand-written C): the camera, the ToF ray and the ground sensors
    assert spec[7:] == ["lib /x/a.so", "colour 0.501961 0.501961 0.501961", "camera", "tof",
                        "ground", "setting EPUCK_TRACE /x/a.jsonl"]
    # a program that reads neither gets neither (each costs a part of every step)
    spec = runner_spec(w, [("/x/a.so", {}, frozenset({"messages"}))]).splitlines()
    assert spec[7:] == ["lib /x/a.so", "colour 0.501961 0.501961 0.501961"]


@pytest.mark.parametrize("text, where, words", [
    ("arena 100 x 60 cm\n", "w.world:1:7:", "has no unit"),
    ("arena 100 cm by 60 cm\n", "w.world:1:14:", "expected `x`"),
    ("arena 100 kg x 60 cm\n", "w.world:1:7:", "not a unit of length"),
    ("arena -1 m x 1 m\n", "w.world:1:7:", "must be positive"),
    ("wall at 1 cm, 2 cm\n", "w.world:1:1:", "unknown item `wall`"),
    ("robot at 1 cm\n", "w.world:1:14:", "expected a length"),
    ("robot at 10 cm, 10 cm speed 3\n", "w.world:1:23:", "unexpected `speed`"),
    ("robot a at 10 cm, 10 cm\nrobot a at 30 cm, 30 cm\n", "w.world:2:7:", "a second robot named `a`"),
    ("robot at 10 cm, 10 cm program nothere.epk\n", "w.world:1:31:", "does not exist"),
    ("seed 1\nseed 2\n", "w.world:2:1:", "a second `seed` line"),
    ("seed -3\n", "w.world:1:6:", "whole number"),
    ("noise 80 %\n", "w.world:1:7:", "from 0 % to 50 %"),
    ("step 0.5 ms\n", "w.world:1:6:", "whole number of ms"),
    ("arena 50 cm x 50 cm\nrobot at 2 cm, 25 cm\n", "w.world:2:1:", "not inside"),
    ("robot at 0 cm, 0 cm\nrobot at 5 cm, 0 cm\n", "w.world:2:1:", "overlaps robot r1"),
    ("cylinder at 0 cm, 8 cm radius 5 cm\nrobot at 0 cm, 0 cm\n", "w.world:2:1:", "overlaps the cylinder"),
    ("box at 0 cm, 4 cm size 10 cm x 2 cm\nrobot at 0 cm, 0 cm\n", "w.world:2:1:", "overlaps the box"),
    ("robot at 0 cm, 0 cm selector 16\n", "w.world:1:30:", "from 0 to 15"),
    ("robot at 0 cm, 0 cm scenario none.scn\n", "w.world:1:30:", "the scenario none.scn does not exist"),
    ("scenario\n", "w.world:1:9:", "a scenario file"),
])
def test_errors_point_at_the_problem(tmp_path, text, where, words):
    message = error(tmp_path, text)
    assert message.startswith(where) and words in message, message


def test_an_error_shows_the_line_a_caret_and_help(tmp_path):
    message = error(tmp_path, "arena 100 x 60 cm\n")
    assert message.splitlines() == [
        "w.world:1:7: error: the length 100 has no unit",
        " 1 | arena 100 x 60 cm",
        "   |       ^",
        "help: add one of mm, cm, m, e.g. 20 cm",
        "",
        "1 error in w.world",
    ]


def test_every_error_of_a_file_at_once(tmp_path):
    """Each line's first error, then (when the items read) every placement
    problem: all of a file's errors in one run, each with its place."""
    message = error(tmp_path, "arena 100 cm x 70 cm\n"
                              "box at 40 cm, 30 cm size 20 cm\n"
                              "robot r1 at 15 cm, 12 cm heading 20 dg\n"
                              "wall at 3 cm\n"
                              "seed -4\n")
    heads = [line.split(" error: ")[0] for line in message.splitlines() if " error: " in line]
    assert heads == ["w.world:2:31:", "w.world:3:34:", "w.world:4:1:", "w.world:5:6:"]
    assert message.splitlines()[-1] == "4 errors in w.world"
    placed = error(tmp_path, "arena 50 cm x 50 cm\nrobot at 2 cm, 25 cm\n"
                             "robot at 30 cm, 30 cm\nrobot at 31 cm, 30 cm\n")
    heads = [line.split(" error: ")[0] for line in placed.splitlines() if " error: " in line]
    assert heads == ["w.world:2:1:", "w.world:4:1:"]
    assert "   | ^" in placed.splitlines()


def test_check_reads_a_world_file_as_one(tmp_path):
    from tests.support.world import epuckc
    (tmp_path / "good.world").write_text("arena 50 cm x 50 cm\nrobot at 25 cm, 25 cm\n")
    (tmp_path / "bad.world").write_text("arena 50 cm x 50 cm\nbox at 1 cm\nseed x\n")
    (tmp_path / "in.scn").write_text("0 ms ir0=0\n")
    good = epuckc("check", "good.world", cwd=tmp_path)
    assert good.returncode == 0 and "E001" not in good.stderr
    assert "epuckc run PROG.epk --world good.world" in good.stderr
    bad = epuckc("check", "bad.world", cwd=tmp_path)
    assert bad.returncode == 1 and "E001" not in bad.stderr
    assert "bad.world:2:" in bad.stderr and "bad.world:3:" in bad.stderr
    scn = epuckc("check", "in.scn", cwd=tmp_path)
    assert scn.returncode == 0 and "epuckc run PROG.epk --scenario in.scn" in scn.stderr


def test_the_examples_parse():
    for path in EXAMPLES.glob("*.world"):
        world = parse_world(path)
        assert world.robots


def test_cli_reports_a_bad_world_with_status_2(tmp_path):
    bad = tmp_path / "bad.world"
    bad.write_text("arena 1 m x 1 m\nrobot at 2 m, 0.5 m\n")
    result = epuckc("run", EXAMPLES / "paper_fig2.epk", "--world", bad)
    assert result.returncode == 2
    assert f"{bad}:2:1: error: robot r1" in result.stderr and "Traceback" not in result.stderr
    missing = epuckc("run", EXAMPLES / "paper_fig2.epk", "--world", tmp_path / "none.world")
    assert missing.returncode == 2 and "does not exist" in missing.stderr


def test_a_worlds_scenario_and_its_robots(tmp_path):
    (tmp_path / "a.scn").write_text("0 ms selector=3\n500 ms key=mute mic=900\n")
    w = parse(tmp_path, "scenario a.scn\nrobot a at 0 cm, 0 cm selector 5 scenario a.scn\n"
                        "robot b at 20 cm, 0 cm\n")
    assert w.scenario == tmp_path / "a.scn"
    assert [(r.selector, r.scenario) for r in w.robots] == [(5, tmp_path / "a.scn"), (None, None)]


def test_a_worlds_scenario_is_checked_where_it_is_written(tmp_path):
    """Its own problems at the scenario's file:line:col, then the world's
    line that names it; what Enki gives (the proximity sensors) refused."""
    (tmp_path / "s.scn").write_text("0 ms selector=3\n200 ms ir0=900 bogus=1\n")
    message = error(tmp_path, "arena 1 m x 1 m\nrobot at 50 cm, 50 cm scenario s.scn\n")
    heads = [line.split(" error: ")[0] for line in message.splitlines() if " error: " in line]
    assert heads == ["s.scn:2:16:", "s.scn:2:8:", "w.world:2:32:"], message
    assert "read Enki's" in message


def test_cli_refuses_a_scenario_of_proximity_readings_with_a_world():
    result = epuckc("run", EXAMPLES / "obstacle_avoidance.epk", "--world", EXAMPLES / "arena.world",
                    "--scenario", EXAMPLES / "obstacle.scn")
    assert result.returncode == 2 and "obstacle.scn:3:12: error:" in result.stderr
    assert "the proximity sensors read Enki's" in result.stderr
