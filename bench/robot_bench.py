#!/usr/bin/env python3
"""The runtime's cost on the robot, each figure side by side with its
reference in one run (issue 11, "On the robot"):

  callgrind  x86 instructions per poll (valgrind's callgrind, host build,
             gcc -O2) of programs of N sensor rules that are armed and never
             fire, compiled by epuckc, against the hand-written reference
             (bench/reference_chain.c: an if-chain with an edge latch per
             rule, the proximity values read once per poll) for the same
             rules; for context also the same rules in hand-written C on the
             paper's dynamic API (an event_sensor registration per rule).  Per poll = (instructions of a run of P2 polls - of P1
             polls) / (P2 - P1); for the runtime the host harness's own
             per-poll work (rt_platform_idle: the virtual robot, the
             scenario) is subtracted, the reference has none.
  ram        RAM per rule on a 16-bit target: avr-gcc -Os for the ATmega128
             (16-bit int and pointers like the dsPIC), a mixed program of N
             rules (bench/check_bench.py's generator) compiled by epuckc for
             the robot, the runtime core and the robot platform layer.  RAM
             = data + bss of the object files: const data and string
             literals are in .rodata, which avr-size counts as text, i.e.
             where XC16 puts them on the dsPIC (program memory, auto_psv);
             avr-gcc itself would copy them to RAM when linking.
  simavr     AVR cycles per poll under simavr (ATmega1284P at 16 MHz, 16 KB
             RAM), programs of N sensor rules that never fire, built with
             the runtime, bench/avr/epuck_avr.c (the e-puck API over plain
             variables) and bench/avr/platform_sim.c (marks each poll on
             port B), timed by bench/avr/simavr_polls.c; against the budget
             of a 1 ms poll at 16 MIPS: 16,000 cycles.

    python3 bench/robot_bench.py                      # all three
    python3 bench/robot_bench.py --only callgrind --sizes 100
    python3 bench/robot_bench.py --keep /tmp/rb       # keep the files

Needs: gcc, valgrind (callgrind); avr-gcc, avr-size (ram, simavr); simavr's
library and headers (libsimavr-dev) for simavr.  A part whose tools are
missing says so and is skipped.  Recorded figures: docs/performance.md.
"""
from __future__ import annotations

import argparse
import os
import platform
import re
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

REPO = Path(__file__).resolve().parent.parent
RT = REPO / "runtime_c"
BENCH = REPO / "bench"
sys.path.insert(0, str(BENCH))
from check_bench import generate as generate_mixed  # noqa: E402

sys.path.insert(0, str(REPO))
from epuckc.base.resources import LIBRARY_SIMULATION, RUNTIME_CORE, RUNTIME_SIMULATED  # noqa: E402

HOST_CFLAGS = ["-std=c99", "-Wall", "-Wextra", "-Werror", "-pedantic", "-O2"]
# as epuckc's robot builds: no name labels
# -fno-common: a global defined without a value is then in the object's .bss,
# where avr-size counts it, not in COMMON, where it does not (the figures of
# RAM before 2026-12-02 left those out)
AVR_CFLAGS = ["-std=c99", "-Wall", "-Wextra", "-Werror", "-pedantic", "-Os", "-fno-common",
              "-DEPUCKRT_NO_NAMES"]
CORE = [RT / name for name in RUNTIME_CORE]     # the runtime, one file per concern
HOST_SOURCES = [*CORE, *(RT / name for name in RUNTIME_SIMULATED), RT / "platform" / "platform_host.c", RT / "host" / "scenario.c",
                *(RT / name for name in LIBRARY_SIMULATION)]
BUDGET_CYCLES = 16000           # 1 ms at 16 MIPS
SIM_MCU = "atmega1284p"
# epuckc before static registration counted every rule against the runtime's
# arrays (E039); `--max-* 100000` let it compile the large programs (set
# EPUCKC_BENCH_OLD=1 to measure such a revision); now they are not needed.
CAPACITY = (["--max-actions", "100000", "--max-events", "100000"]
            if os.environ.get("EPUCKC_BENCH_OLD") else [])


