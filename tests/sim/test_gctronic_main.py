"""GCtronic's own program, as it ships: program/DemoGCtronic-complete's
main_c.c and every file of the demo (byte for byte from the checkout EPUCK_LIB
names; skipped without it, failed in CI), on the simulated e-puck, each demo
picked by the selector as on the robot, in a scenario or a world that
exercises it, and measured against what its source says it does. One build
of the program serves every test (and one robot of it every world).

main_c.c's last branch, run_breitenberg_shocker, is reached by no position
of the selector (0..15 are all taken): test_gctronic_demos.py runs it through
a main of its own."""
import json
import math

import pytest

from conftest import require_checkout, require_enki
from tests.support.programs import epuckc

FILES = ["main_c.c", "runaccelerometer.c", "runbreitenberg_adv.c", "rundetectsound.c",
         "rungrounddirection.c", "rungyroscope.c", "runshow.c", "runsquare.c", "runwallfollow.c",
         "translatorI2C.c", "Asercom.c", "DataEEPROM.s"]
MB_A_MINUTE = 3.0               # no demo's trace may grow faster


@pytest.fixture(scope="module")
def demo():
    folder = require_checkout(
        "EPUCK_LIB", "program/DemoGCtronic-complete/main_c.c",
        "EPUCK_LIB does not name a checkout of GCtronic's e-puck library (git clone "
        "https://github.com/gctronic/e-puck-library; the folder that holds program/)")
    return [folder / "program" / "DemoGCtronic-complete" / f for f in FILES]


def _run(demo, tmp_path, selector, *, scenario="", world=None, limit="5s", expect=3):
    """The demo of `selector`: its trace's records, epuckc's result."""
    name = f"sel{selector}"
    trace = tmp_path / f"{name}.jsonl"
    args = ["run", *demo, "--trace", trace, "--time-limit", limit, "--pose-interval", "100ms"]
    if world is None:
        path = tmp_path / f"{name}.scn"
        path.write_text(f"0 ms selector={selector}\n" + scenario)
        args += ["--scenario", path]
    else:
        path = tmp_path / f"{name}.world"
        path.write_text(world.format(selector=selector))
        args += ["--world", path]
    result = epuckc(*args)
    assert result.returncode == expect, result.stdout[-2000:] + result.stderr[-3000:]
    records = [json.loads(line) for line in trace.read_text().splitlines()]
    # GCtronic's main resets the chip at power-on, then reads the selector
    assert [r["kind"] for r in records if r["kind"] in ("reset", "uart")][:2] == ["reset", "uart"]
    assert f"Selector pos {selector}" in next(r["text"] for r in records if r["kind"] == "uart")
    end_ms = max(r.get("t_ms", 0) for r in records)
    robots = len(records[0]["robots"]) if records[0]["kind"] == "world" else 1
    size_mb = trace.stat().st_size / 1e6 / robots
    assert size_mb / max(end_ms, 1000) * 60000 < MB_A_MINUTE, (size_mb, end_ms)
    return records, result


def _ring(records, t_ms):
    """The ring's LEDs ("01000000": led0..led7) as the trace has them at t_ms."""
    ring = "00000000"
    for r in records:
        if r["kind"] == "led" and r["t_ms"] <= t_ms:
            ring = r["ring"]
    return ring


def _lit(records, t_ms) -> set:
    return {i for i, c in enumerate(_ring(records, t_ms)) if c == "1"}


