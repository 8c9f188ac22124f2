"""Sound in worlds (issue 46): `sound` lines (a point, a frequency, a level,
on and off at set times) read with their errors at file:line:col; each
robot's three microphones hearing them through Enki's microphone model on
the robot's scale (e_get_micro_volume's peak-to-peak A/D units); the
robots that play a sample heard by the others for its length; a robot
that turns toward a sound source and drives to it; GCtronic's own
sound-detection demo lighting the LED of the side a sound comes from; the
sources drawn on the picture and lit in the replay while they play."""
import json
import math
import re
import subprocess

import pytest

from conftest import require_checkout, require_enki, require_tool
from epuckc.sim.replay import replay_html
from epuckc.sim.world import WorldError, parse_world
from tests.support.programs import EXAMPLES, epuckc

FULL_SCALE = 4095


def world(tmp_path, text, name="w.world"):
    path = tmp_path / name
    path.write_text(text)
    return parse_world(path, shown=name)


def test_sound_lines_become_the_sources(tmp_path):
    w = world(tmp_path, "arena 100 cm x 50 cm\n"
                        "sound at 60 cm, 40 cm frequency 2 kHz level 70 dB from 1 s to 3 s "
                        "from 4 s\n"
                        "sound at 10 cm, 10 cm\n")
    a, b = w.sounds
    assert (a.x_mm, a.y_mm, a.frequency_hz, a.level_db) == (600, 400, 2000, 70)
    assert a.intervals == ((1000, 3000), (4000, None))
    assert (b.frequency_hz, b.level_db, b.intervals) == (1000, 80, ())
    assert w.to_json()["sounds"][0]["on_ms"] == [[1000, 3000], [4000, None]]
    assert "sounds" not in world(tmp_path, "arena 1 m x 1 m\n", "quiet.world").to_json()


@pytest.mark.parametrize("line, col, words", [
    ("sound 60 cm, 40 cm", 7, "expected `at`"),
    ("sound at 60 cm, 40 cm frequency 5 Hz", 33, "a frequency is from 20 Hz to 20 kHz"),
    ("sound at 60 cm, 40 cm frequency 1000", 33, "the frequency 1000 has no unit"),
    ("sound at 60 cm, 40 cm level 200 dB", 29, "a level is from 0 dB to 140 dB"),
    ("sound at 60 cm, 40 cm level 80 dB level 70 dB", 35, "a second `level`"),
    ("sound at 60 cm, 40 cm from 3 s to 1 s", 35, "goes off at 1000 ms, not after it comes on"),
    ("sound at 60 cm, 40 cm from 1 s to 3 s from 2 s", 39, "begins before the one before it ends"),
    ("sound at 60 cm, 40 cm from 1 s from 2 s", 32, "begins before the one before it ends"),
    ("sound at 60 cm, 40 cm loud", 23, "unexpected `loud`"),
    ("sound at 160 cm, 40 cm", 1, "this sound source is outside the arena"),
])
def test_a_broken_sound_line_says_where_and_how_to_fix_it(tmp_path, line, col, words):
    with pytest.raises(WorldError) as exc:
        world(tmp_path, f"arena 100 cm x 50 cm\n{line}\n")
    message = str(exc.value)
    assert message.startswith(f"w.world:2:{col}: error:") and words in message, message


PROBE = ("var m0 = 0\nvar m1 = 0\nvar m2 = 0\n"
         "every 10 ms do m0 = mic0, m1 = mic[1], m2 = mic2\n")


def _run(program, tmp_path, world_text, limit="2s", name="run", extra=()):
    path = tmp_path / f"{name}.world"
    path.write_text(world_text)
    trace = tmp_path / f"{name}.jsonl"
    result = epuckc("run", program, "--world", path, "--trace", trace, "--time-limit", limit,
                    *extra)
    assert result.returncode in (0, 3), result.stdout + result.stderr
    return [json.loads(line) for line in trace.read_text().splitlines()]


def _heard(records):
    """robot -> [(t_ms, (mic0, mic1, mic2))] at each change."""
    now, out = {}, {}
    for r in records:
        if r["kind"] == "set" and r["var"] in ("m0", "m1", "m2"):
            robot = r.get("robot", "r1")
            values = now.setdefault(robot, [0, 0, 0])
            values[int(r["var"][1])] = r["value"]
            out.setdefault(robot, []).append((r["t_ms"], tuple(values)))
    return out


