"""Pictures of a run (epuckc/sim/plot.py): the SVG is parsed and what it shows
is checked against the trace it was drawn from."""
import json
import math
import re

import pytest

from epuckc.sim.plot import PlotError, plot_trace

from tests.support.world import EXAMPLES, LED_PROGRAM, by_class, epuckc, run, svg

POINT = re.compile(r"(-?[\d.]+),(-?[\d.]+)")


def path_points(element):
    return [(float(x), float(y)) for x, y in POINT.findall(element.get("points"))]


def test_pose_records_every_interval_and_nothing_else_changes(tmp_path):
    plain, out_plain, _ = run(EXAMPLES / "square.epk", tmp_path, name="plain")
    posed, out_posed, _ = run(EXAMPLES / "square.epk", tmp_path, "--pose-interval", "250ms",
                              name="posed")
    poses = [r for r in posed if r["kind"] == "pose"]
    end = plain[-1]["t_ms"]
    assert [r["t_ms"] for r in poses] == list(range(0, end + 1, 250))
    assert [r for r in posed if r["kind"] != "pose"] == plain
    assert out_posed == out_plain           # pose records are for the JSON trace only
    # the square's corners are among the poses: it drives 200 mm sides
    xs = [r["x_mm"] for r in poses]
    assert max(xs) == pytest.approx(200, abs=1) and min(xs) == pytest.approx(0, abs=1)


def test_the_path_passes_within_half_a_pixel_of_every_pose_of_the_trace(tmp_path):
    """Every pose, thinned to the points that can be seen (sim/thin.py): the
    path drawn is within PATH_TOLERANCE_PX (and its rounding) of each."""
    from epuckc.sim.thin import PATH_TOLERANCE_PX, _distance
    picture = tmp_path / "square.svg"
    records, _, _ = run(EXAMPLES / "square.epk", tmp_path, "--svg", picture)
    root = svg(picture)
    [path] = by_class(root, "path")
    pts = path_points(path)
    poses = [(r["x_mm"], r["y_mm"]) for r in records if "x_mm" in r]
    assert sum(r["kind"] == "pose" for r in records) > 200     # --svg: every 100 ms
    # the picture's scale and offset from the square's extent (200 mm sides)
    xs, ys = [p[0] for p in poses], [p[1] for p in poses]
    px, py = [p[0] for p in pts], [p[1] for p in pts]
    sx = (max(px) - min(px)) / (max(xs) - min(xs))
    sy = (max(py) - min(py)) / (max(ys) - min(ys))
    assert sx == pytest.approx(sy, rel=0.01)                   # one scale, y flipped
    expected = []
    for x, y in poses:
        p = (round(min(px) + (x - min(xs)) * sx, 1), round(max(py) - (y - min(ys)) * sx, 1))
        if not expected or expected[-1] != p:
            expected.append(p)
    assert pts[0] == pytest.approx(expected[0], abs=0.3)
    assert pts[-1] == pytest.approx(expected[-1], abs=0.3)
    assert 4 <= len(pts) < len(expected) / 4        # a square: its corners, not its poses
    for p in expected:
        assert min(_distance(p, a, b) for a, b in zip(pts, pts[1:])) <= PATH_TOLERANCE_PX + 0.3


