"""`epuckc run --int16`: a program (rules and their extern C, or a C main)
and its C on the 16-bit path
(docs/runtime.md, "16 bits: --int16"): built with avr-gcc for an
ATmega1284P (16-bit int and pointers, like the dsPIC) over the host's
virtual robot (runtime_c/host/epuck_stub.c), the scenario compiled into it
as a table (runtime_c/platform/platform_int16.c applies it each ms), run on
simavr (runtime_c/int16/simavr_run.c); its trace lines become the JSON
trace. An int overflow in the user's C then wraps as on the robot, where
the host's 32-bit int would hide it."""
from __future__ import annotations

import hashlib
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path
from typing import Optional

from ..base import cache
from ..base.records import record
from ..base.resources import (LIBRARY_SIMULATION, RUNTIME_CORE, RUNTIME_DEVICES,
                              RUNTIME_TRACE, RUNTIME_TRACE_UART1, runtime_dir)
from ..build.common import USER_CFLAGS, BuildError, Program, _capacity_defines, _run_compiler
from ..build.trace_table import TraceOptions, trace_defines
from .scenario import _BLANKS, _time

MCU = "atmega1284p"
SIMAVR_HEADER = Path("/usr/include/simavr/sim_avr.h")
MISSING = ("--int16 needs avr-gcc, avr-libc and simavr with its headers "
           "(Debian/Ubuntu: apt-get install gcc-avr avr-libc simavr libsimavr-dev)")
AVR_FLAGS = ["-std=c99", "-Os", "-DEPUCK_STUB_NO_POSE", "-DEPUCKRT_NO_NAMES"]
CYCLES_PER_MS = 16000 * 400         # generous: the AVR's 16 MHz, 400 times a ms's work
INPUTS = {"ir": (0, 8), "amb": (1, 8), "mic": (2, 3), "acc": (3, 3), "selector": (4, 0),
          "key": (5, 0), "ground": (6, 3), "rot": (7, 3)}
KEY_NAMES = {"standby": 12, "mute": 13, "vol_up": 16, "vol_down": 17, "chan_up": 32,
             "chan_down": 33}
SETTERS = ["stub_set_prox", "stub_set_ambient", "stub_set_micro", "stub_set_acc"]


def int16_available() -> bool:
    return (shutil.which("avr-gcc") is not None and SIMAVR_HEADER.is_file()
            and shutil.which(os.environ.get("CC") or "cc") is not None)


def scenario_items(path: Optional[str]) -> list:
    """(ms, input, index, value) of every item of a scenario checked before
    (sim/scenario.py), in order."""
    if not path:
        return []
    items = []
    for line in Path(path).read_text(encoding="utf-8-sig").splitlines():
        tokens = [(m.group(0), m.start() + 1) for m in _BLANKS.finditer(line.split("#", 1)[0])]
        if not tokens:
            continue
        ms, used = _time(tokens)
        for text, _ in tokens[used:]:
            name, value = text.split("=", 1)
            name = name.lower()
            value = int(value) if value.lstrip("-").isdigit() else KEY_NAMES.get(value.lower())
            m = re.match(r"(ir|amb|mic|acc|rot|selector|key|ground)([0-9xyz]?)\Z", name)
            kind, index = m.group(1), m.group(2)
            if kind in ("acc", "rot"):
                items.append((ms, INPUTS[kind][0], "xyz".index(index), value))
            elif kind == "mic" and index == "":
                items.extend((ms, 2, n, value) for n in range(3))
            else:
                items.append((ms, INPUTS[kind][0], int(index or 0), value))
    return items


