"""Property: with all priorities equal, behaviour is exactly the paper's.
Random rule programs are run on the harness twice, as written and with the
same `priority N` on every rule; the traces must be the same record for
record (the rule labels, which quote the priority, aside)."""
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from tests.support.programs import run_program

EVENTS = ["immediate", "stop_motor repeat", "stop_motor", "timer(300 ms) repeat",
          "timer(700 ms)", "sensor(ir0 > 500) repeat", "sensor(ir7 > 500)"]
# (no set_timer: the program must reach its exit at 2 s)
ACTIONS = ["start_straight(300, 5 cm)", "start_curve(0 mm, 90 deg, 400)", "stop_motor",
           "start_straight(500, 2 cm) then start_curve(0 mm, -45 deg, 300)",
           "led_toggle(all)", "play_sound(haa), start_straight(200, 1 cm)"]
SCENARIO = "0 ms ir0=0 ir7=0\n400 ms ir0=900\n650 ms ir0=0 ir7=800\n900 ms ir0=700\n"


def _strip(records):
    return [{k: v for k, v in r.items() if k not in ("name", "owner_name")} for r in records]


@settings(max_examples=6, deadline=None, suppress_health_check=[HealthCheck.too_slow,
                                                                 HealthCheck.function_scoped_fixture])
@given(st.lists(st.tuples(st.sampled_from(EVENTS), st.sampled_from(ACTIONS)),
                min_size=2, max_size=6),
       st.integers(1, 255))
def test_equal_priorities_change_nothing(tmp_path, rules, priority):
    lines = ["on immediate do start_sensor, set_timer"]
    lines += [f"on {event} do {action}" for event, action in rules]
    lines.append("on timer(2 s) do exit_main")
    plain = "\n".join(lines) + "\n"
    equal = "\n".join(line.replace(" do ", f" priority {priority} do ", 1)
                      for line in lines) + "\n"
    scenario = tmp_path / "s.scn"
    scenario.write_text(SCENARIO)
    traces = []
    for name, text in (("plain", plain), ("equal", equal)):
        folder = tmp_path / name
        folder.mkdir(exist_ok=True)
        path = folder / "prog.epk"
        path.write_text(text)
        records, _ = run_program(path, folder, "--scenario", scenario)
        traces.append(_strip(records))
    assert traces[0] == traces[1]
    assert not any(r["kind"] == "suppressed" for r in traces[1])
