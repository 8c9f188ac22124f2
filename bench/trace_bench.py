#!/usr/bin/env python3
"""The robot's tracer (runtime_c/rt_trace.c, `epuckc build --trace`), each
figure beside its reference in one run (issue 39):

  record     AVR cycles of each hook (simavr, ATmega1284P at 16 MHz, avr-gcc
             -Os as the 16-bit build), the tracer alone: with the link busy
             (the record made and queued: what a poll pays), the framing of
             a record when the link takes it (its CRC and COBS), and the
             hook when the ring is full (the record dropped and counted);
             the bytes a record puts on the wire.
  examples   every example the 16-bit path runs (no e-puck2 devices), in
             the robot's time on simavr (`epuckc run --int16 --robot-trace`):
             the cycles of its polls with the tracer beside the same build
             without any trace (INT16_ROBOT_TIME), the mean and the longest
             of 16,000 (1 ms at 16 MHz), the overruns; the bytes the tracer
             sent, its records, and the share of the 115200-baud link
             (11,520 bytes a second) the run used.
  size       flash and RAM of the tracer and its UART1 link (avr-size of the
             objects, avr-gcc -Os for the ATmega128, as bench/robot_bench.py
             counts them: .text flash, .data + .bss RAM), and the runtime
             without --trace, whose objects are unchanged by the tracer
             (tests/build/test_trace_builds.py checks them byte for byte).

    python3 bench/trace_bench.py                     # all three
    python3 bench/trace_bench.py --only record,size
    python3 bench/trace_bench.py --only examples --examples square,go_to_goal --time-limit 10s

Needs avr-gcc, avr-size, simavr's library and headers (libsimavr-dev).
Recorded figures: docs/performance.md ("The robot's trace").
"""
from __future__ import annotations

import argparse
import os
import re
import subprocess
import sys
import tempfile
from pathlib import Path

REPO = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(REPO))
from epuckc.base.resources import (RUNTIME_CORE, RUNTIME_DSPIC_DEVICES,  # noqa: E402
                                   RUNTIME_TRACE, RUNTIME_TRACE_UART1)

RT = REPO / "runtime_c"
BENCH = REPO / "bench"
FLAGS = ["-std=c99", "-Wall", "-Wextra", "-Werror", "-pedantic", "-Os", "-DEPUCKRT_NO_NAMES"]
LINK_BYTES_PER_S = 115200 // 10         # 8N1: ten bits a byte
BUDGET = 16000


def run(cmd, **kw):
    res = subprocess.run([str(c) for c in cmd], capture_output=True, text=True, **kw)
    if res.returncode != 0:
        raise RuntimeError(f"failed: {' '.join(map(str, cmd))}\n{res.stdout}{res.stderr}")
    return res


def bench_record(work: Path) -> tuple:
    """The hooks' cycles with the link busy ({hook: cycles}), the framing's
    per record and its bytes on the wire per record, the hooks' cycles
    with the ring full."""
    harness = work / "simavr_cycles"
    run(["cc", "-std=c99", "-O2", BENCH / "avr" / "simavr_cycles.c", "-o", harness, "-lsimavr"])
    elf = work / "trace_cost.elf"
    run(["avr-gcc", "-mmcu=atmega1284p", *FLAGS, "-DEPUCKRT_TRACE", f"-I{RT}",
         f"-I{RT / 'epuck_api'}", BENCH / "avr" / "trace_cost.c", RT / "rt_trace.c", "-o", elf])
    out = run([harness, elf, "atmega1284p"]).stdout
    queued = {m.group(1): int(m.group(2)) for m in re.finditer(r"^(\w+) @(\d+)$", out, re.M)}
    dropped = {m.group(1): int(m.group(2))
               for m in re.finditer(r"^dropped-(\w+) @(\d+)$", out, re.M)}
    m = re.search(r"^framed-(\d+) @(\d+) (\d+)$", out, re.M)
    records, cycles, size = (int(v) for v in m.groups())
    return queued, cycles / records, size / records, dropped


def _examples(names) -> list:
    from epuckc.check.frontend import check_file
    from epuckc.diagnostics import Report
    paths = sorted((REPO / "examples").glob("*.epk"))
    if names:
        paths = [p for p in paths if p.stem in names]
    kept = []
    for path in paths:
        result = check_file(path, Report())
        if result.checked is not None and not result.checked.devices:
            kept.append(path)
    return kept


def bench_examples(names, time_limit_ms: int) -> list:
    from epuckc.build.trace_table import trace_table
    from epuckc.cli.driver import load_program
    from epuckc.diagnostics import Report
    from epuckc.link.stream import TraceDecoder
    from epuckc.sim.int16 import run_int16_robot
    rows = []
    for path in _examples(names):
        scenario = path.with_suffix(".scn")
        scenario = str(scenario) if scenario.is_file() else None
        program = load_program(path, Report())
        plain = run_int16_robot(program, scenario, time_limit_ms, tracer=False)
        traced = run_int16_robot(program, scenario, time_limit_ms, tracer=True)
        decoder = TraceDecoder(trace_table(program))
        records = decoder.feed(traced.uart) + decoder.close()
        shown = [r for r in records if r["kind"] not in ("pose", "dropped", "lost")]
        dropped = sum(r["count"] for r in records if r["kind"] == "dropped")
        seconds = traced.polls / 1000.0
        rows.append((path.stem, plain, traced, len(shown), dropped,
                     len(traced.uart) / seconds / LINK_BYTES_PER_S if seconds else 0.0))
    return rows


