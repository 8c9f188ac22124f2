"""C programs with their own main, written against the e-puck library, on
the simulated e-puck (runtime_c/host/cmain.c, docs/runtime.md "C programs
with their own main"): main's clock in dsPIC cycles, wait() as the
library's busy loop, agendas preempting main, a spinning main letting
simulated time run on, the library's pins and UART, e_calibrate_ir; and
the watchdog, which stops code that keeps the simulator waiting."""
import json
import re

import pytest

from conftest import REPO, require_enki
from tests.support.programs import epuckc

STUB_H = (REPO / "runtime_c" / "host" / "epuck_stub.h").read_text()
CMAIN_C = (REPO / "runtime_c" / "host" / "cmain.c").read_text()


def _define(text: str, name: str) -> int:
    return int(re.search(rf"#define {name} (\d+)", text).group(1))


WAIT_CYCLES = _define(STUB_H, "STUB_WAIT_LOOP_CYCLES")
FCY = 14_745_600        # the e-puck 1's dsPIC: 7.3728 MHz x 8 / 4
EXIT_WATCHDOG = _define(CMAIN_C, "EXIT_WATCHDOG")


def _run(tmp_path, files, *extra, expect):
    trace = tmp_path / "trace.jsonl"
    result = epuckc("run", *files, "--trace", trace, *extra)
    assert result.returncode == expect, result.stdout + result.stderr
    records = [json.loads(line) for line in trace.read_text().splitlines()]
    return records, result


def _write(tmp_path, name, text):
    path = tmp_path / name
    path.write_text(text)
    return path


WAITER = """\
#include <motor_led/e_epuck_ports.h>
#include <motor_led/advance_one_timer/e_led.h>
#include <utility/utility.h>
int main(void)
{
    int k;
    for (k = 0; k < 6; k++) {
        e_set_led(0, 2);
        wait(WAIT_COUNT);
    }
    LED3 = 1;                       /* the pin, as the library's programs write it */
    wait(WAIT_COUNT);
    return 0;
}
"""


def test_wait_takes_the_busy_loops_time_on_the_dspic(tmp_path):
    count = 150000
    main = _write(tmp_path, "main.c", WAITER.replace("WAIT_COUNT", f"{count}L"))
    records, _ = _run(tmp_path, [main], expect=0)
    led0 = [r for r in records if r["kind"] == "led" and r["name"] == "led0"]
    assert [r["state"] for r in led0] == [1, 0, 1, 0, 1, 0]
    toggles = [r["t_ms"] for r in led0]
    expected_ms = count * WAIT_CYCLES * 1000 / FCY            # about 61 ms
    # A LED's record is in the ms the eye saw the change (host/outputs.c: lit
    # when on for a tenth of the ms): an LED turned on at t is seen in t's
    # ms unless it was on for less than a tenth of it, one turned off is
    # seen lit in t's ms (so off in the next) unless it was on for less
    # than a tenth of it. So an "on" is at floor(t + 0.1) and an "off" at
    # floor(t + 0.9): two records of the same kind are a whole number of
    # ms apart that is the loops' time to within 1 ms, two of different
    # kinds are up to 1.8 ms off it (gaps of 60 and 62 for 61.04 ms).
    same = [b - a for a, b in zip(toggles, toggles[2:])]
    assert all(abs(g - 2 * expected_ms) <= 1 for g in same), (toggles, expected_ms)
    assert abs(toggles[4] - toggles[0] - 4 * expected_ms) <= 1, (toggles, expected_ms)
    gaps = [b - a for a, b in zip(toggles, toggles[1:])]
    assert all(abs(g - expected_ms) <= 1.8 for g in gaps), (gaps, expected_ms)
    # the pin written directly is an LED change, in the simulated ms it
    # happened (an "on", as the third of led0's)
    led3 = [r for r in records if r["kind"] == "led" and r["name"] == "led3"]
    assert len(led3) == 1 and led3[0]["state"] == 1 and led3[0]["ring"][3] == "1"
    assert abs(led3[0]["t_ms"] - (toggles[-2] + 2 * expected_ms)) <= 1


SPINNER = """\
#include <motor_led/advance_one_timer/e_agenda.h>
#include <motor_led/advance_one_timer/e_led.h>
#include <motor_led/advance_one_timer/e_motors.h>
int main(void)
{
    e_set_speed_left(200);
    e_set_speed_right(200);
    e_activate_agenda(flow_led, 1000);      /* every 100 ms */
    e_start_agendas_processing();
    while (1);
}
"""