def scenario_c(items: list) -> str:
    """The scenario as C: int16_scenario(t) applies the lines due at t."""
    rows = ",\n".join(f"    {{{ms}L, {inp}, {idx}, {val}}}" for ms, inp, idx, val in items)
    return f"""/* written by epuckc run --int16 from the scenario */
#include "epuck_stub.h"
#include "stub_ground.h"
static const struct {{ long t; unsigned char input, index; int value; }} lines[] = {{
{rows or "    {0L, 255, 0, 0}"}
}};
static unsigned int next;
void int16_scenario(long t_ms);
void int16_scenario(long t_ms)
{{
    while (next < sizeof lines / sizeof lines[0] && lines[next].t <= t_ms) {{
        int n = lines[next].index, v = lines[next].value;
        switch (lines[next].input) {{
        case 0: stub_set_prox(n, v); break;
        case 1: stub_set_ambient(n, v); break;
        case 2: stub_set_micro(n, v); break;
        case 3: stub_set_acc(n, v); break;
        case 4: stub_set_selector(v); break;
        case 5: stub_press_key(v); break;
        case 6: stub_set_ground(n, v); break;
        case 7: stub_set_hand_rate(n, v); break;
        default: break;
        }}
        next++;
    }}
}}
"""


def _runner() -> Path:
    """simavr_run, built once (cached by its source and the compiler)."""
    source = runtime_dir() / "int16" / "simavr_run.c"
    cc = [os.environ.get("CC") or "cc"]
    key = hashlib.sha256(source.read_bytes() + " ".join(cc).encode()).hexdigest()[:24]
    exe = cache.area("int16") / f"runner-{key}" / "simavr_run"

    def complete(folder: Path) -> bool:
        return cache.used(folder) and (folder / exe.name).is_file()
    if complete(exe.parent):
        return exe
    exe = cache.writable_area("int16") / exe.parent.name / exe.name
    if complete(exe.parent):
        return exe
    tmp = cache.temporary_folder(exe.parent.parent)     # built aside, renamed whole
    try:
        _run_compiler(cc + ["-std=c99", "-O2", str(source), "-o", str(tmp / exe.name),
                            "-lsimavr"], "the simavr runner")
        cache.commit_folder(tmp, exe.parent, complete)
    finally:
        if tmp.exists():
            shutil.rmtree(tmp, ignore_errors=True)
    return exe


def build_int16(program: Program, folder: Path, items: list, time_limit_ms: int,
                robot: Optional[str] = None) -> Path:
    """The program as an AVR executable in `folder`. `robot`: the robot's
    time (platform_int16.c, INT16_ROBOT_TIME) with its tracer on the UART1
    ("trace": rt_trace.c, int16/uart1_avr.c) or without any trace ("time")."""
    rt = runtime_dir()
    robot_trace = robot is not None
    if program.generated:
        (folder / f"{program.name}.c").write_text(program.c_text, encoding="utf-8")
        sources = [str(folder / f"{program.name}.c"), *(str(p) for p in program.user_files)]
        mode, more = [], []
        if robot == "trace":
            # the UART1 is the AVR's USART0 (uart1_avr.c), not the simulated
            # one of host/epuck_more.c
            mode = [f"-D{d}" for d in trace_defines(program, "int16", TraceOptions())]
            mode.append("-DEPUCK_STUB_UART1_ELSEWHERE")
            more = [str(rt / n) for n in RUNTIME_TRACE + RUNTIME_TRACE_UART1]
            more.append(str(rt / "int16" / "uart1_avr.c"))
        elif robot == "time":
            mode = ["-DINT16_ROBOT_TIME"]
    elif robot_trace:
        raise BuildError("--robot-trace takes a rule file: a C program's main drives the "
                         "e-puck library itself (its UART1 among it), and the 16-bit path runs "
                         "it with the host's trace (leave out --robot-trace)", status=2)
    else:           # a C main: Timer1 is the simulator's ms (platform_int16.c)
        sources = [str(p) for p in program.user_sources()]
        mode, more = ["-DINT16_C_MAIN"], []
        mode += [f"-I{os.path.dirname(os.path.abspath(s))}" for s in sources]
    if program.header_name:
        (folder / program.header_name).write_text(program.header_text, encoding="utf-8")
    (folder / "scenario.c").write_text(scenario_c(items), encoding="utf-8")
    seed = os.environ.get("EPUCK_SEED", "1")
    elf = folder / f"{program.name}.elf"
    command = (["avr-gcc", f"-mmcu={MCU}"] + AVR_FLAGS + _capacity_defines(program)
               + [f"-DINT16_LIMIT_MS={time_limit_ms}L", f"-DINT16_SEED={int(seed)}UL"] + mode
               + [f"-I{folder}", f"-I{rt}", f"-I{rt / 'epuck_api'}", f"-I{rt / 'host'}",
                  f"-I{rt / 'epuck_api_unsimulated'}", *sources,
                  *(str(rt / n) for n in RUNTIME_CORE), *(str(rt / n) for n in LIBRARY_SIMULATION),
                  # the devices the host's build has (IR messages, ToF, camera,
                  # RGB LEDs, ground module), over LIBRARY_SIMULATION's stubs
                  # of them: a program the host runs builds here too
                  *(str(rt / n) for n in RUNTIME_DEVICES), *more,
                  str(rt / "platform" / "platform_int16.c"), str(folder / "scenario.c"),
                  "-o", str(elf)])
    inline = any(re.search(rb"\basm\b|__asm__|\b(NOP|RESET|CLRWDT|SLEEP|IDLE)\(\)",
                           Path(p).read_bytes()) for p in sources[int(bool(program.generated)):])
    _run_compiler(command, f"{program.name} for the 16-bit path (avr-gcc)",
                  "\nhelp: the dsPIC's instructions written inline (reset, pwrsav, ...) are "
                  "carried out on the host's path only: run it without --int16" if inline else "")
    return elf


