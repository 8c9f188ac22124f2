"""The bitwise operators (`&`, `|`, `^`, `~`, `<<`, `>>`) and hexadecimal
and binary numbers: the runtime's shifts against stdlib/arith.py under
UBSan, the checker's intervals against every value, and a program run on
the host harness whose trace is the arithmetic of arith.py step by step
(the 16-bit build's trace is compared with the host's in
tests/runtime/test_avr_trace.py)."""
import json
import random
import subprocess
from pathlib import Path

from conftest import require_tool
from epuckc.stdlib import arith
from tests.runtime.test_language import HOST, INCLUDES, STRICT, UBSAN, _write
from tests.support.programs import epuckc

SHIFT_HARNESS = r"""
#include <stdio.h>
#include "epuckrt.h"
int main(void)
{
    int a, n;
    while (scanf("%d %d", &a, &n) == 2)
        printf("%d %d %d %d %d %d\n", rt_shl(a, n), rt_shr(a, n), a & n, a | n, a ^ n, ~a);
    return 0;
}
"""

INT16_CORNERS = [-32768, -32767, -16385, -16384, -256, -255, -5, -2, -1, 0, 1, 2, 3, 5, 255,
                 256, 16383, 16384, 32766, 32767]
COUNTS = [-32768, -100, -17, -16, -15, -8, -1, 0, 1, 2, 7, 8, 14, 15, 16, 17, 100, 32767]


def test_runtime_shifts_and_bits_are_the_checkers(tmp_path):
    """rt_shl and rt_shr (and C's `&`, `|`, `^`, `~` on ints) give what the
    checker folds with, for every 16-bit value and any count: negative
    ones, 16 and more, the smallest int, with UBSan watching the C."""
    cc = require_tool("cc")
    src = _write(tmp_path, "shift.c", SHIFT_HARNESS)
    exe = tmp_path / "shift"
    subprocess.run([cc, *STRICT, *UBSAN, *INCLUDES, str(src), *map(str, HOST), "-o", str(exe)],
                   check=True)
    rng = random.Random(46)
    cases = [(a, n) for a in INT16_CORNERS for n in COUNTS + INT16_CORNERS]
    cases += [(rng.randint(-32768, 32767), rng.randint(-20, 20)) for _ in range(2000)]
    cases += [(rng.randint(-32768, 32767), rng.randint(-32768, 32767)) for _ in range(2000)]
    result = subprocess.run([str(exe)], input="".join(f"{a} {n}\n" for a, n in cases),
                            capture_output=True, text=True, check=True)
    assert "runtime error" not in result.stderr
    lines = result.stdout.splitlines()
    assert len(lines) == len(cases)
    for (a, n), line in zip(cases, lines):
        expected = [arith.shl(a, n), arith.shr(a, n), arith.bit_and(a, n), arith.bit_or(a, n),
                    arith.bit_xor(a, n), arith.bit_not(a)]
        assert list(map(int, line.split())) == expected, (a, n)
        assert all(arith.fits16(v, v) for v in expected)


def test_shifts_are_defined_as_documented():
    """What docs/language.md says of the corners, from arith.py itself."""
    assert arith.shl(1, 15) == -32768 and arith.shl(0x4000, 2) == 0
    assert arith.shl(-1, 15) == -32768 and arith.shl(5, 16) == 0 and arith.shl(5, 400) == 0
    assert arith.shr(-5, 1) == -3 and arith.shr(-1, 40) == -1 and arith.shr(32767, 16) == 0
    assert arith.shl(12, -2) == 3 and arith.shr(3, -2) == 12
    assert arith.shr(7, -32768) == 0 and arith.shl(-7, -32768) == -1


def _interval(rng, ends):
    a, b = rng.choice(ends + [rng.randint(-300, 300)]), rng.choice(ends + [rng.randint(-300, 300)])
    return tuple(sorted((a, b)))


def test_bitwise_intervals_hold_every_value():
    """arith.bits_interval contains every result over operands drawn from
    the operands' intervals, their ends included (the checker's intervals
    for `&`, `|`, `^`, `~`, `<<`, `>>`)."""
    rng = random.Random(7)
    ends = [-32768, -32767, -4096, -257, -256, -2, -1, 0, 1, 2, 255, 256, 4095, 32766, 32767]
    counts = [-40, -17, -16, -15, -3, -1, 0, 1, 3, 8, 15, 16, 17, 40]
    for op in ("&", "|", "^", "~", "<<", ">>"):
        for _ in range(1500):
            a = _interval(rng, ends)
            b = tuple(sorted((rng.choice(counts), rng.choice(counts)))) \
                if op in ("<<", ">>") and rng.random() < 0.8 else _interval(rng, ends)
            lo, hi = arith.bits_interval(op, a, b)
            assert arith.fits16(lo, hi)
            for _ in range(25):
                x = rng.choice([a[0], a[1], rng.randint(*a)])
                y = rng.choice([b[0], b[1], rng.randint(*b)])
                v = arith.bit_not(x) if op == "~" else arith.BITS[op](x, y)
                assert lo <= v <= hi, (op, a, b, x, y, v)