def test_a_main_that_spins_lets_simulated_time_run_on_deterministically(tmp_path):
    main = _write(tmp_path, "main.c", SPINNER)
    records, result = _run(tmp_path, [main], "--time-limit", "2s", expect=3)
    leds = [r for r in records if r["kind"] == "led"]
    # flow_led: one step every 100 ms (LED0, then 1 and 7, ...) to the limit
    assert [r["t_ms"] for r in leds if r["name"] == "led0"][:2] == [100, 600]
    assert max(r["t_ms"] for r in leds) >= 1900
    assert records[-1]["kind"] == "timeout" and records[-1]["t_ms"] == 2000
    assert records[-1]["left_steps"] == records[-1]["right_steps"] == 400
    again, _ = _run(tmp_path, [main], "--time-limit", "2s", expect=3)
    assert again == records


CALIBRATED = """\
#include <stdio.h>
#include <string.h>
#include <a_d/advance_ad_scan/e_ad_conv.h>
#include <a_d/advance_ad_scan/e_prox.h>
#include <uart/e_uart_char.h>
#include <motor_led/e_epuck_ports.h>
#include <utility/utility.h>
int main(void)
{
    char text[80];
    e_init_ad_scan(ALL_ADC);
    e_init_uart1();
    e_calibrate_ir();
    sprintf(text, "%d %d", e_get_calibrated_prox(0), e_get_prox(0));
    e_send_uart1_char(text, (int)strlen(text));
    wait(5000000L);                     /* about 2 s */
    sprintf(text, "%d %d sel %d", e_get_calibrated_prox(0), e_get_prox(0),
            SELECTOR0 + 2*SELECTOR1 + 4*SELECTOR2 + 8*SELECTOR3);
    e_send_uart1_char(text, (int)strlen(text));
    return 0;
}
"""


def test_calibration_the_selector_pins_and_the_uart(tmp_path):
    main = _write(tmp_path, "main.c", CALIBRATED)
    scenario = _write(tmp_path, "s.scn", "0 ms ir0=300 selector=6\n1500 ms ir0=500 selector=11\n")
    records, result = _run(tmp_path, [main], "--scenario", scenario, expect=0)
    uart = [r for r in records if r["kind"] == "uart"]
    # the wall seen during calibration is its offset; what comes closer is seen
    assert [r["text"] for r in uart] == ["0 300", "200 500 sel 11"]
    assert all(r["name"] == "uart1" for r in uart)
    assert "uart1     200 500 sel 11" in result.stdout


HANG_RULES = """\
extern action hang() from "hang.c"
after 200 ms do hang()
after 1 s do exit_main
"""

HANG_C = """\
#include "hang_externs.h"
static int calls;
void hang(void *param)
{
    (void)param;
    calls++;
    while (1)
        ;
}
"""


def _watchdog_checks(result, records, function, file_name):
    assert function in result.stderr and "watchdog" in result.stderr, result.stderr
    assert re.search(rf"{re.escape(file_name)}:\d+", result.stderr), result.stderr
    assert records[-1]["kind"] == "watchdog" and records[-1]["name"] == function
    assert records[-1]["where"].split("/")[-1].startswith(file_name + ":")


def test_the_watchdog_stops_an_extern_action_that_never_returns(tmp_path):
    rules = _write(tmp_path, "hang.epk", HANG_RULES)
    _write(tmp_path, "hang.c", HANG_C)
    records, result = _run(tmp_path, [rules], "--watchdog", "0.5", expect=EXIT_WATCHDOG)
    _watchdog_checks(result, records, "hang", "hang.c")
    assert records[-1]["t_ms"] == 201
    assert [r["kind"] for r in records[-3:-1]] == ["event", "action"]


AGENDA_HANG = """\
#include <motor_led/advance_one_timer/e_agenda.h>
#include <motor_led/advance_one_timer/e_motors.h>
static void stuck(void)
{
    e_set_speed_left(100);
    for (;;) { }
}
int main(void)
{
    e_activate_agenda(stuck, 3000);
    e_start_agendas_processing();
    for (;;)
        e_get_steps_left();
}
"""


def test_the_watchdog_stops_an_agenda_that_never_returns(tmp_path):
    main = _write(tmp_path, "stuck.c", AGENDA_HANG)
    records, result = _run(tmp_path, [main], "--watchdog", "0.5", expect=EXIT_WATCHDOG)
    _watchdog_checks(result, records, "stuck", "stuck.c")
    assert records[-1]["t_ms"] == 300


