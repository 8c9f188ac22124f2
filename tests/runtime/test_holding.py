"""Holding the motors under priorities (docs/runtime.md, "Holding the
motors"): one test per row of the table, through the whole pipeline (a rule
file checked, compiled, built and run on the host harness with a scenario
and a trace). In each, a rule of priority 0 renews its motor command every
10 ms (at 11, 21, ... ms: `every` counts from the first poll), so the
`suppressed` records show exactly when a higher rule held the wheels."""
import tempfile
from pathlib import Path

from conftest import REPO
from tests.support.programs import run_program

CRUISE = "every 10 ms do set_speed(left: 300, right: 300)\n"


def _write(tmp_path, name, text):
    path = tmp_path / name
    path.write_text(text, encoding="utf-8")
    return path


def _run(tmp_path, rules, scenario=None, limit="1s"):
    prog = _write(tmp_path, "hold.epk", rules + CRUISE + f"after {limit} priority 9 do exit_main\n")
    extra = []
    if scenario is not None:
        extra = ["--scenario", _write(tmp_path, "hold.scn", scenario)]
    records, _ = run_program(prog, tmp_path, *extra)
    return records


def _suppressed(records, command="set_speed"):
    """When the cruise's commands were refused (its every-10-ms firings)."""
    return [r["t_ms"] for r in records if r["kind"] == "suppressed" and r["command"] == command]


def _cruise_times(start, stop):
    """The cruise's firings in [start, stop): 1 + 10 k ms."""
    return [t for t in range(1, 2000, 10) if start <= t < stop]


def _exit(records):
    return [r for r in records if r["kind"] == "exit"][0]


NEAR_200_TO_500 = "0 ms ir0=0\n200 ms ir0=900\n500 ms ir0=0\n"


def test_when_holds_while_its_condition_is_true_and_lets_go_when_it_is_false(tmp_path):
    """Subsumption: the higher layer backs off for as long as something is
    near; the lower layer's renewed commands are refused exactly then."""
    records = _run(tmp_path, "when ir0 > 500 priority 1 do set_speed(left: -200, right: -200)\n",
                   NEAR_200_TO_500)
    assert _suppressed(records) == _cruise_times(200, 500)
    # and the robot did back off for those 300 ms: forward from 11 ms (the
    # cruise's first firing) at 300 steps/s, back from 200 ms at 200, forward
    # again from 501 ms (the cruise's first firing after) to the end
    steps = _exit(records)["left_steps"]
    expected = round((200 - 11) * 0.300 - (501 - 200) * 0.200 + (1001 - 501) * 0.300)
    assert abs(steps - expected) <= 3, (steps, expected)
    # the `suppressed` record names the holder and both priorities
    first = [r for r in records if r["kind"] == "suppressed"][0]
    assert first["owner_priority"] == 1 and first["priority"] == 0
    assert "when ir0 > 500" in first["owner_name"]


def test_a_guarded_condition_holds_by_its_condition_not_its_guard(tmp_path):
    """A guard decides whether the rule fires; its condition how long it
    holds (a guarded condition is an event function, not a compiled
    condition: its condition is followed after the one-shot rule fired)."""
    records = _run(tmp_path, "var n = 0\nafter 100 ms do n = 5\n"
                   "when ir0 > 500 priority 1 if n >= 5 do set_speed(left: -200, right: -200)\n"
                   "on sensor(ir7 > 500) priority 1 if n >= 5 do set_speed(left: -100, right: -100)\n"
                   "on immediate do start_sensor\n",
                   "0 ms ir0=0 ir7=0\n200 ms ir0=900\n400 ms ir0=0\n600 ms ir7=900\n"
                   "800 ms ir7=0\n")
    assert _suppressed(records) == _cruise_times(200, 400) + _cruise_times(600, 800)


def test_a_guarded_every_holds_until_a_period_whose_guard_is_false(tmp_path):
    records = _run(tmp_path, "every 50 ms priority 1 if ir0 > 500 "
                             "do set_speed(left: -200, right: -200)\n", NEAR_200_TO_500)
    # its periods are 51, 101, ...: the guard is true from 201 to 451, false at 501
    assert _suppressed(records) == _cruise_times(201, 501)


def test_an_every_without_a_guard_holds_only_while_its_action_runs(tmp_path):
    """An unguarded `every` is an event (a tick), not a condition: a
    `set_speed` ends its action at once, so it holds nothing."""
    records = _run(tmp_path, "every 50 ms priority 1 do set_speed(left: -200, right: -200)\n")
    assert _suppressed(records) == []
    # a bounded motion still holds until it ends
    records = _run(tmp_path, "every 300 ms priority 1 do start_straight(200, 1 cm)\n")
    # 1 cm = 78 steps at 200 steps/s: 390 ms, longer than the period: always held
    held = _suppressed(records, "set_speed")
    assert held and held[0] == 301 and held == _cruise_times(301, 1001)


