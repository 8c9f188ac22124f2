"""End to end: the golden corpus compiled with -Werror, run on the harness,
and its trace checked against what each rule form must do."""
from tests.support.programs import REPO, events, run_program

GOLDEN = REPO / "tests" / "golden"


def steps_at(records):
    """Sequence step records: (t_ms, left_steps) when each step started."""
    return [(r["t_ms"], r["left_steps"]) for r in records
            if r["kind"] == "action" and "step" in r]


def exit_time(records):
    [end] = [r for r in records if r["kind"] == "exit"]
    return end["t_ms"]


def test_units_convert_with_the_robots_geometry(tmp_path):
    records, _ = run_program(GOLDEN / "units.epk", tmp_path)
    starts = steps_at(records)
    # 100 mm with the paper's 0.25761 mm steps = 388 steps (1552 ms at 250 steps/s)
    assert starts[1][1] == 388
    # 5 cm at 100 mm/s = 194 steps at 388 steps/s
    assert starts[2][1] == 388 + 194
    # 1 cm at 2 cm/s = 39 steps at 78 steps/s: 500 ms
    assert starts[3][1] - starts[2][1] == 39 and starts[3][0] - starts[2][0] == 500
    # 40 steps backwards
    assert starts[4][1] - starts[3][1] == -40
    # the simulated odometry uses the robot block's geometry too: after the
    # -45 deg curve (a right turn) the robot faces -45 deg
    [end] = [r for r in records if r["kind"] == "exit"]
    assert abs(end["heading_deg"] + 45) < 0.5
    # the timer starts with the last step; only the 1500 ms timer fires
    assert exit_time(records) == starts[-1][0] + 1500
    assert events(records, "timer(2 s)") == []


def test_sensor_timer_and_stop_motor_events(tmp_path):
    records, _ = run_program(GOLDEN / "events.epk", tmp_path,
                             "--scenario", GOLDEN / "events.scn")
    # rising edges: ir5 < 20 at 100 ms, ir2 > 1000 at 500 ms
    assert [r["t_ms"] for r in events(records, "rule near")] == [100, 500]
    # each 1 cm motion (78 steps at 300 steps/s) ends 260 ms later
    moved = [r["t_ms"] for r in events(records, "rule moved")]
    assert moved == [360, 760]
    # reset_timer + set_timer restarts the periodic timer's phase
    ticks = [r["t_ms"] for r in events(records, "timer(400 ms)")]
    assert ticks[:3] == [1160, 1560, 1960]
    # the long spelling event_timer(time: ...) works; 3 s after the last restart
    assert exit_time(records) == 760 + 3000


def test_stop_sensor_silences_sensor_rules(tmp_path):
    scenario = tmp_path / "late.scn"
    scenario.write_text("0 ms ir5=100\n1500 ms ir2=3000\n")
    records, _ = run_program(GOLDEN / "events.epk", tmp_path, "--scenario", scenario)
    # sensors were stopped at 400 ms, so the obstacle at 1.5 s is not seen
    assert events(records, "rule near") == []


def test_cancel_stops_a_repeating_rule(tmp_path):
    records, _ = run_program(GOLDEN / "cancel.epk", tmp_path)
    assert [r["t_ms"] for r in events(records, "rule tick")] == [101, 201, 301]
    assert exit_time(records) == 1001


def test_extern_actions_and_events_get_converted_arguments(tmp_path):
    records, out = run_program(GOLDEN / "extern.epk", tmp_path)
    # distance in steps, speed in steps/s, angle in deg, duration in ms
    assert "mark count=3 length=155 pace=776 turn=45 wait=2000" in out
    assert "mark count=1 length=10 pace=10 turn=1 wait=1" in out
    assert [r["t_ms"] for r in events(records, "elapsed")] == [250]


def test_names_that_are_c_keywords_or_runtime_names(tmp_path):
    records, _ = run_program(GOLDEN / "names.epk", tmp_path)
    assert exit_time(records) == 781      # 78 steps at 100 steps/s, then exit_main


def test_sequence_steps_wait_for_motions_and_hide_their_stops(tmp_path):
    records, _ = run_program(GOLDEN / "sequences.epk", tmp_path)
    starts = [t for t, _ in steps_at(records)]
    # forward (388 steps at 500/s: 776 ms) then turn (323 steps: 646 ms), twice,
    # then set_timer with the next leg, then its turn, then exit_main
    assert starts == [1, 777, 1423, 2199, 2845, 3621, 4267]
    assert len(starts) == 7


def test_timeout_exits_non_zero(tmp_path):
    records, out = run_program(GOLDEN / "cancel.epk", tmp_path, "--time-limit", "500ms",
                               expect=3)
    assert records[-1]["kind"] == "timeout"


def test_set_robot_geometry_converts_the_papers_millimetres(tmp_path):
    """Hand-written C: the paper's figure 2 with the paper's own step length."""
    prog = tmp_path / "fig2_paper_step.c"
    prog.write_text("""#include "utility.h"
int main(void){
    int a1, a2;
    param_start_straight sample = {250, 100};
    set_robot_geometry(257610L, 53000L, 1000L);
    a1 = register_action(start_straight, &sample);
    a2 = register_action(exit_main, NULL);
    register_event(immediate, NULL, a1);
    register_event(event_stop_motor, NULL, a2);
    mainloop();
    return 0;
}
""")
    records, _ = run_program(prog, tmp_path)
    [end] = [r for r in records if r["kind"] == "exit"]
    assert end["left_steps"] == 388 and abs(end["x_mm"] - 100) < 0.2


def test_if_else_takes_the_branch_of_the_readings(tmp_path):
    """ifelse.epk with something near in front all along: `look` takes its
    `else if` branch (150 steps/s) at every period; the timer rule's branch
    counts the turns, turns each way in turn (the named action's `if`),
    and on the fourth its inner `if` cancels `look` and enters `resting`."""
    scenario = tmp_path / "near.scn"
    scenario.write_text("0 ms ir0=900\n", encoding="utf-8")
    records, _ = run_program(GOLDEN / "ifelse.epk", tmp_path, "--scenario", scenario,
                             "--time-limit", "22s", expect=3)
    turns = [(r["t_ms"], r["value"]) for r in records
             if r["kind"] == "set" and r["var"] == "turns"]
    assert [v for _, v in turns] == [1, 2, 3, 4]
    assert [t // 1000 for t, _ in turns] == [5, 10, 15, 20]
    look = events(records, "rule look")
    # 150 steps/s for 20 ms: 3 steps a period, until the first turn
    early = [r["left_steps"] for r in look if r["t_ms"] < 5000]
    assert early[1] - early[0] == 3
    entered = [r["t_ms"] for r in records if r["kind"] == "mode"]
    assert entered[-1] == turns[-1][0]
    assert max(r["t_ms"] for r in look) < entered[-1]     # cancelled with the entry
    # the named action's branches turn opposite ways: right on odd turns,
    # left on even ones (heading when the timer fires, before its dodge)
    headings = [round(r["heading_deg"]) for r in records if r["kind"] == "event"
                and "timer" in r["name"]]
    assert headings == [0, -90, 0, -90]