def run(cmd, **kw):
    res = subprocess.run([str(c) for c in cmd], capture_output=True, text=True, **kw)
    if res.returncode != 0:
        raise RuntimeError(f"failed: {' '.join(map(str, cmd))}\n{res.stdout}{res.stderr}")
    return res


def missing(*tools) -> list:
    return [t for t in tools if shutil.which(t) is None]


# ---- programs -------------------------------------------------------------------

def sensor_rules(n: int) -> list:
    """(sensor, threshold) of n sensor rules; the readings stay 0, so
    "ir > threshold" never holds and no rule fires."""
    return [(i % 8, 1000 + i) for i in range(n)]


PRIORITY_LEVELS = 4


def sensor_program(n: int, priorities: bool = False) -> str:
    """The rules share one action, so that 1,000 of them fit the AVR's RAM
    (avr-gcc copies const tables to RAM); what a rule would do does not
    change the cost of a poll where none fires. With `priorities`, the
    rules take PRIORITY_LEVELS levels in turn (epuckc numbers the events by
    priority, so the runtime's walk is the same as without)."""
    lines = [f"# {n} sensor rules that stay armed and never fire (bench/robot_bench.py)",
             "action turn = start_curve(5 cm, 90 deg, 300)",
             "on immediate do start_sensor"]
    for i, (sensor, threshold) in enumerate(sensor_rules(n)):
        level = f" priority {i % PRIORITY_LEVELS}" if priorities else ""
        lines.append(f"on sensor(ir{sensor} > {threshold}) repeat{level} do turn")
    return "\n".join(lines) + "\n"


def when_program(n: int) -> str:
    """The same rules as `when` condition rules of the language (readings in
    an expression need no start_sensor)."""
    lines = [f"# {n} when rules that stay armed and never fire (bench/robot_bench.py)",
             "action turn = start_curve(5 cm, 90 deg, 300)"]
    for sensor, threshold in sensor_rules(n):
        lines.append(f"when ir{sensor} > {threshold} repeat do turn")
    return "\n".join(lines) + "\n"


def hold_program(n: int) -> str:
    """The sensor rules, plus a `when` rule of priority 1 whose condition is
    true all along, so that it holds the motors for the whole run, and a
    rule of priority 0 that renews its command every 10 ms (refused each
    time): the poll's cost while a condition holds the motors (issue 24)."""
    return (sensor_program(n) + "when selector == 0 priority 1 do set_speed(left: 100, right: 100)\n"
            "every 10 ms do set_speed(left: 200, right: 200)\n")


def vars_program(n: int) -> str:
    """n variables, all given a value by one rule (RAM per variable)."""
    lines = [f"var v{i} = {i}" for i in range(n)]
    lines.append("on immediate do " + ", ".join(f"v{i} += 1" for i in range(n)))
    return "\n".join(lines) + "\n"


def dynamic_program(n: int) -> str:
    """The same rules written by hand with the paper's dynamic API: one
    register_event(event_sensor, ...) per rule (context: the path of
    hand-written C)."""
    params = ",\n".join(
        "    {{" + ", ".join(str(t) if k == s else "SENSOR_OFF" for k in range(8)) + "}, 0}"
        for s, t in sensor_rules(n))
    return f"""#include "epuckrt.h"
static param_event_sensor rules[{n}] = {{
{params}
}};
int main(void)
{{
    int on = register_action(start_sensor, NULL), turn = register_action(stop_motor, NULL), i;
    register_event(immediate, NULL, on);
    for (i = 0; i < {n}; i++)
        set_event_repeat(register_event(event_sensor, &rules[i], turn), 1);
    mainloop();
    return 0;
}}
"""


