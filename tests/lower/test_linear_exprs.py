"""Lowering prints each part of an expression once (issue 42's campaign):
the C of a chain of any operator, or of any operator nested in itself,
costs work in proportion to its length, counted as the Python calls that
check and compile make (never timed). A shift whose value C's `<<` would
not give (a negative value, here) printed its operand twice, once for the
operator and once for the runtime's rt_shl, so that `-ir3 << 1 << 1 ...`
of 42 shifts did not compile in 8 minutes."""
from __future__ import annotations

import sys
from pathlib import Path

import pytest

from epuckc.check.frontend import check_file
from epuckc.diagnostics import Report
from epuckc.emit.program import emit_program

# (a chain from the left, an operator nested to the right, a prefix)
SHAPES = {f"chain {op}": (lambda n, op=op: "-ir3" + f" {op} 1" * n)
          for op in ("<<", ">>", "&", "|", "^", "+", "-", "*", "/", "%")}
SHAPES.update({f"nested {op}": (lambda n, op=op: f"-ir3 {op} (" * n + "v" + ")" * n)
               for op in ("<<", ">>", "&", "|", "^", "-")})
SHAPES.update({"~": lambda n: "~" * n + "(-ir3)", "minus": lambda n: "-(" * n + "v" + ")" * n,
               "abs": lambda n: "abs(" * n + "v" + ")" * n,
               "min": lambda n: "min(" * n + "v" + ", -ir3)" * n,
               # (each index bounded: one left to wander warns W022 with its text,
               # of its whole length)
               "indexes": lambda n: "a[" * n + "v % 3" + "] % 3" * n})
# The checker looks for operations that saturate in each index and then in
# the whole expression, so nested indexes cost the square of their depth:
# bounded by the depth limit (E056: at most about 195), 20,000 steps.
QUADRATIC = {"indexes"}


class _Over(Exception):
    pass


def calls_made(f, *args, most: int) -> int:
    """How many Python functions `f(*args)` calls, or most + 1 where it
    calls more (stopped there: an exponential pass fails, not hangs)."""
    count = 0

    def profile(frame, event, arg):
        nonlocal count
        if event == "call":
            count += 1
            if count > most:
                raise _Over
    sys.setprofile(profile)
    try:
        f(*args)
    except _Over:
        pass
    finally:
        sys.setprofile(None)
    return count


def _compile(text: str):
    report = Report()
    result = check_file(Path("l.epk"), report, shown_name="l.epk", text=text)
    assert [d.message for d in report.diagnostics if d.severity == "error"] == []
    emit_program(result.checked, text, "l")


def program(expression: str) -> str:
    return f"var v = 3\nvar a = [0, 1, 2]\nevery 10 ms do v = {expression}\n"


@pytest.mark.parametrize("shape", sorted(SHAPES))
def test_the_c_of_an_expression_is_linear_in_its_length(shape):
    make = SHAPES[shape]
    _compile(program(make(2)))      # (what is done once, tables and templates, done)
    small = calls_made(_compile, program(make(12)), most=10 ** 7)
    growth = 16 if shape in QUADRATIC else 4
    large = calls_made(_compile, program(make(48)), most=growth * 1.5 * small)
    assert large < growth * 1.5 * small, (shape, small, large)
