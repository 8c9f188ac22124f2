"""A small experiment shared by the tests: one robot, a gain over two
values, six seeds, 1.5 s runs."""
from __future__ import annotations

import csv
import os
import sys
from pathlib import Path

import pytest

from epuckc.sim.enki import enki_available

REPO = Path(__file__).resolve().parents[2]

needs_enki = pytest.mark.skipif(not enki_available() and not os.environ.get(
    "EPUCKC_REQUIRE_ALL_TOOLS"), reason="Enki (libenki-dev) and a C++ compiler are needed")

PROGRAM = """const CRUISE = 500 steps/s
const K = 1 steps/s
var right_near = 0
var left_near = 0
every 10 ms
    do right_near = ir0 + ir1 + ir2 / 2,
        left_near = ir7 + ir6 + ir5 / 2,
        set_speed(left: clamp(CRUISE - right_near * K, -400 steps/s, 1000 steps/s),
            right: clamp(CRUISE - left_near * K, -400 steps/s, 1000 steps/s))
"""

WORLD = """arena 40 cm x 30 cm
cylinder at 25 cm, 15 cm radius 4 cm
robot at 8 cm, 8 cm heading 30 deg
"""

EXPERIMENT = """program = "brait.epk"
world = "arena.world"
duration = "1500 ms"
seeds = 6
metrics = ["contacts", "distance", "coverage", "exit", "var:left_near", "mean:left_near"]

[params]
K = ["1 steps/s", "4 steps/s"]
"""

# a hand-written C program that aborts in the run of seed 2, never
# returns in the run of seed 4 (the watchdog's case) and stops with
# status 2 in the run of seed 5
# Seed 4 hangs: blocked for good (a main that only spins lets simulated
# time run on, runtime_c/host/cmain.c, and would finish its run).
CRASHER = r"""#define _POSIX_C_SOURCE 200809L
#include <stdlib.h>
#include <string.h>
#include <unistd.h>
#include "utility.h"

int main(void)
{
    const char *seed = getenv("EPUCK_SEED");
    if (seed != NULL && strcmp(seed, "2") == 0)
        abort();
    if (seed != NULL && strcmp(seed, "4") == 0)
        for (;;)
            pause();
    if (seed != NULL && strcmp(seed, "5") == 0)
        return 2;
    mainloop();
    return 0;
}
"""


def make(folder: Path, experiment: str = EXPERIMENT) -> Path:
    folder.mkdir(parents=True, exist_ok=True)
    (folder / "brait.epk").write_text(PROGRAM, encoding="utf-8")
    (folder / "arena.world").write_text(WORLD, encoding="utf-8")
    (folder / "crash.c").write_text(CRASHER, encoding="utf-8")
    (folder / "exp.toml").write_text(experiment, encoding="utf-8")
    return folder / "exp.toml"


def rows(path: Path) -> list:
    with open(path, newline="", encoding="utf-8") as f:
        return list(csv.DictReader(f))


def env() -> dict:
    return dict(os.environ, PYTHONPATH=str(REPO) + os.pathsep + os.environ.get("PYTHONPATH", ""))


def command(*args) -> list:
    return [sys.executable, "-m", "epuckc", "experiment", *map(str, args)]
