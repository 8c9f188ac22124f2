"""Idle polls in bulk (runtime_c/rt_idle.c, docs/runtime.md): the host
skips the polls that can change nothing but time, and every trace stays the
same byte for byte. Each run here is made twice, as it is and with
EPUCK_POLL_EVERY_MS=1 (every ms polled, the reference), and the two must
give the same trace, output and exit status: the runtime's test programs
(both registration paths), every example with its scenario, and programs
of the language fuzzer under random scenarios. tests/sim/test_idle_bulk_world.py
does the same in Enki worlds. A test also checks that polls are skipped at
all, so that the comparisons are not of two ms-by-ms runs."""
from __future__ import annotations

import random

import pytest

from tests.runtime.rt_helpers import PROGRAMS, build, registration, run  # noqa: F401
from tests.runtime.test_runtime_build import SANITIZED
from tests.support.bulk import EVERY_MS, GENERATED, accepted_programs, random_scenario
from tests.support.programs import EXAMPLES, epuckc


def same_both_ways(run_once):
    """run_once(env) -> (trace bytes, stdout, status), in bulk and ms by ms."""
    bulk, every = run_once({}), run_once(EVERY_MS)
    assert bulk[0], "no trace"
    assert bulk == every
    return bulk


@pytest.mark.parametrize("name", sorted(SANITIZED))
@pytest.mark.usefixtures("registration")
def test_runtime_programs_trace_the_same(tmp_path, name):
    opts = SANITIZED[name]
    exe = build(tmp_path, PROGRAMS / name, defines=opts.get("defines", ()))
    scenario = (PROGRAMS / name).with_suffix(".scn")

    def once(env):
        r = run(exe, tmp_path, scenario=scenario if scenario.exists() else None,
                time_limit=opts.get("time_limit", 20000), env=env)
        return r.trace_bytes, r.stdout, r.returncode
    same_both_ways(once)


# The compiled sensor condition counts its calls: the runtime calls it once
# in each poll that runs while the sensors are on.
COUNTING = r"""
#include <stdio.h>
#include "epuckrt.h"

static long calls;

static void conditions(const int *ir, unsigned *bits)
{
    calls++;
    bits[0] = ir[0] > 500 ? 2u : 0u;     /* event 1 */
}

static void begin(void *p) { (void)p; start_sensor(NULL); set_timer(NULL); }
static const param_straight_steps drive = {500, 300};
static const param_event_timer at = {900L};
static const rt_action actions[] = {
    {begin, NULL}, {straight_steps, &drive}, {exit_main, NULL},
};
static const rt_event events[] = {
    {immediate, NULL, 0, 0, RT_NO_MEMORY, 0, 0},
    {NULL, NULL, 1, RT_REPEAT, RT_NO_MEMORY, 0, 0},
    {timer, &at, 2, 0, 0, 0, 0},
};
static unsigned state[RT_STATE_WORDS(3, 3)];
static long memory[1];
static const rt_program program = {actions, 3, events, 3, conditions, 0x01, state, memory, NULL};

int main(void)
{
    register_program(&program);
    mainloop();
    fprintf(stderr, "calls %ld\n", calls);
    return 0;
}
"""


def test_idle_polls_are_skipped_and_the_others_run(tmp_path):
    """ir0 passes 500 at 300 ms: the condition fires then, its motion (300
    steps at 500 steps/s) ends at 900 ms, the timer (set at 1 ms) fires at
    901 ms: the same in both runs, while the bulk run calls the condition
    in a few polls only (after a change, at the scenario's lines, the
    motion's end, the timer), not in 900."""
    exe = build(tmp_path, COUNTING, name="counting")
    scenario = "300 ms ir0=800\n600 ms ir0=0\n"
    runs = {}
    for mode, env in (("bulk", {}), ("every", EVERY_MS)):
        r = run(exe, tmp_path, scenario=scenario, env=env)
        assert r.returncode == 0, r.stderr
        runs[mode] = r
    assert runs["bulk"].trace_bytes == runs["every"].trace_bytes
    assert runs["bulk"].times("event") == [1, 300, 901]
    calls = {m: int(r.stderr.split("calls ")[1]) for m, r in runs.items()}
    assert calls["every"] == 900           # every poll from 2 ms (the sensors on) to 901
    assert 3 <= calls["bulk"] <= 10, calls


