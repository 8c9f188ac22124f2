#!/usr/bin/env python3
"""The poll cost of issue 25's expressions, each beside the hand-written C
that does the same, in one run:

  dot       `left = dot(W, ir) / 4 + 550` with GCtronic's weights (what
            epuckc compiles it to: the weighted sum, exact in 32 bits),
            beside GCtronic's loop (`shock_neuron`: a `long` sum over
            `matrix_prox[s] * e_get_prox(s)`) in an extern action
  pair      `(16 * ir7 + 16 * ir0) / 4`: two products that need 32 bits,
            beside the same in hand-written C with `long`
  argmax    `argmax(ir)` beside a hand-written loop

Each program is one rule `every 1 ms do ...`, so its action runs at every
poll; a rule whose action is an empty extern C function is the baseline,
subtracted from both sides, so that each figure is the action's own cost.

  callgrind  x86 instructions per poll (valgrind's callgrind, host build,
             gcc -O2), as bench/robot_bench.py measures them
  simavr     AVR cycles per poll (avr-gcc -Os, ATmega1284P at 16 MHz under
             simavr), as bench/robot_bench.py measures them: the proxy of a
             16-bit target (16-bit int, 32-bit long, like the dsPIC)

    python3 bench/expr_bench.py [--only callgrind,simavr] [--keep DIR]

Recorded figures: docs/performance.md ("Issue 25").
"""
from __future__ import annotations

import argparse
import re
import sys
import tempfile
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from robot_bench import (AVR_CFLAGS, BENCH, CORE, RT, SIM_MCU, compile_epk,  # noqa: E402
                         host_per_poll, machine, missing, run, simavr_misdecodes)

WEIGHTS = [8, 4, 2, 0, 0, -4, -8, -16]

# name -> (the language's expression, the hand-written C body of the action)
CASES = {
    "dot": (f"const W = {WEIGHTS}\nvar left = 0\nevery 1 ms do left = dot(W, ir) / 4 + 550\n",
            f"static const int W[8] = {{{', '.join(map(str, WEIGHTS))}}};\n"
            "int left;\n"
            "void hand(void *param)\n{\n    long potential = 0;\n    int s;\n    (void)param;\n"
            "    for (s = 0; s < 8; s++)\n        potential += (long)W[s] * e_get_prox(s);\n"
            "    left = (int)(potential / 4 + 550);\n}\n"),
    "pair": ("var v = 0\nevery 1 ms do v = (16 * ir7 + 16 * ir0) / 4\n",
             "int v;\nvoid hand(void *param)\n{\n    (void)param;\n"
             "    v = (int)((16L * e_get_prox(7) + 16L * e_get_prox(0)) / 4);\n}\n"),
    "argmax": ("var k = 0\nevery 1 ms do k = argmax(ir)\n",
               "int k;\nvoid hand(void *param)\n{\n    int s, best = 0;\n    (void)param;\n"
               "    for (s = 1; s < 8; s++)\n        if (e_get_prox(s) > e_get_prox(best))\n"
               "            best = s;\n    k = best;\n}\n"),
}
EMPTY = "void hand(void *param)\n{\n    (void)param;\n}\n"
HAND_RULE = 'extern action hand() from "hand.c"\nevery 1 ms do hand\n'


def _programs(d: Path, name: str, lang: str, c_body: str) -> dict:
    """{variant: (C of the program, extra C files, defines)} for the
    language's rule, the hand-written action and the empty one."""
    out = {}
    for variant, text, body in (("lang", lang, None), ("hand", HAND_RULE, c_body),
                                ("empty", HAND_RULE, EMPTY)):
        sub = d / f"{name}_{variant}"
        sub.mkdir(parents=True, exist_ok=True)
        extra = []
        if body is not None:
            (sub / "hand.c").write_text(f'#include "{name}_{variant}_externs.h"\n'
                                        '#include "a_d/advance_ad_scan/e_prox.h"\n' + body)
            extra = [sub / "hand.c"]
        c, defines = compile_epk(text, sub, f"{name}_{variant}")
        out[variant] = (c, extra, defines)
    return out


def avr_per_poll(c: Path, extra: list, defines: list, d: Path, harness: Path) -> int:
    elf = d / (c.stem + ".elf")
    run(["avr-gcc", *AVR_CFLAGS, f"-mmcu={SIM_MCU}", *defines, f"-I{RT}",
         f"-I{RT / 'epuck_api'}", f"-I{BENCH / 'avr'}", f"-I{c.parent}", c, *extra, *CORE,
         BENCH / "avr" / "platform_sim.c", BENCH / "avr" / "epuck_avr.c", "-o", elf])
    bad = simavr_misdecodes(elf)
    if bad:
        raise RuntimeError(f"simavr 1.6 would mis-execute {', '.join(sorted(set(bad)))}")
    out = run([harness, elf, SIM_MCU, 5, 50]).stdout
    line = re.search(r"^polls .*$", out, re.M).group(0).split()
    return int(dict(zip(line[0::2], line[1::2]))["median"])


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--only", default="callgrind,simavr")
    ap.add_argument("--keep", type=Path, help="keep the generated files in this folder")
    args = ap.parse_args()
    parts = set(args.only.split(","))
    if args.keep:
        args.keep.mkdir(parents=True, exist_ok=True)
        work = Path(tempfile.mkdtemp(dir=args.keep))
    else:
        tmp = tempfile.TemporaryDirectory()
        work = Path(tmp.name)
    print(f"machine: {machine()}")
    programs = {name: _programs(work, name, lang, body) for name, (lang, body) in CASES.items()}
    status = 0
    if "callgrind" in parts:
        if missing("cc", "valgrind", "callgrind_annotate"):
            print("callgrind: skipped, missing tools")
            status = 1
        else:
            print("\n== x86 instructions per poll of the action (callgrind, the empty rule "
                  "subtracted)")
            print(f"{'case':>8} {'epuckc':>8} {'hand C':>8} {'ratio':>6}")
            for name, variants in programs.items():
                cost = {v: host_per_poll(*variants[v], work) for v in variants}
                lang, hand = cost["lang"] - cost["empty"], cost["hand"] - cost["empty"]
                print(f"{name:>8} {lang:>8.1f} {hand:>8.1f} {lang / hand:>5.2f}x")
    if "simavr" in parts:
        if missing("avr-gcc", "simavr"):
            print("simavr: skipped, missing tools")
            status = 1
        else:
            harness = work / "simavr_polls"
            run(["cc", "-std=c99", "-O2", BENCH / "avr" / "simavr_polls.c", "-o", harness,
                 "-lsimavr"])
            print("\n== AVR cycles per poll of the action (simavr, median of 50 polls, the "
                  "empty rule subtracted)")
            print(f"{'case':>8} {'epuckc':>8} {'hand C':>8} {'ratio':>6}")
            for name, variants in programs.items():
                cost = {v: avr_per_poll(*variants[v], work, harness) for v in variants}
                lang, hand = cost["lang"] - cost["empty"], cost["hand"] - cost["empty"]
                print(f"{name:>8} {lang:>8} {hand:>8} {lang / hand:>5.2f}x")
    return status


if __name__ == "__main__":
    sys.exit(main())