def avr_size(objects) -> dict:
    out = run(["avr-size", *objects]).stdout.splitlines()[1:]
    return {Path(f.split()[5]).name: tuple(int(v) for v in f.split()[:3]) for f in out}


def bench_size(work: Path) -> tuple:
    flags = ["-mmcu=atmega128", *FLAGS, f"-I{RT}", f"-I{RT / 'epuck_api'}"]
    tracer = []
    for name in (*RUNTIME_TRACE, *RUNTIME_TRACE_UART1):
        obj = work / f"{Path(name).stem}.o"
        run(["avr-gcc", *flags, "-DEPUCKRT_TRACE", "-DEPUCKRT_TRACE_BUFFER=256", "-c",
             RT / name, "-o", obj])
        tracer.append(obj)
    runtime = []
    for name in (*RUNTIME_CORE, *RUNTIME_DSPIC_DEVICES, "platform/platform_robot.c"):
        obj = work / f"plain_{Path(name).stem}.o"
        run(["avr-gcc", *flags, "-c", RT / name, "-o", obj])
        runtime.append(obj)
    return avr_size(tracer), avr_size(runtime)


def machine() -> str:
    cpu = ""
    try:
        cpu = next(line.split(":", 1)[1].strip() for line in
                   Path("/proc/cpuinfo").read_text().splitlines() if line.startswith("model name"))
    except (OSError, StopIteration):
        pass
    version = run(["avr-gcc", "--version"]).stdout.splitlines()[0]
    return f"{cpu}, {os.cpu_count()} CPUs; {version}"


def _ms(text: str) -> int:
    m = re.fullmatch(r"(\d+)(ms|s)", text)
    if not m:
        raise argparse.ArgumentTypeError(f"{text}: a duration such as 5s or 500ms")
    return int(m.group(1)) * (1000 if m.group(2) == "s" else 1)


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--only", default="record,examples,size")
    ap.add_argument("--examples", default="", help="comma-separated names (default: all)")
    ap.add_argument("--time-limit", type=_ms, default=10000, help="each run (default 10s)")
    args = ap.parse_args()
    parts = set(args.only.split(","))
    print(f"machine: {machine()}")
    with tempfile.TemporaryDirectory() as tmp:
        work = Path(tmp)
        if "record" in parts:
            print("\n== AVR cycles of one record (simavr, ATmega1284P, avr-gcc -Os), the tracer"
                  " alone: the hook with the link busy (what a poll pays: the record made and"
                  " queued), its framing when the link takes it (CRC, COBS, paid at the link's"
                  " pace), the hook when the ring is full (dropped and counted)")
            queued, framing, size, dropped = bench_record(work)
            print(f"{'record':>11} {'hook':>6} {'dropped':>8}")
            for name, cycles in queued.items():
                print(f"{name:>11} {cycles:>6} {dropped.get(name, 0):>8}")
            print(f"framing: {framing:.0f} cycles a record when the link takes it;"
                  f" {size:.1f} bytes a record on the wire (these 9 records)")
        if "examples" in parts:
            print(f"\n== the examples in the robot's time on simavr, {args.time_limit} ms each:"
                  f" cycles per poll without any trace and with the tracer (budget {BUDGET});"
                  " the link's share at 115200 baud")
            print(f"{'example':>18} {'mean':>6} {'traced':>7} {'+/poll':>7} {'max':>6}"
                  f" {'traced':>7} {'overruns':>8} {'records':>8} {'dropped':>8} {'bytes':>7}"
                  f" {'link':>6}")
            names = [n for n in args.examples.split(",") if n]
            for name, plain, traced, records, dropped, share in bench_examples(names,
                                                                               args.time_limit):
                mean_plain = plain.total_cycles / max(plain.polls, 1)
                mean_traced = traced.total_cycles / max(traced.polls, 1)
                print(f"{name:>18} {mean_plain:>6.0f} {mean_traced:>7.0f}"
                      f" {mean_traced - mean_plain:>7.0f} {plain.max_cycles:>6}"
                      f" {traced.max_cycles:>7} {traced.overruns:>8} {records:>8} {dropped:>8}"
                      f" {len(traced.uart):>7} {100 * share:>5.1f}%")
        if "size" in parts:
            tracer, runtime = bench_size(work)
            print("\n== flash and RAM on avr-gcc (ATmega128, 16-bit int): text / data / bss")
            for name, (text, data, bss) in {**tracer}.items():
                print(f"{name:>22} {text:>6} {data:>5} {bss:>5}")
            print(f"{'tracer in all':>22} {sum(v[0] for v in tracer.values()):>6}"
                  f" {sum(v[1] for v in tracer.values()):>5} {sum(v[2] for v in tracer.values()):>5}"
                  "   (bss: the 256-byte ring and the tracer's state)")
            print(f"{'runtime, no --trace':>22} {sum(v[0] for v in runtime.values()):>6}"
                  f" {sum(v[1] for v in runtime.values()):>5}"
                  f" {sum(v[2] for v in runtime.values()):>5}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
