"""The floor of a world and the ground sensors that read it (issue 46):
`floor` lines (an image spanning the arena, drawn lines and regions) read
with their errors at file:line:col, the one raster both the physics and
the pictures take, Enki's ground sensors under the robots, Aseba's
track-following example following a closed track for two minutes (the
time its centre stays within the line's width, measured), and the floor
drawn under the robots."""
import base64
import io
import json
import math
import xml.etree.ElementTree as ET

import pytest

from conftest import require_enki
from epuckc.sim import floor as floor_lines
from epuckc.sim.plot import plot_trace
from epuckc.sim.replay import replay_html
from epuckc.sim.world import WorldError, parse_world
from tests.support.programs import EXAMPLES, epuckc

Image = pytest.importorskip("PIL.Image")


def world(tmp_path, text, name="w.world"):
    path = tmp_path / name
    path.write_text(text)
    return parse_world(path, shown=name)


def error_of(tmp_path, text) -> str:
    with pytest.raises(WorldError) as exc:
        world(tmp_path, text)
    return str(exc.value)


def test_floor_lines_become_the_floor(tmp_path):
    Image.new("RGB", (4, 2), "white").save(tmp_path / "t.png")
    w = world(tmp_path, "arena 100 cm x 50 cm\nfloor \"t.png\"\nfloor colour grey\n"
                        "floor line from 10 cm, 10 cm to 50 cm, 10 cm to 50cm, 40 cm width 2 cm\n"
                        "floor polygon from 0 cm, 0 cm to 10 cm, 0 cm to 0 cm, 10 cm colour red\n"
                        "floor circle at 70 cm, 25 cm radius 10 cm width 1 cm colour blue\n"
                        "floor ellipse at 50 cm, 25 cm size 80 cm x 40 cm angle 10 deg width 3 cm\n"
                        "floor rectangle at 20 cm, 30 cm size 10 cm x 4 cm\n")
    f = w.floor
    assert f.image == tmp_path / "t.png" and f.colour == "grey"
    line, polygon, circle, ellipse, rect = f.shapes
    assert line.points == ((100, 100), (500, 100), (500, 400)) and line.width_mm == 20
    assert not line.closed and line.colour == "black"
    assert polygon.width_mm is None and polygon.closed and polygon.colour == "red"
    assert circle.size == (100, 100) and circle.width_mm == 10
    assert ellipse.angle_deg == 10 and ellipse.size == (800, 400)
    assert rect.width_mm is None
    # an outline goes round its shape: the ellipse's points lie on it
    t = math.radians(10)
    for x, y in ellipse.outline():
        u = (x - 500) * math.cos(t) + (y - 250) * math.sin(t)
        v = -(x - 500) * math.sin(t) + (y - 250) * math.cos(t)
        assert (u / 400) ** 2 + (v / 200) ** 2 == pytest.approx(1)


@pytest.mark.parametrize("text, where, words", [
    ("floor colour grey\n", "w.world:1:1:", "a floor spans the arena, and this world has none"),
    ("arena 1 m x 1 m\nfloor\n", "w.world:2:6:", "`floor` needs an image, a colour or a shape"),
    ("arena 1 m x 1 m\nfloor line from 1 cm, 1 cm width 2 cm\n", "w.world:2:28:",
     "a floor line needs at least 2 points"),
    ("arena 1 m x 1 m\nfloor line from 1 cm, 1 cm to 5 cm, 1 cm\n", "w.world:2:41:",
     "a floor line needs a width"),
    ("arena 1 m x 1 m\nfloor circle at 5 cm, 5 cm radius -1 cm\n", "w.world:2:35:",
     "the radius must be positive"),
    ("arena 1 m x 1 m\nfloor triangle at 5 cm, 5 cm\n", "w.world:2:7:",
     "unknown floor item `triangle`"),
    ("arena 1 m x 1 m\nfloor circle at 5 cm, 5 cm radius 1 cm closed\n", "w.world:2:40:",
     "unexpected `closed`"),
    ("arena 1 m x 1 m\nfloor colour grey\nfloor colour white\n", "w.world:3:7:",
     "a second floor colour (the first is line 2)"),
    ("arena 1 m x 1 m\nfloor \"missing.png\"\n", "w.world:2:7:",
     "the image missing.png does not exist"),
    ("arena 1 m x 1 m\nfloor colour pink\n", "w.world:2:14:", "`pink` is not a colour"),
])
def test_a_broken_floor_line_says_where_and_how_to_fix_it(tmp_path, text, where, words):
    message = error_of(tmp_path, text)
    assert message.startswith(where) and words in message, message
    assert "\nhelp: " in message or "^" in message


