"""Registration, cancelling, ordering, one-shot/repeat, sensor and timer
events, the stop_motor event and the sequencer, each a small C program run
on the host harness, checked on its JSON trace."""
import pytest

from rt_helpers import both_paths, build_and_run  # noqa: F401 (both_paths: autouse)

TRACE_KEYS = ["t_ms", "kind", "name", "id", "left_steps", "right_steps",
              "x_mm", "y_mm", "heading_deg"]


def fired(run):
    """(t_ms, kind, name, id) of the event/action records."""
    return [(r["t_ms"], r["kind"], r["name"], r["id"])
            for r in run.trace if r["kind"] in ("event", "action")]


def test_register_and_cancel_return_values(tmp_path):
    r = build_and_run(tmp_path, "registry.c", env={"EPUCK_QUIET": "1"})
    assert r.returncode == 0, r.stderr
    assert r.stdout.splitlines() == [
        "null_action -1",
        "actions 0 1 2",
        "event_null_func -1",
        "event_bad_action -1 -1 -1",
        "event_cancelled_action -1",
        "events 0 1",
        "after_cancel 3",
        "returned",
    ]
    # event 0 runs the user action (no name: action#2), event 1 exits
    assert fired(r) == [(1, "event", "immediate", 0), (1, "action", "action#2", 2),
                        (1, "event", "event_immediate", 1), (1, "action", "exit_main", 0)]
    assert r.trace[-1]["kind"] == "exit"


@pytest.mark.dynamic_only
def test_capacity_from_defines(tmp_path):
    r = build_and_run(tmp_path, "capacity.c", defines=["MAX_ACTIONS=3", "MAX_EVENTS=4"],
                      env={"EPUCK_QUIET": "1"})
    assert r.returncode == 0, r.stderr
    # the cancelled slot 1 is not reused: one more fits, then the array is full
    assert r.stdout.splitlines() == ["actions 0 1 2 -1", "events 0 1 2 3 -1"]
    assert r.times("exit") == [1]


def test_order_oneshot_repeat_cancel(tmp_path):
    r = build_and_run(tmp_path, "ordering.c")
    assert r.returncode == 0, r.stderr
    first_poll = [x for x in fired(r) if x[0] == 1]
    assert first_poll == [
        (1, "event", "immediate", 0), (1, "action", "second", 1),
        (1, "event", "immediate", 1), (1, "action", "first", 0),
        # action cancelled: the event fires (and disarms) but runs nothing
        (1, "event", "immediate", 2),
        # event 3 was cancelled: never fires
        (1, "event", 'every "poll"', 4), (1, "action", "action#3", 3),
    ]
    # the one-shots fired once; the repeating one at every poll 1..5, then the
    # timer (5 ms) exits in poll 5 after it
    assert r.times("event", "immediate") == [1, 1, 1]
    assert r.times("event", 'every "poll"') == [1, 2, 3, 4, 5]
    assert r.times("event", "timer") == [5]
    assert r.stdout.splitlines()[-2].startswith("exit at 5 ms")
    assert r.stdout.splitlines()[-1] == "repeats 5"     # main goes on after mainloop


def test_trace_format(tmp_path):
    r = build_and_run(tmp_path, "ordering.c")
    for line in r.trace_bytes.decode().splitlines():
        assert line.startswith("{") and line.endswith("}")
    for rec in r.trace:
        assert list(rec)[:9] == TRACE_KEYS
    # JSON escaping of a name with quotes
    assert b'"name": "every \\"poll\\""' in r.trace_bytes
    assert r.trace[-1] == {"t_ms": 5, "kind": "exit", "name": "exit_main", "id": -1,
                           "left_steps": 0, "right_steps": 0, "x_mm": 0.0,
                           "y_mm": 0.0, "heading_deg": 0.0}
    assert "[     1 ms] event  #0 immediate" in r.stdout


def test_sensor_rising_edges(tmp_path):
    r = build_and_run(tmp_path, "sensor_edge.c")
    assert r.returncode == 0, r.stderr
    events = [(t, i) for (t, k, n, i) in fired(r) if k == "event" and i in (1, 2, 3, 4)]
    assert events == [
        (2, 3),     # below 500 from the second poll (started by event 0 at the first)
        (100, 1), (100, 2),     # rises at 100: repeat and one-shot
        (200, 3),   # falls: "below" rises
        (300, 1),   # rises again: only the repeating one
    ]
    assert r.times("exit") == [400]


def test_sensor_off_means_false(tmp_path):
    r = build_and_run(tmp_path, "sensor_off.c")
    assert r.returncode == 0, r.stderr
    # on at 150 (after event 0 was polled in that poll) -> fires at 151,
    # which turns the sensors off; on again at 250 -> 251
    assert r.times("event", "sensor") == [151, 251]


def test_timer_periodic_and_restart(tmp_path):
    r = build_and_run(tmp_path, "timer_periodic.c")
    assert r.returncode == 0, r.stderr
    # every 100 ms of the timer; restarted at 250: 350, 450, 550
    assert r.times("action", "tick") == [100, 200, 350, 450, 550]
    assert r.times("action", "set_timer") == [250]
    # the 5th tick called exit_main from a user action
    assert r.times("exit") == [550]


