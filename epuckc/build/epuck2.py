"""`epuckc build --target epuck2`: a project for the e-puck2 (STM32F407,
ChibiOS) on top of GCtronic's firmware e-puck2_main-processor, laid out as
its Project_template, and `make` when arm-none-eabi-gcc and the firmware
are there (docs/epuck2.md)."""
from __future__ import annotations

import os
import shutil
import stat
import subprocess
from pathlib import Path
from typing import Optional

from ..base.output import prepare_directory, write_atomic
from ..base.resources import (RUNTIME_CORE, RUNTIME_CORE_HEADERS, RUNTIME_DEVICES,
                              RUNTIME_TRACE, RUNTIME_TRACE_CHIBIOS, runtime_dir)
from .common import (DSPIC_RUNTIME, EXIT_NO_TOOLCHAIN, BuildError, Program, _capacity_defines,
                     _write_generated, check_outputs)
from .dspic import dspic_user_copies, dspic_user_headers
from .trace_table import TraceOptions, table_path, trace_defines, write_table

# The runtime's files in an e-puck2 project (relative to runtime_c/): the
# core, the robot's platform layer (its hooks and seed) with the ChibiOS
# wait for the clock, the system calls Debian's newlib wants.
EPUCK2_SOURCES = [*RUNTIME_CORE, *RUNTIME_DEVICES, "platform/platform_robot.c", "platform/platform_epuck2.c",
                  "epuck2/newlib_stubs.c"]
EPUCK2_FILES = EPUCK2_SOURCES + list(RUNTIME_CORE_HEADERS)
ARM_GCC = "arm-none-eabi-gcc"
# Where the e-puck2's library layer lacks what a runtime file calls, the
# firmware's headers are found through this folder of it.
EPUCK1X = "src/epuck1x"


def find_firmware(given: Optional[str]) -> Optional[Path]:
    """The firmware folder: --firmware, else $EPUCK2_FIRMWARE; None when
    neither names a folder that holds the firmware's Makefile and its
    epuck1x layer."""
    folder = given or os.environ.get("EPUCK2_FIRMWARE")
    if not folder:
        return None
    path = Path(folder).expanduser()
    return path.resolve() if (path / "Makefile").is_file() and (path / EPUCK1X).is_dir() \
        else None


def write_epuck2_project(program: Program, out_dir: Path, template_render,
                         firmware: Optional[Path], trace: Optional[TraceOptions] = None) -> None:
    """A self-contained project inside out_dir: the program and its
    externs header, program_main.c (the program with main renamed),
    main.c/main.h (the firmware's start), the runtime in runtime/, copies of
    the user's C in user/, and the Makefile; with `trace`, the robot's
    tracer on UART3 or the USB serial port, and the trace table beside the
    program (NAME.trace.json). Unchanged files are not rewritten, so `make`
    rebuilds only what changed."""
    rt = runtime_dir()
    copies = dspic_user_copies(program)
    headers = dspic_user_headers(program)
    generated = [f"{program.name}.c"] if program.generated else []
    if program.generated and program.header_name:
        generated.append(program.header_name)
    sources = EPUCK2_SOURCES + (list(RUNTIME_TRACE + RUNTIME_TRACE_CHIBIOS) if trace else [])
    files = sources + list(RUNTIME_CORE_HEADERS)
    runtime_files = [f"{DSPIC_RUNTIME}/{Path(rel).name}" for rel in files]
    own = ["main.c", "main.h", "program_main.c", "Makefile"]
    if trace:
        own.append(table_path(Path(), program.name).name)
    targets = generated + runtime_files + [copy for _, copy in copies + headers] + own
    check_outputs([out_dir / t for t in targets],
                  program.inputs + [header for header, _ in headers], inside=out_dir)
    out_dir = prepare_directory(out_dir)
    if program.generated:
        _write_generated(program, out_dir, only_if_changed=True)
    for rel in files:
        write_atomic(out_dir / DSPIC_RUNTIME / Path(rel).name, (rt / rel).read_bytes(),
                     only_if_changed=True)
    for source, copy in copies + headers:
        (out_dir / copy).parent.mkdir(parents=True, exist_ok=True)
        write_atomic(out_dir / copy, source.read_bytes(),
                     mode=stat.S_IMODE(source.stat().st_mode), only_if_changed=True)
    defines = [d[2:] for d in _capacity_defines(program)] + ["EPUCKRT_EPUCK2",
                                                              "EPUCKRT_NO_NAMES"]
    if trace:
        defines += trace_defines(program, "epuck2", trace)
        write_table(program, out_dir)
    context = dict(name=program.name, runtime=DSPIC_RUNTIME,
                   camera=program.devices is None or "camera" in program.devices)
    write_atomic(out_dir / "main.c", template_render("epuck2_main.c.j2", **context),
                 only_if_changed=True)
    write_atomic(out_dir / "main.h", template_render("epuck2_main.h.j2", **context),
                 only_if_changed=True)
    write_atomic(out_dir / "program_main.c", template_render("epuck2_program.c.j2", **context),
                 only_if_changed=True)
    write_atomic(out_dir / "Makefile", template_render(
        "epuck2.mk.j2", firmware=str(firmware) if firmware else "",
        runtime_sources=[f"{DSPIC_RUNTIME}/{Path(r).name}" for r in sources],
        user_sources=[copy for _, copy in copies], defines=defines, **context),
        only_if_changed=True)


