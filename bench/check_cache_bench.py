#!/usr/bin/env python3
"""`epuckc check` of many files, as a whole process, with its cache
(check/cache.py) side by side with a check without it, in one run.

    python3 bench/check_cache_bench.py [--files 40] [--rules 200] [--runs 7]

The files are the examples and generated programs (check_bench.py's mixed
program and lsp_bench.py's program of variables), `--rules` rules each. Each
round times, interleaved: `check --no-cache` of every file (the
reference), `check` of every file when none changed (every file a hit),
and `check` after one file was edited (one miss). Times are the CPU time
(user + system) of the child process; the outputs of the cached and
uncached checks are compared byte for byte at every round. Figures go in
docs/performance.md (issue 31).
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
from pathlib import Path

REPO = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(REPO / "bench"))

from check_bench import generate  # noqa: E402
from lsp_bench import expression_program  # noqa: E402


def run(argv, env) -> tuple:
    """`epuckc ARGV`: (CPU seconds of the child, its exit status, stdout +
    stderr)."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    done = subprocess.run([sys.executable, "-m", "epuckc", *argv], env=env,
                          capture_output=True)
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    return cpu, done.returncode, done.stdout + done.stderr


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--files", type=int, default=40)
    ap.add_argument("--rules", type=int, default=200)
    ap.add_argument("--runs", type=int, default=7)
    args = ap.parse_args(argv)
    work = Path(tempfile.mkdtemp(prefix="epuckc-check-cache-"))
    try:
        examples = sorted((REPO / "examples").glob("*.epk"))
        names = []
        for i in range(args.files):
            if i < len(examples):
                shutil.copy(examples[i], work / examples[i].name)
                names.append(examples[i].name)
                continue
            text = generate(args.rules) if i % 2 else expression_program(args.rules, seed=i)
            (work / f"gen{i}.epk").write_text(text)
            names.append(f"gen{i}.epk")
        env = dict(os.environ, EPUCKC_CACHE_DIR=str(work / "cache"),
                   PYTHONPATH=str(REPO) + os.pathsep + os.environ.get("PYTHONPATH", ""))
        env.pop("EPUCKC_NO_CACHE", None)
        env_cwd = env
        os.chdir(work)
        run(["check", *names], env_cwd)                 # the first run fills the cache
        edited = work / names[-1]
        original = edited.read_text()
        times = {"uncached": [], "hit": [], "one edited": []}
        for r in range(args.runs):
            cpu, status, reference = run(["check", "--no-cache", *names], env_cwd)
            times["uncached"].append(cpu)
            cpu, status2, out = run(["check", *names], env_cwd)
            assert (status2, out) == (status, reference), "cached output differs"
            times["hit"].append(cpu)
            edited.write_text(original + f"\non timer({r + 1} s) do stop_motor\n"
                              if r % 2 == 0 else original)
            cpu, status3, out = run(["check", *names], env_cwd)
            _, status4, reference = run(["check", "--no-cache", *names], env_cwd)
            assert (status3, out) == (status4, reference), "cached output differs"
            times["one edited"].append(cpu)
        floor = statistics.median(run(["--version"], env_cwd)[0] for _ in range(args.runs))
        total = sum(len((work / n).read_bytes()) for n in names)
        print(f"python {platform.python_version()} on {platform.machine()}, "
              f"{os.cpu_count()} cpus, load {os.getloadavg()[0]:.2f}; {len(names)} files, "
              f"{total // 1024} kB, {args.runs} runs (CPU time of the process, median / min)")
        for label, xs in times.items():
            print(f"  check, {label:12s}: {statistics.median(xs) * 1000:7.0f} / "
                  f"{min(xs) * 1000:7.0f} ms")
        print(f"  (`epuckc --version`, start-up alone: {floor * 1000:.0f} ms)")
    finally:
        shutil.rmtree(work, ignore_errors=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