def test_run_svg_draws_firings_final_pose_and_timeline(tmp_path):
    picture = tmp_path / "patrol.svg"
    records, _, _ = run(EXAMPLES / "timed_patrol.epk", tmp_path, "--svg", picture)
    root = svg(picture)
    # one marker per firing, each with its time and file:line
    events = [r for r in records if r["kind"] == "event"]
    markers = by_class(root, "firing")
    assert [int(m.get("data-t-ms")) for m in markers] == [r["t_ms"] for r in events]
    assert all(re.fullmatch(r"timed_patrol\.epk:\d+", m.get("data-label")) for m in markers)
    assert {m.get("data-label") for m in markers} == {r["name"].split()[0] for r in events}
    # the final pose is the last record's
    [final] = by_class(root, "final-pose")
    assert float(final.get("data-x-mm")) == records[-1]["x_mm"]
    assert float(final.get("data-heading-deg")) == records[-1]["heading_deg"]
    # a timeline row per rule, a tick per firing in its row
    rows = by_class(root, "timeline-row")
    labels = [r.get("data-label") for r in rows]
    assert len(labels) == len(set(labels)) == len({r["name"].split()[0] for r in events})
    for row in rows:
        ticks = [int(t.get("data-t-ms")) for t in by_class(row, "tick")]
        assert ticks == [r["t_ms"] for r in events if r["name"].split()[0] == row.get("data-label")]
    turn_back = next(r for r in rows if "turn_back" in "".join(r.itertext()))
    assert len(by_class(turn_back, "tick")) == 4      # every 3 s until cancelled at 14 s
    # no world: no walls
    assert by_class(root, "arena") == [] and by_class(root, "ground")


def test_plot_of_a_saved_trace_equals_run_svg(tmp_path):
    picture = tmp_path / "run.svg"
    _, _, _ = run(EXAMPLES / "square.epk", tmp_path, "--svg", picture)
    again = tmp_path / "plot.svg"
    result = epuckc("plot", tmp_path / "trace.jsonl", "-o", again, "--title", "square.epk")
    assert result.returncode == 0, result.stderr
    assert again.read_bytes() == picture.read_bytes()


def test_world_record_draws_walls_boxes_and_cylinders():
    world = {"kind": "world", "arena": {"width_mm": 1000.0, "height_mm": 500.0},
             "boxes": [{"x_mm": 300.0, "y_mm": 200.0, "length_mm": 100.0, "width_mm": 40.0,
                        "angle_deg": 30.0}],
             "cylinders": [{"x_mm": 700.0, "y_mm": 250.0, "radius_mm": 50.0}],
             "robots": [], "robot_radius_mm": 37.0}
    rec = {"t_ms": 0, "robot": "a", "kind": "pose", "name": "pose", "id": -1, "left_steps": 0,
           "right_steps": 0, "x_mm": 100.0, "y_mm": 100.0, "heading_deg": 0.0}
    text = json.dumps(world) + "\n" + json.dumps(rec) + "\n"
    import xml.etree.ElementTree as ET
    root = ET.fromstring(plot_trace(text))
    [arena] = by_class(root, "arena")
    w, h = float(arena.get("width")), float(arena.get("height"))
    assert w / h == pytest.approx(2.0, rel=0.01)          # 1000 x 500 mm
    [box] = by_class(root, "box")
    assert float(box.get("width")) / w == pytest.approx(0.1, rel=0.02)
    assert "rotate(-30" in box.get("transform")
    [cyl] = by_class(root, "cylinder")
    assert float(cyl.get("r")) / w == pytest.approx(0.05, rel=0.02)
    # (700, 250) mm: 70 % across, half-way up (y is flipped)
    assert (float(cyl.get("cx")) - float(arena.get("x"))) / w == pytest.approx(0.7, abs=0.01)
    assert (float(cyl.get("cy")) - float(arena.get("y"))) / h == pytest.approx(0.5, abs=0.01)
    [run_group] = by_class(root, "robot-run")
    assert run_group.get("data-robot") == "a"


@pytest.mark.parametrize("text, words", [
    ("not json\n", "t.jsonl:1: not a JSON trace record"),
    ('{"a": 1}\n', "t.jsonl:1: not a trace record"),
    ('{"kind": "world"}\n', "no record with a pose"),
])
def test_bad_traces_are_reported(tmp_path, text, words):
    with pytest.raises(PlotError, match=re.escape(words)):
        plot_trace(text, source="t.jsonl")
    bad = tmp_path / "t.jsonl"
    bad.write_text(text)
    result = epuckc("plot", bad, "-o", tmp_path / "out.svg")
    assert result.returncode == 2 and words.split(":")[-1].strip() in result.stderr
    assert not (tmp_path / "out.svg").exists()


