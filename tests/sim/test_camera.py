"""The colour camera through the whole pipeline (issue 27): world objects'
colours, Enki's CircularCam, the runtime's one classifier (rt_colour in
runtime_c/rt_camera.c), `seen(COLOUR)` and `bearing(COLOUR)`."""
import math
import subprocess

import pytest

from epuckc.base.resources import LIBRARY_SIMULATION, RUNTIME_CORE

from conftest import require_enki, require_tool
from epuckc.sim.world import COLOURS
from epuckc.stdlib.table import COLOURS as CAMERA_COLOURS
from tests.support.world import EXAMPLES, REPO, pose_records, run

RUNTIME = REPO / "runtime_c"
ROBOT_MM = 37.0


def test_the_classifier_names_each_colour_a_world_gives(tmp_path):
    """The six colours the camera tells apart are themselves, seen through
    the camera's RGB565; white, grey and black are no colour."""
    names = list(COLOURS)
    rows = ",\n".join("{%d, %d, %d}" % COLOURS[n] for n in names)
    (tmp_path / "t.c").write_text(f"""
#include <stdio.h>
#include "epuckrt.h"
static const int rgb[][3] = {{ {rows} }};
int main(void) {{
    unsigned i;
    for (i = 0; i < sizeof rgb / sizeof rgb[0]; i++) {{
        /* as the camera gives it: 5, 6 and 5 bits */
        int r = rgb[i][0] & 0xF8, g = rgb[i][1] & 0xFC, b = rgb[i][2] & 0xF8;
        printf("%d\\n", rt_colour(r, g, b));
    }}
    return 0;
}}
""")
    cc = require_tool("cc")
    sources = [RUNTIME / n for n in (*RUNTIME_CORE, "rt_camera.c", "rt_idle.c")]
    sources += [RUNTIME / "platform" / "platform_host.c", RUNTIME / "host" / "scenario.c"]
    sources += [RUNTIME / n for n in LIBRARY_SIMULATION]
    exe = tmp_path / "t"
    subprocess.run([cc, "-std=c99", "-Wall", "-Wextra", "-Werror", "-pedantic",
                    f"-I{RUNTIME}", f"-I{RUNTIME / 'epuck_api'}", f"-I{RUNTIME / 'host'}",
                    f"-I{RUNTIME / 'epuck_api_unsimulated'}",
                    str(tmp_path / "t.c"), *map(str, sources), "-o", str(exe), "-lm"],
                   check=True)
    got = subprocess.run([str(exe)], capture_output=True, text=True, check=True).stdout.split()
    macros = {c.name: i + 1 for i, c in enumerate(CAMERA_COLOURS.values)}   # RT_RED 1 ...
    expected = [macros.get(n, 0) for n in names]
    assert [int(x) for x in got] == expected
    assert set(macros) <= set(names)        # every colour the camera knows, a world can give


def test_a_robot_finds_the_red_cylinder_past_the_green_one_and_drives_into_it(tmp_path):
    require_enki()
    world = EXAMPLES / "colour_seeker.world"
    records, _, _ = run(EXAMPLES / "colour_seeker.epk", tmp_path, "--world", world,
                        "--time-limit", "15s", "--pose-interval", "100ms", expect=None)
    [w] = [r for r in records if r["kind"] == "world"]
    green, red = ((c["x_mm"], c["y_mm"], c["radius_mm"]) for c in w["cylinders"])
    assert [c["colour"] for c in w["cylinders"]] == ["green", "red"]
    poses = pose_records(records)

    def in_view(p, c):
        a = math.degrees(math.atan2(c[1] - p["y_mm"], c[0] - p["x_mm"])) - p["heading_deg"]
        return abs((a + 180) % 360 - 180) < 30

    # it turned past the green one (in view before the red was) ...
    first_green = next(i for i, p in enumerate(poses) if in_view(p, green))
    first_red = next(i for i, p in enumerate(poses) if in_view(p, red))
    assert first_green < first_red
    # ... never went near it, and ended against the red one
    assert min(math.dist((p["x_mm"], p["y_mm"]), green[:2]) for p in poses) > green[2] + 100
    end = poses[-1]
    assert math.dist((end["x_mm"], end["y_mm"]), red[:2]) < red[2] + ROBOT_MM + 5
    # with both cylinders green it finds nothing and only turns
    both = tmp_path / "green.world"
    both.write_text(world.read_text().replace("colour red", "colour green")
                    .replace("robot seeker", "robot seeker").replace(
                        "heading 180 deg", f"heading 180 deg program "
                        f"{EXAMPLES / 'colour_seeker.epk'}"))
    records, _, _ = run(EXAMPLES / "colour_seeker.epk", tmp_path, "--world", both,
                        "--time-limit", "15s", "--pose-interval", "100ms", expect=None,
                        name="green")
    assert max(math.dist((p["x_mm"], p["y_mm"]), (200, 400)) for p in pose_records(records)) < 5