_TRACE_LINE = re.compile(r"[EASUMXT](?: -?\d+)+\Z|L \d+ \w+ -?\d+\Z|R \d+ \w+ \w+ ,")


def _record(kind: str, t: int, name: str, number: int, left: int, right: int, **more) -> dict:
    record = {"t_ms": t, "kind": kind, "name": name, "id": number, "left_steps": left,
              "right_steps": right}
    record.update(more)
    return record


def parse_lines(text: str, var_names: list) -> list:
    """The runner's lines as JSON trace records (no pose: the 16-bit build
    keeps the wheels' steps, not the odometry)."""
    records, left, right = [], 0, 0
    for line in text.splitlines():
        if not _TRACE_LINE.match(line):
            continue            # simavr's own ("Loaded ... .text")
        kind, *fields = line.split()
        if kind == "R":         # a record of epuck_more.c's (the UART): R t kind name , extra
            _, t, rkind, name, extra = line.split(" ", 4)
            records.append(_record(rkind, int(t), name, -1, left, right,
                                   **json.loads("{" + extra.lstrip(" ,") + "}")))
            continue
        if kind == "L":
            t, name, state = int(fields[0]), fields[1], int(fields[2])
            records.append(_record("led", t, name, -1, left, right, state=state))
            continue
        numbers = list(map(int, fields))
        t = numbers[0]
        if kind == "E":
            left, right = numbers[2], numbers[3]
            records.append(_record("event", t, f"event#{numbers[1]}", numbers[1], left, right))
        elif kind == "A":
            left, right = numbers[4], numbers[5]
            extra = {} if numbers[2] < 0 else {"step": numbers[2] + 1, "steps": numbers[3]}
            records.append(_record("action", t, f"action#{numbers[1]}", numbers[1], left, right,
                                   **extra))
        elif kind == "S":
            name = var_names[numbers[1]] if numbers[1] < len(var_names) else f"var#{numbers[1]}"
            records.append({"t_ms": t, "kind": "set", "var": name, "value": numbers[2]})
        elif kind == "U":
            left, right = numbers[2], numbers[3]
            records.append(_record("suppressed", t, f"event#{numbers[1]}", numbers[1], left, right))
        elif kind == "M":
            left, right = numbers[2], numbers[3]
            records.append(_record("mode", t, f"mode#{numbers[1]}", numbers[1], left, right))
        elif kind in "XT":
            left, right = numbers[1], numbers[2]
            records.append(_record("exit" if kind == "X" else "timeout", t,
                                   "exit_main" if kind == "X" else "timeout", -1, left, right))
    return records


