"""The table of the robot's trace (issue 39; docs/runtime.md, "The robot's
trace"): the robot sends numbers (a rule's event id, an action's, a
variable's), and this table, which a build with `--trace` writes beside
the program (`NAME.trace.json`), gives the names the host's trace shows for
them: each event's rule, each action, the steps of each sequence, the
modes and variables, and the robot block's geometry (for the odometry of
the decoded trace). Its fingerprint, a hash of what it holds, is compiled
into the tracer (EPUCKRT_TRACE_ID) and sent in every hello, so that a
stream is decoded only with the table of the program that sent it. A C
program written by hand has an empty table: its records are shown by
number."""
from __future__ import annotations

import hashlib
import json
from pathlib import Path
from typing import Optional

from ..base.output import write_atomic
from ..base.records import record
from .common import BuildError, Program

FORMAT = 1                      # of the frames (runtime_c/rt_trace.c FORMAT) and the table
SUFFIX = ".trace.json"
# epuckrt.h's defaults, the geometry without a robot block
DEFAULT_GEOMETRY = {"wheel_circumference_um": 128805, "axle_um": 53000, "steps_per_rev": 1000}
LINKS = ("uart", "usb")         # the e-puck2's: UART3 (the programmer's monitor port), SDU1
# the tracer's ring (EPUCKRT_TRACE_BUFFER): the e-puck's 8 KB of RAM, the e-puck2's 192 KB
BUFFER_BYTES = {"dspic": 256, "epuck2": 1024, "int16": 256}


@record
class TraceOptions:
    """`build --trace`: the tracer on, and on the e-puck2 its link."""
    link: str = "uart"


class TableError(Exception):
    """A table that cannot be read or is not one; the message says which."""


def _content(program: Program) -> dict:
    names = program.trace_names or {}
    return {"format": FORMAT,
            "events": list(names.get("events", [])),
            "actions": list(names.get("actions", [])),
            "steps": dict(names.get("steps", {})),
            "modes": dict(names.get("modes", {})),
            "variables": list(names.get("variables", [])),
            "geometry": names.get("geometry") or dict(DEFAULT_GEOMETRY)}


def fingerprint_of(content: dict) -> int:
    """32 bits of the SHA-256 of the table's content (canonical JSON, the
    program's name left out: two files with the same rules decode alike)."""
    data = {k: v for k, v in content.items() if k not in ("fingerprint", "program")}
    text = json.dumps(data, sort_keys=True, separators=(",", ":"), ensure_ascii=True)
    return int.from_bytes(hashlib.sha256(text.encode("ascii")).digest()[:4], "little")


def trace_table(program: Program) -> dict:
    """The table of a program, fingerprint included."""
    content = _content(program)
    return {"program": program.name, "fingerprint": f"{fingerprint_of(content):08x}", **content}


def trace_defines(program: Program, target: str, options: TraceOptions) -> list:
    """The C defines of a build with the tracer (without the -D)."""
    table = trace_table(program)
    defines = ["EPUCKRT_TRACE", f"EPUCKRT_TRACE_ID=0x{table['fingerprint']}UL",
               f"EPUCKRT_TRACE_BUFFER={BUFFER_BYTES[target]}"]
    if target == "epuck2" and options.link == "usb":
        defines.append("EPUCKRT_TRACE_USB")
    return defines


def table_path(folder: Path, name: str) -> Path:
    return Path(folder) / f"{name}{SUFFIX}"


def write_table(program: Program, folder: Path) -> Path:
    """NAME.trace.json in `folder` (rewritten only when it changed)."""
    path = table_path(folder, program.name)
    text = json.dumps(trace_table(program), indent=1, ensure_ascii=False) + "\n"
    write_atomic(path, text, only_if_changed=True)
    return path


def read_table(path: Path) -> dict:
    """A table written by write_table; TableError says what is wrong."""
    try:
        data = json.loads(Path(path).read_text(encoding="utf-8"))
    except OSError as exc:
        raise TableError(f"cannot read the trace table {path}: {exc.strerror or exc}") from None
    except ValueError as exc:
        raise TableError(f"{path} is not a trace table (not JSON: {exc})") from None
    if not isinstance(data, dict) or "fingerprint" not in data or "events" not in data:
        raise TableError(f"{path} is not a trace table (`epuckc build --trace` writes "
                         f"NAME{SUFFIX} beside the program)")
    if data.get("format") != FORMAT:
        raise TableError(f"{path} is a trace table of format {data.get('format')}; this "
                         f"epuckc reads format {FORMAT}: build the program again with it")
    recomputed = f"{fingerprint_of(data):08x}"
    if data["fingerprint"] != recomputed:
        raise TableError(f"{path} was edited after the build (its fingerprint says "
                         f"{data['fingerprint']}, its content {recomputed}): build again")
    return data


def check_trace_target(target: str, options: Optional[TraceOptions]) -> None:
    """BuildError for --trace where it means nothing."""
    if options is None:
        return
    if target == "host":
        raise BuildError("--trace is for the robots' builds (--target dspic or epuck2): the "
                         "host harness traces every run already (`epuckc run --trace "
                         "OUT.jsonl`)", status=2)
    if options.link not in LINKS:
        raise BuildError(f"--trace-link {options.link}: the links are {', '.join(LINKS)}",
                         status=2)
    if target != "epuck2" and options.link != "uart":
        raise BuildError("--trace-link usb is the e-puck2's (its main processor's USB serial "
                         "port); the e-puck's trace goes over its Bluetooth UART", status=2)
