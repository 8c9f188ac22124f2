"""Priorities, modes and the rest of the robot (LEDs, sound, selector,
microphones, accelerometer, remote control, ambient light), each a small C
program run on the host harness, checked on its JSON trace."""
import pytest
from rt_helpers import PROGRAMS, build_and_run

from test_runtime_events import fired


def test_priorities_order_the_poll_and_own_the_motors(tmp_path):
    r = build_and_run(tmp_path, "priority.c")
    assert r.returncode == 0, r.stderr
    # escape (#1, priority 2) is polled before wander (#0) in the first poll
    assert [x for x in fired(r) if x[0] == 1 and x[1] == "event"] == [
        (1, "event", "escape", 1), (1, "event", "wander", 0)]
    suppressed = [(s["t_ms"], s["name"], s["command"], s["priority"], s["owner_name"],
                   s["owner_priority"]) for s in r.records("suppressed")]
    assert suppressed == [
        (1, "wander", "start_straight", 0, "escape", 2),
        (500, "low sequence", "run_sequence", 1, "escape", 2),   # priority 1 polled first
        (500, "low stop", "stop_motor", 0, "escape", 2),
        (2500, "late sequence", "start_straight", 0, "guard", 3),
    ]
    # escape's sequence ran undisturbed: twice 500 steps at 500 steps/s
    resume = r.records("event", "resume")
    assert [x["t_ms"] for x in resume] == [2001, 2600] and resume[0]["left_steps"] == 1000
    # the late sequence ran (its step is traced) though its motion was refused
    assert [(a["t_ms"], a["step"]) for a in r.records("action") if "step" in a][-1] == (2500, 1)
    # an event of equal priority may stop a motion
    end = r.records("event", "equal stop")[0]
    assert r.trace[-1]["kind"] == "exit" and r.trace[-1]["t_ms"] == 3000
    assert r.trace[-1]["left_steps"] == end["left_steps"]
    assert r.records("action", "stop_motor")[-1]["t_ms"] == 3000


def test_modes_arm_rearm_and_stop_what_they_leave(tmp_path):
    r = build_and_run(tmp_path, "modes.c")
    assert r.returncode == 0, r.stderr
    assert [(m["t_ms"], m["name"], m["id"]) for m in r.records("mode")] == [
        (0, "A", 1), (100, "B", 2), (500, "A", 1), (800, "B", 2)]
    # the enter events fire at the poll after the entry; one-shots re-armed
    assert r.times("event", "A enter") == [1, 501]
    assert r.times("event", "B enter") == [101, 801]
    # leaving A abandoned its sequence (no step 2) and stopped its motion
    # without a stop_motor event
    assert not r.records("event", "B stop_motor")
    assert [s["step"] for s in r.records("action") if "step" in s] == [1, 1]
    at_entry = r.records("mode")[1]["left_steps"]
    assert r.records("event", "B selector 2")[0]["left_steps"] == at_entry
    # disarmed at B's first entry; re-armed (state reset) at the second
    assert r.times("event", "B beep")[:3] == [801, 900, 1000]
    assert r.trace[-1]["kind"] == "exit" and r.trace[-1]["t_ms"] == 2000


def test_devices_are_driven_through_the_library_and_traced(tmp_path):
    r = build_and_run(tmp_path, "devices.c")
    assert r.returncode == 0, r.stderr
    # the knock from 500 ms to 550 ms: read within the library's 3.9 ms
    knock = r.times("event", "tap")
    assert len(knock) == 2 and 500 <= knock[0] <= 504 and 550 <= knock[1] <= 554
    [tilt] = r.times("event", "tilt")
    assert 900 <= tilt <= 904
    leds = [(x["t_ms"], x["name"], x["state"], x["ring"], x["body"], x["front"])
            for x in r.records("led")]
    assert leds == [
        (1, "body", 1, "00000000", 1, 0),
        (100, "all", 1, "11111111", 1, 0),        # selector turned to 5
        (300, "all", 0, "00000000", 1, 0),        # ... and again, after 0
        (knock[0], "front", 1, "00000000", 1, 1),     # a knock
        (knock[1], "front", 0, "00000000", 1, 0),     # ... ending
        (600, "front", 1, "00000000", 1, 1),      # mute
        (800, "front", 0, "00000000", 1, 0),      # mute pressed again
        (tilt, "led3", 1, "00010000", 1, 0),      # tilted
        (1000, "all", 1, "11101111", 1, 0),       # ambient light over 1000
    ]
    # a bad sample index plays nothing; the clap and key 7 play "ouah"
    assert [(s["t_ms"], s["name"], s["length"]) for s in r.records("sound")] == [
        (400, "ouah", 3412), (700, "ouah", 3412)]
    assert [(i["t_ms"], i["name"], i["value"]) for i in r.records("input")][:3] == [
        (0, "selector", 2), (100, "selector", 5), (200, "selector", 0)]