def test_a_floor_image_must_be_a_png_pillow_reads(tmp_path):
    (tmp_path / "notes.png").write_text("not an image")
    Image.new("RGB", (8, 8)).save(tmp_path / "photo.jpg")
    assert "is not an image Pillow can read" in error_of(tmp_path, "arena 1 m x 1 m\n"
                                                                   "floor notes.png\n")
    message = error_of(tmp_path, 'arena 1 m x 1 m\nfloor image "photo.jpg"\n')
    assert "photo.jpg is a JPEG image, not a PNG" in message and "save it as PNG" in message


def _pixel(w, im, x_mm, y_mm):
    """The raster's colour at a point of the arena (its top row is y = height)."""
    return im.getpixel((min(im.width - 1, int(x_mm / w.width_mm * im.width)),
                        min(im.height - 1, int((w.height_mm - y_mm) / w.height_mm * im.height))))


def test_the_raster_paints_the_shapes_in_order_over_the_image(tmp_path):
    # an image whose left half is blue and whose top is not its bottom
    picture = Image.new("RGB", (20, 10), "white")
    for x in range(10):
        for y in range(10):
            picture.putpixel((x, y), (0, 0, 255))
    picture.putpixel((19, 0), (255, 0, 0))             # the top right corner: red
    picture.save(tmp_path / "half.png")
    w = world(tmp_path, "arena 100 cm x 50 cm\nfloor \"half.png\"\n"
                        "floor circle at 75 cm, 25 cm radius 10 cm width 2 cm\n"
                        "floor rectangle at 75 cm, 25 cm size 4 cm x 4 cm colour green\n")
    im = floor_lines.raster(w)
    assert im.size == (500, 250)            # MM_PER_PX: 2 mm a pixel
    assert _pixel(w, im, 20, 20)[2] > 200 and _pixel(w, im, 20, 20)[0] < 60     # blue half
    assert _pixel(w, im, 600, 200) == (255, 255, 255)
    assert _pixel(w, im, 998, 498)[0] > 150 > _pixel(w, im, 998, 498)[1]     # red: top right
    assert _pixel(w, im, 750 + 100, 250) == floor_lines.COLOURS["black"]      # on the ring
    assert _pixel(w, im, 750 + 70, 250) == (255, 255, 255)                    # inside it
    assert _pixel(w, im, 750, 250) == floor_lines.COLOURS["green"]
    # Enki's texture starts at y = 0: its first row is the raster's last
    tw, th, data = floor_lines.texture(w)
    assert (tw, th) == im.size and len(data) == 3 * tw * th
    assert tuple(data[3 * (tw - 1):3 * tw]) == _pixel(w, im, 999, 1)
    assert tuple(data[-3:]) == _pixel(w, im, 999, 499)


def test_a_line_is_as_wide_as_it_says_with_no_gap_at_its_joins(tmp_path):
    w = world(tmp_path, "arena 100 cm x 100 cm\n"
                        "floor line from 10 cm, 10 cm to 90 cm, 10 cm to 50 cm, 80 cm closed "
                        "width 3 cm\n")
    im = floor_lines.raster(w)
    black = floor_lines.COLOURS["black"]
    across = [_pixel(w, im, 500, y) == black for y in range(70, 131, 2)]
    assert 14 <= sum(across) <= 16                   # 30 mm at 2 mm a pixel
    # every point of the outline is inked, the corners included
    for x, y in [(100, 100), (900, 100), (500, 800), (300, 450), (700, 450)]:
        assert _pixel(w, im, x, y) == black


