"""The robots of one program share one loaded copy of its shared object in
a world, each robot's globals swapped into it while its code runs
(runtime_c/enki/robot_loader.h, docs/world.md): every run here is made
twice, as it is and with EPUCK_WORLD_COPIES=1 (each robot its own copy of
the file, the design before), and both give the same merged trace, output
and exit status: the examples' worlds of several robots, two programs
interleaved in one world, and generated programs of the whole language in
a world of three robots. And the mechanism itself, seen from C programs:
robots of one program see their globals at one address and each its own
values, also when the world takes over mains that never wait; a program
with thread-local storage or much state is not shared."""
from __future__ import annotations

import re

import pytest

from conftest import REPO

from epuckc.sim.world import parse_world
from tests.support.bulk import GENERATED, accepted_programs
from tests.support.world import EXAMPLES, epuckc, same_run_both_ways, three_robots_world

COPIES = {"EPUCK_WORLD_COPIES": "1"}


pytestmark = pytest.mark.usefixtures("enki")


def run_both(tmp_path, *args):
    """`epuckc run ARGS --trace` with the object shared and with copies: the
    same trace, stdout and status (returned)."""
    return same_run_both_ways(tmp_path, {}, COPIES, *args)


SEVERAL = [p.name for p in sorted(EXAMPLES.glob("*.world"))
           if len(re.findall(r"^robot ", p.read_text(), re.M)) > 1]


def test_the_examples_have_worlds_of_several_robots():
    assert {"aggregation.world", "dispersion.world", "swarm.world"} <= set(SEVERAL)


@pytest.mark.parametrize("world", SEVERAL)
def test_example_worlds_trace_the_same(tmp_path, world):
    program = EXAMPLES / world.replace(".world", ".epk")
    if not program.exists():
        program = EXAMPLES / "random_walk.epk"
    # a world that names every robot's program runs without FILE
    file = () if all(r.program for r in parse_world(EXAMPLES / world).robots) else (program,)
    trace, _, _ = run_both(tmp_path, *file, "--world", EXAMPLES / world,
                           "--time-limit", "10s", "--pose-interval", "90ms")
    assert len(set(re.findall(rb'"robot": ?"([^"]+)"', trace))) > 1


def test_two_programs_interleaved_trace_the_same(tmp_path):
    """Robots of two programs in turn (a b a b): two shared objects, each
    with two robots' states."""
    world = tmp_path / "mixed.world"
    wander, walk = EXAMPLES / "wander.epk", EXAMPLES / "random_walk.epk"
    world.write_text("arena 100 cm x 80 cm\ncylinder at 50 cm, 40 cm radius 8 cm\n"
                     f"robot a at 15 cm, 15 cm heading 30 deg program {wander}\n"
                     f"robot b at 85 cm, 15 cm heading 150 deg program {walk}\n"
                     f"robot c at 15 cm, 65 cm heading 300 deg program {wander}\n"
                     f"robot d at 85 cm, 65 cm heading 200 deg program {walk}\n"
                     "seed 3\n", encoding="utf-8")
    run_both(tmp_path, wander, "--world", world, "--time-limit", "8s", "--pose-interval", "50ms")


@pytest.mark.parametrize("index", range(GENERATED))
def test_generated_programs_in_a_world_trace_the_same(tmp_path, index):
    path = tmp_path / f"g{index}.epk"
    path.write_text(accepted_programs(GENERATED, 3033)[index], encoding="utf-8")
    world = tmp_path / "swarm.world"
    world.write_text(three_robots_world(seed=5), encoding="utf-8")
    run_both(tmp_path, path, "--world", world, "--time-limit", "4s", "--seed", str(index))


COUNTER = """\
#include <stdio.h>
#include <utility/utility.h>
static %sint counter;             /* every robot its own */
%s
int main(void)
{
    int k;
    for (k = 0; k < 5; k++) {
        counter += 1;
        %s
        printf("count %%d at %%p\\n", counter, (void *)&counter);
        wait(20000L * (k + 1));
    }
    return 0;
}
"""

TWO = "arena 60 cm x 60 cm\nrobot a at 15 cm, 15 cm\nrobot b at 45 cm, 45 cm\n"


def _counts(tmp_path, storage: str = "", more: tuple = ("", ""), env=None) -> dict:
    """Each robot's counter counts 1 to 5 (its own); the addresses at which
    each robot saw it. `more`: a declaration, and a statement of the loop."""
    program = tmp_path / "count.c"
    program.write_text(COUNTER % (storage, *more), encoding="utf-8")
    world = tmp_path / "two.world"
    world.write_text(TWO, encoding="utf-8")
    r = epuckc("run", program, "--world", world, "--time-limit", "2s", env=env)
    assert r.returncode == 0, r.stdout + r.stderr
    return _counted_alone(r.stdout)


def _counted_alone(stdout: str) -> dict:
    """Robots a and b each printed counts 1 to 5 (each counts alone, from
    its own start); the addresses at which each saw its counter."""
    seen: dict = {}
    for robot, count, address in re.findall(r"^(\w+): count (\d+) at (\S+)$", stdout, re.M):
        seen.setdefault(robot, []).append((int(count), address))
    assert {r: [c for c, _ in pairs] for r, pairs in seen.items()} == \
        {"a": [1, 2, 3, 4, 5], "b": [1, 2, 3, 4, 5]}, stdout
    return {robot: {a for _, a in pairs} for robot, pairs in seen.items()}


