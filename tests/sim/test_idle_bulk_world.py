"""Idle polls in bulk in Enki worlds (runtime_c/rt_idle.c; the robots'
glue never advances past a world step): each run is made twice, as it is
and with EPUCK_POLL_EVERY_MS=1 (every ms polled), and both give the same
merged trace, output and exit status: every example in its world or in the
walled arena (with pose records), and generated programs of the whole
language in a world with obstacles and other robots. tests/runtime/
test_idle_bulk.py does the same on the stub harness."""
from __future__ import annotations

import pytest

from epuckc.sim.world import parse_world
from tests.support.bulk import EVERY_MS, GENERATED, accepted_programs
from tests.support.world import EXAMPLES, same_run_both_ways, three_robots_world
WORLDS = sorted(p.name for p in EXAMPLES.glob("*.world"))


pytestmark = pytest.mark.usefixtures("enki")


def run_twice(tmp_path, *args, stats=None):
    """`epuckc run ARGS --trace` in bulk and ms by ms: the same trace,
    stdout and status (returned)."""
    return same_run_both_ways(tmp_path, {"EPUCK_POLL_STATS": str(stats)} if stats else {},
                              EVERY_MS, *args)


@pytest.mark.parametrize("world", WORLDS)
def test_example_worlds_trace_the_same(tmp_path, world):
    program = EXAMPLES / world.replace(".world", ".epk")
    if not program.exists():
        program = EXAMPLES / "wander.epk"
    # a world that names every robot's program runs without FILE
    file = () if all(r.program for r in parse_world(EXAMPLES / world).robots) else (program,)
    run_twice(tmp_path, *file, "--world", EXAMPLES / world, "--time-limit", "12s")


@pytest.mark.parametrize("example", sorted(p.name for p in EXAMPLES.glob("*.epk")))
def test_examples_in_the_arena_trace_the_same(tmp_path, example):
    run_twice(tmp_path, EXAMPLES / example, "--world", EXAMPLES / "arena.world",
              "--time-limit", "8s", "--pose-interval", "70ms")


@pytest.mark.parametrize("index", range(GENERATED))
def test_generated_programs_in_a_world_trace_the_same(tmp_path, index):
    path = tmp_path / f"g{index}.epk"
    path.write_text(accepted_programs(GENERATED, 2028)[index], encoding="utf-8")
    world = tmp_path / "swarm.world"
    world.write_text(three_robots_world(seed=7), encoding="utf-8")
    run_twice(tmp_path, path, "--world", world, "--time-limit", "4s", "--seed", str(index))


@pytest.mark.parametrize("example", ["wander", "aggregation"])
def test_worlds_skip_polls(tmp_path, example):
    """The comparisons above are of runs that skip: wander (sensor rules)
    and aggregation (IR messages sent and received) in their worlds poll
    at most a few times in each world step of 10 ms."""
    stats = tmp_path / "stats"
    world = EXAMPLES / ("swarm.world" if example == "wander" else f"{example}.world")
    run_twice(tmp_path, EXAMPLES / f"{example}.epk", "--world", world, "--time-limit", "10s",
              stats=stats)
    lines = [line.split() for line in stats.read_text().splitlines()]
    assert lines and all(int(w[1]) == 10000 for w in lines), lines
    assert all(int(w[3]) >= 7000 for w in lines), lines