def compile_epk(text: str, work: Path, name: str) -> tuple:
    """epuckc compile; returns (C file, [capacity defines])."""
    epk = work / f"{name}.epk"
    epk.write_text(text)
    out = work / f"{name}.c"
    env = dict(os.environ)
    env["PYTHONPATH"] = str(REPO) + os.pathsep + env.get("PYTHONPATH", "")
    run([sys.executable, "-m", "epuckc", "compile", epk, "-o", out] + CAPACITY, env=env)
    text = out.read_text()
    m = re.search(r"Registrations: (\d+) actions, (\d+) events", text)
    if m:   # a program that registers its rules (before register_program)
        return out, [f"-DMAX_ACTIONS={max(1, int(m.group(1)))}",
                     f"-DMAX_EVENTS={max(1, int(m.group(2)))}"]
    # the rules are tables: the dynamic arrays hold nothing (as epuckc's
    # builds of a rule file without user C)
    assert "register_program" in text
    return out, ["-DMAX_ACTIONS=1", "-DMAX_EVENTS=1"]


# ---- callgrind --------------------------------------------------------------------

def callgrind_ir(exe: Path, work: Path, args=(), env=None, function=None) -> tuple:
    """(total Ir, inclusive Ir of `function` or 0) of one run under callgrind."""
    out = work / f"{exe.name}.cg"
    res = subprocess.run(["valgrind", "--tool=callgrind", f"--callgrind-out-file={out}",
                          str(exe), *map(str, args)], capture_output=True, text=True, env=env)
    if res.returncode not in (0, 3):        # 3: the harness's time limit
        raise RuntimeError(f"{exe} failed under callgrind:\n{res.stderr[-2000:]}")
    ann = run(["callgrind_annotate", "--inclusive=yes", "--threshold=100", out]).stdout
    total = int(re.search(r"^\s*([\d,]+)\s.*PROGRAM TOTALS", ann, re.M).group(1).replace(",", ""))
    inner = 0
    if function:
        m = re.search(rf"^\s*([\d,]+) .*:{function} ", ann, re.M)
        if m:
            inner = int(m.group(1).replace(",", ""))
    return total, inner


def per_poll(text: str, d: Path, name: str, p1=1000, p2=2000) -> float:
    """x86 instructions per poll of a rule file's program (the harness's
    own per-poll work subtracted)."""
    c, defines = compile_epk(text, d, name)
    return host_per_poll(c, (), defines, d, p1, p2)


def host_per_poll(c: Path, extra, defines: list, d: Path, p1=1000, p2=2000) -> float:
    """x86 instructions per poll of a compiled program (with `extra` C
    files: its externs), the harness's own per-poll work subtracted."""
    exe = d / (c.stem + ".host")
    run(["cc", *HOST_CFLAGS, *defines, f"-I{RT}", f"-I{RT / 'epuck_api'}", f"-I{RT / 'host'}",
         f"-I{RT / 'epuck_api_unsimulated'}", f"-I{c.parent}", c, *extra, *HOST_SOURCES, "-o",
         exe, "-lm"])
    per = []
    for polls in (p1, p2):
        env = {k: v for k, v in os.environ.items() if not k.startswith("EPUCK_")}
        env.update(EPUCK_QUIET="1", EPUCK_TIME_LIMIT_MS=str(polls),
                   EPUCK_POLL_EVERY_MS="1")     # a poll every ms, as the robot
        total, idle = callgrind_ir(exe, d, env=env, function="rt_platform_idle")
        per.append(total - idle)
    return (per[1] - per[0]) / (p2 - p1)


def reference_per_poll(n: int, d: Path, p1=1000, p2=2000) -> float:
    """The hand-written if-chain with an edge latch per rule."""
    (d / "chain_rules.h").write_text("".join(f"RULE({i}, {s}, {t})\n"
                                             for i, (s, t) in enumerate(sensor_rules(n))))
    ref_exe = d / "chain"
    run(["cc", *HOST_CFLAGS, f"-I{RT}", f"-I{RT / 'epuck_api'}", f"-I{RT / 'host'}",
         f"-I{RT / 'epuck_api_unsimulated'}", f"-I{d}", BENCH / "reference_chain.c",
         *(RT / name for name in LIBRARY_SIMULATION), "-o", ref_exe, "-lm"])
    ref = [callgrind_ir(ref_exe, d, args=[polls])[0] for polls in (p1, p2)]
    return (ref[1] - ref[0]) / (p2 - p1)


