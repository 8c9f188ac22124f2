#!/usr/bin/env python3
"""Large worlds (issue 45): robots against time on both physics providers
of the world runner, side by side in one run, with Enki alone beside them.

For each robot count, one walled square arena with the robots in a grid
22 cm apart (about 20 robots per square metre, SIERRA's usual density) and
a cylinder every 50 robots, each robot running examples/wander.epk
(obstacle avoidance), measured as a user runs it (the whole `epuckc run
--world` process: parsing the world, loading the robots, the run, the
results), EPUCK_QUIET, no trace:

1. `physics enki` (up to --enki-max robots: Enki tests every pair);
2. `physics chipmunk`;
3. Enki alone (bench/enki_alone.cpp: Enki's own step, a trivial controller
   on the IR values, nothing else), up to --enki-max robots;

each on one core (EPUCK_WORLD_THREADS=1, the process pinned to one CPU),
so that the CPU time is the time on a core of its own; then Chipmunk on
every CPU (EPUCK_WORLD_THREADS unset: one thread per CPU, at most one per
64 robots), against the wall clock. Each rate is the run's own: the
simulated time it adds over the CPU time it adds, against a 0.1 s run of
the same world (Python's start, the world's parse, the robots' loading
and the results cost the same in both); beside it, the whole process's.
Peak memory is the largest resident
set of the process and its children. Goals (on one core): 1,000 robots at
10 x real time or faster, 10,000 at 1 x; the cost linear in the robots
(the CPU time per robot and simulated second about flat on Chipmunk).

    python3 bench/large_world_bench.py [--counts 100,200,400,1000,2000,5000,10000]
        [--enki-max 1000] [--seconds 10] [--runs 1]

The simulated time is shortened for the largest worlds (at least 2 s) so
that a run stays under a minute or so; the rates are per simulated second.
"""
import argparse
import math
import os
import platform
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from world_bench import _cpu_model  # noqa: E402

REPO = Path(__file__).resolve().parent.parent
PROGRAM = REPO / "examples" / "wander.epk"
SPACING_CM = 22
SHORT_S = 0.1         # a run this long: what every run costs besides its steps


