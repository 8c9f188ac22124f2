"""From a file on the command line to a built or running program."""
from __future__ import annotations

import os
import re
from pathlib import Path
from typing import Optional

from .build import (EXIT_NO_TOOLCHAIN, BuildError, Program, build_host, find_xc16,
                    host_executable, run_make, write_dspic_project)
from .diagnostics import Report
from .frontend import InputError, check_file, read_error
from .harness import run_executable


def _program_name(path: Path) -> str:
    return re.sub(r"[^A-Za-z0-9_-]", "_", path.stem) or "program"


def load_program(path: Path, report: Report, max_actions: Optional[int] = None,
                 max_events: Optional[int] = None,
                 shown_name: Optional[str] = None) -> Optional[Program]:
    """A rule file is checked and compiled; a .c file is taken as it is."""
    name = _program_name(path)
    shown = shown_name if shown_name is not None else str(path)
    if path.suffix == ".c":
        try:
            text = path.read_text(encoding="utf-8")
        except OSError as exc:
            raise read_error(shown, exc) from None
        except UnicodeDecodeError:
            raise InputError(f"cannot read {shown}: it is not UTF-8 text") from None
        return Program(name, text, path.resolve().parent, [], max_actions, max_events,
                       generated=False)
    result = check_file(path, report, shown_name=shown,
                        max_actions=max_actions, max_events=max_events)
    if result.checked is None:
        return None
    from .emit import emit_c
    c_text = emit_c(result.checked, result.source.text)
    user_files = sorted({e.file for e in result.checked.externs.values()})
    return Program(name, c_text, path.resolve().parent, user_files, max_actions, max_events)


def build(program: Program, target: str, out_dir: Optional[Path]) -> str:
    """Build for a target; returns what to tell the user."""
    out_dir = out_dir or Path("build") / f"{program.name}-{target}"
    if target == "host":
        exe = build_host(program, out_dir)
        return f"built {exe}"
    from .emit import render_template
    write_dspic_project(program, out_dir, render_template)
    xc16 = find_xc16()
    if xc16 is None:
        raise BuildError(
            f"the project was written to {out_dir}, but it was not built: xc16-gcc "
            "(Microchip MPLAB XC16) was found neither on PATH nor in $XC16_DIR/bin.\n"
            f"Install XC16, then run: make -C {out_dir} EPUCK_LIB=/path/to/e-puck-library",
            status=EXIT_NO_TOOLCHAIN)
    if not os.environ.get("EPUCK_LIB"):
        raise BuildError(
            f"the project was written to {out_dir}, but it was not built: EPUCK_LIB is not set.\n"
            "Set it to the e-puck library's folder (the one that holds library/), then run: "
            f"make -C {out_dir}", status=EXIT_NO_TOOLCHAIN)
    run_make(out_dir, xc16)
    return f"built {out_dir / (program.name + '.hex')}"


def run_host(program: Program, scenario: Optional[str], time_limit_ms: int,
             trace: Optional[str], pose_ms: Optional[int] = None, on_built=None) -> int:
    """Build for the host (cached) and run; `on_built(exe)` is told where
    the executable is before it runs."""
    with host_executable(program) as exe:
        if on_built is not None:
            on_built(exe)
        try:
            return run_executable(exe, scenario, time_limit_ms, trace, pose_ms)
        except OSError as exc:
            raise BuildError(f"cannot run {exe}: {exc.strerror or exc}") from None
