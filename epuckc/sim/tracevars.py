"""`epuckc run --trace-vars NAMES`: the variables whose changes the trace
writes (`set` records and their readable lines), the others left out: a
counter set every 20 ms by ten robots was most of a run's 79 MB. NAMES are
separated by commas; an array's name stands for its elements (`counts`
for `counts[2]`); `none` leaves every variable out. The harness reads the
selection from EPUCK_TRACE_VARS with the same rule (var_traced in
runtime_c/platform/platform_host.c); the replay's variables panel lists only
the variables traced."""
from __future__ import annotations

import re
from typing import Optional

ENV = "EPUCK_TRACE_VARS"
_NAME = re.compile(r"[A-Za-z_][A-Za-z0-9_]*\Z")


class TraceVarsError(Exception):
    """A bad --trace-vars; str() says what and how to fix it."""


def parse(text: str) -> tuple:
    """The names given (`none`: no name)."""
    names = tuple(n.strip() for n in text.split(",") if n.strip())
    for name in names:
        if not _NAME.match(name):
            raise TraceVarsError(f"--trace-vars {text}: `{name}` is not a variable's name "
                                 f"(names are separated by commas: --trace-vars speed,count)")
    return names


def traced(name: str, selection: Optional[tuple]) -> bool:
    """Whether variable `name` (`counts[2]` for an element) is traced;
    `selection` None: every variable."""
    if selection is None:
        return True
    return name in selection or name.split("[", 1)[0] in selection


def setting(selection: tuple, declared: set) -> str:
    """EPUCK_TRACE_VARS for `selection` against the variables the run's
    programs declare (their names, an array's elements as `a[2]`), or
    TraceVarsError naming one that none declares and the one meant."""
    bases = {n.split("[", 1)[0] for n in declared}
    if selection == ("none",) and "none" not in bases:
        return ""
    for name in selection:
        if name not in bases:
            import difflib
            close = difflib.get_close_matches(name, sorted(bases), n=1, cutoff=0.6)
            hint = f"did you mean `{close[0]}`?" if close else (
                "the variables are " + ", ".join(f"`{b}`" for b in sorted(bases))
                if bases else "the program declares no variable")
            raise TraceVarsError(f"--trace-vars: no program of the run declares a variable "
                                 f"`{name}`: {hint}")
    return ",".join(selection)
