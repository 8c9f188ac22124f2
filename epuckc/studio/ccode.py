"""`Show C`: the C that `epuckc compile` gives for the editor's text (saved
or not), and the parts of it that a statement becomes.

The generated C names its sources: each parameter struct, function and
variable of a statement is preceded by a `/* NAME.epk:LINE: ... */`
comment at the start of a line, and each table entry and name of it
carries one (templates/program.c.j2). The parts shown for a line are the
pieces that such a comment opens, when it cites the statement at the
cursor, and, of the tables and main, their first and last lines around
the lines that cite it.
"""
from __future__ import annotations

import re
from pathlib import Path


class NoC(Exception):
    """The text has errors; the message holds the diagnostics."""


def _blocks(c_text: str) -> list:
    """The C's top-level pieces: runs of lines between blank lines, cut
    again before each comment at the start of a line."""
    blocks, current = [], []
    for line in c_text.splitlines():
        if not line.strip() or (line.startswith("/* ") and current
                                and not current[-1].startswith("/* ")):
            if current:
                blocks.append(current)
            current = [line] if line.strip() else []
        else:
            current.append(line)
    if current:
        blocks.append(current)
    return blocks


def _parts(c_text: str, cite) -> list:
    parts = []
    for block in _blocks(c_text):
        if block[0].startswith("/* ") and cite.search(block[0]):
            parts.append("\n".join(block))
            continue
        lines = [line for line in block if cite.search(line)]
        if not lines:
            continue
        if len(block) <= 3 or lines == block:
            parts.append("\n".join(lines))
        else:       # a table or main: its first and last lines around the cited ones
            inner = [line for line in block[1:-1] if cite.search(line)]
            parts.append("\n".join([block[0], "    ..."] + inner + ["    ...", block[-1]]))
    return parts


def generated_c(path: Path, text: str, line: int) -> dict:
    """{"c": the whole file, "parts": the blocks of the statement at `line`
    (from 1), "line": that statement's first line}."""
    from ..check.frontend import check_file
    from ..diagnostics import Report
    from ..diagnostics.render import render_report
    from ..emit.program import emit_program
    report = Report()
    name = path.name
    result = check_file(path, report, shown_name=name, text=text)
    if result.checked is None:
        raise NoC(render_report(report, "human"))
    program = re.sub(r"[^A-Za-z0-9_-]", "_", path.stem) or "program"
    c_text = emit_program(result.checked, result.source.text, program).c_text
    first = _statement_line(text, line)
    cite = re.compile(re.escape(name) + r":" + str(first) + r"\b")
    parts = _parts(c_text, cite)
    return {"c": c_text, "parts": parts, "line": first}


def _statement_line(text: str, line: int) -> int:
    """The first line of the statement that holds `line`: statements start
    in the first column; indented lines and blank ones continue the one
    above (the layout fmt gives and the grammar's continuation lines)."""
    lines = text.splitlines()
    line = max(1, min(line, len(lines) or 1))
    while line > 1:
        row = lines[line - 1]
        if row.strip() and not row[0].isspace() and not row.lstrip().startswith("#"):
            break
        line -= 1
    return line