def test_the_watchdog_in_a_world_names_the_robots_function(tmp_path):
    require_enki()
    rules = _write(tmp_path, "hang.epk", HANG_RULES)
    _write(tmp_path, "hang.c", HANG_C)
    world = _write(tmp_path, "w.world", "arena 50 cm x 50 cm\nrobot at 25 cm, 25 cm\n")
    records, result = _run(tmp_path, [rules], "--world", world, "--watchdog", "0.5",
                           expect=EXIT_WATCHDOG)
    assert "hang" in result.stderr and "watchdog" in result.stderr
    kinds = [r["kind"] for r in records]
    assert "watchdog" in kinds and kinds[-1] == "contacts"


@pytest.mark.parametrize("value", ["0", "-1", "x", "5000"])
def test_a_bad_watchdog_is_a_usage_error(tmp_path, value):
    main = _write(tmp_path, "main.c", "int main(void) { return 0; }\n")
    result = epuckc("run", main, "--watchdog", value)
    assert result.returncode == 2 and "--watchdog" in result.stderr


def test_more_files_follow_only_a_c_main(tmp_path):
    rules = _write(tmp_path, "hang.epk", HANG_RULES)
    other = _write(tmp_path, "hang.c", HANG_C)
    result = epuckc("run", rules, other)
    assert result.returncode == 2 and "extern action" in result.stderr
    main = _write(tmp_path, "main.c", "int main(void) { return 0; }\n")
    result = epuckc("run", main, tmp_path / "s.scn")
    assert result.returncode == 2 and "only C files" in result.stderr


def test_a_worlds_robot_runs_a_c_program_of_several_files(tmp_path):
    require_enki()
    (tmp_path / "lib").mkdir()
    _write(tmp_path / "lib", "drive.h", "void drive(int speed);\n")
    _write(tmp_path / "lib", "drive.c", '#include "drive.h"\n'
           "#include <motor_led/advance_one_timer/e_motors.h>\n"
           "void drive(int speed) { e_set_speed_left(speed); e_set_speed_right(speed); }\n")
    _write(tmp_path, "main.c", '#include "drive.h"\n#include <utility/utility.h>\n'
           "int main(void) { drive(300); for (;;) wait(1000L); }\n")
    world = _write(tmp_path, "w.world", "arena 100 cm x 100 cm\n"
                   "robot a at 20 cm, 20 cm program main.c lib/drive.c\n"
                   "robot b at 20 cm, 60 cm\n")
    other = _write(tmp_path, "still.c", "int main(void) { for (;;); }\n")
    records, _ = _run(tmp_path, [other], "--world", world, "--time-limit", "1s", expect=3)
    end = {r["robot"]: r for r in records if r["kind"] == "timeout"}
    assert end["a"]["left_steps"] == end["a"]["right_steps"] == 300
    assert end["b"]["left_steps"] == 0


def _declared_functions() -> tuple:
    """(every header of runtime_c/epuck_api, every function they declare)."""
    api = REPO / "runtime_c" / "epuck_api"
    headers, names = [], set()
    for header in sorted(api.rglob("*.h")):
        text = re.sub(r"/\*.*?\*/", "", header.read_text(), flags=re.S)
        if "#error" in text:
            continue            # not simulated: the next test
        headers.append(header.relative_to(api).as_posix())
        names.update(m.group(1) for m in re.finditer(
            r"^[A-Za-z_][\w \*]*?\b(\w+)\s*\([^;{]*\)\s*;", text, re.M))
    return headers, sorted(names)


def test_every_function_of_the_librarys_headers_links(tmp_path):
    """A program may call anything the headers declare: never a link error."""
    headers, names = _declared_functions()
    assert len(names) > 80 and "flow_led" in names and "e_send_uart1_char" in names
    body = "".join(f"    printf(\"%p\\n\", (void *)(size_t){name});\n" for name in names)
    main = _write(tmp_path, "all.c", "#include <stdio.h>\n#include <stddef.h>\n"
                  + "".join(f"#include <{h}>\n" for h in headers)
                  + f"int main(void)\n{{\n{body}    return 0;\n}}\n")
    result = epuckc("run", main, "--time-limit", "10ms")
    assert result.returncode == 0, result.stderr
    assert "undefined reference" not in result.stderr


UNSIMULATED = """\
#include <motor_led/e_epuck_ports.h>
#include <motor_led/e_init_port.h>
#include <bluetooth/e_bluetooth.h>
#include <I2C/e_I2C_protocol.h>
#include <utility/utility.h>
int main(void)
{
    e_init_port();
    LED2 = 1;
    wait(100000L);                  /* 41 ms */
    if (getselector() == 3)
        e_i2cp_init();
    return e_bt_reset();
}
"""


