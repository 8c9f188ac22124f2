#!/usr/bin/env python3
"""The cost of IR messages in an Enki world (issue 27), measured side by
side in one run: the 50 robots of bench/world_bench.py (walled arena with
obstacles) for 60 s of simulated time, once running examples/wander.epk,
once running the same program with messages: each robot sends ten times
a second (`every 100 ms do send(...)`) and counts what it hears
(`on message repeat`). Both are the whole `epuckc run --world` process;
the difference is the channel (runtime_c/enki/world_channel.h: every send
tested against every other robot), the robots' libIrcom stubs and the
runtime's queue, and the trace's send and message records.

Prints the median (and min, max) CPU time of each over --runs runs, the
cost per physics step, and the messages sent and delivered.

    python3 bench/messages_bench.py [--runs 3] [--robots 50] [--seconds 60]
"""
import argparse
import json
import statistics
import sys
import tempfile
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from world_bench import PROGRAM, REPO, timed, world_text  # noqa: E402

MESSAGES = """
# messages (bench/messages_bench.py): ten a second, and count what comes
var heard = 0
every 100 ms do send(heard / 4)
rule hear: on message repeat do heard = clamp(heard + 1, 0, 1000)
"""
STEP_MS = 10


def main() -> int:
    parser = argparse.ArgumentParser()
    parser.add_argument("--runs", type=int, default=3)
    parser.add_argument("--robots", type=int, default=50)
    parser.add_argument("--seconds", type=int, default=60)
    args = parser.parse_args()
    with tempfile.TemporaryDirectory() as tmp:
        tmp = Path(tmp)
        world = tmp / "bench.world"
        world.write_text(world_text(args.robots))
        talking = tmp / "wander_talking.epk"
        talking.write_text(PROGRAM.read_text() + MESSAGES)
        env = {"PYTHONPATH": str(REPO), "EPUCK_QUIET": "1", "PATH": "/usr/bin:/bin"}
        results = {}
        for label, program in (("without messages", PROGRAM), ("with messages", talking)):
            trace = tmp / f"{program.stem}.jsonl"
            command = [sys.executable, "-m", "epuckc", "run", str(program), "--world", str(world),
                       "--time-limit", f"{args.seconds}s", "--trace", str(trace)]
            timed(command, env, 0)                      # warm-up: builds, caches
            times = [timed(command, env, 0) for _ in range(args.runs)]
            kinds = {}
            for line in trace.read_text().splitlines():
                kind = json.loads(line)["kind"]
                kinds[kind] = kinds.get(kind, 0) + 1
            results[label] = (times, kinds)
        steps = args.seconds * 1000 // STEP_MS
        base = statistics.median(c for _, c in results["without messages"][0])
        for label, (times, kinds) in results.items():
            cpus = [c for _, c in times]
            cpu = statistics.median(cpus)
            print(f"{args.robots} robots, {args.seconds} s, {label}: CPU median {cpu:.3f} s "
                  f"(min {min(cpus):.3f}, max {max(cpus):.3f}) = "
                  f"{cpu / steps * 1e6:.0f} us per physics step of {STEP_MS} ms, "
                  f"{args.seconds / cpu:.0f} x real time; sends {kinds.get('send', 0)}, "
                  f"deliveries {kinds.get('message', 0)}")
        cpu = statistics.median(c for _, c in results["with messages"][0])
        print(f"messages cost {cpu / base:.2f} x the world without them")
    return 0


if __name__ == "__main__":
    sys.exit(main())
