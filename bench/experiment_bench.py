#!/usr/bin/env python3
"""Throughput of `epuckc experiment`, measured side by side in one run:

1. Runs per second with 1 local worker and with N (default: every core
   this process may use), the same experiment (one robot, examples/
   wander.epk in a walled arena with obstacles, 10 s per run, --runs
   seeds), each a whole `epuckc experiment` process into a fresh folder,
   the two alternated --repeat times (best of each). Target: N workers give
   at least 0.85 x N times the runs per second of one.
   On a shared machine the wall clock gives N workers only the cores the
   others leave, so each run's CPU time (the experiment process, its
   workers and their world runners, all of it) is measured as well: the
   CPU efficiency of N workers is the CPU per run of one worker over that
   of N (1.0: the pool adds no work), and N x that efficiency is the
   speed-up N free cores would give, while the parent's own share (which
   does not spread) is small.
2. 1,000 runs of 10 s with one robot on N workers (--thousand; it takes
   the longest). Target: within 2 minutes on 2 cores.
3. The cost of a run beside the run itself, at scale (--scale M): short
   runs (100 ms, one robot), 1,000 of them and M, each in tasks of one run
   (--batch 1, as before batches) and in batches (the default), side by
   side: the CPU per run of the whole process tree, and of the experiment's
   own process (what does not spread over workers). Target: batched, M runs
   cost no more CPU per run than 1,000 (within 10 %), and less than tasks
   of one run.

Prints the machine and its load average before and after.

    python3 bench/experiment_bench.py [--runs 300] [--workers N] [--repeat 3] [--thousand]
                                      [--scale 10000]
"""
import argparse
import os
import platform
import resource
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

REPO = Path(__file__).resolve().parent.parent
PROGRAM = REPO / "examples" / "wander.epk"

WORLD = """arena 100 cm x 70 cm
box at 30 cm, 45 cm size 20 cm x 6 cm angle 30 deg
box at 75 cm, 15 cm size 8 cm x 8 cm
cylinder at 70 cm, 48 cm radius 7 cm
cylinder at 45 cm, 15 cm radius 4 cm
robot at 15 cm, 12 cm heading 20 deg
"""


def experiment(folder: Path, seeds: int, duration: str = "10 s") -> Path:
    folder.mkdir(parents=True, exist_ok=True)
    (folder / "wander.epk").write_text(PROGRAM.read_text())
    (folder / "arena.world").write_text(WORLD)
    exp = folder / "exp.toml"
    exp.write_text(f'program = "wander.epk"\nworld = "arena.world"\nduration = "{duration}"\n'
                   f'seeds = {seeds}\nmetrics = ["contacts", "distance", "coverage"]\n')
    return exp


def cpu_of_children() -> float:
    r = resource.getrusage(resource.RUSAGE_CHILDREN)
    return r.ru_utime + r.ru_stime


# `epuckc experiment` as `python3 -m epuckc experiment` runs it, which then
# tells its own CPU time (without its workers'): the share that does not spread
RUN = ("import resource, sys\n"
       "from epuckc.cli import main\n"
       "status = main(sys.argv[1:])\n"
       "r = resource.getrusage(resource.RUSAGE_SELF)\n"
       "print(f'parent CPU {r.ru_utime + r.ru_stime}', file=sys.stderr)\n"
       "sys.exit(status)\n")


def timed(exp: Path, out: Path, workers: int, env, more=()) -> tuple:
    """(wall seconds, rows, CPU seconds of the whole process tree, CPU
    seconds of the experiment's own process)."""
    cpu = cpu_of_children()
    start = time.perf_counter()
    proc = subprocess.run([sys.executable, "-c", RUN, "experiment", str(exp), "-o", str(out),
                           "--workers", str(workers), *more], env=env, capture_output=True,
                          text=True)
    wall = time.perf_counter() - start
    cpu = cpu_of_children() - cpu
    if proc.returncode != 0:
        sys.exit(f"failed ({proc.returncode}):\n{proc.stderr}")
    parent = float(proc.stderr.rsplit("parent CPU ", 1)[1])
    rows = (out / "runs.csv").read_text().count("\n") - 1
    failed = (out / "runs.csv").read_text().count("the ")
    if failed:
        sys.exit(f"{failed} runs failed:\n{(out / 'runs.csv').read_text()}")
    return wall, rows, cpu, parent


def load() -> str:
    return " ".join(f"{x:.1f}" for x in os.getloadavg())