def test_reset_timer_and_time_limit(tmp_path):
    r = build_and_run(tmp_path, "timer_reset.c", time_limit=1000)
    assert r.returncode == 3
    assert r.times("event", "timer") == [100, 150]
    assert r.trace[-1]["kind"] == "timeout" and r.trace[-1]["t_ms"] == 1000
    assert r.stdout.splitlines()[-1].startswith("timeout at 1000 ms")


def test_stop_motor_action_fires_event_next_poll(tmp_path):
    r = build_and_run(tmp_path, "stop_action.c")
    assert r.returncode == 0, r.stderr
    assert r.times("action", "stop_motor") == [500]
    assert r.times("event", "event_stop_motor") == [501]
    # 500 steps/s for 499 ms
    assert r.trace[-1]["left_steps"] == 249


def test_stop_and_start_in_one_poll_does_not_fire(tmp_path):
    r = build_and_run(tmp_path, "stop_restart.c")
    assert r.returncode == 0, r.stderr
    assert r.times("action", "swap") == [500]
    # only when the 10-step motion at 1000 steps/s has ended
    assert r.times("event", "event_stop_motor") == [510]
    assert r.trace[-1]["left_steps"] == 249 + 10


def test_zero_motions_fire_once_each(tmp_path):
    r = build_and_run(tmp_path, "zero_motion.c")
    assert r.returncode == 0, r.stderr
    assert r.times("event", "event_stop_motor") == [11, 21]
    assert r.trace[-1]["left_steps"] == 0


def test_sequence_runs_steps_after_motions(tmp_path):
    r = build_and_run(tmp_path, "sequence.c")
    assert r.returncode == 0, r.stderr
    steps = [(x["t_ms"], x["step"], x["steps"]) for x in r.trace if "step" in x]
    # straight 200 steps at 1000/s: 1..201; set_timer at once; spin 90 deg
    # (323 steps at 500/s: 646 ms) until 847; then 100 steps back
    assert steps == [(1, 1, 4), (201, 2, 4), (201, 3, 4), (847, 4, 4)]
    assert all(x["name"] == "square" and x["id"] == 0 for x in r.trace if "step" in x)
    # one stop, after the last step's motion
    assert r.times("event", "event_stop_motor") == [947]
    end = r.trace[-1]
    assert end["kind"] == "exit"
    assert abs(end["heading_deg"] - 90.0) < 0.5
    assert abs(end["x_mm"] - 200 * 0.128805) < 0.2
    assert abs(end["y_mm"] + 100 * 0.128805) < 0.2


def test_sequence_abandoned_by_outside_motion_and_exit_step(tmp_path):
    r = build_and_run(tmp_path, "sequence_abandon.c")
    assert r.returncode == 0, r.stderr
    first = [x["step"] for x in r.trace if x.get("id") == 0 and "step" in x]
    assert first == [1]         # step 2 never runs: abandoned at 300
    assert r.times("action", "straight_steps") == [300]
    # the outside motion (20 steps) ends at 320: the second sequence runs
    # its first step, then at 370 exit_main as its second; step 3 never runs
    second = [(x["t_ms"], x["step"]) for x in r.trace if x.get("id") == 2 and "step" in x]
    assert second == [(320, 1), (370, 2)]
    assert r.times("exit") == [370]


def test_sequence_that_runs_itself_loops_once_per_poll(tmp_path):
    r = build_and_run(tmp_path, "sequence_self.c")
    assert r.returncode == 0, r.stderr
    ticks = [x["t_ms"] for x in r.trace if x.get("step") == 1]
    # once before mainloop (0 ms, before the JSON trace is opened: stdout
    # only), then once per poll, until the 20th
    assert ticks == list(range(1, 20))
    assert r.times("exit") == [19]
    assert r.stdout.startswith("[     0 ms] action #-1 action#-1 step 1 of 2\n")
    assert "step 0" not in r.stdout


def test_quiet_holds_before_mainloop(tmp_path):
    r = build_and_run(tmp_path, "sequence_self.c", env={"EPUCK_QUIET": "1"})
    assert r.returncode == 0, r.stderr
    assert r.stdout == ""


def test_static_tables_by_hand(tmp_path):
    """register_program: refusals, ids after the tables, compiled conditions
    (from the poll after an event started the sensors), cancel and
    set_event_repeat on table entries, two words of events, a dynamic event
    registered by a table action and polled in the same walk."""
    r = build_and_run(tmp_path, "static_table.c", env={"EPUCK_QUIET": "1"})
    assert r.returncode == 0, r.stderr
    assert r.stdout.splitlines() == ["refuse -1 -1 -1 -1 -1 -1", "register 0", "again -1",
                                     "ids 5", "more 19", "notes 5"]
    assert [(x["id"], x["t_ms"]) for x in r.records("event")] == [
        (0, 1), (3, 1),                     # 3 fires, its cancelled action runs nothing
        (1, 2), (17, 2),                    # the sensors are on from the poll after 0
        (1, 8), (17, 8),                    # rising edges again; 17 repeats now
        (2, 10), (19, 10),                  # 19 registered by 2's action, same walk
        (18, 30)]
    assert [x["id"] for x in r.records("action")] == [0, 1, 1, 1, 1, 3, 1, 2]
    assert r.records("event")[3]["name"] == "ir0 > 800"
    assert r.records("action")[1]["name"] == "note"