def test_the_accelerometer_demo_lights_the_led_of_each_shock_and_plays_once(demo, tmp_path):
    """selector 0, run_accelerometer: a shock (two axes at the LSM330's 2 g,
    for 20 ms) lights the LED its atan2 formula gives for the shock's
    direction and plays one sample, for as long as the sample plays; free
    fall (0 g) lights the body LED and plays the long sample."""
    shocks = {"front": ("accy=512", "accx=2048"), "left": ("accx=512", "accy=2048"),
              "back": ("accy=3584", "accx=2048"), "right": ("accx=3584", "accy=2048")}
    lines, t = [], 1000
    for a, b in shocks.values():
        lines.append(f"{t} ms {a} {b} accz=3584\n{t + 20} ms accx=2048 accy=2048 accz=2816\n")
        t += 1500
    lines.append(f"{t} ms accx=2048 accy=2048 accz=2048\n{t + 300} ms accz=2816\n")
    records, _ = _run(demo, tmp_path, 0, scenario="".join(lines), limit=f"{t + 1500}ms")
    sounds = [r for r in records if r["kind"] == "sound"]
    assert len(sounds) == 5                          # one a shock, one the fall
    t = 1000
    for name, (a, b) in shocks.items():
        # the library's frame: x the robot's left, y its front; 2 g on two axes
        x = {"left": -1536, "right": 1536}.get(name, 0)
        y = {"front": -1536, "back": 1536}.get(name, 0)
        lednum = math.floor(math.atan2(y, x) / math.pi * 4 + math.pi / 2 + math.pi / 8) % 8
        assert _lit(records, t + 100) == {lednum}, (name, _ring(records, t + 100))
        assert any(s["t_ms"] - t < 10 for s in sounds if s["t_ms"] >= t), name
        t += 1500
    assert _lit(records, t - 200) == set()          # the sample ended: back to normal
    fall = [s for s in sounds if s["t_ms"] >= t]
    assert fall and fall[0]["name"] == "wouaaaaaaaah"
    body = [r for r in records if r["kind"] == "led" and r["name"] == "body" and r["t_ms"] >= t]
    assert body[0]["state"] == 1 and body[0]["t_ms"] - t < 60
    # the body LED goes off when the 8016 words (1113 ms at 7200 a second) ended
    off = next(r for r in body if r["state"] == 0)
    assert off["t_ms"] - fall[0]["t_ms"] == pytest.approx(1113, abs=6)


def test_the_sound_demo_lights_the_loudest_microphones_led_for_a_second(demo, tmp_path):
    """selector 1, run_detectsound: the LED of the loudest microphone (0:
    LED1, 1: LED7, 2: LED4) for one second of getDiffTimeMs."""
    scenario = "500 ms mic0=1500\n600 ms mic0=0\n2000 ms mic2=1800\n2100 ms mic2=0\n" \
               "3500 ms mic1=1200 mic2=1100\n3600 ms mic=0\n"
    records, _ = _run(demo, tmp_path, 1, scenario=scenario, limit="5s")
    for start, led in ((500, 1), (2000, 4), (3500, 7)):
        on = [r for r in records if r["kind"] == "led" and r["name"] == f"led{led}"
              and r["t_ms"] >= start]
        assert on[0]["state"] == 1 and on[0]["t_ms"] - start <= 2
        assert on[1]["state"] == 0 and on[1]["t_ms"] - on[0]["t_ms"] == pytest.approx(1000, abs=3)
    assert _lit(records, 1800) == set()


WALL_WORLD = """arena 150 cm x 100 cm
robot at 110 cm, 25 cm heading 200 deg selector {selector}
"""


def test_the_wall_follower_keeps_the_wall_on_its_left(demo, tmp_path):
    """selector 2, run_wallfollow (bit 0 clear: the wall on its left):
    along the bottom wall without touching it, LED6 on, LED2 off."""
    require_enki()
    records, _ = _run(demo, tmp_path, 2, world=WALL_WORLD, limit="60s")
    contacts = [r for r in records if r["kind"] == "contacts"][0]
    assert contacts["walls"] + contacts["objects"] == 0
    poses = [r for r in records if r["kind"] == "pose"]
    reached = next(p["t_ms"] for p in poses if p["y_mm"] <= 150)
    after = [p for p in poses if p["t_ms"] >= reached]
    assert max(p["y_mm"] for p in after) <= 400
    assert sum(math.dist((a["x_mm"], a["y_mm"]), (b["x_mm"], b["y_mm"]))
               for a, b in zip(after, after[1:])) >= 1000
    assert _ring(records, 60000)[6] == "1" and _ring(records, 60000)[2] == "0"