def test_a_bad_pose_interval_setting_is_reported(tmp_path):
    import subprocess
    built = epuckc("build", EXAMPLES / "square.epk", "-o", tmp_path / "b")
    assert built.returncode == 0, built.stderr
    for value in ("abc", "0", "-5", "10x"):
        result = subprocess.run([str(tmp_path / "b" / "square")], capture_output=True, text=True,
                                env={"EPUCK_POSE_MS": value})
        assert result.returncode == 2
        assert result.stderr == ("epuck host: EPUCK_POSE_MS: expected a whole number of "
                                 f"milliseconds from 1 to 1000000000, got '{value}'\n")


def test_a_rule_of_continuous_control_is_one_band_not_thousands_of_marks(tmp_path):
    """`every 10 ms do set_speed(...)`: its firings are not drawn one by one
    on the map (they would bury the path), and its timeline row is one band
    from the first firing to the last; a rule that fires now and then keeps
    its marks."""
    prog = tmp_path / "steer.epk"
    prog.write_text("var n = 0\nevery 10 ms do n += 1, set_speed(left: 300, right: 200)\n"
                    "after 1 s do exit_main\n")
    picture = tmp_path / "steer.svg"
    records, _, _ = run(prog, tmp_path, "--svg", picture)
    root = svg(picture)
    firings = by_class(root, "firing")
    assert [f.get("data-t-ms") for f in firings] == ["1001"]        # the `after` only
    [band] = by_class(root, "dense")
    assert band.get("data-count") == str(sum(1 for r in records if r["kind"] == "event"
                                             and "every" in r["name"]))
    assert not [t for t in by_class(root, "tick") if t.get("data-t-ms") != "1001"]


# -- seeing why (issue 24): the LEDs, who holds the motors, when the robot is still


def led_elements(group):
    """{'ring': '01100000', 'body': '1', 'front': '0'} of a drawn robot."""
    ring = sorted(by_class(group, "ring-led"), key=lambda e: int(e.get("data-led")))
    [body], [front] = by_class(group, "body-led"), by_class(group, "front-led")
    return {"ring": "".join(e.get("data-on") for e in ring), "body": body.get("data-on"),
            "front": front.get("data-on")}


def test_the_final_pose_shows_the_leds_as_the_trace_left_them(tmp_path):
    prog = tmp_path / "count.epk"
    prog.write_text(LED_PROGRAM)
    picture = tmp_path / "count.svg"
    records, _, _ = run(prog, tmp_path, "--svg", picture)
    last = [r for r in records if r["kind"] == "led"][-1]
    [final] = by_class(svg(picture), "final-pose")
    assert led_elements(final) == {"ring": last["ring"], "body": str(last["body"]),
                                   "front": str(last["front"])}
    assert last["ring"] != "00000000" and last["body"] == 1     # something to see
    # led0 at the front, then clockwise seen from above (led2 on the right)
    heading = float(final.get("data-heading-deg"))
    assert heading == pytest.approx(120, abs=2)
    [disc] = [c for c in final if c.tag.endswith("circle")][:1]
    cx, cy = float(disc.get("cx")), float(disc.get("cy"))
    for led in by_class(final, "ring-led"):
        i = int(led.get("data-led"))
        angle = math.degrees(math.atan2(cy - float(led.get("cy")), float(led.get("cx")) - cx))
        assert (angle - (heading - 45 * i) + 180) % 360 - 180 == pytest.approx(0, abs=2)
    lit = [e for e in by_class(final, "ring-led") if e.get("data-on") == "1"]
    assert lit and all(e.get("fill") != "none" for e in lit)


def hold_spans(root):
    return [(int(r.get("data-from-ms")), int(r.get("data-to-ms")), r.get("data-label"))
            for r in by_class(root, "hold")]