# Programs for what a poll sees besides its armed events: a one-shot rule
# that fired still holds the motors while its condition holds (read at each
# poll, even disarmed), conditions on the odometry and on random numbers,
# waits in sequences, guarded timers, a stop_motor rule after a motion.
HELD = {
    "odometry": """on immediate do set_speed(200 steps/s, 200 steps/s)
rule h: when x < 50 mm priority 1 do led_on(body), set_speed(300 steps/s, 300 steps/s)
""",
    "random": """var n = 0
on immediate do set_speed(150 steps/s, -150 steps/s)
rule h: when random(0, 999) > 3 priority 2 do n += 1, set_speed(100 steps/s, 100 steps/s)
every 37 ms priority 1 do set_speed(-80 steps/s, 80 steps/s)
""",
    "guards": """var k = 0
on immediate do set_timer, start_sensor
on timer(230 ms) repeat priority 1 if k < 4 do k += 1, start_curve(radius: 0 mm, degrees: 45 deg, speed: 300)
on sensor(ir0 > 300) repeat priority 2 if k > 1 do start_straight(-200, 1 cm) then wait(150 ms) then set_speed(100, 100)
rule s: on stop_motor repeat do led_toggle(front)
after 1700 ms if k >= 2 do exit_main
""",
}


@pytest.mark.parametrize("name", sorted(HELD))
def test_held_motors_and_odd_conditions_trace_the_same(tmp_path, name):
    path = tmp_path / f"{name}.epk"
    path.write_text(HELD[name], encoding="utf-8")
    scenario = tmp_path / "s.scn"
    scenario.write_text("0 ms ir0=0\n400 ms ir0=800\n420 ms ir0=0\n1100 ms ir0=900\n1150 ms ir0=0\n",
                        encoding="utf-8")

    def once(env):
        trace = tmp_path / "t.jsonl"
        r = epuckc("run", path, "--scenario", scenario, "--time-limit", "3s", "--trace", trace,
                   env=env)
        assert r.returncode in (0, 3), r.stderr
        return trace.read_bytes(), r.stdout, r.returncode
    same_both_ways(once)


@pytest.mark.parametrize("example", sorted(p.name for p in EXAMPLES.glob("*.epk")))
def test_examples_trace_the_same(tmp_path, example):
    path = EXAMPLES / example
    scenario = path.with_suffix(".scn")
    extra = ["--scenario", scenario] if scenario.exists() else []

    def once(env):
        trace = tmp_path / "t.jsonl"
        r = epuckc("run", path, *extra, "--time-limit", "30s", "--pose-interval", "250ms",
                   "--trace", trace, env=env)
        assert r.returncode in (0, 3), r.stderr
        return trace.read_bytes(), r.stdout, r.returncode
    same_both_ways(once)


def run_generated(tmp_path, index: int, env: dict):
    """`epuckc run` of generated program `index` under its random scenario:
    (trace bytes, stdout, status)."""
    text = accepted_programs(GENERATED, 2028)[index]
    path = tmp_path / f"g{index}.epk"
    path.write_text(text, encoding="utf-8")
    scenario = tmp_path / f"g{index}.scn"
    scenario.write_text(random_scenario(random.Random(index), 2000), encoding="utf-8")
    trace = tmp_path / f"g{index}.jsonl"
    r = epuckc("run", path, "--scenario", scenario, "--time-limit", "6s", "--trace", trace,
               env=env)
    assert r.returncode in (0, 3), r.stderr + text
    return trace.read_bytes(), r.stdout, r.returncode


@pytest.mark.parametrize("index", range(GENERATED))
def test_generated_programs_trace_the_same(tmp_path, index):
    """Random programs of the whole language (timers, every/after, guards,
    `when` on readings, variables, odometry and random numbers, modes,
    priorities, sequences with waits) under random scenarios."""
    same_both_ways(lambda env: run_generated(tmp_path, index, env))


def test_generated_programs_skip_polls(tmp_path):
    """The comparisons above are of runs that skip: most of the generated
    programs skip most of their polls (EPUCK_POLL_STATS)."""
    stats = tmp_path / "stats"
    for index in range(GENERATED):
        run_generated(tmp_path, index, {"EPUCK_POLL_STATS": str(stats)})
    lines = [line.split() for line in stats.read_text().splitlines()]
    assert len(lines) == GENERATED
    skipping = [int(w[3]) / int(w[1]) for w in lines if int(w[1]) > 0 and int(w[3]) > 0]
    assert len(skipping) >= GENERATED // 2, lines
    assert max(skipping) > 0.5, lines