@pytest.mark.parametrize("selector,function,device", [(3, "e_i2cp_init", "the I2C bus"),
                                                      (7, "e_i2cp_init", "the I2C bus")])
def test_the_demos_that_need_i2c_run_up_to_it(demo, tmp_path, selector, function, device):
    """selector 3 (run_asercom: the floor sensors over I2C first) and 7
    (run_translatorI2C: its welcome on the UART first) run up to their first
    call of the I2C bus, which ends the run saying so."""
    records, result = _run(demo, tmp_path, selector, limit="2s", expect=6)
    assert records[-1]["kind"] == "unsimulated" and records[-1]["name"] == function
    assert f"epuckc: {function}: {device}" in result.stderr and "is not simulated" in result.stderr
    if selector == 7:
        assert "WELCOME to the RS232 - I2C translator" in "".join(
            r["text"] for r in records if r["kind"] == "uart")


def test_the_square_turns_by_gctronics_step_counts(demo, tmp_path):
    """selector 4, run_square: sides of 800 steps at 150 steps/s, turns until
    the left wheel went back 330 steps (the right as far forward), as its
    constants say: the corners where they take the robot."""
    from tests.sim.test_gctronic_demos import _square_expectation
    records, _ = _run(demo, tmp_path, 4, limit="27s")
    poses = [r for r in records if r["kind"] == "pose"]
    side, turn_deg = _square_expectation()
    corners, straight = [], True
    for a, b in zip(poses, poses[1:]):
        if b["heading_deg"] != a["heading_deg"] and straight:
            corners.append(a)
            straight = False
        elif b["heading_deg"] == a["heading_deg"]:
            straight = True
    assert len(corners) >= 3
    for c0, c1 in zip(corners, corners[1:3]):
        assert math.dist((c0["x_mm"], c0["y_mm"]), (c1["x_mm"], c1["y_mm"])) == \
            pytest.approx(side, abs=2.0)
        assert (c1["heading_deg"] - c0["heading_deg"]) % 360 == pytest.approx(turn_deg, abs=1.0)


SENS_WORLD = """arena 100 cm x 100 cm colour black
cylinder at 30 cm, 58 cm radius 5 cm colour white
cylinder at 70 cm, 58 cm radius 5 cm colour black
robot white at 30 cm, 48 cm heading 90 deg selector {selector}
robot dark at 70 cm, 48 cm heading 90 deg selector {selector}
"""


def test_the_sensor_display_reads_the_cameras_grey_light(demo, tmp_path):
    """selector 5, run_SensDispl: the camera's 20 x 20 grey pixels summed,
    the front LED on above 48000 (a mean of 120); the ring's LEDs of the
    proximity sensors above 400. Facing a white cylinder the sum
    is near 400 x 240 (a robot reads about 100,000 in a lit room); facing a
    black one, near 400 x 20. The cylinders' surfaces 1.3 cm before them:
    their front sensors above 400."""
    require_enki()
    records, _ = _run(demo, tmp_path, 5, world=SENS_WORLD, limit="3s")
    light = {}
    for r in records:
        if r["kind"] == "uart" and r["text"].startswith("Cam light"):
            light.setdefault(r["robot"], []).append(int(r["text"].split()[2]))
    assert 90000 <= light["white"][-1] <= 400 * 255
    assert light["dark"][-1] <= 12000
    # lit for the 2 ms of wait(5000) after each capture of the white
    flashes = {}
    for r in records:
        if r["kind"] == "led" and r["name"] == "front" and r["state"] == 1:
            flashes[r["robot"]] = flashes.get(r["robot"], 0) + 1
    assert flashes.get("white", 0) >= len(light["white"]) - 2 and "dark" not in flashes
    # the cylinder in front: the front sensors' LEDs (0 and 7)
    last = {r["robot"]: r["ring"] for r in records if r["kind"] == "led"}
    assert last["white"][0] == "1" and last["white"][7] == "1"


