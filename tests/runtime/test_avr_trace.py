"""The 16-bit path executed, not only compiled: every example and the
language's test programs run on simavr (ATmega1284P, 16-bit int) over the
host's virtual robot (bench/avr/platform_trace.c, simavr_trace.c), and
give the trace the host gives: the same events at the same milliseconds
with the same steps of each wheel, the same variables' values, the same
suppressed motor commands, modes and end. A difference is a bug in the
runtime or the generated C where int is 16 bits, not a tolerance."""
import json
import re
import subprocess
from pathlib import Path

import pytest

from conftest import REPO, require_tool
from epuckc.base.resources import RUNTIME_CORE
from tests.runtime.test_language import EVERY_FEATURE
from tests.support.programs import epuckc

RUNTIME = REPO / "runtime_c"
AVR = REPO / "bench" / "avr"
MCU = "atmega1284p"
LIMIT_MS = 5000
def _without_devices(paths) -> list:
    """The examples that use no device beyond the e-puck's own (messages,
    the camera, ToF, RGB LEDs: check/devices.py): the AVR proxy has the
    runtime's core and the stub robot, not the device layer; those examples
    are tested in their worlds (tests/sim)."""
    from epuckc.check.frontend import check_file
    from epuckc.diagnostics import Report
    kept = []
    for path in paths:
        result = check_file(path, Report())
        if result.checked is None or not result.checked.devices:
            kept.append(path)
    return kept


EXAMPLES = _without_devices(sorted((REPO / "examples").glob("*.epk")))
EXTRA = {
    "every_feature": EVERY_FEATURE,
    "arithmetic": """\
var a = 30000
var b = -7
var c = 0
every 7 ms do a += 1234, b = b * -3 + a % 97 - a / 13, c = clamp(abs(b) - 16000, -50, 50)
every 11 ms do a = max(min(a, 32000) - random(0, 20000), -32768) * 2 / 3
after 1 s do exit_main
""",
    # the smallest int by -1 where int is 16 bits: `%` and `/` in C would be
    # undefined there, the language's are 0 and 32767 (saturated where stored)
    "smallest_by_minus_one": """\
var a = 1
var b = 1
var m = 5
var q = 5
every 3 ms do a = -32768, b = -1, m = a % b, q = a / b
every 5 ms do a = a + 1, b = b - 1
after 40 ms do exit_main
""",
    "timers_and_modes": """\
var n = 0
var m = 0
initial mode a {
    after 100 ms do n += 1, enter b
    every 30 ms do m += 2
}
mode b {
    after 50 ms do enter a
    on enter do start_straight(500, 1 cm) then wait(40 ms) then start_curve(0 mm, -45 deg, 300)
}
when n >= 3 priority 2 do set_speed(left: 200, right: -150)
after 2 s do exit_main
""",
    "if_else": """\
var n = 0
var phase = 0
every 7 ms do n = clamp(n + 3, 0, 300),
    if n > 200 { phase = 3, set_speed(-200, 200) }
    else if n > 100 { phase = 2, start_straight(300, 2 cm) }
    else if n % 2 == 0 { phase = 1 } else { phase = 0, n += 1 }
every 50 ms priority 1 do if phase == 3 and n >= 300 { n = 0, stop_motor, if phase > 2 { phase = 4 } }
after 2 s priority 2 do exit_main
""",
}


@pytest.fixture(scope="module")
def harness(tmp_path_factory):
    for tool in ("cc", "avr-gcc", "simavr"):
        require_tool(tool)
    if not Path("/usr/include/simavr/sim_avr.h").exists():
        require_tool("libsimavr-dev (the simavr headers)")
    exe = tmp_path_factory.mktemp("simavr") / "simavr_trace"
    subprocess.run(["cc", "-std=c99", "-O2", str(AVR / "simavr_trace.c"), "-o", str(exe),
                    "-lsimavr"], check=True)
    return exe


