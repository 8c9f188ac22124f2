#!/usr/bin/env python3
"""The cache's bookkeeping (epuckc/base/cache.py: marking entries used, the
bound, eviction) against the start of the commands that hit the cache,
side by side with another checkout in one run (interleaved, medians):

  check   `epuckc check` of the examples, every one a hit of check's cache
  run     `epuckc run examples/paper_fig2.epk`, a hit of run's cache
  trim    one trim (what a write costs at most once a minute) of a cache
          of --entries entries, in process

    python3 bench/cache_bench.py --before DIR [--runs 15] [--entries 2000]

DIR is an export of the epuckc to compare with (`git archive main | tar -x
-C DIR`); each side has its own cache folder, filled before the timing.
Times are the CPU time (user + system) of each child process, and its wall
time. Figures go in docs/performance.md (issue 44).
"""
from __future__ import annotations

import argparse
import os
import platform
import resource
import shutil
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

REPO = Path(__file__).resolve().parent.parent


def timed(argv, env) -> tuple:
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    start = time.perf_counter()
    done = subprocess.run([sys.executable, "-m", "epuckc", *argv], env=env,
                          capture_output=True, text=True)
    wall = time.perf_counter() - start
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    if done.returncode not in (0, 3):
        raise SystemExit(f"epuckc {' '.join(argv)} failed:\n{done.stderr}")
    return (after.ru_utime - before.ru_utime + after.ru_stime - before.ru_stime), wall


def side(root: Path, cache: Path) -> dict:
    env = dict(os.environ, PYTHONPATH=str(root), EPUCKC_CACHE_DIR=str(cache))
    env.pop("PYTHONDONTWRITEBYTECODE", None)
    return env


def trim_time(root: Path, entries: int, work: Path) -> float:
    """Seconds of one trim over `entries` file entries and a tenth as many
    folders, nothing to evict (the common case), in a child of `root`."""
    script = f"""
import os, sys, time
from pathlib import Path
os.environ["EPUCKC_CACHE_DIR"] = {str(work)!r}
from epuckc.base import cache
for i in range({entries}):
    p = cache.area("check") / f"e{{i}}.marshal"
    p.parent.mkdir(parents=True, exist_ok=True)
    p.write_bytes(b"x" * 100)
for i in range({entries} // 10):
    d = cache.area("host") / f"h{{i}}"
    d.mkdir(parents=True, exist_ok=True)
    (d / "prog").write_bytes(b"x" * 1000)
best = 1e9
for _ in range(5):
    t = time.perf_counter()
    cache.trim()
    best = min(best, time.perf_counter() - t)
print(best)
"""
    done = subprocess.run([sys.executable, "-c", script], env=dict(os.environ, PYTHONPATH=str(root)),
                          capture_output=True, text=True, check=True)
    return float(done.stdout)


def main() -> int:
    ap = argparse.ArgumentParser()
    ap.add_argument("--before", metavar="DIR", type=Path, required=True)
    ap.add_argument("--runs", type=int, default=15)
    ap.add_argument("--entries", type=int, default=2000)
    args = ap.parse_args()
    work = Path(tempfile.mkdtemp(prefix="cache-bench-"))
    try:
        shutil.copytree(REPO / "examples", work / "files")     # (with their extern C files)
        files = [str(p) for p in sorted((work / "files").glob("*.epk"))]
        prog = str(REPO / "examples" / "paper_fig2.epk")
        sides = {"before": side(args.before, work / "cache-before"),
                 "after": side(REPO, work / "cache-after")}
        tasks = {"check": ["check", *files], "run": ["run", prog]}
        for env in sides.values():          # fill the caches (and the bytecode)
            for argv in tasks.values():
                timed(argv, env)
                timed(argv, env)
        got = {(s, t): [] for s in sides for t in tasks}
        for _ in range(args.runs):
            for t, argv in tasks.items():
                for s, env in sides.items():
                    got[(s, t)].append(timed(argv, env))
        print(f"{platform.processor() or platform.machine()}, {os.cpu_count()} CPUs, "
              f"load {os.getloadavg()[0]:.1f}, {args.runs} runs each, interleaved")
        print("| measure | before: CPU / wall ms | after: CPU / wall ms | after / before (CPU) |")
        print("|---|---:|---:|---:|")
        for t in tasks:
            row = []
            for s in sides:
                cpu = statistics.median(c for c, _ in got[(s, t)]) * 1000
                wall = statistics.median(w for _, w in got[(s, t)]) * 1000
                row.append((cpu, wall))
            what = f"check of {len(files)} files" if t == "check" else "run paper_fig2.epk"
            print(f"| {what}, cached | {row[0][0]:.0f} / {row[0][1]:.0f} "
                  f"| {row[1][0]:.0f} / {row[1][1]:.0f} | {row[1][0] / row[0][0]:.2f}x |")
        trim = trim_time(REPO, args.entries, work / "trim")
        print(f"| one trim of {args.entries + args.entries // 10} entries (after only) | | "
              f"{trim * 1000:.1f} ms | |")
    finally:
        shutil.rmtree(work, ignore_errors=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