def test_the_motors_band_follows_the_rule_that_holds_them(tmp_path):
    prog = tmp_path / "hold.epk"
    prog.write_text("on immediate do start_straight(300 steps/s, 5 cm)\n"
                    "after 3 s do start_curve(radius: 0 mm, degrees: 90 deg, speed: 300 steps/s)\n"
                    "after 5 s do exit_main\n")
    picture = tmp_path / "hold.svg"
    records, _, _ = run(prog, tmp_path, "--svg", picture, "--pose-interval", "10ms")
    spans = hold_spans(svg(picture))
    events = [r for r in records if r["kind"] == "event"]
    assert [(a, label) for a, _, label in spans] == [(e["t_ms"], e["name"].split()[0])
                                                     for e in events[:2]]
    posed = [r for r in records if "left_steps" in r]
    for (a, b, _), next_start in zip(spans, [spans[1][0], records[-1]["t_ms"]]):
        # the motion ran until the band's end; from there the wheels stood
        during = [r["right_steps"] for r in posed if a <= r["t_ms"] <= b]
        after = [r["right_steps"] for r in posed if b <= r["t_ms"] <= next_start]
        assert len(set(during)) > 10 and len(set(after)) == 1
        assert b < next_start
    # a key in the rule's colour beside each rule's row
    root = svg(picture)
    keys = {k.get("data-label"): k.get("fill") for k in by_class(root, "hold-key")}
    assert keys == {label: r.get("fill") for r in by_class(root, "hold")
                    for label in [r.get("data-label")]}
    assert len(set(keys.values())) == 2


def test_a_suppressed_command_meets_the_band_of_the_rule_that_held_the_motors(tmp_path):
    picture = tmp_path / "explorer.svg"
    records, _, _ = run(EXAMPLES / "explorer.epk", tmp_path, "--svg", picture,
                        "--scenario", EXAMPLES / "explorer.scn")
    spans = hold_spans(svg(picture))
    refused = [r for r in records if r["kind"] == "suppressed"]
    assert refused
    for r in refused:
        [holder] = [label for a, b, label in spans if a <= r["t_ms"] < b]
        assert holder == r["owner_name"].split()[0]


def still_spans(root):
    return [(int(r.get("data-from-ms")), int(r.get("data-to-ms"))) for r in by_class(root, "still")]


def test_the_still_band_covers_the_time_the_robot_stood(tmp_path):
    prog = tmp_path / "pause.epk"
    prog.write_text("on immediate do start_straight(300 steps/s, 5 cm)\n"
                    "after 4 s do start_straight(300 steps/s, 5 cm)\n"
                    "after 8 s do exit_main\n")
    picture = tmp_path / "pause.svg"
    records, _, _ = run(prog, tmp_path, "--svg", picture, "--pose-interval", "10ms")
    poses = [r for r in records if r["kind"] == "pose"]
    go = [r["t_ms"] for r in records if r["kind"] == "event"][1]
    # the wheels stood from the first pose of the first motion's last steps ...
    first_end = max(r["right_steps"] for r in poses if r["t_ms"] < go)
    stop = min(r["t_ms"] for r in poses if r["right_steps"] == first_end)
    final = records[-1]
    second_stop = min(r["t_ms"] for r in poses if r["right_steps"] == final["right_steps"])
    assert stop < go - 2000 and second_stop < final["t_ms"] - 2000
    # ... at 38.6 mm/s the last 5 mm take 130 ms: the band starts a little
    # before the stop and ends a little after the start
    [(a1, b1), (a2, b2)] = still_spans(svg(picture))
    assert stop - 300 <= a1 <= stop and go <= b1 <= go + 300
    assert second_stop - 300 <= a2 <= second_stop and b2 == final["t_ms"]


@pytest.mark.parametrize("mm_per_s, still", [(4.0, True), (6.0, False)])
def test_still_means_less_than_5_mm_in_any_second(mm_per_s, still):
    from epuckc.sim.timeline import still_intervals
    poses = [(t, mm_per_s * t / 1000, 0.0, 0.0) for t in range(0, 5001, 100)]
    assert still_intervals(poses, 5000) == ([(0, 5000)] if still else [])
