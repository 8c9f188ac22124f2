"""Emission: lay a lowered CProgram out as C through the Jinja2 template.

The template only prints what lowering decided (StrictUndefined catches a
missing field rather than printing nothing)."""
from __future__ import annotations

import gc
from dataclasses import dataclass
from functools import lru_cache
from typing import Optional

import jinja2

from .. import __version__
from ..check.program import CheckedProgram
from ..lower.program import lower
from ..base.resources import templates_dir


@lru_cache(maxsize=1)
def _environment() -> jinja2.Environment:
    return jinja2.Environment(
        loader=jinja2.FileSystemLoader(str(templates_dir())),
        undefined=jinja2.StrictUndefined,
        keep_trailing_newline=True,
        trim_blocks=True,
        lstrip_blocks=True,
        autoescape=False,
    )


@dataclass
class GeneratedC:
    c_text: str
    header_name: Optional[str] = None      # `<program>_externs.h`, when there are externs
    header_text: Optional[str] = None
    # the names the host's trace shows (name_event, name_action, ...), for
    # the table of the robot's trace (build/trace_table.py): trace_names()
    names: Optional[dict] = None


def c_string_value(literal: str) -> str:
    """The text of a C string literal as lower.program.c_string writes
    them (printable ASCII, escaped quotes, backslashes and `?`, octal escapes of UTF-8
    bytes)."""
    body, out, i = literal[1:-1], bytearray(), 0
    while i < len(body):
        if body[i] == "\\":
            if body[i + 1] in "01234567":
                out.append(int(body[i + 1:i + 4], 8))
                i += 4
                continue
            out += body[i + 1].encode("ascii")
            i += 2
            continue
        out += body[i].encode("ascii")
        i += 1
    return out.decode("utf-8", "replace")


def trace_names(cprogram) -> dict:
    """What the program names in the host's trace, by id: its events,
    actions, the steps of each sequence (by the id of the action that runs
    it), modes and variables; and the geometry of its robot block (None:
    the runtime's defaults)."""
    geometry = None
    if cprogram.geometry:
        wheel, axle, steps = (int(v.strip().rstrip("L")) for v in cprogram.geometry.split(","))
        geometry = {"wheel_circumference_um": wheel, "axle_um": axle, "steps_per_rev": steps}
    return {
        "events": [c_string_value(e.event_label) for e in cprogram.events],
        "actions": [c_string_value(a.action_label) for a in cprogram.actions],
        "steps": {str(s.action_id): [c_string_value(label) for label in s.labels]
                  for s in cprogram.sequences if s.action_id >= 0},
        "modes": {str(i): c_string_value(label) for i, label in cprogram.modes},
        "variables": [c_string_value(v.label) for v in cprogram.variables],
        "geometry": geometry,
    }


def emit_program(program: CheckedProgram, source_text: str, program_name: str) -> GeneratedC:
    """The C program and, for a program with externs, the header that the
    program and the user's C files include."""
    # As in frontend.check_file: the lowered program holds no reference
    # cycles, and the cyclic collector rescanning the growing heap tripled
    # the time of large programs; it is paused meanwhile.
    collecting = gc.isenabled()
    gc.disable()
    try:
        cprogram = lower(program, source_text, __version__, program_name)
        env = _environment()
        c_text = env.get_template("program.c.j2").render(program=cprogram)
        header = None
        if cprogram.externs_header is not None:
            header = env.get_template("externs.h.j2").render(program=cprogram)
    finally:
        if collecting:
            gc.enable()
    return GeneratedC(c_text, cprogram.externs_header, header, trace_names(cprogram))


def emit_c(program: CheckedProgram, source_text: str, program_name: str = "program") -> str:
    return emit_program(program, source_text, program_name).c_text


def render_template(template: str, **context) -> str:
    return _environment().get_template(template).render(**context)
