"""Every example runs on the host harness and does what it says."""
import math

from tests.support.programs import EXAMPLES, events, run_program


def final(records):
    exits = [r for r in records if r["kind"] == "exit"]
    assert len(exits) == 1, records[-3:]
    return exits[0]


def test_paper_fig2_drives_100_mm_then_exits(tmp_path):
    records, out = run_program(EXAMPLES / "paper_fig2.epk", tmp_path)
    end = final(records)
    assert end["left_steps"] in (776, 777) and end["right_steps"] in (776, 777)
    assert 3000 <= end["t_ms"] <= 3200
    assert abs(end["x_mm"] - 100) < 0.5 and abs(end["y_mm"]) < 0.1
    [stop] = events(records, "on stop_motor")
    assert stop["name"].startswith("paper_fig2.epk:7")
    # the readable trace names the rule's file:line and the action it ran
    assert "paper_fig2.epk:6 on immediate" in out and "action #0 go" in out
    assert out.strip().splitlines()[-1].startswith("exit at")


def test_square_comes_back_to_its_start_facing_the_same_way(tmp_path):
    records, _ = run_program(EXAMPLES / "square.epk", tmp_path)
    end = final(records)
    assert math.hypot(end["x_mm"], end["y_mm"]) < 3.0
    heading = (end["heading_deg"] + 180) % 360 - 180
    assert abs(heading) < 1.0
    # four sides of 20 cm were driven: each wheel about 4 * 1553 steps forward
    # plus the turns (+-323 each), so the sum of both wheels is 8 straight sides
    assert abs(end["left_steps"] + end["right_steps"] - 8 * 1553) <= 8


def test_obstacle_avoidance_turns_once_per_obstacle(tmp_path):
    records, _ = run_program(EXAMPLES / "obstacle_avoidance.epk", tmp_path,
                             "--scenario", EXAMPLES / "obstacle.scn")
    avoid = events(records, "rule avoid")
    # the scenario puts an obstacle in front at 1.2 s and again at 5.0 s;
    # the repeated rule fires on each rising edge, not at every poll
    assert [r["t_ms"] for r in avoid] == [1200, 5000]
    cruise = events(records, "rule cruise")
    assert len(cruise) == 2
    assert abs(cruise[0]["heading_deg"] - 90) < 1.0     # turned left on the spot
    assert final(records)["t_ms"] == 8001


def test_obstacle_avoidance_without_scenario_never_turns(tmp_path):
    records, _ = run_program(EXAMPLES / "obstacle_avoidance.epk", tmp_path)
    assert events(records, "rule avoid") == []


def test_timed_patrol_fires_periodically_until_cancelled(tmp_path):
    records, _ = run_program(EXAMPLES / "timed_patrol.epk", tmp_path)
    times = [r["t_ms"] for r in events(records, "rule turn_back")]
    assert times == [3001, 6001, 9001, 12001]       # every 3 s, none after the cancel at 14 s
    assert final(records)["t_ms"] == 16001


def test_extern_action_in_c_spins_two_turns(tmp_path):
    records, _ = run_program(EXAMPLES / "extern_spin.epk", tmp_path)
    end = final(records)
    # 2 turns on the spot: the outer wheel's arc is 2 * pi * 53 mm = 333 mm
    expected = round(2 * math.pi * 53.0 / (math.pi * 41.0 / 1000))
    assert abs(end["right_steps"] - expected) <= 2 and abs(end["left_steps"] + expected) <= 2
    assert math.hypot(end["x_mm"], end["y_mm"]) < 0.5


def test_explorer_layers_wander_avoid_escape(tmp_path):
    records, out = run_program(EXAMPLES / "explorer.epk", tmp_path,
                               "--scenario", EXAMPLES / "explorer.scn")
    assert [r["t_ms"] for r in events(records, "rule avoid")] == [2000, 6000]
    [escape] = events(records, "rule escape")
    assert escape["t_ms"] == 6000
    # at 6 s both fire; escape (priority 2) runs first and avoid's turn is suppressed
    at_6s = [r for r in records if r["t_ms"] == 6000 and r["kind"] in ("event", "suppressed")]
    assert [r["kind"] for r in at_6s] == ["event", "event", "suppressed"]
    assert "escape" in at_6s[0]["name"] and "avoid" in at_6s[1]["name"]
    [refused] = [r for r in records if r["kind"] == "suppressed"]
    assert refused["command"] == "start_curve" and "escape" in refused["owner_name"]
    assert (refused["priority"], refused["owner_priority"]) == (1, 2)
    assert "suppressed start_curve" in out
    # escape backed off 5 cm and turned round: heading from +90 to -90
    wander_after = [r for r in events(records, "rule wander") if r["t_ms"] > 6000]
    assert abs(wander_after[0]["heading_deg"] + 90) < 1.0
    assert [r["name"] for r in records if r["kind"] == "sound"] == ["spaah"]
    assert final(records)["t_ms"] == 15001


