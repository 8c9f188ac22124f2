"""Constant folding computes exactly what the running program computes.

The checker folds operations on constants with stdlib/arith.py; the runtime
computes the same operations on variables with rt_lang.c. For random
expressions over the whole 16-bit range (-32768, -1, 32767 and division by
-1 included), one program assigns each expression twice: once written
with numbers (folded by the checker: the C holds its value) and once with
variables that get those numbers while the program runs (computed by the
runtime). Both values, read from the trace, must be equal, and equal to
the Python model of the arithmetic."""
from __future__ import annotations

import random
import re

import pytest

from conftest import require_tool
from epuckc.stdlib import arith
from tests.support.programs import epuckc, run_program

EDGES = [-32768, -32767, -2, -1, 0, 1, 2, 181, 255, 32766, 32767]
BINARY = ["+", "-", "*", "/", "%", "min", "max"]


def _leaf(rng):
    return rng.choice(EDGES) if rng.random() < 0.6 else rng.randint(-32768, 32767)


def _tree(rng, depth):
    """(text with numbers, text with variables, value, leaves): leaves are
    the numbers in order; the variables' text names them c0, c1, ..."""
    leaves = []

    def build(d):
        if d == 0 or rng.random() < 0.25:
            v = _leaf(rng)
            leaves.append(v)
            name = f"L{len(leaves) - 1}"
            if rng.random() < 0.3:          # a constant: `K3`, and `-K3` below
                return name.replace("L", "K"), name, v
            return f"({v})" if v < 0 else str(v), name, v
        kind = rng.random()
        if kind < 0.15:
            t, n, v = build(d - 1)
            if rng.random() < 0.5:
                minus = f"-{t}" if t.startswith("K") else f"-({t})"     # `-K`: a negated constant
                return minus, f"-({n})", arith.neg(v)
            return f"abs({t})", f"abs({n})", arith.absolute(v)
        if kind < 0.22:
            parts = [build(d - 1) for _ in range(3)]
            return (f"clamp({', '.join(p[0] for p in parts)})",
                    f"clamp({', '.join(p[1] for p in parts)})",
                    arith.clamp(*(p[2] for p in parts)))
        op = rng.choice(BINARY)
        a = build(d - 1)
        if op in ("/", "%") and rng.random() < 0.3:
            leaves.append(-1)
            b = ("(-1)", f"L{len(leaves) - 1}", -1)
        else:
            b = build(d - 1)
        if op in ("/", "%") and b[2] == 0:
            op = "+"        # a divisor that is always 0 is an error (E049), not a fold
        value = arith.BINARY[op](a[2], b[2])
        if op in ("min", "max"):
            return f"{op}({a[0]}, {b[0]})", f"{op}({a[1]}, {b[1]})", value
        return f"({a[0]} {op} {b[0]})", f"({a[1]} {op} {b[1]})", value

    numbers, names, value = build(depth)
    return numbers, names, value, leaves


@pytest.mark.parametrize("seed", [1, 2, 3])
def test_folding_equals_running(tmp_path, seed):
    require_tool("cc")
    rng = random.Random(seed)
    lines, assigns, expected = [], [], {}
    n_leaf = 0
    for i in range(40):
        numbers, names, value, leaves = _tree(rng, rng.randint(1, 4))
        names = re.sub(r"L(\d+)", lambda m: f"c{n_leaf + int(m[1])}", names)
        numbers = re.sub(r"K(\d+)", lambda m: f"K{n_leaf + int(m[1])}", numbers)
        for k, v in enumerate(leaves):
            lines.append(f"const K{n_leaf + k} = {v}")
            lines.append(f"var c{n_leaf + k} = 0")
            assigns.append(f"c{n_leaf + k} = {v}")
        n_leaf += len(leaves)
        lines += [f"var f{i} = 0", f"var g{i} = 0"]
        assigns += [f"f{i} = {numbers}", f"g{i} = {names}"]
        expected[i] = arith.sat(value)      # stored: saturated to 16 bits
    program = "\n".join(lines) + "\non immediate do " + ",\n    ".join(assigns) + \
        "\nafter 10 ms do exit_main\n"
    path = tmp_path / "fold.epk"
    path.write_text(program, encoding="utf-8")
    records, _ = run_program(path, tmp_path, "--time-limit", "1s")
    final = {}
    for r in records:
        if r["kind"] == "set":
            final[r["var"]] = r["value"]
    for i, value in expected.items():
        folded, ran = final.get(f"f{i}", 0), final.get(f"g{i}", 0)
        assert folded == ran == value, (i, folded, ran, value,
                                        [a for a in assigns if a.startswith((f"f{i} ", f"g{i} "))])
    # the folded side really was folded: its C assigns numbers only
    c_file = tmp_path / "fold.c"
    epuckc("compile", path, "-o", c_file, check=True)
    folded = re.findall(r"rt_assign\(&epk_v_f\d+, \d+, ([^;]*)\);", c_file.read_text())
    assert len(folded) == len(expected)
    assert all(re.fullmatch(r"-?\d+|RT_INT_MIN", c) for c in folded), folded
