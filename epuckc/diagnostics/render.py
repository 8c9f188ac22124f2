"""Renderings of a report: the human form (the source line and an underline),
the one-line gcc form that editors' problem matchers read, rustc's short form,
JSON for tools, and SARIF 2.1.0 for code scanning (sarif.py)."""
from __future__ import annotations

from typing import Optional

from ..base.source import SourceFile
from . import ERROR, WARNING, Diagnostic, Report

_COLOURS = {ERROR: "\033[1;31m", WARNING: "\033[1;33m", "help": "\033[1;36m",
            "note": "\033[1;32m", "bold": "\033[1m", "dim": "\033[2m"}
_RESET = "\033[0m"
_MAX_SHOWN_LINE = 100     # characters of a source line shown around the span


class _Paint:
    def __init__(self, enabled: bool):
        self.enabled = enabled

    def __call__(self, style: str, text: str) -> str:
        return f"{_COLOURS[style]}{text}{_RESET}" if self.enabled else text


def _visible(line: str, start: int, end: int) -> tuple[str, int, int]:
    """The line with tabs as one space and other control characters written
    out (a NUL as `\\0`, the others as `\\xNN`), and [start, end) moved to
    where the same characters are in it."""
    line = line.replace("\t", " ")
    if all(c >= " " for c in line):
        return line, start, end
    out, where = [], []
    for c in line:
        where.append(sum(map(len, out)))
        out.append(c if c >= " " else "\\0" if c == "\0" else f"\\x{ord(c):02x}")
    where.append(sum(map(len, out)))
    return "".join(out), where[min(start, len(line))], where[min(end, len(line))]


def _excerpt(line: str, start: int, end: int) -> tuple[str, int, int]:
    """A window of a (possibly huge) line around columns [start, end), with
    tabs expanded and control characters written out; returns the text and
    the new start/end columns (0-based)."""
    end = max(end, start + 1)
    line, start, end = _visible(line, start, end)
    if len(line) <= _MAX_SHOWN_LINE:
        return line, start, end
    left = max(0, min(start - 20, len(line) - _MAX_SHOWN_LINE))
    right = min(len(line), left + _MAX_SHOWN_LINE)
    prefix = "..." if left > 0 else ""
    suffix = "..." if right < len(line) else ""
    shift = left - len(prefix)
    return (prefix + line[left:right] + suffix, start - shift,
            min(end, right) - shift)


def render_human(diag: Diagnostic, source: Optional[SourceFile], colour: bool) -> str:
    paint = _Paint(colour)
    s = diag.span
    head = (f"{paint('bold', f'{diag.file}:{s.line}:{s.column}:')} "
            f"{paint(diag.severity, f'{diag.severity}[{diag.code}]')}: "
            f"{paint('bold', diag.message)}")
    out = [head]
    if source is not None and 1 <= s.line <= source.line_count:
        text = source.line_text(s.line)
        end_col = s.end_column if s.end_line == s.line else len(text) + 1
        shown, start, end = _excerpt(text, s.column - 1, end_col - 1)
        gutter = str(s.line)
        pad = " " * len(gutter)
        out.append(f" {paint('dim', gutter + ' |')} {shown}".rstrip())
        out.append(f" {paint('dim', pad + ' |')} {' ' * start}"
                   f"{paint(diag.severity, '^' * max(1, end - start))}")
    for note in diag.notes:
        where = f"{diag.file}:{note.span.line}:{note.span.column}: " if note.span else ""
        out.append(f"{paint('note', 'note')}: {where}{note.message}")
    if diag.help:
        out.append(f"{paint('help', 'help')}: {diag.help}")
    return "\n".join(out)


def render_gcc(diag: Diagnostic) -> str:
    """file:line:col: severity: message [CODE] - the form gcc prints, which
    Vim's errorformat, Emacs' compilation mode and VS Code's $gcc read."""
    s = diag.span
    text = f"{diag.file}:{s.line}:{s.column}: {diag.severity}: {diag.message} [{diag.code}]"
    if diag.help:
        text += f" (help: {diag.help})"
    return text


def render_short(diag: Diagnostic) -> str:
    """rustc's --error-format=short."""
    s = diag.span
    return f"{diag.file}:{s.line}:{s.column}: {diag.severity}[{diag.code}]: {diag.message}"


def to_json_object(diag: Diagnostic) -> dict:
    s = diag.span
    return {
        "code": diag.code,
        "severity": diag.severity,
        "message": diag.message,
        "file": diag.file,
        "line": s.line,
        "column": s.column,
        "end_line": s.end_line,
        "end_column": s.end_column,
        "help": diag.help,
        "notes": [n.message for n in diag.notes],
        # what an editor's quick fix does: replace the text from
        # line:column to end_line:end_column (exclusive) with `text`
        "fixes": [{"line": f.span.line, "column": f.span.column,
                   "end_line": f.span.end_line, "end_column": f.span.end_column,
                   "text": f.text, "help": f.help} for f in diag.fixes],
    }


def summary_line(errors: int, warnings: int) -> str:
    parts = []
    if errors:
        parts.append(f"{errors} error{'s' if errors != 1 else ''}")
    if warnings:
        parts.append(f"{warnings} warning{'s' if warnings != 1 else ''}")
    return " and ".join(parts) + (" found" if parts else "")


def render_report(report: Report, fmt: str, colour: bool = False) -> str:
    if fmt == "sarif":
        from .sarif import render_sarif
        return render_sarif(report)
    diags = report.sorted()
    if fmt == "json":
        import json  # only here: `check` starts faster without it
        return json.dumps([to_json_object(d) for d in diags], indent=2) + "\n"
    if fmt == "gcc":
        return "".join(render_gcc(d) + "\n" for d in diags)
    if fmt == "short":
        return "".join(render_short(d) + "\n" for d in diags)
    blocks = [render_human(d, report.sources.get(d.file), colour) for d in diags]
    if not blocks:
        return ""
    return "\n\n".join(blocks) + "\n\n" + summary_line(report.error_count,
                                                       report.warning_count) + "\n"
