"""`epuckc build --target dspic`: the MPLAB/XC16 project for the e-puck's
dsPIC30F6014A, and `make` when XC16 and the e-puck library are there."""
from __future__ import annotations

import os
import re
import shutil
import stat
import subprocess
from pathlib import Path
from typing import Optional

from ..base.output import prepare_directory, write_atomic
from ..base.resources import RUNTIME_TRACE, RUNTIME_TRACE_UART1, runtime_dir
from .common import (DSPIC_RUNTIME, DSPIC_USER, EXIT_NO_TOOLCHAIN, EXIT_USAGE, ROBOT_COPIES,
                     ROBOT_HEADERS, ROBOT_SOURCES, BuildError, Program, _capacity_defines,
                     _write_generated, check_outputs, user_headers)
from .trace_table import TraceOptions, table_path, trace_defines, write_table


def find_xc16() -> Optional[Path]:
    xc16_dir = os.environ.get("XC16_DIR")
    if xc16_dir:
        candidate = Path(xc16_dir) / "bin" / "xc16-gcc"
        if candidate.is_file() and os.access(candidate, os.X_OK):
            return candidate
    found = shutil.which("xc16-gcc")
    return Path(found) if found else None


def dspic_user_copies(program: Program) -> list:
    """(the user's file, its copy's path inside the project): numbered in
    the `user/` folder, so no two copies and nothing else share a name."""
    copies = []
    for i, source in enumerate(program.user_sources(), 1):
        stem = re.sub(r"[^A-Za-z0-9_-]", "_", Path(source).stem) or "file"
        copies.append((Path(source), f"{DSPIC_USER}/{i}_{stem}.c"))
    return copies


def dspic_user_headers(program: Program) -> list:
    """(a header, its copy's path inside the project) for each of
    user_headers: the C is copied into user/, so its headers go there at
    the same place relative to it. One that climbs out of the C's folder,
    or two different headers that would land on the same copy, cannot be
    laid out so: BuildError."""
    copies: dict = {}               # path in the project -> (header, its bytes)
    for source, header, rel in user_headers(program):
        if rel.startswith("../") or rel == ".." or os.path.isabs(rel):
            raise BuildError(
                f"{source} includes {header}, a header outside its folder; the dspic project "
                f"copies your C into {DSPIC_USER}/ with the headers beside it or below it "
                f"only: move {header.name} next to {source.name}", status=EXIT_USAGE)
        target = f"{DSPIC_USER}/{rel}"
        content = header.read_bytes()
        if target in copies and copies[target][1] != content:
            raise BuildError(
                f"two different headers would both be {target} in the dspic project: "
                f"{copies[target][0]} and {header}; give them different names",
                status=EXIT_USAGE)
        copies[target] = (header, content)
    return [(header, target) for target, (header, _) in sorted(copies.items())]


def write_dspic_project(program: Program, out_dir: Path, template_render,
                        trace: Optional[TraceOptions] = None) -> None:
    """A self-contained project inside out_dir: the program (and its
    externs header) at the top, the runtime files the robot needs in
    runtime/, copies of the user's C in user/, and a Makefile for XC16.
    With `trace`, the robot's tracer on the Bluetooth UART1 too, and the
    trace table beside the program (NAME.trace.json). Files whose contents
    did not change are not rewritten, so `make` rebuilds only what
    changed."""
    rt = runtime_dir()
    copies = dspic_user_copies(program)
    headers = dspic_user_headers(program)
    generated = [f"{program.name}.c"] if program.generated else []
    if program.generated and program.header_name:
        generated.append(program.header_name)
    sources = ROBOT_SOURCES + (list(RUNTIME_TRACE + RUNTIME_TRACE_UART1) if trace else [])
    files = sources + ROBOT_HEADERS
    runtime_files = [f"{DSPIC_RUNTIME}/{rel}" for rel in files]
    targets = (generated + runtime_files + [copy for _, copy in copies + headers]
               + ["Makefile"] + ([table_path(Path(), program.name).name] if trace else []))
    check_outputs([out_dir / t for t in targets],
                  program.inputs + [header for header, _ in headers], inside=out_dir)
    out_dir = prepare_directory(out_dir)
    if program.generated:
        _write_generated(program, out_dir, only_if_changed=True)
    for rel in files:
        write_atomic(out_dir / DSPIC_RUNTIME / rel, (rt / ROBOT_COPIES.get(rel, rel)).read_bytes(),
                     only_if_changed=True)
    for source, copy in copies + headers:
        (out_dir / copy).parent.mkdir(parents=True, exist_ok=True)
        write_atomic(out_dir / copy, source.read_bytes(),
                     mode=stat.S_IMODE(source.stat().st_mode), only_if_changed=True)
    # the name labels are not stored on the robot (the trace's are in its table)
    defines = [d[2:] for d in _capacity_defines(program)] + ["EPUCKRT_NO_NAMES"]
    if trace:
        defines += trace_defines(program, "dspic", trace)
        write_table(program, out_dir)
    write_atomic(out_dir / "Makefile", template_render(
        "dspic.mk.j2", name=program.name, generated=program.generated,
        header=program.header_name if program.generated else None,
        runtime=DSPIC_RUNTIME, runtime_sources=[f"{DSPIC_RUNTIME}/{r}" for r in sources],
        runtime_headers=[f"{DSPIC_RUNTIME}/{r}" for r in ROBOT_HEADERS],
        user_sources=[copy for _, copy in copies], user_headers=[copy for _, copy in headers],
        defines=defines, trace=bool(trace)), only_if_changed=True)


def run_make(out_dir: Path, xc16: Path) -> None:
    env = dict(os.environ)
    env["PATH"] = f"{xc16.parent}{os.pathsep}{env.get('PATH', '')}"
    make = shutil.which("make")
    if make is None:
        raise BuildError(f"`make` was not found; the project is in {out_dir}",
                         status=EXIT_NO_TOOLCHAIN)
    # the folder of the xc16-gcc found (XC16_DIR, or PATH's), as the Makefile reads it
    install = xc16.parent.parent if xc16.parent.name == "bin" else None
    result = subprocess.run([make, "-C", str(out_dir), f"XC16_DIR={install or ''}"],
                            capture_output=True, text=True, env=env)
    if result.returncode != 0:
        raise BuildError(f"make failed in {out_dir}:\n{(result.stdout + result.stderr).rstrip()}")
