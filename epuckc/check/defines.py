"""`-D NAME=VALUE`: a constant's value given on the command line (or by an
experiment's grid) instead of the one its `const` line gives.

The override is a rewrite of the text before checking: the value of
`const NAME = ...` is replaced by VALUE, so that the checker sees the
program as if the user had written it, and every diagnostic (a value of
the wrong unit, out of range, ...) is the checker's usual one, pointing at
the line with the new value. VALUE is one value of the language: a number
with its unit (`3`, `-400 steps/s`, `20cm`) or a constant's name. A name
that no `const` of the program defines is an error (`DefineError`).
"""
from __future__ import annotations

import re

from ..base.source import SourceFile
from ..diagnostics import Collector
from ..syntax import ast
from ..syntax.parser import parse

_NAME = r"[A-Za-z_][A-Za-z0-9_]*"
NAME_RE = re.compile(_NAME + r"\Z")
VALUE_RE = re.compile(r"-?\s*(?:(?:[0-9]+(?:\.[0-9]*)?|\.[0-9]+)\s*(?:" + _NAME + r"(?:\s*/\s*"
                      + _NAME + r")?|%)?|" + _NAME + r")\Z")


class DefineError(Exception):
    """A -D that cannot apply; str() says why and how to fix it."""


def parse_define(text: str) -> tuple:
    """`NAME=VALUE` -> (NAME, VALUE), or DefineError."""
    name, eq, value = text.partition("=")
    name, value = name.strip(), value.strip()
    if not eq or not NAME_RE.match(name):
        raise DefineError(f"-D {text!r}: write -D NAME=VALUE, e.g. -D GAIN=3 or "
                          f"-D SPEED=400steps/s")
    check_value(name, value)
    return name, value


def check_value(name: str, value: str):
    if not VALUE_RE.match(value):
        raise DefineError(f"-D {name}={value}: `{value}` is not one value of the language; "
                          f"give a number with its unit (3, 20 cm, -400 steps/s) or a "
                          f"constant's name")


def format_value(value) -> str:
    """A TOML value (a number, or a string such as "20 cm") as the text of
    a value of the language."""
    if isinstance(value, bool):
        raise DefineError(f"{value!r} is not a value of the language")
    if isinstance(value, float):
        text = repr(value)
        if "e" in text or "inf" in text or "nan" in text:
            raise DefineError(f"{value!r}: write the number without an exponent")
        return text
    return str(value).strip()


def apply_defines(text: str, defines: dict, name: str = "<program>") -> str:
    """The program's text with each constant of `defines` (NAME -> VALUE
    text) given its new value. DefineError when a NAME has no `const` in
    the program. A text that does not parse is returned as it is (the
    checker reports its syntax errors)."""
    for const, value in defines.items():
        check_value(const, value)
    source = SourceFile(name, text)
    diags = Collector(source)
    program = parse(source, diags)
    found = {}
    for stmt in program.statements:
        if isinstance(stmt, ast.ConstDef) and stmt.name.name in defines:
            found.setdefault(stmt.name.name, stmt.value.span)
    missing = [c for c in defines if c not in found]
    if missing and not diags.has_errors:
        known = sorted(s.name.name for s in program.statements if isinstance(s, ast.ConstDef))
        consts = ", ".join(known) if known else "none"
        raise DefineError(f"-D {missing[0]}: {name} has no constant {missing[0]} "
                          f"(its constants: {consts})")
    out = source.text
    lines = out.split("\n")
    starts = [0]
    for line in lines[:-1]:
        starts.append(starts[-1] + len(line) + 1)
    # from the end, so that earlier offsets stay true
    for const, span in sorted(found.items(), key=lambda kv: kv[1], reverse=True):
        start = starts[span.line - 1] + span.column - 1
        end = starts[span.end_line - 1] + span.end_column - 1
        out = out[:start] + defines[const] + out[end:]
    return out


def declared_of(text: str, name: str = "<program>") -> tuple:
    """The constants and the variables a program's text declares (those
    that parse), a variable as the trace names it (an array's elements:
    `counts[2]`), as two sets."""
    source = SourceFile(name, text)
    consts, variables = set(), set()
    for s in parse(source, Collector(source)).statements:
        if isinstance(s, ast.ConstDef):
            consts.add(s.name.name)
        elif isinstance(s, ast.VarDef):
            variables.update([f"{s.name.name}[{k}]" for k in range(len(s.value.items))]
                             if isinstance(s.value, ast.ArrayLit) else [s.name.name])
    return consts, variables


def constants_of(text: str, name: str = "<program>") -> list:
    """The names of the constants a program's text defines (`const` lines
    that parse), in order."""
    source = SourceFile(name, text)
    program = parse(source, Collector(source))
    return [s.name.name for s in program.statements if isinstance(s, ast.ConstDef)]
