"""Emission: lay a lowered CProgram out as C through the Jinja2 template.

The template only prints what lowering decided (StrictUndefined catches a
missing field rather than printing nothing)."""
from __future__ import annotations

from functools import lru_cache

import jinja2

from . import __version__
from .checker import CheckedProgram
from .lower import lower
from .resources import templates_dir


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


def emit_c(program: CheckedProgram, source_text: str) -> str:
    cprogram = lower(program, source_text, __version__)
    return _environment().get_template("program.c.j2").render(program=cprogram)


def render_template(template: str, **context) -> str:
    return _environment().get_template(template).render(**context)