def _at(changes, t_ms):
    values = (0, 0, 0)
    for t, v in changes:
        if t > t_ms:
            break
        values = v
    return values


def test_microphones_hear_a_source_while_it_plays_less_farther_and_louder_on_its_side(tmp_path):
    require_enki()
    (tmp_path / "probe.epk").write_text(PROBE)
    # the source straight ahead of `near` and `far` (twice as far), to the left of `side`
    records = _run(tmp_path / "probe.epk", tmp_path,
                   "arena 300 cm x 100 cm\n"
                   "sound at 150 cm, 50 cm level 80 dB from 500 ms to 1 s\n"
                   "robot near at 110 cm, 50 cm\nrobot far at 70 cm, 50 cm\n"
                   "robot side at 150 cm, 10 cm heading 0 deg\n")
    heard = _heard(records)
    near, far, side = (_at(heard[n], 750) for n in ("near", "far", "side"))
    assert all(v == (0, 0, 0) for v in (_at(heard["near"], 450), _at(heard["near"], 1200)))
    assert near[0] == near[1] and far[0] == far[1]        # right and left alike: ahead
    # the amplitude falls as 1 / distance: the microphones are 8.35 mm ahead of the centre
    assert near[0] / far[0] == pytest.approx(math.hypot(800 - 8.35, 30.3)
                                             / math.hypot(400 - 8.35, 30.3), rel=0.01)
    assert near[2] < near[0]                             # the back microphone: farther
    assert side[1] > side[0]                             # left (mic1) nearer than right
    # the scale: 80 dB SPL at 1 m is 20 dB below the 100 dB that fill the 12 bits
    calibrate = _run(tmp_path / "probe.epk", tmp_path,
                     "arena 300 cm x 300 cm\nsound at 150 cm, 150 cm level 80 dB\n"
                     "robot at 150 cm, 50 cm heading 90 deg\n", limit="100ms", name="scale")
    m0, m1, _ = _at(_heard(calibrate)["r1"], 50)
    distance_m = math.hypot(1000 - 8.35, 30.3) / 1000
    assert m0 == m1 == pytest.approx(FULL_SCALE * 10 ** (-20 / 20) / distance_m, abs=2)


def test_a_robot_that_plays_a_sample_is_heard_for_the_samples_length(tmp_path):
    require_enki()
    (tmp_path / "probe.epk").write_text(PROBE)
    (tmp_path / "player.epk").write_text(PROBE + "after 1 s do play_sound(haa)\n"
                                         "after 2 s do play_sound(wouaaaaaaaah)\n")
    records = _run(tmp_path / "probe.epk", tmp_path,
                   f"arena 100 cm x 100 cm\nrobot a at 20 cm, 50 cm program "
                   f"{tmp_path / 'player.epk'}\nrobot b at 50 cm, 50 cm\n", limit="3500ms")
    heard = _heard(records)
    for robot in ("a", "b"):
        spans, start = [], None
        for t, values in heard[robot]:
            if max(values) > 0 and start is None:
                start = t
            elif max(values) == 0 and start is not None:
                spans.append((start, t))
                start = None
        # it plays from 1001 ms and 2001 ms (after 1 s, after 2 s); the
        # microphones hear it from the next physics step (10 ms), for its
        # words at the codec's 7200 a second (read every 10 ms)
        assert [s for s, _ in spans] == [1011, 2011], (robot, spans)
        lengths = [e - s for s, e in spans]
        assert abs(lengths[0] - 2112 / 7.2) <= 10 and abs(lengths[1] - 8016 / 7.2) <= 10, lengths
    # the player hears itself louder than its neighbour 30 cm away does
    assert max(_at(heard["a"], 1100)) > 5 * max(_at(heard["b"], 1100)) > 0


CLAP = "var heard = 0\non clap(600) repeat do heard = heard + 1, led_on(body)\n"


