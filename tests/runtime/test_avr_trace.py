"""The 16-bit path executed, not only compiled: every example and the
language's test programs run on simavr (ATmega1284P, 16-bit int) over the
host's virtual robot, as `epuckc run --int16` runs them (epuckc/sim/int16.py,
runtime_c/int16/), and give the trace the host gives: the same events and
actions at the same milliseconds with the same steps of each wheel, the
same variables' values, the same suppressed motor commands, modes, LEDs
and end. A difference is a bug in the runtime or the generated C where int is 16
bits, not a tolerance."""
import json
from pathlib import Path

import pytest

from conftest import REPO, require_tool
from tests.runtime.test_language import EVERY_FEATURE
from tests.support.programs import epuckc

LIMIT_MS = 5000


# every example, those of the devices too (messages, camera, ground
# module): the 16-bit path links the runtime's device files as the host's
# build does, over the same simulated library (epuckc/sim/int16.py)
EXAMPLES = sorted((REPO / "examples").glob("*.epk"))
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
    # the bitwise operators on 16 bits: shifts by negative counts and by 16
    # or more, of negative values, masks in hexadecimal and binary; whole
    # arrays assigned (a swap), filled, and read in slices
    "bits_and_arrays": """\
var n = 0x1F
var m = 0b101
var k = 3
var s = -0x7FFF
var a = [1, 2, 3, 4]
every 7 ms do n = (n + 0x123) & 0x7FFF, m = n << 2 | m >> 1 ^ ~n, k = (k + 1) % 40 - 20
every 11 ms do s = s >> 1 | s << k, m = (m ^ 0xA5A5) >> k, a = [a[3], a[0] ^ n, a[1], a[2] >> 1]
every 13 ms do fill(a, ir0 & 0b111 | m << 3), n = sum(a[1:3]) + max(a[:2]) + dot(a[2:], a[0:2])
after 600 ms do exit_main
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


# what the 16-bit path traces (epuckc/sim/int16.py), and the fields of each
# record that both traces must agree on (the host's also name the rules,
# and give poses and who holds the motors, which the AVR build leaves out)
FIELDS = {"event": ("id", "left_steps", "right_steps"),
          "action": ("id", "left_steps", "right_steps", "step", "steps"),
          "set": ("var", "value"), "suppressed": ("id", "left_steps", "right_steps"),
          "mode": ("id", "left_steps", "right_steps"),
          "led": ("name", "state"), "exit": ("left_steps", "right_steps"),
          "timeout": ("left_steps", "right_steps")}


@pytest.fixture(scope="module")
def harness():
    for tool in ("cc", "avr-gcc", "simavr"):
        require_tool(tool)
    if not Path("/usr/include/simavr/sim_avr.h").exists():
        require_tool("libsimavr-dev (the simavr headers)")


def _trace(program: Path, tmp: Path, *how) -> list:
    """The records of `epuckc run PROGRAM [how]` that the 16-bit path gives,
    each as the tuple of the fields both paths trace."""
    trace = tmp / f"{program.stem}{''.join(how).replace('-', '_')}.jsonl"
    r = epuckc("run", program, *how, "--time-limit", f"{LIMIT_MS}ms", "--trace", trace)
    assert r.returncode in (0, 3), r.stdout + r.stderr
    return [(rec["kind"], rec["t_ms"], *(rec.get(f) for f in FIELDS[rec["kind"]]))
            for rec in map(json.loads, trace.read_text().splitlines())
            if rec["kind"] in FIELDS]


def _avr_trace(harness, program: Path, tmp: Path) -> list:
    return _trace(program, tmp, "--int16")


def _host_trace(program: Path, tmp: Path) -> list:
    return _trace(program, tmp)


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
    assert avr and avr[-1][0] in ("exit", "timeout")


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