def test_an_event_rule_ending_in_set_speed_lets_go_when_its_sequence_ends(tmp_path):
    """Issue 24: a final `set_speed` leaves the wheels turning but no longer
    holds them (it used to own them for good)."""
    records = _run(tmp_path, "after 100 ms priority 1 do start_curve(radius: 0 mm, "
                             "degrees: 90 deg, speed: 500) then set_speed(left: -300, right: -300)\n")
    # 90 degrees on the spot: 323 steps at 500 steps/s, from 101 ms
    end = 101 + 323 * 2
    held = _suppressed(records)
    assert held == _cruise_times(101, end + 1)
    assert held[-1] > 700
    # the cruise took the wheels back: it drove forward to the end (the
    # turn left took the left wheel 323 steps back)
    assert _exit(records)["left_steps"] > -323 + 50


def test_a_sequence_holds_through_its_waits(tmp_path):
    records = _run(tmp_path, "after 100 ms priority 1 do stop_motor then wait(300 ms) "
                             "then set_speed(left: 0, right: 0)\n")
    assert _suppressed(records) == _cruise_times(101, 402)


def test_a_sensor_rule_holds_while_its_condition_or_its_sequence_lasts(tmp_path):
    """`on sensor(...)`: whichever is later, its condition or its sequence."""
    rule = ("on immediate do start_sensor\n"
            "on sensor(ir0 > 500) repeat priority 1 do start_straight(-200, 1 cm) "
            "then set_speed(left: -100, right: -100)\n")
    # the condition outlasts the sequence (78 steps at 200 steps/s: 390 ms)
    records = _run(tmp_path, rule, "0 ms ir0=0\n200 ms ir0=900\n800 ms ir0=0\n")
    assert _suppressed(records) == _cruise_times(200, 800)
    # the sequence outlasts the condition
    records = _run(tmp_path, rule, "0 ms ir0=0\n200 ms ir0=900\n250 ms ir0=0\n")
    assert _suppressed(records) == _cruise_times(200, 591)


def test_stop_motor_by_a_condition_holds_the_robot_still(tmp_path):
    records = _run(tmp_path, "when ir0 > 500 priority 1 do stop_motor\n", NEAR_200_TO_500)
    assert _suppressed(records) == _cruise_times(200, 500)
    # while an event rule's stop holds nothing: the motion has ended
    records = _run(tmp_path, "after 200 ms priority 1 do stop_motor\n")
    assert _suppressed(records) == []


def test_leaving_the_holders_mode_ends_its_hold(tmp_path):
    records = _run(tmp_path, "initial mode a {\n"
                             "    when ir0 > 500 priority 1 do set_speed(left: -200, right: -200)\n"
                             "}\nmode b {\n    on enter do led_on(body)\n}\n"
                             "after 300 ms priority 2 do enter b\n",
                   "0 ms ir0=0\n100 ms ir0=900\n")
    assert _suppressed(records) == _cruise_times(100, 301)


def test_a_higher_layer_that_took_over_does_not_end_a_lower_hold(tmp_path):
    """Each layer suppresses the ones below it while it is active: the
    `when` layer still holds against the cruise after the higher layer's
    motion has ended, since its condition is still true."""
    records = _run(tmp_path, "when ir0 > 500 priority 1 do set_speed(left: -200, right: -200)\n"
                             "after 300 ms priority 2 do start_straight(300, 1 cm)\n",
                   "0 ms ir0=0\n200 ms ir0=900\n700 ms ir0=0\n")
    assert _suppressed(records) == _cruise_times(200, 700)


def test_equal_priorities_suppress_nothing(tmp_path):
    """The paper's behaviour: with one priority the later rule in the poll
    wins, whatever holds."""
    records = _run(tmp_path, "when ir0 > 500 do set_speed(left: -200, right: -200)\n"
                             "on immediate do start_straight(200, 1 cm) then wait(300 ms)\n",
                   NEAR_200_TO_500)
    assert [r for r in records if r["kind"] == "suppressed"] == []


def test_cancel_ends_the_hold_of_the_rule_cancelled(tmp_path):
    records = _run(tmp_path, "rule back: when ir0 > 500 repeat priority 1 "
                             "do set_speed(left: -200, right: -200)\n"
                             "after 300 ms priority 2 do cancel back\n",
                   "0 ms ir0=0\n200 ms ir0=900\n")
    assert _suppressed(records) == _cruise_times(200, 301)


def test_random_walk_example_is_not_suppressed_once_the_way_is_clear():
    """examples/random_walk.epk on the harness, nothing near: the wander
    turns are never suppressed (they were all suppressed after the first
    avoid); with an obstacle for a while, only the turns while it is near."""
    with tempfile.TemporaryDirectory() as d:
        scn = _write(Path(d), "near.scn", "0 ms ir0=0\n1000 ms ir0=900\n3000 ms ir0=0\n")
        records, _ = run_program(REPO / "examples" / "random_walk.epk", Path(d), "--scenario",
                                 scn, "--time-limit", "12s", expect=3)
    wander = [r["t_ms"] for r in records if r["kind"] == "event" and "rule wander" in r["name"]]
    held = [r["t_ms"] for r in records if r["kind"] == "suppressed"]
    assert wander == [2001, 4001, 6001, 8001, 10001]
    # the wander at 2001 ms comes while avoid turns away: refused; after
    # 3 s the way is clear and every later wander turns the robot
    assert held == [2001]