def main() -> int:
    parser = argparse.ArgumentParser(description="experiment throughput")
    parser.add_argument("--runs", type=int, default=60)
    parser.add_argument("--workers", type=int, default=len(os.sched_getaffinity(0)))
    parser.add_argument("--repeat", type=int, default=2)
    parser.add_argument("--thousand", action="store_true")
    parser.add_argument("--scale", type=int, metavar="M",
                        help="only the cost per run of 1,000 and M short runs, in tasks of one "
                             "run and in batches")
    args = parser.parse_args()
    env = dict(os.environ, PYTHONPATH=str(REPO) + os.pathsep + os.environ.get("PYTHONPATH", ""))
    print(f"machine: {platform.machine()}, {os.cpu_count()} CPUs, {args.workers} usable by this "
          f"process; {platform.system()} {platform.release()}, Python "
          f"{platform.python_version()}; load average {load()}")
    from world_bench import compile_package     # (bench/, beside this script)
    compile_package()
    ok = True
    if args.scale:
        return 0 if scale(args, env) else 1
    with tempfile.TemporaryDirectory() as tmp:
        tmp = Path(tmp)
        exp = experiment(tmp / "exp", args.runs)
        timed(exp, tmp / "warm", 1, env)            # builds the runner and the robot (cached)
        rates, cpus, parents = {}, {}, {}
        # alternate, so that a change in the machine's load hits both
        for rep in range(args.repeat):
            for workers in (1, args.workers):
                wall, rows, cpu, parent = timed(exp, tmp / f"o{workers}-{rep}", workers, env)
                rates.setdefault(workers, []).append(rows / wall)
                cpus.setdefault(workers, []).append(cpu / rows)
                parents.setdefault(workers, []).append(parent / rows)
        one, many = max(rates[1]), max(rates[args.workers])
        ratio = many / one
        cpu_one, cpu_many = min(cpus[1]), min(cpus[args.workers])
        efficiency = cpu_one / cpu_many
        print(f"{args.runs} runs of 10 s, one robot, wander.epk (best of {args.repeat} each):\n"
              f"  1 worker {one:.1f} runs/s, {1000 * cpu_one:.1f} ms CPU a run\n"
              f"  {args.workers} workers {many:.1f} runs/s = {ratio:.2f} x one worker, "
              f"{1000 * cpu_many:.1f} ms CPU a run, of which the experiment's own process "
              f"{1000 * min(parents[args.workers]):.1f} ms\n"
              f"  target {0.85 * args.workers:.2f} x: {'met' if ratio >= 0.85 * args.workers else 'NOT met'}"
              f" on the wall clock; CPU efficiency {efficiency:.2f}: {args.workers} free cores "
              f"would give {args.workers * efficiency:.2f} x "
              f"({'met' if efficiency >= 0.85 else 'NOT met'} by CPU time); load average {load()}")
        ok &= ratio >= 0.85 * args.workers
        if args.thousand:
            exp = experiment(tmp / "thousand", 1000)
            wall, rows, cpu, _ = timed(exp, tmp / "o1000", args.workers, env)
            print(f"1000 runs of 10 s, one robot, {args.workers} workers: {wall:.1f} s "
                  f"({rows} rows, {cpu:.1f} s CPU); target 120 s: "
                  f"{'met' if wall <= 120 else 'NOT met'}; load average {load()}")
            ok &= wall <= 120
    return 0 if ok else 1


def scale(args, env) -> bool:
    """Part 3: CPU per run of 1,000 and M short runs, tasks of one run
    against batches, alternated in one session."""
    figures = {}
    with tempfile.TemporaryDirectory() as tmp:
        tmp = Path(tmp)
        timed(experiment(tmp / "warm", 4, "100 ms"), tmp / "warm-o", 1, env)
        for runs in (1000, args.scale):
            exp = experiment(tmp / f"e{runs}", runs, "100 ms")
            for label, more in (("tasks of one run", ["--batch", "1"]), ("batches", [])):
                wall, rows, cpu, parent = timed(exp, tmp / f"o{runs}-{len(more)}", args.workers,
                                                env, more)
                figures[(runs, label)] = (wall, cpu / rows, parent / rows)
                print(f"{runs} runs of 100 ms, {label}, {args.workers} workers: {wall:.1f} s, "
                      f"{1000 * cpu / rows:.2f} ms CPU a run (the experiment's own process "
                      f"{1000 * parent / rows:.2f} ms); load average {load()}", flush=True)
                shutil.rmtree(tmp / f"o{runs}-{len(more)}")
    small, big = figures[(1000, "batches")][1], figures[(args.scale, "batches")][1]
    ok = big <= 1.10 * small and big < figures[(args.scale, "tasks of one run")][1]
    print(f"batched: {args.scale} runs cost {big / small:.2f} x the CPU per run of 1,000 "
          f"(target <= 1.10) and {big / figures[(args.scale, 'tasks of one run')][1]:.2f} x "
          f"tasks of one run: {'met' if ok else 'NOT met'}")
    return ok


if __name__ == "__main__":
    sys.exit(main())