def bench_conditions(sizes, work: Path) -> list:
    """(n, sensor rules, when rules, sensor rules on 4 priority levels,
    the reference chain), x86 instructions per poll."""
    rows = []
    for n in sizes:
        d = work / f"cond{n}"
        d.mkdir()
        rows.append((n, per_poll(sensor_program(n), d, f"sensors{n}"),
                     per_poll(when_program(n), d, f"when{n}"),
                     per_poll(sensor_program(n, priorities=True), d, f"levels{n}"),
                     reference_per_poll(n, d)))
    return rows


def bench_vars(sizes, work: Path, mcu="atmega128") -> list:
    """(n, RAM bytes of the program's object) for n variables on avr-gcc."""
    rows = []
    for n in sizes:
        d = work / f"vars{n}"
        d.mkdir()
        c, _ = compile_epk(vars_program(n), d, f"vars{n}")
        obj = d / f"vars{n}.o"
        run(["avr-gcc", *AVR_CFLAGS, f"-mmcu={mcu}", f"-I{RT}", f"-I{RT / 'epuck_api'}", "-c", c,
             "-o", obj])
        (_, _, data, bss), = avr_size([obj])
        rows.append((n, data + bss))
    return rows


def bench_callgrind(sizes, work: Path, p1=1000, p2=2000) -> list:
    rows = []
    for n in sizes:
        d = work / f"cg{n}"
        d.mkdir()
        runtime = per_poll(sensor_program(n), d, f"sensors{n}", p1, p2)
        dyn_c = d / f"dynamic{n}.c"
        dyn_c.write_text(dynamic_program(n))
        dyn_exe = d / f"dynamic{n}"
        run(["cc", *HOST_CFLAGS, "-DMAX_ACTIONS=2", f"-DMAX_EVENTS={n + 1}", f"-I{RT}",
             f"-I{RT / 'epuck_api'}", f"-I{RT / 'host'}", f"-I{RT / 'epuck_api_unsimulated'}",
             dyn_c, *HOST_SOURCES, "-o", dyn_exe, "-lm"])
        per = []
        for polls in (p1, p2):
            env = {k: v for k, v in os.environ.items() if not k.startswith("EPUCK_")}
            env.update(EPUCK_QUIET="1", EPUCK_TIME_LIMIT_MS=str(polls),
                       EPUCK_POLL_EVERY_MS="1")     # a poll every ms, as the robot
            total, idle = callgrind_ir(dyn_exe, d, env=env, function="rt_platform_idle")
            per.append(total - idle)
        dynamic = (per[1] - per[0]) / (p2 - p1)
        rows.append((n, runtime, reference_per_poll(n, d, p1, p2), dynamic))
    return rows


# ---- RAM on avr-gcc ------------------------------------------------------------------

def avr_size(objects) -> list:
    """(name, text, data, bss) per object file."""
    out = run(["avr-size", *objects]).stdout.splitlines()[1:]
    rows = []
    for line in out:
        f = line.split()
        rows.append((Path(f[5]).name, int(f[0]), int(f[1]), int(f[2])))
    return rows


def bench_ram(sizes, work: Path, mcu="atmega128") -> list:
    rows = []
    for n in sizes:
        d = work / f"ram{n}"
        d.mkdir()
        c, defines = compile_epk(generate_mixed(n), d, f"mixed{n}")
        flags = [*AVR_CFLAGS, f"-mmcu={mcu}", f"-I{RT}", f"-I{RT / 'epuck_api'}"]
        objs = []
        for src, extra in ((c, []), *((core, defines) for core in CORE), (RT / "platform" / "platform_robot.c", [])):
            obj = d / (Path(src).stem + ".o")
            run(["avr-gcc", *flags, *extra, "-c", src, "-o", obj])
            objs.append(obj)
        sizes_ = avr_size(objs)
        ram = sum(r[2] + r[3] for r in sizes_)
        flash = sum(r[1] for r in sizes_)
        rows.append((n, ram, flash, {r[0]: r[1:] for r in sizes_}))
    return rows


