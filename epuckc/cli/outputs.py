"""What `epuckc run` writes, kept in proportion: the variables the trace
follows (`--trace-vars`, sim/tracevars.py) and one warning, with the way
to narrow it, when the run's outputs (the JSON trace, the SVG, the replay
page) pass LARGE_BYTES (sim/outsize.py says what fills them)."""
from __future__ import annotations

import os
import sys
from pathlib import Path
from typing import Optional

EXIT_USAGE = 2


def names_of(variables) -> set:
    """The names in lists of a program's variables, (name, initial value)
    each (an array's elements as `a[2]`)."""
    return {v[0] for values in variables for v in (values or ())}


def selection(args) -> Optional[tuple]:
    """--trace-vars as names (None: every variable); raises TraceVarsError."""
    text = getattr(args, "trace_vars", None)
    if text is None:
        return None
    from ..sim.tracevars import parse
    return parse(text)


def set_trace_vars(args, variables) -> Optional[int]:
    """Hands --trace-vars to the harness (EPUCK_TRACE_VARS) once the
    programs that run are known (`variables`: each one's, as Program has
    them); an exit status after saying why it cannot, else None."""
    from ..sim.tracevars import ENV, TraceVarsError, setting
    try:
        chosen = selection(args)
        if chosen is None:
            os.environ.pop(ENV, None)
            return None
        os.environ[ENV] = setting(chosen, names_of(variables))
    except TraceVarsError as exc:
        print(f"epuckc: error: {exc}", file=sys.stderr)
        return EXIT_USAGE
    return None


def traced_variables(variables: dict, args) -> dict:
    """The replay's declared variables (robot -> (name, initial value)),
    those --trace-vars leaves out taken away."""
    from ..sim.tracevars import traced
    chosen = selection(args)
    return {robot: [v for v in values if traced(v[0], chosen)]
            for robot, values in variables.items()}


def warn_if_large(trace, outputs) -> None:
    """One warning for the run's outputs over LARGE_BYTES (a trace on
    standard output is not measured), saying what fills the trace and how
    to narrow it."""
    from ..sim.outsize import large_outputs_warning
    files = [Path(p) for p in outputs if p and str(p) != "-"]
    text = large_outputs_warning([p for p in dict.fromkeys(files) if p.is_file()],
                                 Path(trace) if trace and str(trace) != "-" else None)
    if text:
        print(f"epuckc: warning: {text}", file=sys.stderr)