LIGHT_WORLD = """arena 200 cm x 200 cm
cylinder at {x} cm, {y} cm radius 2 cm colour white
robot at 100 cm, 100 cm heading 0 deg selector {{selector}}
"""


def test_the_camera_turn_stops_with_the_light_at_the_images_middle(demo, tmp_path):
    """selector 6, run_CameraTurn: a window one column wide and 60 rows
    tall (what its ReadEE's value, the page, makes it choose: the camera
    "not rotated"), grey; the first of the lightest pixels (in the order of
    a capture mirrored by e_poxxxx_set_mirror(1,1): from the left) turned to
    the middle (pixel 30): the robot turns left toward a white light 35
    degrees to its left and stops with the light's left edge there."""
    require_enki()
    bearing = 35.0
    x = 100 + 40 * math.cos(math.radians(bearing))
    y = 100 + 40 * math.sin(math.radians(bearing))
    records, _ = _run(demo, tmp_path, 6, world=LIGHT_WORLD.format(x=round(x, 2), y=round(y, 2)),
                      limit="12s")
    poses = [r for r in records if r["kind"] == "pose"]
    # the light's left edge (2 cm at 40 cm: 2.9 degrees) at the middle
    edge = bearing + math.degrees(math.asin(2 / 40))
    final = poses[-1]["heading_deg"]
    assert final == pytest.approx(edge, abs=3.0)
    late = [p["heading_deg"] for p in poses if p["t_ms"] >= poses[-1]["t_ms"] - 3000]
    assert max(late) - min(late) <= 1.0             # stopped there, not dithering
    # LED0 (the light ahead) flashes for the 2 ms of wait(5000) after each frame
    flashes = {r["name"] for r in records if r["kind"] == "led" and r["state"] == 1
               and r["t_ms"] >= poses[-1]["t_ms"] - 3000}
    assert flashes == {"led0"}


def test_the_ground_direction_lights_the_led_toward_the_floor(demo, tmp_path):
    """selector 8, run_grounddirection: e_display_angle's LED toward the
    ground as the robot is tilted by 30 degrees to each side (the
    accelerometer's x the robot's left, y its front)."""
    s, c = 768 * math.sin(math.radians(30)), 768 * math.cos(math.radians(30))
    tilts = {0: (0, -s), 6: (-s, 0), 4: (0, s), 2: (s, 0),
             7: (-s / math.sqrt(2), -s / math.sqrt(2))}
    lines, t = [], 500
    for x, y in tilts.values():
        lines.append(f"{t} ms accx={round(2048 + x)} accy={round(2048 + y)} "
                     f"accz={round(2048 + c)}\n")
        t += 500
    records, _ = _run(demo, tmp_path, 8, scenario="".join(lines), limit=f"{t}ms")
    t = 500
    for led in tilts:
        assert _lit(records, t + 400) == {led}, (led, _ring(records, t + 400))
        t += 500


def test_the_gyroscope_bar_is_steady_at_a_steady_turn(demo, tmp_path):
    """selector 9, run_gyroscope: turned by hand at 120 degrees/s about z,
    LEDs 0, 7, 6 and 5 (27 degrees/s each) stay on, the others off, not one
    change while the rate holds; at -230 degrees/s all eight, and the long
    sample once; about x at 200 degrees/s, LEDs 0..4 and the body."""
    scenario = "1000 ms rotz=120\n3000 ms rotz=-230\n5000 ms rotz=0 rotx=200\n7000 ms rotx=0\n"
    records, _ = _run(demo, tmp_path, 9, scenario=scenario, limit="8s")
    leds = [r for r in records if r["kind"] == "led"]
    steady = [r for r in leds if 1100 <= r["t_ms"] < 3000]
    assert steady == [] and _lit(records, 2900) == {0, 7, 6, 5}
    assert [r for r in leds if 3100 <= r["t_ms"] < 5000] == []
    assert _lit(records, 4900) == set(range(8))
    sounds = [r for r in records if r["kind"] == "sound"]
    assert len(sounds) == 1 and 3000 <= sounds[0]["t_ms"] <= 3100
    assert _lit(records, 6900) == {0, 1, 2, 3, 4}
    assert [r for r in leds if r["name"] == "body" and r["t_ms"] < 6900][-1]["state"] == 1
    assert _lit(records, 7900) == set()