def test_old_scenarios_still_work_and_new_inputs_are_checked(tmp_path):
    r = build_and_run(tmp_path, "sensor_edge.c")
    assert r.returncode == 0, r.stderr
    assert not r.records("input")           # proximity changes are not input records
    for bad in ("selector=16", "mic3=5", "accw=5", "key=power", "amb8=1", "ir0=4096"):
        run = build_and_run(tmp_path, "sensor_edge.c", scenario=f"0 ms {bad}\n")
        assert run.returncode == 2, bad
        assert f"got '{bad}'" in run.stderr and "selector=V" in run.stderr


def test_all_priorities_equal_is_the_paper_s_order(tmp_path):
    """The ordering program of test_runtime_events, with every event given the
    same non-zero priority, polls and fires exactly as before."""
    text = (PROGRAMS / "ordering.c").read_text()
    text = text.replace("    mainloop();", "    { int i; for (i = 0; i < 6; i++) "
                        "set_event_priority(i, 7); }\n    mainloop();")
    (tmp_path / "plain").mkdir()
    plain = build_and_run(tmp_path / "plain", "ordering.c")
    same = build_and_run(tmp_path, text)
    assert plain.returncode == same.returncode == 0
    assert fired(plain) == fired(same) and plain.stdout == same.stdout


@pytest.mark.parametrize("defines", [(), ("WITH_ORDER",)], ids=["levels", "order"])
def test_static_tables_with_priorities_and_modes(tmp_path, defines):
    """register_program with priorities and modes in the table: the walk by
    priority levels over table and dynamic events, compiled conditions in
    it, enter_mode re-arming a mode's table entries (latches and memories
    reset) but not a cancelled one, disarm_event until the next entry, and
    set_event_priority/set_event_mode ignoring table ids. The same with the
    table's events given in priority order (rt_program.order, one pass
    instead of one per level); an order that is not by priority then id is
    refused."""
    r = build_and_run(tmp_path, "static_ranked.c", defines=defines, env={"EPUCK_QUIET": "1"})
    assert r.returncode == 0, r.stderr
    assert r.stdout.splitlines() == ["bad order -1 -1", "negative mode -1", "register 0",
                                     "dynamic 11"]
    assert [(x["id"], x["t_ms"]) for x in r.records("event")] == [
        # the poll after mode 1's entry starts with its entry event, which
        # enters mode 2: no mode's event fires in the rest of the poll; then
        # the dynamic event of priority 5, then priority 0
        (3, 1), (11, 1), (0, 1),
        # mode 2: its entry event 4 first, whatever the priorities: its action
        # cancels 7 and disarms 8 before the walk reaches them (priority 2)
        (4, 2),
        # ir0 rises: priorities 3, 2, 1 (6 enters mode 1), then 0; 1 stays at
        # priority 0 (set_event_priority ignored the table id)
        (5, 5), (2, 5), (6, 5), (1, 5),
        (3, 6),                 # mode 1 again: its entry event re-armed
        # mode 2 again: 4 re-armed and first; 5 and 6 fire though ir0 stayed
        # high (latches reset), 8 re-armed, 7 cancelled for good
        (4, 7), (5, 7), (8, 7), (6, 7),
        (3, 8),                 # to_2 enters no more
        (10, 21)]               # event 9 (mode 3) never
    assert [(x["t_ms"], x["name"]) for x in r.records("mode")] == [
        (0, "one"), (1, "two"), (5, "one"), (6, "two"), (7, "one")]


def test_a_mode_entered_again_rearms_its_rules_and_on_enter_goes_first(tmp_path):
    r = build_and_run(tmp_path, "mode_reentry.c")
    assert r.returncode == 0, r.stderr
    # `A again` is one-shot, and its own `enter A` re-arms it each time
    assert r.times("event", "A again") == [51, 102, 153]
    assert r.times("event", "A enter") == [1, 52, 103]
    # at B's entry the timer A set at 103 has run 50 ms: B's priority-1
    # rule (20 ms) would fire at once if it were polled before `on enter`
    assert r.times("event", "B enter") == [154]
    assert r.times("event", "B early") == [174]
    assert r.trace[-1]["kind"] == "exit" and r.trace[-1]["t_ms"] == 174
