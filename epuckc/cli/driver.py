"""From a file on the command line to a built or running program."""
from __future__ import annotations

import os
import re
import sys
from pathlib import Path
from typing import Optional

from ..base.output import write_atomic

from ..build.common import EXIT_NO_TOOLCHAIN, BuildError, Program, check_outputs

from ..build.dspic import find_xc16, run_make, write_dspic_project

from ..build.host import build_host, host_executable
from ..diagnostics import Report
from ..check.frontend import InputError, check_file, read_error
from ..sim.harness import run_executable
from ..base.output import is_stdout


def _read_text(path: Path, shown: str) -> str:
    """A file's text, or InputError that says why it cannot be read."""
    try:
        return path.read_text(encoding="utf-8")
    except OSError as exc:
        raise read_error(shown, exc) from None
    except UnicodeDecodeError:
        raise InputError(f"cannot read {shown}: it is not UTF-8 text") from None


def _without_stood_in(files: list) -> list:
    """The C files; each dsPIC assembly file among them is one the simulated
    library stands in for (build/dspic_asm.py), with a one-line note, or
    InputError."""
    from ..build.dspic_asm import AsmError, stood_in
    kept = []
    for path in files:
        if path.suffix != ".s":
            kept.append(path)
            continue
        try:
            names = stood_in(path)
        except (AsmError, OSError) as exc:
            raise InputError(str(exc)) from None
        print(f"epuckc: note: {path.name} ({', '.join(names)}) is dsPIC assembly: the "
              f"simulated e-puck's own data EEPROM stands in for it", file=sys.stderr)
    return kept


def _program_name(path: Path) -> str:
    return re.sub(r"[^A-Za-z0-9_-]", "_", path.stem) or "program"


def load_program(path: Path, report: Report, max_actions: Optional[int] = None,
                 max_events: Optional[int] = None,
                 shown_name: Optional[str] = None,
                 defines: Optional[dict] = None, target: str = "host",
                 more_c=(), world: bool = True) -> Optional[Program]:
    """A rule file is checked and compiled; a .c file is taken as it is,
    with `more_c`, the program's other C files (a C main and the demo it
    calls). `defines` (NAME -> VALUE text, `-D`) override constants before
    checking (check/defines.py; DefineError for an unknown name). `target`:
    the robot it is built for, whose devices the checker knows (E070);
    `world` False: it runs without a world (W070)."""
    name = _program_name(path)
    shown = shown_name if shown_name is not None else str(path)
    more_c = [Path(m) for m in more_c]
    for extra in more_c:
        if extra.suffix not in (".c", ".s"):
            raise InputError(f"{extra}: after the program's FILE only C files (.c) may follow, "
                             f"the rest of a C program (or the dsPIC assembly of its data "
                             f"EEPROM, DataEEPROM.s)")
        if not extra.is_file():
            raise InputError(f"cannot read {extra}: the file does not exist")
    more_c = _without_stood_in(more_c)
    if more_c and path.suffix != ".c":
        raise InputError(f"{shown} is a rule file: it names its C files itself (`extern action "
                         f"... from \"{more_c[0].name}\"`); more C files follow only a C "
                         f"program's main.c")
    if path.suffix == ".c":
        if defines:
            from ..check.defines import DefineError
            raise DefineError(f"-D {next(iter(defines))}: {shown} is C, which has no "
                              f"constants of the language to override")
        # the compiler reads C as bytes (a Latin-1 comment is no error):
        # only that it can be read is checked here
        try:
            path.read_bytes()
        except OSError as exc:
            raise read_error(shown, exc) from None
        return Program(name, "", path.parent, more_c, max_actions, max_events,
                       generated=False, source_path=path, inputs=[path] + more_c)
    text = None
    if defines:
        from ..check.defines import apply_defines
        text = apply_defines(_read_text(path, shown), defines, shown)
    result = check_file(path, report, shown_name=shown, text=text, target=target, world=world)
    if result.checked is None:
        return None
    from ..emit.program import emit_program
    generated = emit_program(result.checked, result.source.text, name)
    # the user's C files in the order they are declared, each once (two
    # spellings of one file would define its functions twice)
    user_files, seen = [], set()
    for info in result.checked.externs.values():
        file = path.parent / info.file
        if os.path.realpath(file) not in seen:
            seen.add(os.path.realpath(file))
            user_files.append(file)
    return Program(name, generated.c_text, path.parent, user_files, max_actions, max_events,
                   header_name=generated.header_name, header_text=generated.header_text,
                   inputs=[path] + user_files,
                   variables=[slot for v in result.checked.variables.values()
                              for slot in v.traced()],
                   devices=result.checked.devices, trace_names=generated.names)


def write_compiled(program: Program, out):
    """`epuckc compile`: the C file, and beside it the externs header when
    the program has externs. Neither may be one of the inputs. With `-o -`
    the C goes to standard output and the header is not written (a note
    says how to get it)."""
    if is_stdout(out):
        write_atomic(out, program.c_text)
        if program.header_name:
            print(f"epuckc: note: the program includes {program.header_name}, which is not "
                  f"written with -o -; `epuckc compile FILE -o OUT.c` writes it beside OUT.c",
                  file=sys.stderr)
        return
    out = Path(out)
    outputs = [out] + ([out.parent / program.header_name] if program.header_name else [])
    check_outputs(outputs, program.inputs)
    write_atomic(out, program.c_text)
    if program.header_name:
        write_atomic(out.parent / program.header_name, program.header_text)


def build_folder(program: Program, target: str, out_dir: Optional[Path]) -> Path:
    """The folder a build writes: -o, else build/NAME-TARGET."""
    return out_dir or Path("build") / f"{program.name}-{target}"


def build_output(program: Program, target: str, out_dir: Optional[Path]) -> Path:
    """What a robot's build leaves to flash: NAME.hex in the dspic project,
    build/NAME.elf in the epuck2's."""
    folder = build_folder(program, target, out_dir)
    if target == "epuck2":
        return folder / "build" / f"{program.name}.elf"
    return folder / f"{program.name}.hex"


def build(program: Program, target: str, out_dir: Optional[Path],
          firmware: Optional[str] = None, trace=None) -> str:
    """Build for a target; returns what to tell the user. `trace`
    (build.trace_table.TraceOptions, `--trace`): the robot's tracer on."""
    from ..build.trace_table import check_trace_target
    check_trace_target(target, trace)
    out_dir = build_folder(program, target, out_dir)
    if target == "host":
        exe = build_host(program, out_dir)
        return f"built {exe}"
    from ..emit.program import render_template
    if target == "epuck2":
        from ..build.epuck2 import build_epuck2
        return build_epuck2(program, out_dir, render_template, firmware, trace)
    write_dspic_project(program, out_dir, render_template, trace)
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
    return f"built {build_output(program, target, out_dir)}"


def run_host(program: Program, scenario: Optional[str], time_limit_ms: int,
             trace: Optional[str], pose_ms: Optional[int] = None, on_built=None) -> int:
    """Build for the host (cached) and run; `on_built(exe)` is told where
    the executable is before it runs."""
    if trace and trace != "-":
        check_outputs([Path(trace)], program.inputs + ([Path(scenario)] if scenario else []))
    with host_executable(program) as exe:
        if on_built is not None:
            on_built(exe)
        try:
            return run_executable(exe, scenario, time_limit_ms, trace, pose_ms)
        except OSError as exc:
            raise BuildError(f"cannot run {exe}: {exc.strerror or exc}") from None