def world_text(robots: int, physics: str) -> str:
    side = math.ceil(math.sqrt(robots))
    width = side * SPACING_CM + 20
    lines = [f"arena {width} cm x {width} cm", f"physics {physics}"]
    for k in range(robots // 50):
        i = (k * 37) % robots
        lines.append(f"cylinder at {20 + (i % side) * SPACING_CM + SPACING_CM / 2} cm, "
                     f"{20 + (i // side) * SPACING_CM + SPACING_CM / 2} cm radius 3 cm")
    lines += [f"robot at {20 + (i % side) * SPACING_CM} cm, {20 + (i // side) * SPACING_CM} cm "
              f"heading {(i * 37) % 360} deg" for i in range(robots)]
    return "\n".join(lines) + "\n"


def timed(command, env, cpu):
    """(wall s, CPU s, peak resident MB) of one process and its children."""
    start = time.perf_counter()
    proc = subprocess.Popen(command, env=env, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE,
                            preexec_fn=(lambda: os.sched_setaffinity(0, {cpu}))
                            if cpu is not None else None)
    err = proc.stderr.read()
    _, status, usage = os.wait4(proc.pid, 0)
    wall = time.perf_counter() - start
    code = os.waitstatus_to_exitcode(status)
    if code not in (0, 3):
        sys.exit(f"failed ({code}): {' '.join(map(str, command))}\n{err.decode()}")
    return wall, usage.ru_utime + usage.ru_stime, usage.ru_maxrss / 1024


def median_of(runs, f):
    times = [f() for _ in range(runs)]
    return tuple(statistics.median(t[i] for t in times) for i in range(3))


def main() -> int:
    parser = argparse.ArgumentParser(description="robots against time on Enki and Chipmunk")
    parser.add_argument("--counts", default="100,200,400,1000,2000,5000,10000")
    parser.add_argument("--enki-max", type=int, default=1000)
    parser.add_argument("--seconds", type=float, default=10)
    parser.add_argument("--runs", type=int, default=1)
    args = parser.parse_args()
    counts = [int(c) for c in args.counts.split(",")]
    cpu = min(os.sched_getaffinity(0))
    env = dict(os.environ, PYTHONPATH=str(REPO) + os.pathsep + os.environ.get("PYTHONPATH", ""),
               EPUCK_QUIET="1")
    one = dict(env, EPUCK_WORLD_THREADS="1")
    print(f"machine: {platform.machine()}, {os.cpu_count()} CPUs ({_cpu_model()}), "
          f"{platform.system()} {platform.release()}; one-core runs pinned to CPU {cpu}; load "
          f"average {' '.join(f'{x:.1f}' for x in os.getloadavg())}; {PROGRAM.name}, "
          f"{args.runs} run(s) each, medians")
    ok = True
    with tempfile.TemporaryDirectory() as tmp:
        tmp = Path(tmp)
        alone = tmp / "enki_alone"
        subprocess.run(["c++", "-O2", "-std=c++14", str(REPO / "bench" / "enki_alone.cpp"),
                        "-o", str(alone), "-lenki"], check=True)
        print(f"{'robots':>7} {'sim s':>5} | {'enki x':>7} {'whole':>6} {'MB':>5} | "
              f"{'chip x':>7} {'whole':>6} {'MB':>5} {'us/r/s':>6} | {'alone x':>7} | "
              f"{'threads':>7}")
        measured = {}
        for n in counts:
            seconds = max(2.0, min(args.seconds, args.seconds * 1000 / n))
            row = {}
            for physics in ("enki", "chipmunk"):
                if physics == "enki" and n > args.enki_max:
                    continue
                world = tmp / f"{physics}-{n}.world"
                world.write_text(world_text(n, physics))

                def command(limit):
                    return [sys.executable, "-m", "epuckc", "run", str(PROGRAM), "--world",
                            str(world), "--time-limit", limit]
                timed(command(f"{SHORT_S}s"), one, cpu)        # builds and caches
                short = median_of(args.runs, lambda: timed(command(f"{SHORT_S}s"), one, cpu))
                full = median_of(args.runs, lambda: timed(command(f"{seconds:g}s"), one, cpu))
                # the run's own rate: the simulated time added over the CPU
                # time added (Python's start, the world's parse, the robots'
                # loading and the results cost the same in both)
                row[physics] = ((seconds - SHORT_S) / max(full[1] - short[1], 1e-9),
                                seconds / full[1], full[2], full[1] - short[1])
                if physics == "chipmunk":
                    many = median_of(args.runs, lambda: timed(command(f"{seconds:g}s"), env,
                                                              None))
                    short_many = median_of(args.runs, lambda: timed(command(f"{SHORT_S}s"), env,
                                                                    None))
                    row["threads"] = (seconds - SHORT_S) / max(many[0] - short_many[0], 1e-9)
            if n <= args.enki_max:
                whole = max(1, round(seconds))
                a = median_of(args.runs, lambda: timed([str(alone), str(n), str(whole)], env, cpu))
                row["alone"] = whole / a[1]
            measured[n] = row["chipmunk"][0]

            def provider(key):
                if key not in row:
                    return f"{'-':>7} {'-':>6} {'-':>5}"
                x, whole, mb, _ = row[key]
                return f"{x:7.2f} {whole:6.2f} {mb:5.0f}"
            per = row["chipmunk"][3] / (seconds - SHORT_S) / n * 1e6
            alone_x = f"{row['alone']:7.2f}" if "alone" in row else f"{'-':>7}"
            print(f"{n:>7} {seconds:>5g} | {provider('enki')} | {provider('chipmunk')} "
                  f"{per:6.0f} | {alone_x} | {row['threads']:7.2f}", flush=True)
    print("x: simulated seconds per CPU second of the run itself on one core (the time a "
          f"{SHORT_S:g} s run takes, taken out); whole: of the whole process; threads: per "
          "wall-clock second on every CPU; us/r/s: Chipmunk's CPU microseconds per robot and "
          "simulated second; MB: peak resident")
    goals = [(n, x) for n, x in ((1000, 10), (10000, 1)) if n in measured]
    for n, x in goals:
        met = measured[n] >= x
        ok &= met
        print(f"goal {n:,} robots >= {x} x on one core: {measured[n]:.2f} x, "
              f"{'met' if met else 'NOT met'}")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
