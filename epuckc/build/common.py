"""What every build shares: the program to build, the compiler flags and the
-Werror policy, exit statuses, output checks, running a compiler."""
from __future__ import annotations

import os
import re
import shlex
import subprocess
import sys
from pathlib import Path
from typing import Optional

from ..base.output import write_atomic
from ..base.records import field, record
from ..base.resources import (LIBRARY_SIMULATION, RUNTIME_CORE, RUNTIME_CORE_HEADERS,
                              RUNTIME_DEVICES, RUNTIME_DSPIC_DEVICES, RUNTIME_SIMULATED)

# -O1 as on the robot (the dspic Makefile; XC16's free edition stops there)
# and in the sanitizer builds of the tests: the harness runs no slower than
# at -O2 (virtual time, a poll a millisecond), and gcc takes 40% less time.
HOST_CFLAGS = ["-std=c99", "-Wall", "-Wextra", "-pedantic", "-O1"]


# The -Werror policy, the same on the host and the robot: the C epuckc
# writes (the generated program, and on the host the runtime) is
# warning-free by design, so a warning there is a bug in epuckc and fails the
# build; the user's own C (extern files, a hand-written program: the paper's
# figure 2 sets variables it never reads) gets its warnings shown, not fatal.
GENERATED_CFLAGS = HOST_CFLAGS + ["-Werror"]


USER_CFLAGS = HOST_CFLAGS


# The user's C on the host and in worlds also calls the C main model at
# every basic block (runtime_c/host/cmain.c: main's clock in dsPIC cycles,
# the watchdog's last place), with the lines addr2line names. Its loops
# read memory at each turn, as GCtronic's builds of the library and its
# demos (no -O: XC16 at -O0) do: e-puck programs wait for a flag that an
# interrupt sets without `volatile` (`while (e_dci_unavailable);`), which
# gcc would read once before such a loop. Its globals go one section each
# (build/dspic_asm.py moves them where a reset restores them).
HOST_USER_FLAGS = ["-fsanitize-coverage=trace-pc", "-g", "-fno-tree-loop-im",
                   "-fno-move-loop-invariants", "-fdata-sections"]


# How gcc runs, not what it makes: no temporary assembly files.
BUILD_FLAGS = ["-pipe"]


# The runtime's files for each target, relative to runtime_c/.
HOST_SOURCES = [*RUNTIME_CORE, *RUNTIME_SIMULATED, *RUNTIME_DEVICES, "platform/platform_host.c",
                "host/scenario.c", "host/cmain.c", *LIBRARY_SIMULATION]


# epuck_api_unsimulated: #error headers of what the simulator does not model
HOST_INCLUDES = [".", "epuck_api", "host", "epuck_api_unsimulated"]


# (the project's files, relative to its runtime/: ROBOT_COPIES says where
# those of another place in runtime_c/ are)
ROBOT_SOURCES = [*RUNTIME_CORE, *RUNTIME_DSPIC_DEVICES, "platform_robot.c"]


# sensors/ground.h: the e-puck2 firmware's ground API, which ground_i2c.c
# provides on the e-puck (the e-puck library has none), at the firmware's path
ROBOT_HEADERS = list(RUNTIME_CORE_HEADERS) + ["sensors/ground.h"]


# A file of the project (relative to its runtime/) -> where it is in runtime_c/
# when that is another place.
ROBOT_COPIES = {"sensors/ground.h": "epuck_api/sensors/ground.h",
                "platform_robot.c": "platform/platform_robot.c"}


ROBOT_FILES = ROBOT_SOURCES + ROBOT_HEADERS


# Folders of the dspic project: the runtime's copies and the user's.
DSPIC_RUNTIME = "runtime"


DSPIC_USER = "user"


EXIT_USAGE = 2             # bad request: e.g. an output that is one of the inputs


EXIT_NO_TOOLCHAIN = 3      # the project is written but XC16, the library or make is missing


class BuildError(Exception):
    """A build step failed; the message says what and how to go on."""

    def __init__(self, message: str, status: int = 1):
        super().__init__(message)
        self.status = status


@record
class Program:
    """A C program ready to build.

    Generated from a rule file: `c_text`, the externs header
    (`header_name`, `header_text`) when there are externs, and the user's C
    files that define them (`user_files`, paths as the user's rule file
    names them, joined to its folder: gcc's messages then name the user's
    own file). Hand-written: `source_path` is compiled where it is.
    `inputs` are every file the command reads: nothing is written over them.
    `variables`: the values a rule file's trace follows (`VarInfo.traced`:
    each variable, each element of an array), (name, initial value as the
    runtime holds it) in the order of their numbers in the trace, for the
    replay of a run and the names of the 16-bit path's trace.
    """
    name: str
    c_text: str
    base_dir: Path
    user_files: list = field(default_factory=list)
    max_actions: Optional[int] = None
    max_events: Optional[int] = None
    generated: bool = True
    header_name: Optional[str] = None
    header_text: Optional[str] = None
    source_path: Optional[Path] = None        # a C program's main; user_files: its other C
    inputs: list = field(default_factory=list)
    variables: list = field(default_factory=list)
    # the devices it uses (stdlib DEVICES); None: not known (hand-written C)
    devices: Optional[frozenset] = None
    # what the host's trace names (emit.program.trace_names): the table of
    # the robot's trace (trace_table.py); None: hand-written C (by number)
    trace_names: Optional[dict] = None

    def user_sources(self) -> list:
        """The C files of the user's that are compiled on their own."""
        return ([self.source_path] if self.source_path is not None else []) + list(self.user_files)


