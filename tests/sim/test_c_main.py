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
    toggles = [r["t_ms"] for r in records if r["kind"] == "led" and r["name"] == "led0"]
    assert len(toggles) == 6
    expected_ms = count * WAIT_CYCLES * 1000 / FCY            # about 61 ms
    gaps = [b - a for a, b in zip(toggles, toggles[1:])]
    assert all(abs(g - expected_ms) <= 1 for g in gaps), (gaps, expected_ms)
    # the pin written directly is an LED change, in the simulated ms it happened
    led3 = [r for r in records if r["kind"] == "led" and r["name"] == "led3"]
    assert len(led3) == 1 and led3[0]["state"] == 1 and led3[0]["ring"][3] == "1"
    assert abs(led3[0]["t_ms"] - (toggles[-1] + expected_ms)) <= 1


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


@pytest.mark.parametrize("header,what", [("camera/fast_2_timer/e_po8030d.h", "camera"),
                                         ("bluetooth/e_bluetooth.h", "Bluetooth"),
                                         ("a_d/e_prox.h", "a_d/advance_ad_scan/e_prox.h")])
def test_what_is_not_simulated_is_a_build_error_naming_it(tmp_path, header, what):
    main = _write(tmp_path, "cam.c", f"#include <{header}>\nint main(void) {{ return 0; }}\n")
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
