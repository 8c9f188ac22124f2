"""GCtronic's own demo programs (program/DemoGCtronic-complete of
gctronic/e-puck-library), byte for byte from the checkout EPUCK_LIB names,
each with a three-line main, built and run on the simulated e-puck: alone
and in Enki worlds, with no warning from epuckc's own files. The project
never copies GCtronic's code: without EPUCK_LIB these tests skip (CI
points it at a checkout and fails instead)."""
import json
import math
import re

import pytest

from conftest import REPO, require_enki, require_epuck_library, require_tool
from tests.support.programs import epuckc
from tests.support.world import pose_records

EPUCKRT_H = (REPO / "runtime_c" / "epuckrt.h").read_text()


def _define(name: str) -> int:
    return int(re.search(rf"#define {name} (\d+)L", EPUCKRT_H).group(1))


MM_PER_STEP = _define("EPUCK_WHEEL_CIRCUMFERENCE_UM") / 1000 / _define("EPUCK_STEPS_PER_REV")
AXLE_MM = _define("EPUCK_AXLE_UM") / 1000

MAINS = {
    "shocker": '#include "runbreitenberg_adv.h"\n'
               'int main(void) { run_breitenberg_shocker(); return 0; }\n',
    "follower": '#include "runbreitenberg_adv.h"\n'
                'int main(void) { run_breitenberg_follower(); return 0; }\n',
    # GCtronic's main_c.c defines the buffer, starts the A/D scan and the UART
    "wallfollow": '#include <a_d/advance_ad_scan/e_ad_conv.h>\n#include <uart/e_uart_char.h>\n'
                  'char buffer[60];\nvoid run_wallfollow(void);\n'
                  'int main(void) { e_init_uart1(); e_init_ad_scan(ALL_ADC); run_wallfollow();'
                  ' return 0; }\n',
    "square": 'void run_square(void);\nint main(void) { run_square(); return 0; }\n',
}
DEMOS = "program/DemoGCtronic-complete"
DEMO_FILE = {"shocker": "runbreitenberg_adv.c", "follower": "runbreitenberg_adv.c",
             "wallfollow": "runwallfollow.c", "square": "runsquare.c"}


@pytest.fixture(scope="module")
def demos():
    return require_epuck_library(DEMOS) / DEMOS


def _run(demos, tmp_path, demo, *extra, world=None, expect=3, env=None):
    main = tmp_path / f"main_{demo}.c"
    main.write_text(MAINS[demo])
    trace = tmp_path / f"{demo}.jsonl"
    args = ["run", main, demos / DEMO_FILE[demo], "--trace", trace, "--pose-interval", "100ms",
            *extra]
    if world is not None:
        path = tmp_path / f"{demo}.world"
        path.write_text(world)
        args += ["--world", path]
    result = epuckc(*args, env=env)
    assert result.returncode == expect, result.stdout + result.stderr
    # the demos' own warnings may show; never one from epuckc's files
    ours = [line for line in result.stderr.splitlines()
            if "runtime_c" in line or "epuck_api" in line or "main_" in line]
    assert ours == [], result.stderr
    records = [json.loads(line) for line in trace.read_text().splitlines()]
    return records, result


def _path_mm(poses):
    return sum(math.hypot(b["x_mm"] - a["x_mm"], b["y_mm"] - a["y_mm"])
               for a, b in zip(poses, poses[1:]))


def _contacts(records):
    [c] = [r for r in records if r["kind"] == "contacts"]
    return c["walls"] + c["objects"] + c["robots"]


def test_the_avoider_explores_the_arena_without_hitting_it(demos, tmp_path):
    require_enki()
    world = (REPO / "examples" / "arena.world").read_text()
    records, _ = _run(demos, tmp_path, "shocker", "--time-limit", "2min", world=world)
    poses = pose_records(records)
    assert poses[-1]["t_ms"] == 120000
    assert _path_mm(poses) >= 1500
    assert _contacts(records) <= 10
    # flow_led's agenda (90 ms) ran all along, beside shock_neuron's
    leds = [r["t_ms"] for r in records if r["kind"] == "led"]
    assert len(leds) > 1000 and leds[-1] > 119000
    # e_calibrate_ir took the library's busy loops first: no motion before
    first_move = next(p["t_ms"] for p in poses if p["left_steps"] or p["right_steps"])
    assert 350 <= first_move <= 600


def test_the_avoider_is_deterministic(demos, tmp_path):
    require_enki()
    world = (REPO / "examples" / "arena.world").read_text()
    first, _ = _run(demos, tmp_path, "shocker", "--time-limit", "10s", world=world)
    second, _ = _run(demos, tmp_path, "shocker", "--time-limit", "10s", world=world)
    assert first == second


def test_several_avoiders_share_their_object_as_copies_would(demos, tmp_path):
    """Three robots of one C program with its own main (signals, agendas,
    the library's busy loops) share its loaded object, each with its own
    globals swapped in (runtime_c/enki/robot_loader.h): the same trace as
    when each loads its own copy (EPUCK_WORLD_COPIES=1)."""
    require_enki()
    world = ("arena 100 cm x 80 cm\ncylinder at 50 cm, 40 cm radius 8 cm\n"
             "robot a at 15 cm, 15 cm heading 30 deg\nrobot b at 85 cm, 20 cm heading 150 deg\n"
             "robot c at 50 cm, 70 cm heading 270 deg\n")
    shared, _ = _run(demos, tmp_path, "shocker", "--time-limit", "6s", world=world)
    copies, _ = _run(demos, tmp_path, "shocker", "--time-limit", "6s", world=world,
                     env={"EPUCK_WORLD_COPIES": "1"})
    assert shared == copies
    assert {r["robot"] for r in shared if r["kind"] == "pose"} == {"a", "b", "c"}


