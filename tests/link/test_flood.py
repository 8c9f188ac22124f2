"""A program that sends more than the robot's link carries (four records
a ms; the 115200-baud link takes about one): on simavr, in the robot's
time, its records are dropped, each counted where it is missing, the link
runs full, and every poll still ends within its 1 ms (16000 cycles of the
AVR at 16 MHz, measured on its Timer1 as bench/robot_bench.py measures
polls: cycle for cycle in the simulator)."""

from epuckc.build.trace_table import trace_table
from epuckc.sim.readable import readable_trace
from tests.support.programs import run_program
from tests.support.robot_trace import (assert_robot_trace_is_hosts, decode, program_of,
                                       require_simavr, robot_run)

FLOOD = """\
# four records a ms: the event, its action, two variables
var n = 0
var m = 0
every 1 ms do n += 1, m = n % 7
after 3 s do exit_main
"""
BUDGET = 16000


def test_a_flood_drops_and_counts_and_the_poll_keeps_its_ms(tmp_path):
    require_simavr()
    program = program_of(tmp_path / "flood.epk", FLOOD)
    run = robot_run(program, None, 4000)
    robot = decode(trace_table(program), run.uart)
    host, _ = run_program(tmp_path / "flood.epk", tmp_path, "--time-limit", "4s")
    assert_robot_trace_is_hosts(host, robot)
    dropped = [r for r in robot if r["kind"] == "dropped"]
    total = dropped[-1]["total"]
    assert sum(r["count"] for r in dropped) == total
    kept = len([r for r in robot if r["kind"] not in ("dropped", "pose")])
    assert kept + total == len([r for r in host if r["kind"] not in ("input", "pose")])
    assert total > kept             # most of the flood could not go
    # the link ran full: 3 s at about 11,360 bytes a second (simavr's byte
    # time at the model's rate: 88 us)
    assert len(run.uart) > 0.9 * 3.0 * 1_000_000 / 88
    assert run.overruns == 0 and run.max_cycles < BUDGET, (run.max_cycles, run.max_ms)
    assert robot[-1]["kind"] == "exit"
    # and the readable trace says so, as `epuckc monitor` prints it
    shown = readable_trace(robot).splitlines()
    told = [line for line in shown if " dropped   " in line]
    assert len(told) == len(dropped)
    assert told[-1].endswith(f"the robot's link was full ({total} so far)")