def _run(program, tmp_path, world_path, *extra, name="run"):
    trace = tmp_path / f"{name}.jsonl"
    result = epuckc("run", program, "--world", world_path, "--trace", trace, *extra)
    assert result.returncode in (0, 3), result.stdout + result.stderr
    return [json.loads(line) for line in trace.read_text().splitlines()]


PROBE = ("var g0 = 0\nvar g1 = 0\nvar g2 = 0\n"
         "after 100 ms do g0 = ground0, g1 = ground[1], g2 = ground2\n"
         "after 150 ms do exit_main\n")


def _readings(records):
    """Each robot's variables as set (a variable left at its 0 has no record)."""
    got = {"black": {}, "edge": {}}
    for r in records:
        if r["kind"] == "set":
            got.setdefault(r.get("robot", "r1"), {})[r["var"]] = r["value"]
    return got


def test_the_ground_sensors_read_the_floor_under_them(tmp_path):
    """Over black the module reads near 0, over white near 1000; a robot
    astride the edge reads black on its left sensor and white on its right
    (ground0 is 1 cm left of ground2's 1 cm right, 3 cm ahead)."""
    require_enki()
    picture = Image.new("RGB", (100, 50), "white")
    for x in range(50):
        for y in range(50):
            picture.putpixel((x, y), (0, 0, 0))
    picture.save(tmp_path / "halves.png")
    (tmp_path / "probe.epk").write_text(PROBE)
    path = tmp_path / "halves.world"
    path.write_text("arena 100 cm x 50 cm\nfloor halves.png\n"
                    "robot black at 20 cm, 25 cm\nrobot white at 80 cm, 25 cm\n"
                    # facing +y with its sensors' row across x = 50 cm: left is -x
                    "robot edge at 50 cm, 10 cm heading 90 deg\n")
    got = _readings(_run(tmp_path / "probe.epk", tmp_path, path))
    for n in ("g0", "g1", "g2"):
        assert 0 <= got["black"].get(n, 0) < 40
        assert 960 < got["white"][n] < 1040
    assert got["edge"].get("g0", 0) < 100 and got["edge"]["g2"] > 900
    assert 300 < got["edge"]["g1"] < 700            # the centre sensor over the edge: grey
    # without a floor line a walled world is white paper; open ground too
    (tmp_path / "plain.world").write_text("arena 50 cm x 50 cm\n")
    (tmp_path / "open.world").write_text("arena none\n")
    for plain in ("plain", "open"):
        got = _readings(_run(tmp_path / "probe.epk", tmp_path, tmp_path / f"{plain}.world",
                             name=plain))
        assert all(960 < got["r1"][n] < 1040 for n in ("g0", "g1", "g2")), (plain, got)


def _distance_to(outline, x, y):
    best = math.inf
    for (ax, ay), (bx, by) in zip(outline, outline[1:] + outline[:1]):
        dx, dy = bx - ax, by - ay
        t = max(0.0, min(1.0, ((x - ax) * dx + (y - ay) * dy) / (dx * dx + dy * dy)))
        best = min(best, math.hypot(x - ax - t * dx, y - ay - t * dy))
    return best


