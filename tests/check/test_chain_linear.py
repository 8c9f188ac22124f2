"""No pass grows with the square of an `else if` chain (issue 42): the
work of `check`, `compile`, the language server's analysis and an edit of
it, and the formatter, counted as the Python calls they make (never
timed), grows in proportion to the chain. The conditions before a branch
are shared by the branches after it (check/dependencies.py's Held links,
check/conditions.py's boxes built one condition at a time), where each
branch's held a copy of all of them: 400 branches took 16 times the work
of 100. bench/chain_bench.py measures 100 to 10,000 branches side by side."""
from __future__ import annotations

import sys
from pathlib import Path

from epuckc.check.frontend import check_file
from epuckc.diagnostics import Report
from epuckc.emit.program import emit_program
from epuckc.ide.fmt import format_text
from epuckc.ide.incremental import Analyzer


def chain(n: int, edit: int = 0) -> str:
    """A rule of one `if` and n - 1 `else if`s over a variable it assigns and
    a reading (each negated condition two boxes), and an `else`."""
    lines = ["var v = 0", "var w = 0", "every 10 ms do if ir0 > 4000 { v = 0 }"]
    lines += [f"    else if v > {k} and ir1 < {k + edit} {{ v = v + {k % 7}, w = {k % 50} }}"
              for k in range(1, n)]
    lines += ["    else { v = 7 }", "every 20 ms if w != 3 do v = 1"]
    return "\n".join(lines) + "\n"


def calls_made(f, *args) -> int:
    """How many Python functions `f(*args)` calls."""
    count = 0

    def profile(frame, event, arg):
        nonlocal count
        if event == "call":
            count += 1
    sys.setprofile(profile)
    try:
        f(*args)
    finally:
        sys.setprofile(None)
    return count


def _compile(text: str):
    report = Report()
    result = check_file(Path("c.epk"), report, shown_name="c.epk", text=text)
    assert [d for d in report.diagnostics if d.severity == "error"] == []
    emit_program(result.checked, text, "c")


def _edited(n: int):
    analyzer = Analyzer("c.epk")
    analyzer.analyse(chain(n))
    return lambda: analyzer.analyse(chain(n, 1))


def test_check_compile_edit_and_format_are_linear_in_the_chain():
    _compile(chain(20))         # (what is done once, tables and templates, done)
    for name, work in (("check and compile", lambda n: calls_made(_compile, chain(n))),
                       ("the language server", lambda n: calls_made(Analyzer("c.epk").analyse,
                                                                     chain(n))),
                       ("an edit", lambda n: calls_made(_edited(n))),
                       ("the formatter", lambda n: calls_made(format_text, chain(n)))):
        small, large = work(100), work(400)
        assert large < 4 * 1.25 * small, (name, small, large)
