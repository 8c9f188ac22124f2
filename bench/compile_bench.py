#!/usr/bin/env python3
"""Time `epuckc compile` against `epuckc check` on the same files, side by
side (whole processes, alternating runs), with the size of the C and each
process's peak memory. The target: compile of 10,000 rules within 2x check.

    python3 bench/compile_bench.py [--runs N] [--sizes 1000,10000] [--steps 4000]

The rule files are bench/check_bench.py's (every kind of statement, named
rules and cancels), plus one rule of `--steps` sequence steps (the shape
that made the C quadratic: each step's comment repeated the whole rule).
See docs/performance.md for recorded figures.
"""
from __future__ import annotations

import argparse
import os
import platform
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

REPO = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(REPO / "bench"))

from check_bench import generate  # noqa: E402


def long_sequence(steps: int) -> str:
    body = " then ".join(f"start_straight({100 + i % 800}, {1 + i % 30} cm), set_timer"
                         for i in range(steps))
    return f"on immediate do {body}\non stop_motor do exit_main\n"


def timed(cmd: list) -> tuple[float, int]:
    """(seconds, peak resident kB) of one process."""
    env = dict(os.environ, PYTHONPATH=str(REPO))
    start = time.perf_counter()
    proc = subprocess.Popen(cmd, cwd=REPO, env=env, stdout=subprocess.DEVNULL,
                            stderr=subprocess.PIPE)
    _, status, usage = os.wait4(proc.pid, 0)
    elapsed = time.perf_counter() - start
    err = proc.stderr.read().decode()
    proc.stderr.close()
    if os.waitstatus_to_exitcode(status) != 0:
        sys.exit(f"{' '.join(cmd)} failed:\n{err[:2000]}")
    return elapsed, usage.ru_maxrss


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--runs", type=int, default=5)
    ap.add_argument("--sizes", default="1000,10000")
    ap.add_argument("--steps", type=int, default=4000)
    args = ap.parse_args(argv)
    folder = Path(tempfile.mkdtemp(prefix="epuckc-compile-bench-"))
    cases = []
    for size in (int(s) for s in args.sizes.split(",")):
        cases.append((f"{size} rules", folder / f"rules_{size}.epk", generate(size)))
    if args.steps:
        cases.append((f"1 rule of {args.steps} steps", folder / f"steps_{args.steps}.epk",
                      long_sequence(args.steps)))
    print(f"python {platform.python_version()} on {platform.machine()}, {os.cpu_count()} cpus; "
          f"median of {args.runs} alternating runs after one warm-up")
    print(f"{'input':>22} {'kB in':>7} {'check s':>8} {'compile s':>10} {'ratio':>6} "
          f"{'kB of C':>8} {'check MB':>9} {'compile MB':>11}")
    # no capacity options: a rule file's rules are const tables (issue 11),
    # which the runtime's arrays need not hold
    for label, path, text in cases:
        path.write_text(text, encoding="utf-8")
        out = folder / "out.c"
        check = [sys.executable, "-m", "epuckc", "check", str(path)]
        compile_ = [sys.executable, "-m", "epuckc", "compile", str(path), "-o", str(out)]
        timed(check), timed(compile_)
        checks, compiles = [], []
        for _ in range(args.runs):
            checks.append(timed(check))
            compiles.append(timed(compile_))
        c_time = statistics.median(t for t, _ in checks)
        k_time = statistics.median(t for t, _ in compiles)
        print(f"{label:>22} {len(text) / 1000:>7.0f} {c_time:>8.2f} {k_time:>10.2f} "
              f"{k_time / c_time:>6.2f} {out.stat().st_size / 1000:>8.0f} "
              f"{max(m for _, m in checks) / 1024:>9.0f} {max(m for _, m in compiles) / 1024:>11.0f}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
