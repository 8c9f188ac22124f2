"""Worlds under AddressSanitizer and UBSan (issue 42, point 3), as the host
harness runs under them (tests/support/hostile.py): the world runner and
every robot's shared object built with -fsanitize=address,undefined (through
CC and CXX, as a user would), then the campaign's reproducer (any program
in a three-robot world failed at start: the runner's copies of a robot's
state read the redzones ASan puts between globals, and the glue read its
robot's io before the runner attached it; three robots that hear each
other) and a sample of fuzzed message
programs (tests/support/language.py with messages=True) run clean: no
sanitizer report, no leak, the usual exit status. Skips, with its reason,
where the compilers cannot build and run a sanitized program."""
from __future__ import annotations

import json
import os
import random
import shutil
import subprocess
from pathlib import Path

import pytest

from conftest import require_enki
from epuckc.check.frontend import check_file
from epuckc.diagnostics import Report

from tests.support.language import RandomChoices, language_program
from tests.support.world import epuckc

SANITIZE = "-fsanitize=address,undefined -fno-sanitize-recover=all -g"
SAMPLE = 2          # fuzzed message programs (each a robot built with the sanitizers)

# three robots within each other's IR range (some 25 cm)
WORLD = """arena 60 cm x 60 cm
robot a at 20 cm, 20 cm heading 0 deg
robot b at 32 cm, 20 cm heading 180 deg
robot c at 26 cm, 31 cm heading -90 deg
seed 7
"""

MESSAGES = """var heard = 0
var sent = 0
every 100 ms do send(sent), sent += 1
on message repeat do heard = message, set_speed(200 steps/s, 100 steps/s)
after 1500 ms do exit_main
"""


def _sanitizers_work(tmp: Path) -> str:
    """"" when gcc and g++ build and run a sanitized program, else why not."""
    for compiler, name in (("cc", "a.c"), ("c++", "a.cpp")):
        if shutil.which(compiler) is None:
            return f"no `{compiler}`"
        source = tmp / name
        source.write_text("int main(void) { return 0; }\n")
        exe = tmp / f"{name}.out"
        built = subprocess.run([compiler, *SANITIZE.split(), str(source), "-o", str(exe)],
                               capture_output=True, text=True)
        if built.returncode != 0:
            return f"`{compiler}` cannot build with {SANITIZE}: {built.stderr.strip()[:300]}"
        ran = subprocess.run([str(exe)], capture_output=True, text=True)
        if ran.returncode != 0:
            return f"a sanitized program does not run here: {ran.stderr.strip()[:300]}"
    return ""


@pytest.fixture(scope="module")
def sanitized(tmp_path_factory):
    """The environment of a sanitized world run (its own cache: the
    sanitized runner and robots are not the plain ones)."""
    require_enki()
    tmp = tmp_path_factory.mktemp("sanitized")
    why = _sanitizers_work(tmp)
    if why:
        pytest.skip(f"sanitizers unavailable: {why}")
    return {"CC": f"{os.environ.get('CC') or 'cc'} {SANITIZE}",
            "CXX": f"{os.environ.get('CXX') or 'c++'} {SANITIZE}",
            "EPUCKC_CACHE_DIR": str(tmp / "cache"),
            "ASAN_OPTIONS": "detect_leaks=1:abort_on_error=0",
            "UBSAN_OPTIONS": "print_stacktrace=1"}


def _run_clean(program: str, tmp: Path, env: dict, name: str) -> list:
    """The program in the three-robot world, sanitized: its trace's records."""
    rules, world, trace = tmp / f"{name}.epk", tmp / "three.world", tmp / f"{name}.jsonl"
    rules.write_text(program)
    world.write_text(WORLD)
    done = epuckc("run", rules, "--world", world, "--time-limit", "2s", "--trace", trace,
                  env=env)
    context = f"\n--- {name}.epk ---\n{program}\n--- stderr ---\n{done.stderr[-4000:]}"
    assert "Sanitizer" not in done.stderr and "runtime error" not in done.stderr, context
    assert done.returncode in (0, 3), context
    return [json.loads(line) for line in trace.read_text().splitlines()]


def test_the_campaigns_three_robot_world_runs_clean(sanitized, tmp_path):
    records = _run_clean(MESSAGES, tmp_path, sanitized, "messages")
    robots = {r.get("robot") for r in records if r.get("kind") == "set"}
    assert robots == {"a", "b", "c"}
    assert any(r.get("var") == "heard" for r in records if r.get("kind") == "set")


def _accepted_message_programs(count: int) -> list:
    """The first `count` accepted message programs of the generator's seeds."""
    out = []
    for k in range(10_000):
        program = language_program(RandomChoices(random.Random(42_000 + k)), messages=True)
        result = check_file(Path("m.epk"), Report(), shown_name="m.epk", text=program.text)
        if result.checked is not None and "send(" in program.text:
            out.append(program.text)
            if len(out) == count:
                return out
    raise AssertionError("the generator gave too few accepted message programs")


@pytest.mark.parametrize("k", range(SAMPLE))
def test_fuzzed_message_programs_run_clean_in_a_world(sanitized, tmp_path, k):
    records = _run_clean(_accepted_message_programs(SAMPLE)[k], tmp_path, sanitized, f"fuzz{k}")
    assert {r.get("robot") for r in records if "robot" in r} >= {"a", "b", "c"}
