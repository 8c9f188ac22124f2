#!/usr/bin/env python3
"""Time how long the host harness takes to load a long scenario, side by
side with a reference version of runtime_c/platform/platform_host.c taken from
git (by default 7e6f262, whose loader grew its array one line at a time).

    python3 bench/scenario_load.py [--lines 80000] [--reference REV] [--no-asan]

Both harnesses are built the same way (with ASan/UBSan unless --no-asan,
as the issue measured), run the same program with a 1 ms time limit, so
the time is the loading of the scenario; the median of --runs runs is
printed. Figures are recorded in docs/performance.md.
"""
from __future__ import annotations

import argparse
import os
import platform
import shlex
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

REPO = Path(__file__).resolve().parent.parent
RUNTIME = REPO / "runtime_c"
sys.path.insert(0, str(REPO))
from epuckc.base.resources import LIBRARY_SIMULATION, RUNTIME_CORE  # noqa: E402
PROGRAM = REPO / "tests" / "runtime" / "programs" / "straight.c"
SANITIZE = ["-g", "-O1", "-fsanitize=address,undefined"]


def build(out: Path, platform_host: Path, asan: bool) -> Path:
    cc = shlex.split(os.environ.get("CC") or "cc")
    exe = out / "harness"
    subprocess.run(cc + ["-std=c99", *(SANITIZE if asan else ["-O2"]),
                         f"-I{RUNTIME}", f"-I{RUNTIME / 'epuck_api'}", f"-I{RUNTIME / 'host'}",
                         f"-I{RUNTIME / 'epuck_api_unsimulated'}",
                         str(PROGRAM), *(str(RUNTIME / name) for name in RUNTIME_CORE), str(platform_host),
                         *(str(RUNTIME / name) for name in LIBRARY_SIMULATION), "-o", str(exe), "-lm"],
                   check=True)
    return exe


def time_load(exe: Path, scenario: Path, runs: int) -> list:
    env = {k: v for k, v in os.environ.items() if not k.startswith("EPUCK_")}
    env.update(EPUCK_SCENARIO=str(scenario), EPUCK_TIME_LIMIT_MS="1", EPUCK_QUIET="1")
    times = []
    for _ in range(runs):
        start = time.perf_counter()
        result = subprocess.run([str(exe)], env=env, capture_output=True)
        times.append(time.perf_counter() - start)
        if result.returncode != 3:
            sys.exit(f"{exe} failed ({result.returncode}): {result.stderr.decode()[:500]}")
    return times


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--lines", type=int, default=80000)
    parser.add_argument("--reference", default="7e6f262",
                        help="git revision of the reference platform_host.c")
    parser.add_argument("--runs", type=int, default=3)
    parser.add_argument("--no-asan", action="store_true")
    args = parser.parse_args()
    asan = not args.no_asan
    with tempfile.TemporaryDirectory() as tmp:
        tmp = Path(tmp)
        scenario = tmp / "long.scn"
        scenario.write_text("".join(f"{t} ms ir0={t % 4096} ir7={(t * 7) % 4096}\n"
                                    for t in range(args.lines)))
        reference_src = tmp / "platform_host_reference.c"
        # (the file was runtime_c/host/platform_host.c before the platforms had a folder)
        for where in ("runtime_c/platform/platform_host.c", "runtime_c/host/platform_host.c"):
            shown = subprocess.run(["git", "-C", str(REPO), "show", f"{args.reference}:{where}"],
                                   capture_output=True)
            if shown.returncode == 0:
                break
        else:
            raise SystemExit(f"no platform_host.c at {args.reference}")
        reference_src.write_bytes(shown.stdout)
        (tmp / "ref").mkdir()
        (tmp / "now").mkdir()
        builds = [("reference " + args.reference, build(tmp / "ref", reference_src, asan)),
                  ("this checkout", build(tmp / "now", RUNTIME / "platform" / "platform_host.c",
                                          asan))]
        print(f"{args.lines} scenario lines, {'ASan/UBSan' if asan else '-O2'}, "
              f"{platform.processor() or platform.machine()}, {os.cpu_count()} cores, "
              f"Python {platform.python_version()}")
        print("| harness | median (s) | min (s) |")
        print("|---|---:|---:|")
        for label, exe in builds:
            times = time_load(exe, scenario, args.runs)
            print(f"| {label} | {statistics.median(times):.2f} | {min(times):.2f} |",
                  flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