def _avr_trace(harness, program: Path, tmp: Path) -> list:
    c = tmp / f"{program.stem}.c"
    epuckc("compile", program, "-o", c, check=True)
    elf = tmp / f"{program.stem}.elf"
    user = [str(program.parent / m) for m in re.findall(r'from "([^"]+\.c)"',
                                                         program.read_text())]
    subprocess.run(["avr-gcc", f"-mmcu={MCU}", "-std=c99", "-Wall", "-Wextra", "-Werror",
                    "-pedantic", "-Os", "-DEPUCK_STUB_NO_POSE", "-DEPUCKRT_NO_NAMES",
                    "-DMAX_ACTIONS=4", "-DMAX_EVENTS=4", f"-DTRACE_LIMIT_MS={LIMIT_MS}L",
                    f"-I{tmp}", f"-I{RUNTIME}", f"-I{RUNTIME / 'epuck_api'}",
                    f"-I{RUNTIME / 'host'}", str(c), *user,
                    *(str(RUNTIME / n) for n in RUNTIME_CORE), str(RUNTIME / "host" / "epuck_stub.c"),
                    str(AVR / "platform_trace.c"), "-o", str(elf)], check=True)
    run = subprocess.run([str(harness), str(elf), MCU], capture_output=True, text=True,
                         timeout=300)
    assert run.returncode == 0, run.stderr
    out = []
    for line in run.stdout.splitlines():
        kind, *numbers = line.split()
        if kind in "ESUMXT" and len(kind) == 1:
            out.append((kind, *map(int, numbers)))
    return out


def _host_trace(program: Path, tmp: Path) -> list:
    trace = tmp / f"{program.stem}.jsonl"
    r = epuckc("run", program, "--time-limit", f"{LIMIT_MS}ms", "--trace", trace)
    assert r.returncode in (0, 3), r.stderr
    c_text = epuckc("compile", program, "-o", "-").stdout
    var_ids = {name: int(i) for i, name in re.findall(r'name_var\((\d+), "([^"]+)"\)', c_text)}
    out = []
    for rec in map(json.loads, trace.read_text().splitlines()):
        kind, t = rec["kind"], rec["t_ms"]
        if kind == "event":
            out.append(("E", t, rec["id"], rec["left_steps"], rec["right_steps"]))
        elif kind == "set":
            out.append(("S", t, var_ids[rec["var"]], rec["value"]))
        elif kind == "suppressed":
            out.append(("U", t, rec["id"]))
        elif kind == "mode":
            out.append(("M", t, rec["id"]))
        elif kind in ("exit", "timeout"):
            out.append(("X" if kind == "exit" else "T", t, rec["left_steps"], rec["right_steps"]))
    return out


@pytest.mark.parametrize("program", EXAMPLES + list(EXTRA), ids=lambda p: getattr(p, "stem", p))
def test_the_16_bit_build_gives_the_hosts_trace(harness, tmp_path, program):
    if isinstance(program, str):
        path = tmp_path / f"{program}.epk"
        path.write_text(EXTRA[program], encoding="utf-8")
        program = path
    avr = _avr_trace(harness, program, tmp_path)
    host = _host_trace(program, tmp_path)
    # the mode set before mainloop is traced at its start on the host
    assert avr == host
    assert avr and avr[-1][0] in "XT"


def _generated_programs(count: int) -> list:
    """`count` programs of the language fuzzer (fixed seed) that the
    checker accepts, spread over its examples (the first are the smallest,
    and the following ones near each other)."""
    from hypothesis import HealthCheck, given, seed, settings
    from conftest import FUZZ_FIXED_SEED
    from epuckc.check.frontend import check_file
    from epuckc.diagnostics import Report
    from tests.support.language import language_programs
    found, seen = [], [0]

    @seed(FUZZ_FIXED_SEED)
    @settings(max_examples=400, deadline=None, database=None,
              suppress_health_check=list(HealthCheck))
    @given(language_programs())
    def collect(program):
        seen[0] += 1
        if seen[0] % 25 == 0 and len(found) < count and check_file(Path("g.epk"), Report(), shown_name="g.epk",
                                             text=program.text).checked is not None:
            found.append(program.text)

    collect()
    return found


GENERATED = 4


@pytest.mark.parametrize("index", range(GENERATED))
def test_generated_programs_give_the_hosts_trace_on_16_bits(harness, tmp_path, index):
    """A sample of the fuzzer's accepted programs (tests/emit/
    test_language_fuzz.py): the 16-bit build runs as the host's does."""
    programs = _generated_programs(GENERATED)
    path = tmp_path / f"generated{index}.epk"
    path.write_text(programs[index], encoding="utf-8")
    avr = _avr_trace(harness, path, tmp_path)
    assert avr == _host_trace(path, tmp_path), programs[index]
