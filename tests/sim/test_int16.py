"""`epuckc run --int16` (epuckc/sim/int16.py): a rule program and its extern
C on the 16-bit path (avr-gcc, simavr) against a scenario: the extern's int
overflow wraps as on the dsPIC, where the host's 32-bit int hides it."""
import json
from pathlib import Path

import pytest

from conftest import require_tool
from tests.support.programs import epuckc

RULES = """\
extern action steer() from "steer.c"
every 50 ms do steer()
after 1 s do exit_main
"""

# GCtronic's shock_neuron multiplies a weight by a reading in int
STEER_C = """\
#include "ovf_externs.h"
#include <a_d/advance_ad_scan/e_prox.h>
#include <motor_led/advance_one_timer/e_motors.h>
static int weight = WEIGHT;
void steer(void *param)
{
    int potential = weight * e_get_prox(0);
    (void)param;
    e_set_speed_left(potential / 64);
    e_set_speed_right(potential / 64);
}
"""
WEIGHT, NEAR, FAR = 16, 2100, 1000


@pytest.fixture
def program(tmp_path):
    require_tool("avr-gcc")
    require_tool("simavr")
    if not Path("/usr/include/simavr/sim_avr.h").exists():
        require_tool("libsimavr-dev (the simavr headers)")
    (tmp_path / "ovf.epk").write_text(RULES)
    (tmp_path / "steer.c").write_text(STEER_C.replace("WEIGHT", str(WEIGHT)))
    (tmp_path / "s.scn").write_text(f"0 ms ir0={FAR}\n300 ms ir0={NEAR}\n")
    return tmp_path


def _c_int(value: int, bits: int) -> int:
    value &= (1 << bits) - 1
    return value - (1 << bits) if value >> (bits - 1) else value


def _c_div(a: int, b: int) -> int:
    q = abs(a) // abs(b)
    return q if (a >= 0) == (b >= 0) else -q


def _speeds(bits: int) -> tuple:
    return tuple(_c_div(_c_int(WEIGHT * reading, bits), 64) for reading in (FAR, NEAR))


def _last(tmp_path, *extra):
    trace = tmp_path / "t.jsonl"
    result = epuckc("run", tmp_path / "ovf.epk", "--scenario", tmp_path / "s.scn",
                    "--trace", trace, *extra)
    assert result.returncode == 0, result.stdout + result.stderr
    records = [json.loads(line) for line in trace.read_text().splitlines()]
    return records


def test_an_int_overflow_in_the_extern_wraps_as_on_the_dspic(program):
    far16, near16 = _speeds(16)
    far32, near32 = _speeds(32)
    assert near16 < 0 < near32          # 16 * 2100 = 33600 does not fit 16 bits
    # the first command at 51 ms, the reading near from the one at 301 ms
    def steps(far, near):
        return int(far * 250 / 1000) + near * 700 / 1000
    avr = _last(program, "--int16")
    host = _last(program)
    assert avr[-1]["kind"] == host[-1]["kind"] == "exit"
    assert avr[-1]["left_steps"] == pytest.approx(steps(far16, near16), abs=2)
    assert host[-1]["left_steps"] == pytest.approx(steps(far32, near32), abs=2)
    # the same events at the same times on both paths
    assert [(r["t_ms"], r["id"]) for r in avr if r["kind"] == "event"] == \
        [(r["t_ms"], r["id"]) for r in host if r["kind"] == "event"]


def test_int16_runs_against_a_scenario_only(program):
    world = program / "w.world"
    world.write_text("arena 50 cm x 50 cm\nrobot at 25 cm, 25 cm\n")
    result = epuckc("run", program / "ovf.epk", "--int16", "--world", world)
    assert result.returncode == 2 and "--int16" in result.stderr


C_MAIN = """\
#include <string.h>
#include <motor_led/advance_one_timer/e_agenda.h>
#include <motor_led/advance_one_timer/e_led.h>
#include <motor_led/advance_one_timer/e_motors.h>
#include <uart/e_uart_char.h>
#include <utility/utility.h>
int main(void)
{
    const char *hello = "hello\\r\\n";
    e_init_uart1();                     /* off until then, as on the robot */
    e_send_uart1_char(hello, (int)strlen(hello));
    wait(100000L);                      /* 40.7 ms on the dsPIC */
    e_set_speed_left(200);
    e_set_speed_right(-200);
    e_activate_agenda(flow_led, 1000);
    e_start_agendas_processing();
    while (1);
}
"""


def test_a_c_main_runs_on_the_16_bit_path_as_on_the_host(program):
    main = program / "main.c"
    main.write_text(C_MAIN)
    runs = []
    for extra in (["--int16"], []):
        trace = program / f"c{len(runs)}.jsonl"
        result = epuckc("run", main, "--time-limit", "1s", "--trace", trace, *extra)
        assert result.returncode == 3, result.stdout + result.stderr
        runs.append([json.loads(line) for line in trace.read_text().splitlines()])
    avr, host = runs
    assert [r["text"] for r in avr if r["kind"] == "uart"] == ["hello\r\n"]
    # the agenda's LED steps, the wheels' steps at the end: as on the host,
    # within the AVR's own time for main's code (it runs at its speed, not
    # the dsPIC's: a ms or two)
    def leds(records):
        return [(r["t_ms"], r["name"], r["state"]) for r in records if r["kind"] == "led"]
    assert [x[1:] for x in leds(avr)] == [x[1:] for x in leds(host)] and len(leds(avr)) >= 9
    assert all(abs(a[0] - h[0]) <= 2 for a, h in zip(leds(avr), leds(host)))
    assert avr[-1]["left_steps"] == pytest.approx(host[-1]["left_steps"], abs=1)
    assert avr[-1]["right_steps"] == pytest.approx(host[-1]["right_steps"], abs=1)
    assert avr[-1]["kind"] == host[-1]["kind"] == "timeout"


def test_inline_dspic_instructions_are_refused_on_the_16_bit_path_with_the_way_out(program):
    main = program / "reset.c"
    main.write_text("#include <p30F6014A.h>\nint main(void)\n{\n"
                    "    __asm__ volatile (\"reset\");\n    while (1);\n}\n")
    trace = program / "r.jsonl"
    refused = epuckc("run", main, "--int16", "--time-limit", "50ms", "--trace", trace)
    assert refused.returncode != 0 and "Traceback" not in refused.stderr
    assert "run it without --int16" in refused.stderr and not trace.exists()
    # the same C without inline instructions builds on the 16-bit path
    main.write_text("#include <p30F6014A.h>\nint main(void)\n{\n    while (1);\n}\n")
    built = epuckc("run", main, "--int16", "--time-limit", "50ms", "--trace", trace)
    assert built.returncode == 3 and "--int16" not in built.stderr, built.stderr
