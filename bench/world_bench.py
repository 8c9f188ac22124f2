#!/usr/bin/env python3
"""Speed of simulation against real time, measured side by side in one run:

1. 50 robots running examples/wander.epk (obstacle avoidance) in a walled
   arena with obstacles, in Enki, for 60 s of simulated time:
   `epuckc run examples/wander.epk --world <50 robots>` as a whole process
   (Python start-up, cache look-ups, loading 50 robots, the run, merging
   the traces). Target: at least 50 times faster than real time.
2. The stub harness alone (the executable `epuckc build` makes), one robot,
   the same program for 60 s. Target: at least 1,000 times faster.
3. Enki alone (bench/enki_alone.cpp: the same world, the same robots with
   a trivial controller, nothing else), beside 1. Target: the whole
   `epuckc run --world` within 1.25 x Enki alone's CPU time. Beside both,
   the same run with each robot loading its own copy of the program
   (EPUCK_WORLD_COPIES=1, the runner's design before its robots shared one).

Each process is pinned to one CPU (sched_setaffinity), so "on one core"
holds on a machine with several. Prints the median of --runs runs, their
minimum and maximum, against both the wall clock and the process's CPU time
(see `report`), with the machine and its load.

    python3 bench/world_bench.py [--runs 5] [--robots 50] [--seconds 60]
"""
import argparse
import os
import platform
import resource
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

REPO = Path(__file__).resolve().parent.parent
PROGRAM = REPO / "examples" / "wander.epk"