def test_a_clap_rule_fires_at_each_burst_a_robot_hears_loud_enough(tmp_path):
    """`on clap(V) repeat` over a world's sound: it fires as each burst
    begins (a rising edge of the microphones' volume, each time), and not
    for a robot so far away that the sound is under V there; the robots
    poll nothing else, so the world's sound itself wakes them."""
    require_enki()
    (tmp_path / "clap.epk").write_text(CLAP)
    records = _run(tmp_path / "clap.epk", tmp_path,
                   "arena 300 cm x 100 cm\n"
                   "sound at 30 cm, 50 cm level 85 dB from 1 s to 1200 ms from 2 s to 2100 ms\n"
                   "robot near at 30 cm, 30 cm heading 90 deg\n"
                   "robot far at 270 cm, 50 cm heading 180 deg\n", limit="3s", name="clap")
    fired = {}
    for r in records:
        if r["kind"] == "event" and "on clap(600)" in r["name"]:
            fired.setdefault(r.get("robot", "r1"), []).append(r["t_ms"])
    assert "far" not in fired, fired
    assert len(fired["near"]) == 2, fired
    for t, start in zip(fired["near"], (1000, 2000)):
        assert start <= t <= start + 20, fired


def _heading_error(pose, source):
    bearing = math.degrees(math.atan2(source[1] - pose["y_mm"], source[0] - pose["x_mm"]))
    return abs((bearing - pose["heading_deg"] + 180) % 360 - 180)


def test_the_sound_follower_turns_toward_the_source_and_drives_to_it(tmp_path):
    """examples/sound_follower.epk in examples/sound.world, and with the
    source moved to the other side of the robot: it turns the other way."""
    require_enki()
    text = (EXAMPLES / "sound.world").read_text()
    [source] = parse_world(EXAMPLES / "sound.world").sounds
    moved = text.replace("sound at 100 cm, 60 cm", "sound at 30 cm, 75 cm")
    for name, world_text, at in (("example", text, (source.x_mm, source.y_mm)),
                                 ("moved", moved, (300, 750))):
        records = _run(EXAMPLES / "sound_follower.epk", tmp_path, world_text, limit="25s",
                       name=name, extra=("--pose-interval", "100ms"))
        poses = [r for r in records if r["kind"] == "pose"]
        before = [p for p in poses if p["t_ms"] < 1000]
        assert max(math.dist((p["x_mm"], p["y_mm"]), (300, 250)) for p in before) < 1
        assert _heading_error(before[-1], at) > 90          # it starts facing away
        # within 4 s of the sound's start it faces it, and it keeps facing it
        facing = [p for p in poses if 5000 <= p["t_ms"] and
                  math.dist((p["x_mm"], p["y_mm"]), at) > 150]
        assert facing and max(_heading_error(p, at) for p in facing) < 15, name
        end = poses[-1]
        assert math.dist((end["x_mm"], end["y_mm"]), at) < 150, (name, end)
    # the turns went opposite ways: the first source is to its right, the second to its left
    turned = {}
    for name in ("example", "moved"):
        records = [json.loads(line) for line in (tmp_path / f"{name}.jsonl").read_text()
                   .splitlines()]
        poses = [r for r in records if r["kind"] == "pose" and 1000 <= r["t_ms"] <= 1500]
        turned[name] = sum((b["heading_deg"] - a["heading_deg"] + 180) % 360 - 180
                           for a, b in zip(poses, poses[1:]))
    assert turned["example"] * turned["moved"] < 0


DETECT_MAIN = ('#include <a_d/advance_ad_scan/e_ad_conv.h>\n#include "rundetectsound.h"\n'
               "int main(void) { e_init_ad_scan(ALL_ADC); run_detectsound(); return 0; }\n")


