#!/usr/bin/env python3
"""What the ground sensors and sound cost in a world (issue 46), measured
side by side in one run: 50 robots in a walled arena for 60 s of simulated
time, each running a program that drives and, every 10 ms, reads

1. nothing more (the reference: no ground sensors attached, no sound);
2. its three ground sensors, over a floor of 50 drawn ellipses (Enki's
   GroundSensor x 3 on each body, the floor's raster made by Pillow);
3. its three microphones, with 10 sound sources on all the time (Enki's
   Microphone x 3 on each robot, called by the runner at every step);
4. both.

Each `epuckc run --world` is a whole process pinned to one CPU; the four
alternate in each round, so that a shared machine's load hits all of them.
Prints each one's median CPU time and its cost over the reference, per
robot and physics step.

    python3 bench/floor_sound_bench.py [--runs 5] [--robots 50] [--seconds 60]
"""
import argparse
import os
import statistics
import subprocess
import sys
import tempfile
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from world_bench import _cpu_model, compile_package, timed  # noqa: E402

REPO = Path(__file__).resolve().parent.parent
READS = {"reference": "", "ground": "g = ground0 + ground1 + ground2,",
         "sound": "m = mic0 + mic1 + mic2,",
         "both": "g = ground0 + ground1 + ground2, m = mic0 + mic1 + mic2,"}


def program(reads: str) -> str:
    return ("var g = 0\nvar m = 0\nvar turn = 0 steps/s\n"
            f"every 10 ms do {reads} turn = (ir0 - ir7) * 1 steps/s,\n"
            "    set_speed(clamp(300 steps/s - turn, -300 steps/s, 600 steps/s), "
            "clamp(300 steps/s + turn, -300 steps/s, 600 steps/s))\n")


def world_text(robots: int, floor: bool, sounds: bool) -> str:
    cols = 10
    rows = (robots + cols - 1) // cols
    width, height = cols * 30 + 40, rows * 30 + 100
    lines = [f"arena {width} cm x {height} cm"]
    for i in range(robots):
        x, y = 35 + (i % cols) * 30, 35 + (i // cols) * 30
        lines.append(f"robot at {x} cm, {y} cm heading {(i * 37) % 360} deg")
        if floor:
            lines.append(f"floor ellipse at {x} cm, {y} cm size 20 cm x 14 cm width 2 cm")
    if sounds:
        lines += [f"sound at {20 + 30 * k} cm, {height - 20} cm level 80 dB" for k in range(10)]
    return "\n".join(lines) + "\n"


def main() -> int:
    parser = argparse.ArgumentParser(description="the cost of ground sensors and sound")
    parser.add_argument("--runs", type=int, default=5)
    parser.add_argument("--robots", type=int, default=50)
    parser.add_argument("--seconds", type=int, default=60)
    args = parser.parse_args()
    cpu = min(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity") else None
    env = dict(os.environ, PYTHONPATH=str(REPO) + os.pathsep + os.environ.get("PYTHONPATH", ""),
               EPUCK_QUIET="1")
    print(f"{os.cpu_count()} CPUs ({_cpu_model()}); each run pinned to CPU {cpu}; load average "
          f"{' '.join(f'{x:.1f}' for x in os.getloadavg())}")
    compile_package()
    with tempfile.TemporaryDirectory() as tmp:
        runs = {}
        for name, reads in READS.items():
            (Path(tmp) / f"{name}.epk").write_text(program(reads))
            world = Path(tmp) / f"{name}.world"
            world.write_text(world_text(args.robots, name in ("ground", "both"),
                                        name in ("sound", "both")))
            runs[name] = [sys.executable, "-m", "epuckc", "run", str(Path(tmp) / f"{name}.epk"),
                          "--world", str(world), "--time-limit", f"{args.seconds}s"]
            timed(runs[name], env, cpu)         # builds the robot (cached)
        rounds = [{name: timed(command, env, cpu)[1] for name, command in runs.items()}
                  for _ in range(args.runs)]
    steps = args.seconds * 100 * args.robots            # 10 ms physics steps, robots
    reference = statistics.median(r["reference"] for r in rounds)
    for name in READS:
        cpus = [r[name] for r in rounds]
        median = statistics.median(cpus)
        extra = statistics.median(r[name] - r["reference"] for r in rounds)
        print(f"{name:>9}: CPU median {median:.3f} s (min {min(cpus):.3f}, max {max(cpus):.3f})"
              f" = {args.seconds / median:,.0f} x real time"
              + ("" if name == "reference" else
                 f"; over the reference {extra:+.3f} s = {extra / steps * 1e6:+.2f} us a robot "
                 f"and step ({extra / reference:+.0%})"))
    return 0


if __name__ == "__main__":
    sys.exit(main())