# ---- simavr --------------------------------------------------------------------------

def simavr_misdecodes(elf: Path) -> list:
    """Functions where simavr 1.6 would mis-execute the program: after a skip
    instruction (sbrc, sbrs, sbic, sbis, cpse) it takes an adiw/sbiw whose
    opcode & 0xfc0f is 0x940c..0x940f for a two-word CALL/JMP and skips one
    word too many (fixed in later simavr by masking with 0xfe0e).  A figure
    from such a program would be wrong, so the bench refuses it."""
    out = run(["avr-objdump", "-d", elf]).stdout
    found, function, previous = [], "?", ""
    for line in out.splitlines():
        m = re.match(r"^[0-9a-f]+ <(.+)>:$", line)
        if m:
            function, previous = m.group(1), ""
            continue
        m = re.match(r"^\s*[0-9a-f]+:\s+([0-9a-f]{2}) ([0-9a-f]{2})\s+(\w+)", line)
        if not m:
            continue
        opcode = int(m.group(2) + m.group(1), 16)
        if previous in ("sbrc", "sbrs", "sbic", "sbis", "cpse") and (opcode & 0xfc0f) in (
                0x940c, 0x940d, 0x940e, 0x940f) and m.group(3) in ("adiw", "sbiw"):
            found.append(function)
        previous = m.group(3)
    return found


def bench_simavr(sizes, work: Path, priorities: bool = False, when: bool = False) -> list:
    harness = work / "simavr_polls"
    if not harness.exists():
        run(["cc", "-std=c99", "-O2", BENCH / "avr" / "simavr_polls.c", "-o", harness,
             "-lsimavr"])
    rows = []
    for n in sizes:
        d = work / (f"sim{n}" + ("p" if priorities else "") + ("w" if when else ""))
        d.mkdir(exist_ok=True)
        c, defines = compile_epk(when_program(n) if when else sensor_program(n, priorities), d,
                                 f"sensors{n}")
        elf = d / f"sensors{n}.elf"
        res = subprocess.run(["avr-gcc", *AVR_CFLAGS, f"-mmcu={SIM_MCU}", *defines, f"-I{RT}",
                              f"-I{RT / 'epuck_api'}", f"-I{BENCH / 'avr'}", str(c),
                              *map(str, CORE), str(BENCH / "avr" / "platform_sim.c"),
                              str(BENCH / "avr" / "epuck_avr.c"), "-o", str(elf)],
                             capture_output=True, text=True)
        if res.returncode != 0:
            if "overflowed" in res.stderr or "not within region" in res.stderr:
                rows.append((n, None, "does not fit the ATmega1284P's 16 KB of RAM"))
                continue
            raise RuntimeError(res.stderr)
        bad = simavr_misdecodes(elf)
        if bad:
            rows.append((n, None, "simavr 1.6 would mis-execute " + ", ".join(sorted(set(bad)))))
            continue
        out = run([harness, elf, SIM_MCU, 5, 50]).stdout
        line = re.search(r"^polls .*$", out, re.M).group(0).split()
        stats = dict(zip(line[0::2], line[1::2]))
        rows.append((n, int(stats["median"]), f"min {stats['min']}, max {stats['max']}"))
    return rows


# ---- main ----------------------------------------------------------------------------