def test_two_phase_modes_explore_then_go_home(tmp_path):
    records, out = run_program(EXAMPLES / "two_phase.epk", tmp_path,
                               "--scenario", EXAMPLES / "explorer.scn")
    assert [(r["t_ms"], r["name"]) for r in records if r["kind"] == "mode"] == [
        (0, "explore"), (20001, "home")]
    assert "mode      home" in out
    # no explore rule fires once home is entered; home's rules only after it
    entered = 20001
    assert all(r["t_ms"] <= entered for r in events(records, "wander"))
    home_enter = [r for r in events(records, "on enter") if r["t_ms"] > entered]
    assert [r["t_ms"] for r in home_enter] == [entered + 1]
    # entering home stopped explore's drive at once: no wheel moved in between
    at_entry = [r for r in records if r["kind"] == "mode" and r["t_ms"] == entered][0]
    assert home_enter[0]["left_steps"] == at_entry["left_steps"]
    end = final(records)
    assert [r["name"] for r in records if r["kind"] == "sound"] == ["ouah", "yaouh"]
    assert abs(abs(end["heading_deg"]) - abs(at_entry["heading_deg"] - 180)) < 1.0


def test_selector_menu_switches_behaviours(tmp_path):
    records, _ = run_program(EXAMPLES / "selector_menu.epk", tmp_path,
                             "--scenario", EXAMPLES / "selector_menu.scn")
    assert [(r["t_ms"], r["name"]) for r in records if r["kind"] == "mode"] == [
        (0, "idle"), (1, "square"), (8000, "dance"), (12000, "idle")]
    assert [r["name"] for r in records if r["kind"] == "sound"] == [
        "haa", "spaah", "wouaaaaaaaah"]
    # the square closed on itself before the dance
    square_done = [r for r in events(records, "on stop_motor") if r["t_ms"] < 8000][0]
    assert math.hypot(square_done["x_mm"], square_done["y_mm"]) < 2.0
    # idle blinks the front LED every 500 ms until the standby key
    blinks = [r["t_ms"] for r in records if r["kind"] == "led" and r["name"] == "front"]
    assert blinks[:3] == [12501, 13001, 13501]
    end = final(records)
    assert end["t_ms"] == 14000
    last_led = [r for r in records if r["kind"] == "led"][-1]
    assert last_led["ring"] == "00000000" and last_led["body"] == 0


def test_the_readable_trace_names_the_call_of_each_step(tmp_path):
    """A step of a sequence is shown with its call, as the rule file writes
    it (named actions spliced in), not only its number."""
    _, shown = run_program(EXAMPLES / "square.epk", tmp_path, "--time-limit", "30s")
    steps = [line.split(" step ", 1)[1] for line in shown.splitlines() if " step " in line]
    assert steps[:3] == ["1 of 9: start_straight(speed: SPEED, distance: 20 cm)",
                         "2 of 9: start_curve(radius: 0 mm, degrees: 90 deg, speed: SPEED)",
                         "3 of 9: start_straight(speed: SPEED, distance: 20 cm)"]
    assert steps[-1] == "9 of 9: exit_main"


def test_zones_slows_near_and_turns_away_from_the_nearer_side(tmp_path):
    """examples/zones.epk: its `if/else` turns right when the obstacle is
    nearer on the left (ir7 > ir0 at 1.2 s), left when it is nearer on the
    right (ir0 > ir7 at 5 s), and slows while something is near."""
    records, _ = run_program(EXAMPLES / "zones.epk", tmp_path,
                             "--scenario", EXAMPLES / "obstacle.scn")
    avoid = events(records, "rule avoid")
    assert [r["t_ms"] for r in avoid] == [1200, 5000]
    end = final(records)
    # -90 then +90: back to the first heading, having driven a step aside
    assert round(avoid[1]["heading_deg"]) == -90 and round(end["heading_deg"]) == 0
    assert [v for _, v in [(r["t_ms"], r["value"]) for r in records
                           if r["kind"] == "set" and r["var"] == "turns"]] == [1, 2]