def test_bearing_is_positive_to_the_left_and_seen_grows_nearer(tmp_path):
    """A robot that stands still reads where a red cylinder is: to its left
    a positive bearing, to its right a negative one, and a wider run when
    it is nearer (the camera starts at the first reading, and takes 4.3
    frames a second in colour: what it read last)."""
    require_enki()
    (tmp_path / "look.epk").write_text(
        "var s = 0\nvar b = 0 deg\nevery 100 ms do s = seen(red), b = bearing(red)\n"
        "after 650 ms do exit_main\n")
    results = {}
    for name, (dx, dy) in {"left": (200, 100), "right": (200, -100), "near": (100, 50),
                           "far": (300, 150)}.items():
        world = tmp_path / f"{name}.world"
        world.write_text(f"arena 100 cm x 100 cm colour white\nrobot at 30 cm, 50 cm\n"
                         f"cylinder at {300 + dx} mm, {500 + dy} mm radius 2 cm colour red\n")
        records, _, _ = run(tmp_path / "look.epk", tmp_path, "--world", world, name=name)
        sets = {r["var"]: r["value"] for r in records if r["kind"] == "set"}    # the last
        results[name] = (sets.get("s", 0), sets.get("b", 0))
    for name, (dx, dy) in {"left": (200, 100), "right": (200, -100)}.items():
        true = math.degrees(math.atan2(dy, dx))
        seen, bearing = results[name]
        assert seen > 0 and abs(bearing - true) <= 3 + seen / 2
    assert results["left"][1] > 0 > results["right"][1]
    assert results["near"][0] > results["far"][0] > 0


def test_the_picture_fills_obstacles_with_their_world_colour():
    from epuckc.sim.plot import plot_trace
    import json
    import xml.etree.ElementTree as ET
    world = {"kind": "world", "arena": {"width_mm": 500, "height_mm": 500, "colour": "white"},
             "boxes": [{"x_mm": 100, "y_mm": 100, "length_mm": 50, "width_mm": 20,
                        "angle_deg": 0, "colour": "blue"}],
             "cylinders": [{"x_mm": 300, "y_mm": 300, "radius_mm": 30, "colour": "red"},
                           {"x_mm": 400, "y_mm": 100, "radius_mm": 30, "colour": "grey"}],
             "robots": [], "robot_radius_mm": 37}
    pose = {"t_ms": 0, "robot": "r1", "kind": "pose", "name": "pose", "x_mm": 250.0,
            "y_mm": 250.0, "heading_deg": 0.0}
    root = ET.fromstring(plot_trace(json.dumps(world) + "\n" + json.dumps(pose) + "\n"))
    fills = {e.get("class"): [] for e in root.iter()}
    for e in root.iter():
        if e.get("class") in ("box", "cylinder"):
            fills[e.get("class")].append(e.get("fill"))
    hexed = {n: "#%02x%02x%02x" % COLOURS[n] for n in ("blue", "red")}
    assert fills["box"] == [hexed["blue"]]
    assert fills["cylinder"][0] == hexed["red"] and fills["cylinder"][1] not in hexed.values()


@pytest.mark.parametrize("line, word", [
    ("cylinder at 10 cm, 10 cm radius 2 cm colour purple", "purple"),
    ("box at 10 cm, 10 cm size 2 cm x 2 cm colour 3", "3"),
    ("robot at 50 cm, 50 cm colour", None),
])
def test_a_colour_that_is_not_one_is_reported_with_its_place(tmp_path, line, word):
    from tests.support.world import epuckc
    column = line.index(word.strip(), line.index("colour")) + 1 if word else None
    path = tmp_path / "bad.world"
    path.write_text(f"arena 1 m x 1 m\n{line}\n")
    result = epuckc("check", path)
    out = result.stdout + result.stderr
    assert result.returncode == 1
    assert (f"bad.world:2:{column}:" if column else "bad.world:2:") in out
    assert "is not a colour of a world" in out or "expected a colour" in out
    assert "red, yellow, green" in out or "expected a colour" in out
