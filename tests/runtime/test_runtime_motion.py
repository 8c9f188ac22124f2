"""Motion control on the host harness: distances, curves, directions and the
16-bit wrap of the step counters."""
import pytest

from rt_helpers import both_paths, build_and_run  # noqa: F401 (both_paths: autouse)

MM_PER_STEP = 0.128805


def end(run):
    assert run.returncode == 0, run.stderr
    assert run.trace[-1]["kind"] == "exit"
    return run.trace[-1]


def test_straight_paper_figures(tmp_path):
    r = build_and_run(tmp_path, "straight.c")
    e = end(r)
    assert e["left_steps"] in (776, 777) and e["right_steps"] == e["left_steps"]
    assert 3090 <= e["t_ms"] <= 3120        # about 3.1 s of virtual time
    assert abs(e["x_mm"] - 100.0) < 0.5 and e["y_mm"] == 0.0
    assert e["heading_deg"] == 0.0


@pytest.mark.parametrize("speed,dist,expect_x", [
    (-250, 100, -100.0), (250, -100, -100.0), (-250, -100, 100.0)])
def test_straight_directions(tmp_path, speed, dist, expect_x):
    r = build_and_run(tmp_path, "straight.c", defines=[f"SPEED={speed}", f"DIST={dist}"])
    e = end(r)
    assert abs(e["x_mm"] - expect_x) < 0.5
    assert abs(e["left_steps"]) == 776 and e["left_steps"] == e["right_steps"]


def test_speed_is_clamped(tmp_path):
    r = build_and_run(tmp_path, "straight.c", defines=["SPEED=5000", "STEPS=1000"])
    e = end(r)
    assert e["left_steps"] == 1000 and e["t_ms"] == 1001     # 1000 steps/s


def test_long_straight_wraps_counters(tmp_path):
    # 33000 steps > 32767: the 16-bit counters wrap during the motion
    r = build_and_run(tmp_path, "straight.c", defines=["SPEED=1000", "STEPS=33000"])
    e = end(r)
    assert e["left_steps"] == 33000 and e["t_ms"] == 33001
    assert abs(e["x_mm"] - 33000 * MM_PER_STEP) < 0.5


def test_preset_counters_wrap_both_ways(tmp_path):
    r = build_and_run(tmp_path, "wrap.c")
    assert r.returncode == 0, r.stderr
    # 776 steps forwards (left counter 32500 -> wraps; right -32500 -> ...),
    # then back twice
    assert r.times("event", "event_stop_motor") == [777, 1553, 2329]
    stops = r.records("event", "event_stop_motor")
    assert [s["left_steps"] for s in stops] == [776, 0, -776]
    assert abs(stops[0]["x_mm"] - 100.0) < 0.5
    assert abs(stops[1]["x_mm"]) < 0.05


def test_spin_90_on_the_spot(tmp_path):
    r = build_and_run(tmp_path, "curve.c", defines=["RADIUS=0", "DEGREES=90", "SPEED=500"])
    e = end(r)
    assert e["right_steps"] == 323 and e["left_steps"] == -323
    assert abs(e["heading_deg"] - 90.0) < 0.5
    assert abs(e["x_mm"]) < 0.05 and abs(e["y_mm"]) < 0.05


def test_spin_right(tmp_path):
    r = build_and_run(tmp_path, "curve.c", defines=["RADIUS=0", "DEGREES=-90", "SPEED=500"])
    e = end(r)
    assert e["left_steps"] == 323 and e["right_steps"] == -323
    assert abs(e["heading_deg"] + 90.0) < 0.5


def test_quarter_circle_left(tmp_path):
    r = build_and_run(tmp_path, "curve.c", defines=["RADIUS=100", "DEGREES=90", "SPEED=800"])
    e = end(r)
    # outer (right) wheel: (100 + 26.5) mm * pi/2 / 0.128805 = 1543 steps;
    # inner at 800 * 73.5/126.5 = 465 steps/s
    assert e["right_steps"] == 1543
    assert abs(e["left_steps"] - round(1543 * 465 / 800)) <= 2
    assert abs(e["heading_deg"] - 90.0) < 1.0
    assert abs(e["x_mm"] - 100.0) < 1.5 and abs(e["y_mm"] - 100.0) < 1.5


def test_curve_in_exact_steps(tmp_path):
    # the extension param_curve_steps: the faster (right) wheel turns 500 steps
    r = build_and_run(tmp_path, "curve.c", defines=["LEFT=250", "RIGHT=1000", "STEPS=500"])
    e = end(r)
    assert e["right_steps"] == 500 and e["left_steps"] == 125
    assert e["t_ms"] == 501


def test_extreme_geometry_and_parameters_saturate(tmp_path):
    # under UBSan: no signed overflow in the conversions
    r = build_and_run(tmp_path, "overflow.c", sanitize=True)
    assert r.returncode == 0, r.stderr
    assert "runtime error" not in r.stderr
    assert r.times("exit") == [5]


def test_holds_on_the_papers_api(tmp_path):
    """hold.c: the same holds on both registration paths (a sensor event is
    a condition whether it is event_sensor or a compiled condition)."""
    r = build_and_run(tmp_path, "hold.c")
    assert r.returncode == 0, r.stderr
    held = [(s["t_ms"], s["name"], s["owner_name"]) for s in r.records("suppressed")]
    # the timer renews `cruise` every 10 ms; `back off` holds from its edge at
    # 200 ms to the poll at 500 ms where nothing is near
    assert [t for t, _, o in held if o == "back off"] == list(range(200, 500, 10))
    # `turn` (600 ms): its curve (150 steps at 300 steps/s: 500 ms) and its
    # wait (100 ms) hold, its final set_speed does not: the cruise takes the
    # wheels back once that last step has run
    [last] = [a["t_ms"] for a in r.records("action") if a.get("step") == 3]
    assert 1200 <= last <= 1202
    assert [t for t, _, o in held if o == "turn"] == list(range(600, last, 10))
    assert r.records("exit")[0]["left_steps"] > -150 + 50
    assert {n for _, n, _ in held} == {"cruise"}