def make_command(make: str, out_dir: Path, firmware: Path,
                 environ: Optional[dict] = None) -> tuple[list[str], dict, Optional[str]]:
    """`make` of the project on every core, through ccache when it is on
    PATH (and EPUCKC_NO_CCACHE is not set). The firmware's ~200 files are
    the same in every project (same sources, flags and headers: main.h is
    the template's), so from the second project on ccache gives their
    objects back and only the program and the runtime compile. ccache
    hashes the working folder where -g is used (the firmware's -ggdb);
    CCACHE_NOHASHDIR lets one project's objects serve another's, at the
    cost ccache documents: the debug information's compilation folder may
    name the project that compiled the file first (the firmware's files
    are named by absolute paths, so gdb finds them anyway). Returns the
    command, its environment and the ccache used (None: none)."""
    environ = dict(os.environ if environ is None else environ)
    command = [make, f"-j{os.cpu_count() or 1}", "-C", str(out_dir),
               f"EPUCK2_FIRMWARE={firmware}"]
    ccache = None if environ.get("EPUCKC_NO_CCACHE") else shutil.which(
        "ccache", path=environ.get("PATH"))
    if ccache is not None:
        command.append(f"CC={ccache} {ARM_GCC}")
        if "CCACHE_HASHDIR" not in environ:
            environ.setdefault("CCACHE_NOHASHDIR", "1")
    return command, environ, ccache


def build_epuck2(program: Program, out_dir: Path, template_render,
                 firmware_option: Optional[str], trace: Optional[TraceOptions] = None) -> str:
    """Write the project, then `make` it when arm-none-eabi-gcc and the
    firmware are there; otherwise BuildError with the exact next command."""
    firmware = find_firmware(firmware_option)
    write_epuck2_project(program, out_dir, template_render, firmware, trace)
    gcc = shutil.which(ARM_GCC)
    if gcc is None:
        raise BuildError(
            f"the project was written to {out_dir}, but it was not built: {ARM_GCC} was not "
            "found on PATH.\nInstall it (Debian: apt-get install gcc-arm-none-eabi "
            f"libnewlib-arm-none-eabi), then run: make -C {out_dir} "
            "EPUCK2_FIRMWARE=/path/to/e-puck2_main-processor", status=EXIT_NO_TOOLCHAIN)
    if firmware is None:
        given = firmware_option or os.environ.get("EPUCK2_FIRMWARE")
        why = (f"{given} is not the firmware's folder (it holds no Makefile and "
               f"{EPUCK1X}/)" if given else "neither --firmware nor EPUCK2_FIRMWARE says where "
               "the firmware is")
        raise BuildError(
            f"the project was written to {out_dir}, but it was not built: {why}.\n"
            "Get it with: git clone --recursive "
            "https://github.com/e-puck2/e-puck2_main-processor\n"
            f"then run: make -C {out_dir} EPUCK2_FIRMWARE=/path/to/e-puck2_main-processor",
            status=EXIT_NO_TOOLCHAIN)
    make = shutil.which("make")
    if make is None:
        raise BuildError(f"`make` was not found; the project is in {out_dir}",
                         status=EXIT_NO_TOOLCHAIN)
    command, env, ccache = make_command(make, out_dir, firmware)
    result = subprocess.run(command, capture_output=True, text=True, env=env)
    if result.returncode != 0:
        hint = (f"\n(the compiler ran through {ccache}; if ccache is what failed, "
                "EPUCKC_NO_CCACHE=1 builds without it)" if ccache else "")
        raise BuildError(f"make failed in {out_dir}:\n{(result.stdout + result.stderr).rstrip()}"
                         + hint)
    return f"built {out_dir / 'build' / (program.name + '.elf')} and .bin"
