#!/usr/bin/env python3
"""The poll cost of an `if/else` action (issue 25), beside what it replaces,
on x86 (callgrind) and on the AVR (simavr), with robot_bench.py's tools:

  assign     one rule that fires at every poll (`on immediate repeat`) and
             assigns a variable: the cost of the rule itself
  if/else    the same rule choosing the value with an `if` / `else if` /
             `else if` / `else` over two proximity readings (all readings
             0: every condition is evaluated, the `else` runs: the worst case)
  guards     the same choice as before `if/else` existed: four rules, one a
             branch, on four priorities, each guarded by its branch's
             condition and the negation of those before
The generated C of `if/else` is the `if (...) { ... } else if ...` chain
one would write by hand in the step's function, over the runtime's readings
(`rt_ir(k)`) and assignments (`rt_assign`, which traces): the difference
if/else - assign is that chain's cost, the hand-written C's too.

    python3 bench/ifelse_bench.py
    python3 bench/ifelse_bench.py --only callgrind

Recorded figures: docs/performance.md, "Issue 25: if/else".
"""
from __future__ import annotations

import argparse
import re
import subprocess
import sys
import tempfile
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from robot_bench import (AVR_CFLAGS, BENCH, BUDGET_CYCLES, CORE, RT, SIM_MCU,  # noqa: E402
                         compile_epk, machine, missing, per_poll, run, simavr_misdecodes)

HEAD = "var v = 0\non immediate do start_sensor\n"
PROGRAMS = {
    "assign": HEAD + "on immediate repeat do v = 1\n",
    "if/else": HEAD + (
        "on immediate repeat do if ir0 > 2000 { v = 3 } else if ir0 > 500 { v = 2 }"
        " else if ir7 > 500 { v = 1 } else { v = 0 }\n"),
    "guards": HEAD + (
        "on immediate repeat priority 4 if ir0 > 2000 do v = 3\n"
        "on immediate repeat priority 3 if ir0 > 500 and ir0 <= 2000 do v = 2\n"
        "on immediate repeat priority 2 if ir0 <= 500 and ir7 > 500 do v = 1\n"
        "on immediate repeat priority 1 if ir0 <= 500 and ir7 <= 500 do v = 0\n"),
}


def simavr_per_poll(text: str, d: Path, name: str, harness: Path) -> tuple:
    """(median, min, max) AVR cycles per poll of a rule file's program."""
    c, defines = compile_epk(text, d, name)
    elf = d / f"{name}.elf"
    run(["avr-gcc", *AVR_CFLAGS, f"-mmcu={SIM_MCU}", *defines, f"-I{RT}",
         f"-I{RT / 'epuck_api'}", f"-I{BENCH / 'avr'}", c, *CORE,
         BENCH / "avr" / "platform_sim.c", BENCH / "avr" / "epuck_avr.c", "-o", elf])
    bad = simavr_misdecodes(elf)
    if bad:
        raise RuntimeError("simavr 1.6 would mis-execute " + ", ".join(sorted(set(bad))))
    out = run([harness, elf, SIM_MCU, 5, 50]).stdout
    line = re.search(r"^polls .*$", out, re.M).group(0).split()
    stats = dict(zip(line[0::2], line[1::2]))
    return int(stats["median"]), int(stats["min"]), int(stats["max"])


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--only", default="callgrind,simavr")
    args = ap.parse_args()
    parts = set(args.only.split(","))
    work = Path(tempfile.mkdtemp(prefix="ifelse_bench"))
    print(f"machine: {machine()}")
    status = 0
    if "callgrind" in parts:
        if missing("cc", "valgrind", "callgrind_annotate"):
            print("callgrind: skipped")
            status = 1
        else:
            print("\n== x86 instructions per poll (callgrind, gcc -O2)")
            base = None
            for name, text in PROGRAMS.items():
                d = work / f"x86_{name.replace('/', '_')}"
                d.mkdir()
                ir = per_poll(text, d, "p")
                base = ir if base is None else base
                print(f"{name:>8} {ir:>8.0f}   {ir - base:>+6.0f} beside `assign`")
    if "simavr" in parts:
        if missing("avr-gcc", "cc") or not Path("/usr/include/simavr/sim_avr.h").exists():
            print("simavr: skipped")
            status = 1
        else:
            harness = work / "simavr_polls"
            run(["cc", "-std=c99", "-O2", BENCH / "avr" / "simavr_polls.c", "-o", harness,
                 "-lsimavr"])
            print(f"\n== AVR cycles per poll ({SIM_MCU}, simavr, avr-gcc -Os); budget"
                  f" {BUDGET_CYCLES}")
            base = None
            for name, text in PROGRAMS.items():
                d = work / f"avr_{name.replace('/', '_')}"
                d.mkdir()
                median, lo, hi = simavr_per_poll(text, d, "p", harness)
                base = median if base is None else base
                print(f"{name:>8} {median:>8}   {median - base:>+6} beside `assign`"
                      f"   (min {lo}, max {hi})")
    return status


if __name__ == "__main__":
    sys.exit(main())