def test_gctronic_sound_demo_lights_the_led_of_the_side_a_sound_comes_from(tmp_path):
    """GCtronic's rundetectsound.c (DemoGCtronic-complete), byte for byte
    from EPUCK_LIB: a microphone louder than 1000 over its level at start
    lights LED1 (microphone 0, right), LED7 (1, left) or LED4 (2, back) for
    a second, then it listens again. Sounds from the robot's left, right and
    back in turn, each 1.6 s long: the demo lights an LED as each begins,
    and, listening again a second later while it still plays, the LED of
    its side, until a second after the sound ends. (At a sound's first millisecond the demo may pick another
    microphone: it reads the three one after the other, and the sound can
    begin between two reads, as on the robot.)"""
    require_enki()
    demos = require_checkout(
        "EPUCK_LIB", "program/DemoGCtronic-complete",
        "EPUCK_LIB does not name a checkout of GCtronic's e-puck library") \
        / "program" / "DemoGCtronic-complete"
    (tmp_path / "main_detect.c").write_text(DETECT_MAIN)
    path = tmp_path / "detect.world"
    path.write_text("arena 100 cm x 70 cm\nrobot at 50 cm, 35 cm heading 0 deg\n"
                    "sound at 50 cm, 60 cm level 85 dB from 200 ms to 1800 ms\n"     # left
                    "sound at 50 cm, 10 cm level 85 dB from 2400 ms to 4000 ms\n"    # right
                    "sound at 25 cm, 35 cm level 85 dB from 4600 ms to 6200 ms\n")   # back
    trace = tmp_path / "detect.jsonl"
    result = epuckc("run", tmp_path / "main_detect.c", demos / "rundetectsound.c", "--world",
                    path, "--time-limit", "6500ms", "--trace", trace)
    assert result.returncode == 3, result.stdout + result.stderr
    changes = []                # (t, led, on): the LEDs as the eye sees them
    with trace.open() as f:
        for line in f:
            if '"kind": "led"' in line:
                r = json.loads(line)
                changes.append((r["t_ms"], r["name"], bool(r["state"])))

    def on_at(t):
        state = {}
        for when, name, on in changes:
            if when <= t:
                state[name] = on
        return {name for name, on in state.items() if on}

    for start, side in ((200, "led7"), (2400, "led1"), (4600, "led4")):
        # an LED as the sound begins ...
        assert any(on and start <= t < start + 100 for t, _, on in changes), (start, changes)
        # ... and, listening again a second later while it still plays, its
        # side's (turned off and on again at once: the eye sees it stay on)
        assert on_at(start + 1300) == {side}, (start, changes)
    # and off a second after the sound ends, before the next begins
    assert on_at(2399) == on_at(4599) == set(), changes


def test_the_picture_marks_the_sources_and_the_replay_lights_them_while_they_play(tmp_path):
    w = world(tmp_path, "arena 100 cm x 50 cm\n"
                        "sound at 30 cm, 20 cm frequency 500 Hz from 1 s to 2 s\n"
                        "sound at 70 cm, 20 cm\n")
    lines = [json.dumps(w.to_json())] + [json.dumps(
        {"t_ms": t, "robot": "r1", "kind": "pose", "name": "pose", "x_mm": 200.0,
         "y_mm": 200.0, "heading_deg": 0.0}) for t in (0, 3000)]
    page = tmp_path / "s.html"
    page.write_text(replay_html("\n".join(lines) + "\n", title="sound"))
    text = page.read_text()
    assert text.count('class="sound"') == 2
    assert "sound 500 Hz, 80 dB at 1 m, from 1 s to 2 s" in text
    assert "sound 1000 Hz, 80 dB at 1 m, all the time" in text
    chromium = require_tool("chromium")
    for at, first in ((500, "0"), (1500, "1"), (2500, "0")):
        dom = subprocess.run([chromium, "--headless", "--no-sandbox", "--disable-gpu",
                              "--dump-dom", page.as_uri() + f"#t={at}"],
                             capture_output=True, text=True, timeout=120).stdout
        playing = re.findall(r'<g class="sound"[^>]*data-playing="([01])"', dom)
        assert playing == [first, "1"], (at, playing)


def test_the_runner_gets_the_sources_in_cm_and_ms(tmp_path):
    from epuckc.sim.world import runner_spec
    w = world(tmp_path, "arena 100 cm x 50 cm\n"
                        "sound at 60 cm, 40 cm frequency 2 kHz level 70 dB from 1 s to 3 s "
                        "from 4 s\nsound at 10 cm, 10 cm\n")
    spec = runner_spec(w, [("/x/a.so", {})]).splitlines()
    assert [line for line in spec if line.startswith("sound ")] == [
        "sound 60.0 40.0 2000.0 70.0 2 1000 3000 4000 -1", "sound 10.0 10.0 1000.0 80.0 0"]