def machine() -> str:
    cpu = platform.processor() or platform.machine()
    try:
        for line in Path("/proc/cpuinfo").read_text().splitlines():
            if line.startswith("model name"):
                cpu = line.split(":", 1)[1].strip()
                break
    except OSError:
        pass
    def version(cmd):
        try:
            return subprocess.run(cmd, capture_output=True, text=True).stdout.splitlines()[0]
        except (OSError, IndexError):
            return "not installed"
    return (f"{cpu}, {os.cpu_count()} CPUs; {version(['cc', '--version'])}; "
            f"{version(['valgrind', '--version'])}; {version(['avr-gcc', '--version'])}")


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--only", default="callgrind,ram,simavr",
                    help="comma-separated parts: callgrind, ram, simavr, priorities (simavr's "
                         "programs with and without priorities, side by side), when (callgrind: "
                         "sensor rules, when rules, priority levels, the reference chain), vars "
                         "(RAM per variable), holding (callgrind: while a condition holds the motors)")
    ap.add_argument("--sizes", default="10,100,1000", help="rule counts (default 10,100,1000)")
    ap.add_argument("--keep", type=Path, help="keep the generated files in this folder")
    args = ap.parse_args()
    parts = set(args.only.split(","))
    sizes = [int(s) for s in args.sizes.split(",")]
    if args.keep:
        args.keep.mkdir(parents=True, exist_ok=True)
        work = Path(tempfile.mkdtemp(dir=args.keep))
    else:
        tmp = tempfile.TemporaryDirectory()
        work = Path(tmp.name)
    print(f"machine: {machine()}")
    status = 0
    if "callgrind" in parts:
        if missing("cc", "valgrind", "callgrind_annotate"):
            print(f"callgrind: skipped, missing {missing('cc', 'valgrind', 'callgrind_annotate')}")
            status = 1
        else:
            print("\n== x86 instructions per poll, N armed sensor rules that never fire (callgrind)")
            print(f"{'rules':>6} {'epuckc':>10} {'reference chain':>16} {'ratio':>7} {'per rule':>9}"
                  f"   {'dynamic API (hand-written C)':>28}")
            for n, rt, ref, dyn in bench_callgrind(sizes, work):
                print(f"{n:>6} {rt:>10.0f} {ref:>16.0f} {rt / ref:>6.2f}x {rt / n:>9.1f}"
                      f"   {dyn:>28.0f}")
    if "ram" in parts:
        if missing("avr-gcc", "avr-size"):
            print(f"ram: skipped, missing {missing('avr-gcc', 'avr-size')}")
            status = 1
        else:
            print("\n== RAM on avr-gcc (16-bit), mixed programs (data + bss of the objects;"
                  " const and strings count as flash, as on the dsPIC)")
            print(f"{'rules':>6} {'RAM B':>8} {'B/rule':>7} {'flash B':>8}   objects (text/data/bss)")
            rows = bench_ram(sizes, work)
            for n, ram, flash, objs in rows:
                detail = ", ".join(f"{k} {v[0]}/{v[1]}/{v[2]}" for k, v in objs.items())
                print(f"{n:>6} {ram:>8} {ram / n:>7.1f} {flash:>8}   {detail}")
            if len(rows) >= 2:
                (n0, r0, *_), (n1, r1, *_) = rows[-2], rows[-1]
                print(f"marginal RAM per rule, {n0} -> {n1} rules: {(r1 - r0) / (n1 - n0):.2f} B")
    if "simavr" in parts:
        if missing("avr-gcc", "cc") or not Path("/usr/include/simavr/sim_avr.h").exists():
            print("simavr: skipped, needs avr-gcc and libsimavr-dev")
            status = 1
        else:
            print(f"\n== AVR cycles per poll ({SIM_MCU}, simavr), N armed sensor rules that never"
                  f" fire; budget {BUDGET_CYCLES} (1 ms at 16 MIPS)")
            print(f"{'rules':>6} {'cycles':>8} {'of budget':>10}   spread")
            for n, cyc, note in bench_simavr(sizes, work):
                if cyc is None:
                    print(f"{n:>6} {'-':>8} {'-':>10}   {note}")
                else:
                    print(f"{n:>6} {cyc:>8} {100 * cyc / BUDGET_CYCLES:>9.1f}%   {note}")
    if "when" in parts:
        if missing("cc", "valgrind", "callgrind_annotate"):
            print(f"when: skipped, missing {missing('cc', 'valgrind', 'callgrind_annotate')}")
            status = 1
        else:
            print("\n== x86 instructions per poll (callgrind), N armed rules that never fire:"
                  " sensor rules, the same as `when irK > T repeat` rules, the sensor rules on"
                  f" {PRIORITY_LEVELS} priority levels, and the hand-written edge-latch chain")
            print(f"{'rules':>6} {'sensor':>8} {'when':>8} {'levels':>8} {'chain':>8}"
                  f" {'when/sensor':>12} {'when/chain':>11} {'levels/sensor':>14}")
            for n, sensor, when, levels, chain in bench_conditions(sizes, work):
                print(f"{n:>6} {sensor:>8.0f} {when:>8.0f} {levels:>8.0f} {chain:>8.0f}"
                      f" {when / sensor:>11.2f}x {when / chain:>10.2f}x {levels / sensor:>13.2f}x")
    if "holding" in parts:
        if missing("cc", "valgrind", "callgrind_annotate"):
            print(f"holding: skipped, missing {missing('cc', 'valgrind', 'callgrind_annotate')}")
            status = 1
        else:
            print("\n== x86 instructions per poll (callgrind) while a `when` rule of priority 1"
                  " holds the motors, N sensor rules that never fire (hold_program); a reference"
                  " revision runs the same program with its own per_poll")
            print(f"{'rules':>6} {'per poll':>9}")
            for n in sizes:
                d = work / f"hold{n}"
                d.mkdir()
                print(f"{n:>6} {per_poll(hold_program(n), d, 'hold'):>9.0f}")
    if "vars" in parts:
        if missing("avr-gcc", "avr-size"):
            print(f"vars: skipped, missing {missing('avr-gcc', 'avr-size')}")
            status = 1
        else:
            print("\n== RAM of N variables on avr-gcc (16-bit): data + bss of the program's"
                  " object (its event state and memory included)")
            rows = bench_vars(sizes, work)
            print(f"{'vars':>6} {'RAM B':>8}")
            for n, ram in rows:
                print(f"{n:>6} {ram:>8}")
            if len(rows) >= 2:
                (n0, r0), (n1, r1) = rows[-2], rows[-1]
                print(f"marginal RAM per variable, {n0} -> {n1}: "
                      f"{(r1 - r0) / (n1 - n0):.2f} B")
    if "priorities" in parts:
        if missing("avr-gcc", "cc") or not Path("/usr/include/simavr/sim_avr.h").exists():
            print("priorities: skipped, needs avr-gcc and libsimavr-dev")
            status = 1
        else:
            print(f"\n== AVR cycles per poll ({SIM_MCU}, simavr), N armed sensor rules that never"
                  f" fire, without and with {PRIORITY_LEVELS} priority levels, and as `when`"
                  f" rules; budget {BUDGET_CYCLES}")
            print(f"{'rules':>6} {'plain':>8} {'priorities':>11} {'ratio':>7} {'of budget':>10}"
                  f" {'when rules':>11} {'ratio':>7}")
            plain = bench_simavr(sizes, work)
            levels = bench_simavr(sizes, work, priorities=True)
            whens = bench_simavr(sizes, work, when=True)
            for (n, a, note_a), (_, b, note_b), (_, w, note_w) in zip(plain, levels, whens):
                if a is None or b is None or w is None:
                    print(f"{n:>6}   {note_a if a is None else note_b if b is None else note_w}")
                else:
                    print(f"{n:>6} {a:>8} {b:>11} {b / a:>6.2f}x {100 * b / BUDGET_CYCLES:>9.1f}%"
                          f" {w:>11} {w / a:>6.2f}x")
    return status


if __name__ == "__main__":
    sys.exit(main())