def test_the_track_follower_keeps_to_a_closed_track_for_two_minutes(tmp_path):
    """Aseba's track-following example, ported (examples/line_follower.epk),
    on examples/line_follower.world's ellipse of black tape: the time its
    centre (the middle of its axle) is within the tape's width, measured
    over two minutes from its poses every 100 ms, and how far it drove."""
    require_enki()
    w = parse_world(EXAMPLES / "line_follower.world")
    [track] = w.floor.shapes
    outline = track.outline()
    records = _run(EXAMPLES / "line_follower.epk", tmp_path, EXAMPLES / "line_follower.world",
                   "--time-limit", "120s", "--pose-interval", "100ms")
    poses = sorted((r["t_ms"], r["x_mm"], r["y_mm"]) for r in records if r["kind"] == "pose")
    assert poses[-1][0] >= 119_900
    on, total = 0, 0
    for (t0, x, y), (t1, _, _) in zip(poses, poses[1:]):
        total += t1 - t0
        on += (t1 - t0) * (_distance_to(outline, x, y) <= track.width_mm / 2)
    perimeter = sum(math.dist(a, b) for a, b in zip(outline, outline[1:] + outline[:1]))
    driven = sum(math.dist(a[1:], b[1:]) for a, b in zip(poses, poses[1:]))
    print(f"on the track {on / total:.1%} of {total / 1000:g} s, {driven / perimeter:.2f} laps")
    assert on / total >= 0.99
    assert driven >= 2.5 * perimeter            # it goes round, not on the spot
    contacts = [r for r in records if r["kind"] == "contacts"]
    assert contacts and all(c["walls"] == c["objects"] == c["robots"] == 0 for c in contacts)
    # the same robot on white paper: no track, both sensors white, it stops
    plain = tmp_path / "plain.world"
    plain.write_text((EXAMPLES / "line_follower.world").read_text()
                     .replace("floor ellipse", "# floor ellipse"))
    records = _run(EXAMPLES / "line_follower.epk", tmp_path, plain, "--time-limit", "5s",
                   "--pose-interval", "100ms", name="plain")
    poses = [(r["x_mm"], r["y_mm"]) for r in records if r["kind"] == "pose"]
    assert max(math.dist(poses[0], p) for p in poses) < 5


def test_the_picture_and_the_replay_draw_the_floor_under_everything_else(tmp_path):
    w = world(tmp_path, "arena 100 cm x 50 cm\nfloor colour grey\n"
                        "floor circle at 50 cm, 25 cm radius 10 cm\n"
                        "box at 90 cm, 40 cm size 5 cm x 5 cm\n")
    pose = {"t_ms": 0, "robot": "r1", "kind": "pose", "name": "pose", "x_mm": 200.0,
            "y_mm": 200.0, "heading_deg": 0.0}
    svg = plot_trace(json.dumps(w.to_json()) + "\n" + json.dumps(pose) + "\n")
    root = ET.fromstring(svg)
    order = [e.get("class") for e in root.iter() if e.get("class") in ("arena", "floor", "box",
                                                                        "path", "robot-run")]
    assert order[:3] == ["arena", "floor", "box"]
    [image] = [e for e in root.iter() if e.get("class") == "floor"]
    href = image.get("href") or image.get("{http://www.w3.org/1999/xlink}href")
    picture = Image.open(io.BytesIO(base64.b64decode(href.split(",", 1)[1])))
    assert picture.size[0] == 500 and picture.size[1] == 250
    rgb = picture.convert("RGB")
    assert rgb.getpixel((250, 125)) == floor_lines.COLOURS["black"]     # the disc
    assert rgb.getpixel((20, 20)) == floor_lines.COLOURS["grey"]
    # the replay draws the same floor under its moving robots
    page = replay_html(json.dumps(w.to_json()) + "\n" + json.dumps(pose) + "\n")
    assert page.count('class="floor"') == 1 and href in page
    assert page.index('class="floor"') < page.index('class="robot-run"')
    # the world without a floor draws none, and its record has no floor key
    plain = world(tmp_path, "arena 100 cm x 50 cm\n", name="plain.world")
    assert "floor" not in plain.to_json()
    assert 'class="floor"' not in plot_trace(json.dumps(plain.to_json()) + "\n"
                                             + json.dumps(pose) + "\n")


def test_the_runner_gets_the_floor_as_a_file_of_pixels(tmp_path):
    from epuckc.sim.world import runner_spec
    w = world(tmp_path, "arena 100 cm x 50 cm\nfloor circle at 50 cm, 25 cm radius 5 cm\n"
                        "robot at 20 cm, 20 cm\n")
    with pytest.raises(ValueError):
        runner_spec(w, [("/x/a.so", {}, frozenset({"ground"}))])
    spec = runner_spec(w, [("/x/a.so", {}, frozenset({"ground"}))],
                       tmp_path / "floor.rgb").splitlines()
    assert f"floor 500 250 {tmp_path / 'floor.rgb'}" in spec and spec[-1] == "ground"
    assert (tmp_path / "floor.rgb").stat().st_size == 500 * 250 * 3