FOLLOW_WORLD = """arena 100 cm x 60 cm
robot at 40 cm, 30 cm heading 0 deg selector {selector}
"""


def test_the_follower_holds_its_distance_to_the_wall(demo, tmp_path):
    """selector 14, run_breitenberg_follower: up to the wall ahead, and
    there at a distance held steady."""
    require_enki()
    records, _ = _run(demo, tmp_path, 14, world=FOLLOW_WORLD, limit="20s")
    poses = [r for r in records if r["kind"] == "pose"]
    late = [p["x_mm"] for p in poses if p["t_ms"] >= 12000]
    gap = 1000 - max(late)
    assert 40 <= gap <= 150 and max(late) - min(late) <= 15
    contacts = [r for r in records if r["kind"] == "contacts"][0]
    assert contacts["walls"] == 0


DUST_WORLD = """arena 150 cm x 150 cm
robot open at 40 cm, 75 cm heading 90 deg selector {selector}
robot wall at 143 cm, 75 cm heading 0 deg selector {selector}
"""


def _curvature(a, b, c) -> float:
    """1 / the radius of the circle through three points (mm)."""
    ab, bc, ca = (math.dist((p["x_mm"], p["y_mm"]), (q["x_mm"], q["y_mm"]))
                  for p, q in ((a, b), (b, c), (c, a)))
    cross = abs((b["x_mm"] - a["x_mm"]) * (c["y_mm"] - a["y_mm"])
                - (b["y_mm"] - a["y_mm"]) * (c["x_mm"] - a["x_mm"]))
    return 2 * cross / (ab * bc * ca) if ab * bc * ca else 0.0


def test_the_dust_cleaner_spirals_out_and_avoids_the_walls(demo, tmp_path):
    """selector 15, run_DustCleaner: in the open a spiral (the right wheel
    from 100 steps/s up, a step each turn of its loop: the radius grows),
    near a wall the weighted sum turns it away; it never stays in contact."""
    require_enki()
    records, _ = _run(demo, tmp_path, 15, world=DUST_WORLD, limit="20s")
    poses = [r for r in records if r["kind"] == "pose" and r["robot"] == "open"]
    assert not any(r["kind"] == "led" and r["name"] == "body" and r["robot"] == "open"
                   for r in records)        # nothing in its way
    early = sum(_curvature(*poses[i:i + 3]) for i in range(5, 10)) / 5
    later = sum(_curvature(*poses[i:i + 3]) for i in range(25, 30)) / 5
    assert early > 2 * later                    # the spiral opens
    # the other, 3 cm from a wall: near it (the body LED on) it turns away,
    # never more than a few physics steps in contact
    body = [r for r in records if r["kind"] == "led" and r["name"] == "body"
            and r["robot"] == "wall"]
    assert sum(r["state"] for r in body) >= 2
    near = [r for r in records if r["kind"] == "pose" and r["robot"] == "wall"]
    moved = sum(math.dist((a["x_mm"], a["y_mm"]), (b["x_mm"], b["y_mm"]))
                for a, b in zip(near[100:], near[101:]))
    assert moved > 300                          # not stuck there: on along the wall
    contacts = {r["robot"]: r for r in records if r["kind"] == "contacts"}
    assert contacts["wall"]["walls"] <= 5 and contacts["open"]["walls"] == 0
