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
    return GeneratedC(c_text, cprogram.externs_header, header)


def emit_c(program: CheckedProgram, source_text: str, program_name: str = "program") -> str:
    return emit_program(program, source_text, program_name).c_text


def render_template(template: str, **context) -> str:
    return _environment().get_template(template).render(**context)