def test_robots_of_a_program_share_its_object_each_with_its_globals(tmp_path):
    shared = _counts(tmp_path)
    assert shared["a"] == shared["b"] and len(shared["a"]) == 1
    copies = _counts(tmp_path, env=COPIES)
    assert copies["a"] != copies["b"]


def test_a_program_with_thread_local_storage_is_not_shared(tmp_path):
    """Thread-local storage is not in the data pages that are swapped: each
    robot loads its own copy of the file (its own TLS block) and counts
    alone."""
    addresses = _counts(tmp_path, "__thread ")
    assert addresses["a"] != addresses["b"]


def test_a_program_with_much_state_is_not_shared(tmp_path):
    """Swapping more than MAX_SWAPPED_STATE bytes (robot_loader.h) at every
    step would cost more than the copies: its robots load their copies."""
    header = (REPO / "runtime_c" / "enki" / "robot_loader.h").read_text()
    limit = int(re.search(r"MAX_SWAPPED_STATE = (\d+);", header).group(1))
    large = (f"static volatile unsigned char table[{limit + 1}];", "table[k] = (unsigned char)k;")
    addresses = _counts(tmp_path, "", large)
    assert addresses["a"] != addresses["b"]


SPINNER = """\
#include <stdio.h>
static long spins;              /* every robot its own */
int main(void)
{
    for (;;) {                  /* main's clock runs on the blocks it executes */
        spins++;
        if (spins % 20000 == 0)
            printf("spins %ld\\n", spins);
    }
}
"""


def test_spinning_mains_are_taken_over_each_with_its_globals(tmp_path):
    """Mains that never wait: the world takes each over inside its loop
    (host/cmain.c charges its blocks to main's clock), its globals half-way
    through an update; each robot still counts alone, as with copies."""
    program = tmp_path / "spin.c"
    program.write_text(SPINNER, encoding="utf-8")
    world = tmp_path / "two.world"
    world.write_text(TWO, encoding="utf-8")
    trace, stdout, status = run_both(tmp_path, program, "--world", world, "--time-limit", "1s")
    assert status == 3
    for robot in ("a", "b"):
        seen = [int(n) for n in re.findall(rf"^{robot}: spins (\d+)$", stdout, re.M)]
        assert len(seen) > 3 and seen == [20000 * (k + 1) for k in range(len(seen))], stdout


@pytest.mark.parametrize("storage", ["", "__thread "])
def test_one_file_by_two_names_is_one_object_and_robots_still_count_alone(tmp_path, storage):
    """Two robots' `lib` lines naming one file by two paths (links): the
    dynamic loader gives the object loaded already, and the runner treats
    it as one program's: shared with the state swapped, or (thread-local
    storage) a copy for the second robot."""
    import os
    import subprocess
    from epuckc.cli.driver import load_program
    from epuckc.diagnostics import Report
    from epuckc.sim import enki
    from epuckc.sim.world import parse_world, runner_spec
    program = tmp_path / "count.c"
    program.write_text(COUNTER % (storage, "", ""), encoding="utf-8")
    lib = enki.build_robot(load_program(program, Report()))
    world = tmp_path / "two.world"
    world.write_text(TWO, encoding="utf-8")
    robots = []
    for i in range(2):
        os.symlink(lib, tmp_path / f"r{i}.so")
        robots.append((tmp_path / f"r{i}.so", {"EPUCK_TIME_LIMIT_MS": "2000"}))
    (tmp_path / "spec").write_text(runner_spec(parse_world(world), robots))
    result = subprocess.run([str(enki.build_runner()), str(tmp_path / "spec"),
                             str(tmp_path / "results")], capture_output=True, text=True)
    assert result.returncode == 0, result.stderr
    addresses = _counted_alone(result.stdout)
    assert (addresses["a"] == addresses["b"]) == (storage == "")


def _swapped_state(lib) -> int:
    """The bytes robot_loader.h's state_of swaps for the object: its
    writable loaded segments less what RELRO makes read-only."""
    import subprocess
    headers = subprocess.run(["readelf", "-lW", str(lib)], capture_output=True, text=True,
                             check=True).stdout.splitlines()
    writable = sum(int(h.split()[5], 16) for h in headers
                   if h.split()[:1] == ["LOAD"] and "RW" in h.split()[6:])
    relro = sum(int(h.split()[5], 16) for h in headers if h.split()[:1] == ["GNU_RELRO"])
    return writable - relro


@pytest.mark.parametrize("example", ["wander.epk", "colour_seeker.epk", "aggregation.epk"])
def test_the_examples_robots_are_shared(example):
    """A rule program's state (the runtime's and the simulated library's)
    stays under the bound with a quarter of it left for the program's own
    C, so that a world's robots share its object: a buffer added to the
    library's state shows here, not as a slower world."""
    from epuckc.cli.driver import load_program
    from epuckc.diagnostics import Report
    from epuckc.sim import enki
    header = (REPO / "runtime_c" / "enki" / "robot_loader.h").read_text()
    limit = int(re.search(r"MAX_SWAPPED_STATE = (\d+);", header).group(1))
    lib = enki.build_robot(load_program(EXAMPLES / example, Report()))
    assert 0 < _swapped_state(lib) <= limit * 3 // 4