def test_the_follower_holds_its_distance_to_what_it_faces(demos, tmp_path):
    require_enki()
    world = "arena 100 cm x 60 cm\nrobot at 40 cm, 30 cm heading 0 deg\n"
    records, _ = _run(demos, tmp_path, "follower", "--time-limit", "30s", world=world)
    poses = pose_records(records)
    assert _contacts(records) == 0
    late = [p["x_mm"] for p in poses if p["t_ms"] >= 15000]
    gap = 1000 - max(late)                      # to the wall in front, from the centre
    assert 40 <= gap <= 150                     # the body is 37 mm in radius
    assert max(late) - min(late) <= 15          # held, not oscillating


def test_the_wall_follower_keeps_the_wall(demos, tmp_path):
    require_enki()
    # selector 0: the wall on the robot's left; it starts 25 cm from the
    # bottom wall, heading into it at 20 degrees
    world = "arena 150 cm x 100 cm\nrobot at 110 cm, 25 cm heading 200 deg\n"
    records, result = _run(demos, tmp_path, "wallfollow", "--time-limit", "2min", world=world)
    assert "calibration done" in result.stdout
    # the eight offsets and the line's end, sent back to back: one burst
    uart = [r["text"] for r in records if r["kind"] == "uart"]
    assert len(uart) == 1 and re.fullmatch(r"(\d+, ){8} calibration done\r\n", uart[0]), uart
    assert _contacts(records) == 0
    poses = pose_records(records)
    reached = next(p["t_ms"] for p in poses if p["y_mm"] <= 150)
    after = [p for p in poses if p["t_ms"] >= reached]
    # beside the bottom wall from then on, going along it
    assert max(p["y_mm"] for p in after) <= 400
    assert _path_mm(after) >= 1000
    # the left-follow LEDs: 6 on, 2 off
    led6 = [r for r in records if r["kind"] == "led" and r["name"] == "led6"]
    assert led6 and led6[-1]["state"] == 1 and led6[-1]["ring"][2] == "0"


def _square_expectation():
    """Where GCtronic's constants take the robot: sides of 800 steps, turns
    until the left wheel has gone back 330 steps (the right forward as
    much), on the default geometry; the corners as they turn out."""
    side = 800 * MM_PER_STEP
    turn = 2 * 330 * MM_PER_STEP / AXLE_MM
    return side, math.degrees(turn)


def test_the_square_closes_as_gctronics_constants_make_it(demos, tmp_path):
    records, _ = _run(demos, tmp_path, "square", "--time-limit", "45s")
    poses = pose_records(records)
    side, turn_deg = _square_expectation()
    # the corners: where the heading starts to change after a side
    corners, straight_since = [], 0
    for a, b in zip(poses, poses[1:]):
        if b["heading_deg"] != a["heading_deg"] and straight_since is not None:
            corners.append(a)
            straight_since = None
        elif b["heading_deg"] == a["heading_deg"] and straight_since is None:
            straight_since = b["t_ms"]
    for c0, c1 in zip(corners, corners[1:4]):
        assert math.hypot(c1["x_mm"] - c0["x_mm"], c1["y_mm"] - c0["y_mm"]) == \
            pytest.approx(side, abs=2.0)
        turned = (c1["heading_deg"] - c0["heading_deg"]) % 360
        assert turned == pytest.approx(turn_deg, abs=1.0)
    # four sides and corners later the robot is where the constants take
    # it: back near its corner, off by what four turns of 91.9 degrees make
    assert len(corners) >= 5
    expected = [sum(side * f(math.radians(k * turn_deg)) for k in range(1, 5))
                for f in (math.cos, math.sin)]
    moved = [corners[4]["x_mm"] - corners[0]["x_mm"], corners[4]["y_mm"] - corners[0]["y_mm"]]
    assert math.dist(moved, expected) < 5
    assert math.hypot(*moved) < 30


def test_the_square_runs_in_a_world(demos, tmp_path):
    require_enki()
    world = "arena 100 cm x 100 cm\nrobot at 40 cm, 40 cm heading 0 deg\n"
    records, _ = _run(demos, tmp_path, "square", "--time-limit", "36s", world=world)
    poses = pose_records(records)
    end = [p for p in poses if p["t_ms"] == 34600][0]   # after four sides and corners
    assert math.dist((end["x_mm"], end["y_mm"]), (400.0, 400.0)) < 40
    assert _contacts(records) == 0


def test_the_avoiders_overflow_shows_on_the_16_bit_path(demos, tmp_path):
    """shock_neuron's `matrix_prox[m][s]*e_get_calibrated_prox(s)` is an int
    product: -16 * 2100 wraps on the dsPIC's 16 bits. On the host the robot
    turns away from what its front-left sensor sees; with --int16, as on the
    robot, the wrapped sum drives it straight on."""
    require_tool("avr-gcc")
    require_tool("simavr")
    reading = 2100
    assert -16 * reading < -32768
    scenario = tmp_path / "left.scn"
    scenario.write_text(f"0 ms ir7=0\n2000 ms ir7={reading}\n2300 ms ir7=0\n")
    host, _ = _run(demos, tmp_path, "shocker", "--scenario", scenario, "--time-limit", "2400ms")
    avr, _ = _run(demos, tmp_path, "shocker", "--scenario", scenario, "--time-limit", "2400ms",
                  "--int16")
    turned = lambda r: r[-1]["left_steps"] - r[-1]["right_steps"]    # noqa: E731
    assert turned(host) > 300           # full speed apart for most of 0.3 s
    assert turned(avr) == 0