def _same_file(a: Path, b: Path) -> bool:
    try:
        if os.path.samefile(a, b):
            return True
    except OSError:
        pass
    return os.path.realpath(a) == os.path.realpath(b)


def check_outputs(outputs, inputs, inside: Optional[Path] = None):
    """Refuse, before anything is written, to write over one of the
    command's inputs, or (with `inside`) anywhere outside that folder, e.g.
    through a link."""
    for out in outputs:
        for given in inputs:
            if _same_file(out, given):
                raise BuildError(f"refusing to write {out}: it is {given}, one of the files "
                                 f"this command reads; choose another output with -o",
                                 status=EXIT_USAGE)
        if inside is not None:
            root = os.path.realpath(inside)
            real = os.path.realpath(out)
            if os.path.commonpath([root, real]) != root:
                raise BuildError(f"refusing to write {out}: it leads outside {inside} "
                                 f"(to {real})", status=EXIT_USAGE)


def c_compiler() -> list:
    return shlex.split(os.environ.get("CC") or "cc")


def _capacity_defines(program: Program) -> list:
    """The dynamic arrays' capacities.  A rule file's rules are tables: with
    no user C nothing can register, so the arrays shrink to one entry each
    (the least the runtime takes) unless asked; otherwise the runtime's
    defaults or the options."""
    max_actions, max_events = program.max_actions, program.max_events
    if program.generated and not program.user_files:
        max_actions, max_events = max_actions or 1, max_events or 1
    defines = []
    if max_actions:
        defines.append(f"-DMAX_ACTIONS={max_actions}")
    if max_events:
        defines.append(f"-DMAX_EVENTS={max_events}")
    return defines


def _compiler_missing(command: list) -> BuildError:
    return BuildError(f"the C compiler `{command[0]}` was not found; install one "
                      f"(e.g. `apt-get install gcc`) or set CC")


def _run_compiler(command: list, what: str, hint: str = ""):
    try:
        # its messages quote the user's C, whose bytes may not be UTF-8
        result = subprocess.run(command, capture_output=True, text=True, errors="replace")
    except FileNotFoundError:
        raise _compiler_missing(command) from None
    if result.stderr and result.returncode == 0:
        sys.stderr.write(result.stderr)      # warnings in the user's C
    if result.returncode != 0:
        output = (result.stdout + result.stderr).rstrip()
        raise BuildError(f"the C compiler failed to build {what}:\n{output}\n"
                         f"command: {shlex.join(command)}{hint}")


_QUOTED_INCLUDE = re.compile(rb'^[ \t]*#[ \t]*include[ \t]*"([^"\n]+)"', re.MULTILINE)


def user_headers(program: Program) -> list:
    """(header, its path relative to the folder of the user's C file that
    includes it, first or through other headers) for every header the
    user's C includes with quotes that is found where the compiler looks
    first, beside the including file; followed through the headers it
    includes. A quoted include found nowhere there (the program's own
    externs header, the runtime's, the e-puck library's) is left to the
    include paths. The builds depend on these headers as on the C."""
    found = []
    for source in program.user_sources():
        source = Path(source)
        home = os.path.dirname(os.path.abspath(source))
        queue, seen = [source], set()
        while queue:
            including = queue.pop(0)
            try:
                data = including.read_bytes()
            except OSError:
                continue            # the compiler says why
            for match in _QUOTED_INCLUDE.finditer(data):
                name = match.group(1).decode("utf-8", "surrogateescape")
                header = Path(os.path.normpath(os.path.join(including.parent, name)))
                if name == program.header_name:
                    continue        # generated (a file beside it: stale_externs_header)
                if header in seen or not header.is_file():
                    continue
                seen.add(header)
                found.append((source, header,
                              Path(os.path.relpath(os.path.abspath(header), home)).as_posix()))
                queue.append(header)
    return found


def stale_externs_header(program: Program) -> Optional[str]:
    """A file named like the program's externs header beside the user's C
    that is not that header (written by an earlier `epuckc compile`,
    before the externs changed): the compiler would read it instead of the
    current one, since a quoted include looks beside the including file
    first. The message that says so, or None."""
    if not program.header_name:
        return None
    for source in program.user_sources():
        beside = Path(source).parent / program.header_name
        try:
            if beside.is_file() and beside.read_text(encoding="utf-8") != program.header_text:
                return (f"{beside} is not the externs header of this program (an earlier "
                        f"`epuckc compile` wrote it, before the externs changed), and "
                        f"{Path(source).name} would include it instead of the current one: "
                        f"delete it, or run `epuckc compile` again to rewrite it")
        except (OSError, UnicodeDecodeError):
            continue
    return None


def _write_generated(program: Program, folder: Path, only_if_changed: bool = False):
    write_atomic(folder / f"{program.name}.c", program.c_text, only_if_changed=only_if_changed)
    if program.header_name:
        write_atomic(folder / program.header_name, program.header_text,
                     only_if_changed=only_if_changed)