def test_tight_intervals_of_masks():
    """A mask bounds its result (what an index or a W020 needs)."""
    assert arith.bits_interval("&", (-32768, 32767), (0, 7)) == (0, 7)
    assert arith.bits_interval("&", (0, 4095), (0xFF, 0xFF)) == (0, 255)
    assert arith.bits_interval(">>", (0, 4095), (4, 4)) == (0, 255)
    assert arith.bits_interval("<<", (0, 255), (2, 2)) == (0, 1020)
    assert arith.bits_interval("~", (0, 7)) == (-8, -1)


PROGRAM = """\
var n = 0
var mask = 0
var bits = 0b1010
var back = 0
var low = 0
every 10 ms do n = (n + 0x111) & 0x7FFF, mask = n ^ 0xFF00 | 0b1, bits = ~(bits << 1) >> 1,
    back = (n >> 3) & 0x0F, low = -n >> (n & 0b111)
after 300 ms do exit_main
"""


def _sets(records, var):
    return [r["value"] for r in records if r["kind"] == "set" and r["var"] == var]


def test_a_program_computes_as_arith_does(tmp_path):
    """The program's variables, step by step, are the values of arith.py's
    operations (the hexadecimal numbers as their 16-bit patterns:
    0xFF00 is -256)."""
    require_tool("cc")
    prog = _write(tmp_path, "bits.epk", PROGRAM)
    trace = tmp_path / "bits.jsonl"
    result = epuckc("run", prog, "--trace", trace)
    assert result.returncode == 0, result.stdout + result.stderr
    records = [json.loads(line) for line in trace.read_text().splitlines()]
    n, bits, want = 0, 0b1010, {"n": [], "mask": [], "bits": [], "back": [], "low": []}
    for _ in range(len(_sets(records, "n")) + 1):
        n = arith.bit_and(n + 0x111, 0x7FFF)
        bits = arith.shr(arith.bit_not(arith.shl(bits, 1)), 1)
        values = {"n": n, "mask": arith.bit_or(arith.bit_xor(n, -256), 1), "bits": bits,
                  "back": arith.bit_and(arith.shr(n, 3), 15),
                  "low": arith.shr(-n, arith.bit_and(n, 7))}
        for name, v in values.items():
            want[name].append(v)
    assert len(_sets(records, "n")) >= 25
    for name in want:
        got = _sets(records, name)
        # (a variable is traced when its value changes)
        expected = [v for k, v in enumerate(want[name]) if v != ([0, 0, 0b1010, 0, 0][
            list(want).index(name)] if k == 0 else want[name][k - 1])]
        assert got == expected[:len(got)] and len(got) >= len(expected) - 2, name


# values whose interval the checker knows to be small and >= 0 (the shape
# C's own `<<` and `>>` are printed for), shifted by counts around 16
SHIFTED = ["argmin(ir[0:1])", "v & 0", "ir0 & 3", "v & 0x7F", "7"]
SHIFT_COUNTS = ["14", "15", "16", "17", "31", "(v & 0) + 16", "ir0 & 31"]


def test_shifts_by_16_or_more_build_where_int_is_16_bits(tmp_path):
    """A count of 16 or more is undefined in C's shifts of a 16-bit int,
    whatever the value (`0 << 16` too): such a shift is the runtime's
    rt_shl or rt_shr, and every accepted program builds with avr-gcc
    (-Werror) and gcc (found by issue 42's campaign: `argmin(...) << 16`)."""
    from tests.support.hostile import Outcome, Program, check_one
    cc, avr = require_tool("cc"), require_tool("avr-gcc")
    built = 0
    for i, value in enumerate(SHIFTED):
        for j, count in enumerate(SHIFT_COUNTS):
            text = (f"var v = 1\nvar w = 0\nevery 10 ms do w = ({value}) << ({count}), "
                    f"w = ({value}) >> ({count}), w = (({value}) << ({count})) >> 1\n")
            outcome = check_one(Program(f"s{i}_{j}", text), tmp_path / f"s{i}_{j}", cc, avr, [],
                                run=False)
            built += outcome == Outcome.COMPILED
    assert built == len(SHIFTED) * len(SHIFT_COUNTS)


def test_a_long_sum_whose_value_is_an_ints_builds_where_int_is_16_bits(tmp_path):
    """A value computed in long that the checker knows fits an int is
    converted with a cast where an int is wanted: gcc's -Woverflow (and
    avr-gcc's) took `v1 + (-200L + -v1)`, which it folds to the constant
    -200, for an overflow in the implicit conversion. The program is the
    campaign's input that found it (issue 42, seed 42172, input 923)."""
    from tests.support.hostile import Outcome, Program, check_one
    cc, avr = require_tool("cc"), require_tool("avr-gcc")
    text = (Path(__file__).parent / "programs" / "folded_long_sum.epk").read_text()
    assert "v1 += K0 + -v1" in text
    outcome = check_one(Program("folded", text), tmp_path / "folded", cc, avr, [], run=False)
    assert outcome == Outcome.COMPILED