def world_text(robots: int) -> str:
    cols = 10
    rows = (robots + cols - 1) // cols
    width, height = cols * 30 + 40, rows * 30 + 100
    lines = [f"arena {width} cm x {height} cm",
             f"cylinder at {width / 2} cm, {height - 25} cm radius 8 cm",
             f"box at {width / 4} cm, {height - 30} cm size 30 cm x 6 cm angle 20 deg"]
    for i in range(robots):
        x, y = 35 + (i % cols) * 30, 35 + (i // cols) * 30
        lines.append(f"robot at {x} cm, {y} cm heading {(i * 37) % 360} deg")
    return "\n".join(lines) + "\n"


def timed(command, env, cpu):
    """(wall seconds, CPU seconds of the child) for one run on one CPU."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    start = time.perf_counter()
    result = subprocess.run(command, env=env, capture_output=True, text=True,
                            preexec_fn=(lambda: os.sched_setaffinity(0, {cpu})) if cpu is not None else None)
    wall = time.perf_counter() - start
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    if result.returncode not in (0, 3):
        sys.exit(f"failed ({result.returncode}): {' '.join(map(str, command))}\n{result.stderr}")
    return wall, (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)


def compile_package():
    """epuckc's modules as an installed package has them, compiled: with
    PYTHONDONTWRITEBYTECODE set (as in some shells and containers) a source
    checkout's epuckc compiles every module it imports at every start (about
    0.04 s of CPU here, a third of `run --world`'s own), which no user of a
    pip install pays."""
    subprocess.run([sys.executable, "-m", "compileall", "-q", str(REPO / "epuckc")], check=True)


def report(label, seconds, times, target):
    """Simulated time against the wall clock and against the CPU time of the
    process. Each process is single-threaded and pinned to one CPU, so its
    CPU time is how long it takes on a core of its own; the wall clock also
    counts the time other processes of a shared machine held that core.
    The target is judged on the CPU time."""
    walls = [w for w, _ in times]
    cpus = [c for _, c in times]
    wall, cpu = statistics.median(walls), statistics.median(cpus)
    print(f"{label}\n  simulated {seconds:g} s"
          f"\n  wall clock: median {wall:.3f} s (min {min(walls):.3f}, max {max(walls):.3f})"
          f" = {seconds / wall:,.0f} x real time"
          f"\n  CPU time:   median {cpu:.3f} s (min {min(cpus):.3f}, max {max(cpus):.3f})"
          f" = {seconds / cpu:,.0f} x real time on one core"
          f"\n  target {target:,} x real time on one core: "
          f"{'met' if seconds / cpu >= target else 'NOT met'}")
    return seconds / cpu >= target


def main() -> int:
    parser = argparse.ArgumentParser(description="Enki world and stub harness speed")
    parser.add_argument("--runs", type=int, default=5)
    parser.add_argument("--robots", type=int, default=50)
    parser.add_argument("--seconds", type=int, default=60)
    args = parser.parse_args()
    cpu = min(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity") else None
    env = dict(os.environ, PYTHONPATH=str(REPO) + os.pathsep + os.environ.get("PYTHONPATH", ""),
               EPUCK_QUIET="1")
    limit = f"{args.seconds}s"
    print(f"machine: {platform.machine()}, {os.cpu_count()} CPUs "
          f"({_cpu_model()}), {platform.system()} {platform.release()}, Python "
          f"{platform.python_version()}; each run pinned to CPU {cpu}; load average "
          f"{' '.join(f'{x:.1f}' for x in os.getloadavg())}")
    compile_package()
    ok = True
    with tempfile.TemporaryDirectory() as tmp:
        world = Path(tmp) / "bench.world"
        world.write_text(world_text(args.robots))
        run = [sys.executable, "-m", "epuckc", "run", str(PROGRAM), "--world", str(world),
               "--time-limit", limit]
        timed(run, env, cpu)            # warm-up: builds the runner and the robot (cached)
        times = [timed(run, env, cpu) for _ in range(args.runs)]
        ok &= report(f"{args.robots} robots, {PROGRAM.name}, walled arena, Enki "
                     f"(whole `epuckc run --world`)", args.seconds, times, 50)
        alone = Path(tmp) / "enki_alone"
        subprocess.run(["c++", "-O2", "-std=c++14", str(REPO / "bench" / "enki_alone.cpp"),
                        "-o", str(alone), "-lenki"], check=True)
        # side by side: the three alternate, so that the machine's load hits
        # all; the third is the runner as it was, each robot loading its own
        # copy of the program (EPUCK_WORLD_COPIES, robot_loader.h)
        copies_env = dict(env, EPUCK_WORLD_COPIES="1")
        rounds = [(timed(run, env, cpu), timed([str(alone), str(args.robots), str(args.seconds)],
                                               env, cpu), timed(run, copies_env, cpu))
                  for _ in range(args.runs)]
        ours = statistics.median(r[0][1] for r in rounds)
        enki = statistics.median(r[1][1] for r in rounds)
        copies = statistics.median(r[2][1] for r in rounds)
        print(f"Enki alone, {args.robots} robots, a trivial controller, {args.seconds} s: CPU "
              f"median {enki:.3f} s; `epuckc run --world` beside it {ours:.3f} s = "
              f"{ours / enki:.2f} x Enki alone; target 1.25 x: "
              f"{'met' if ours / enki <= 1.25 else 'NOT met'}"
              f"\n  (each robot its own copy of the program, EPUCK_WORLD_COPIES=1: "
              f"{copies:.3f} s = {copies / enki:.2f} x)"
              f"\n  each round's own ratio (the machine's speed drifts less within a round): "
              f"median {statistics.median(r[0][1] / r[1][1] for r in rounds):.2f} x, copies "
              f"{statistics.median(r[2][1] / r[1][1] for r in rounds):.2f} x")
        ok &= ours / enki <= 1.25
        exe_dir = Path(tmp) / "stub"
        subprocess.run([sys.executable, "-m", "epuckc", "build", str(PROGRAM), "-o", str(exe_dir)],
                       env=env, check=True, capture_output=True)
        exe = exe_dir / PROGRAM.stem
        stub_env = dict(env, EPUCK_TIME_LIMIT_MS=str(args.seconds * 1000))
        timed([str(exe)], stub_env, cpu)
        times = [timed([str(exe)], stub_env, cpu) for _ in range(args.runs)]
        ok &= report(f"1 robot, {PROGRAM.name}, stub harness alone (the built executable)",
                     args.seconds, times, 1000)
    return 0 if ok else 1


def _cpu_model() -> str:
    try:
        for line in Path("/proc/cpuinfo").read_text().splitlines():
            if line.startswith("model name"):
                return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return platform.processor() or "unknown CPU"


if __name__ == "__main__":
    sys.exit(main())