def _readable(r: dict) -> str:
    if r["kind"] == "set":
        return f"[{r['t_ms']:6d} ms] set       {r['var']} = {r['value']}"
    if r["kind"] == "uart":
        return f"[{r['t_ms']:6d} ms] {r['name']:<9} {json.dumps(r['text'])[1:-1]}"
    if r["kind"] == "led":
        return f"[{r['t_ms']:6d} ms] led       {r['name']:<5} {'on' if r['state'] else 'off'}"
    return (f"[{r['t_ms']:6d} ms] {r['kind']:<9} {r['name']} "
            f"(steps {r['left_steps']}, {r['right_steps']})")


@record
class RobotRun:
    """A run of the 16-bit build with the robot's tracer: the bytes its
    UART sent, how its polls went (`P` line: polls, the most cycles one
    took of its 16000, how many overran their ms, the ms of the longest,
    the cycles of all), simavr's status."""
    uart: bytes
    polls: int
    max_cycles: int
    overruns: int
    max_ms: int
    total_cycles: int
    status: int


def run_int16_robot(program: Program, scenario: Optional[str], time_limit_ms: int,
                    tracer: bool = True) -> RobotRun:
    """`run --int16 --robot-trace`: build with the tracer, run on simavr in
    the robot's time, the UART's bytes for the monitor's decoder
    (epuckc/link/); without `tracer`, the same without any trace (what the
    tracer's cost is measured against)."""
    if not int16_available():
        raise BuildError(MISSING)
    items = scenario_items(scenario)
    runner = _runner()
    with tempfile.TemporaryDirectory(prefix="epuckc-int16-") as tmp:
        elf = build_int16(program, Path(tmp), items, time_limit_ms,
                          robot="trace" if tracer else "time")
        uart = Path(tmp) / "uart.bin"
        # the robot's own time: each ms is 16000 cycles (most of them asleep)
        run = subprocess.run([str(runner), str(elf), MCU, str(16000 * (time_limit_ms + 1000)),
                              str(uart)], capture_output=True, text=True)
        data = uart.read_bytes() if uart.is_file() else b""
    stats = re.search(r"^P (\d+) (\d+) (\d+) (\d+) (\d+)$", run.stdout, re.M)
    if run.returncode != 0 or stats is None:
        why = {1: "it crashed", 4: "it ran out of cycles (a loop that never ends?)"}.get(
            run.returncode, f"simavr said {run.stderr.strip() or run.returncode}")
        raise BuildError(f"the 16-bit build of {program.name} with the robot's tracer did not "
                         f"finish on simavr: {why}")
    return RobotRun(data, *(int(v) for v in stats.groups()), run.returncode)


def run_int16(program: Program, scenario: Optional[str], time_limit_ms: int,
              trace: Optional[str]) -> int:
    """Build, run on simavr, print the readable trace (or the JSON lines with
    `trace` "-"), write the JSON trace; the exit status as the host's: 0 at
    exit_main, 3 at the time limit; 1 when the AVR program crashed."""
    if not int16_available():
        raise BuildError(MISSING)
    items = scenario_items(scenario)
    runner = _runner()
    var_names = [name for name, _ in program.variables]
    with tempfile.TemporaryDirectory(prefix="epuckc-int16-") as tmp:
        elf = build_int16(program, Path(tmp), items, time_limit_ms)
        run = subprocess.run([str(runner), str(elf), MCU,
                              str(CYCLES_PER_MS * (time_limit_ms + 1))],
                             capture_output=True, text=True)
    records = parse_lines(run.stdout, var_names)
    lines = [json.dumps(r) for r in records]
    if trace == "-":
        print("\n".join(lines))
    else:
        if trace:
            Path(trace).write_text("".join(line + "\n" for line in lines), encoding="utf-8")
        if not os.environ.get("EPUCK_QUIET"):
            print("\n".join(_readable(r) for r in records))
    sys.stdout.flush()
    if run.returncode != 0 or not records or records[-1]["kind"] not in ("exit", "timeout"):
        why = {1: "it crashed", 4: "it ran out of cycles (a loop that never ends?)"}.get(
            run.returncode, f"simavr said {run.stderr.strip()}")
        raise BuildError(f"the 16-bit build of {program.name} did not finish on simavr: {why}")
    return 0 if records[-1]["kind"] == "exit" else 3