def test_what_is_not_simulated_builds_and_a_call_of_it_ends_the_run(tmp_path):
    """Bluetooth and I2C are declared at the library's paths and link; the
    program runs until it calls one (the selector decides here), which ends
    the run with status 6, naming the function and the device."""
    main = _write(tmp_path, "bt.c", UNSIMULATED)
    records, result = _run(tmp_path, [main], "--time-limit", "1s", expect=6)
    assert "e_bt_reset: Bluetooth" in result.stderr and "not simulated" in result.stderr
    assert records[-1]["kind"] == "unsimulated" and records[-1]["name"] == "e_bt_reset"
    assert 40 <= records[-1]["t_ms"] <= 45
    assert any(r["kind"] == "led" and r["name"] == "led2" for r in records)
    scenario = _write(tmp_path, "s.scn", "0 ms selector=3\n")
    records, result = _run(tmp_path, [main], "--scenario", scenario, expect=6)
    assert records[-1]["name"] == "e_i2cp_init" and "the I2C bus" in result.stderr


@pytest.mark.parametrize("header,what", [("a_d/e_micro.h", "a_d/advance_ad_scan/e_micro.h"),
                                         ("motor_led/advance_one_timer/fast_agenda/"
                                          "e_agenda_fast.h", "advance_one_timer/e_agenda.h")])
def test_a_variant_the_simulation_does_not_have_is_a_build_error_naming_it(tmp_path, header,
                                                                           what):
    """The library's variants whose functions differ from the simulated
    ones' (the timer-driven A/D, the fast agenda) stop at the build with the
    header to use instead, never at a link error."""
    main = _write(tmp_path, "v.c", f"#include <{header}>\nint main(void) {{ return 0; }}\n")
    result = epuckc("run", main)
    assert result.returncode == 1
    assert f"{header}: " in result.stderr and what in result.stderr
    assert "not simulated" in result.stderr and "undefined reference" not in result.stderr


BLOCKED = """\
#define _POSIX_C_SOURCE 200809L
#include <unistd.h>
#include <motor_led/advance_one_timer/e_motors.h>
int main(void)
{
    e_set_speed_left(100);
    for (;;)
        pause();
}
"""


def test_the_watchdog_stops_a_main_that_never_reaches_the_simulator(tmp_path):
    """Blocked in a system call, main's clock barely moves (a block a
    wake-up): simulated time stands still, the watchdog names main."""
    main = _write(tmp_path, "block.c", BLOCKED)
    records, result = _run(tmp_path, [main], "--watchdog", "0.5", expect=EXIT_WATCHDOG)
    _watchdog_checks(result, records, "main", "block.c")
    assert records[-1]["t_ms"] == 0


GYRO_SPIN = """\
#include <stdio.h>
#include <string.h>
#include <motor_led/e_init_port.h>
#include <motor_led/advance_one_timer/e_motors.h>
#include <motor_led/advance_one_timer/e_agenda.h>
#include <acc_gyro/e_lsm330.h>
#include <uart/e_uart_char.h>
#include <utility/utility.h>
int main(void)
{
    char line[16];
    int k;
    e_init_port();
    e_init_uart1();
    e_init_motors();
    initAccAndGyro();
    e_start_agendas_processing();
    e_set_speed_left(-SPEED);
    e_set_speed_right(SPEED);
    wait(600000L);                  /* about 0.25 s: the turn under way */
    for (k = 0; k < 50; k++) {
        sprintf(line, "%d\\n", getZAxisGyro());
        e_send_uart1_char(line, (int)strlen(line));
        wait(8000L);                /* about 3.3 ms: the samples' phase against the steps moves on */
    }
    return 0;
}
"""


@pytest.mark.parametrize("speed", [400, 130])
def test_the_gyroscope_reads_the_bodys_turn_in_a_world_steady(tmp_path, speed):
    """Spinning on the spot in a world: z is the body's rate of turn at the
    sensor's 8.75 mdps a unit, steady (the wheels step every 2.5 or 7.7 ms;
    a rate taken over one ms of steps would swing between 0 and twice it)."""
    require_enki()
    main = _write(tmp_path, "spin.c", GYRO_SPIN.replace("SPEED", str(speed)))
    world = _write(tmp_path, "w.world", "arena 1 m x 1 m\nnoise 0 %\n"
                   "robot at 50 cm, 50 cm program spin.c\n")
    records, _ = _run(tmp_path, [main], "--world", world, "--time-limit", "2s", expect=0)
    text = "".join(r["text"] for r in records if r["kind"] == "uart")
    readings = [int(v) for v in text.split()]
    assert len(readings) == 50
    mm_per_s = speed * 128.805 / 1000
    expected = 2 * mm_per_s / 53.0 * 180 / 3.141592653589793 / 0.00875     # counter-clockwise
    assert abs(sum(readings) / 50 / expected - 1) < 0.02, (readings, expected)
    assert max(readings) - min(readings) < 0.03 * expected, readings
