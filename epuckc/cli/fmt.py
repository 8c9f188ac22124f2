"""`epuckc fmt [--check] [--diff] [--errors] FILE|DIR|-`: format files in
place, or standard input to standard output; the layout itself is
ide/fmt.py.

Standard input is an editor's filter (Vim's `gq` with `formatprg=epuckc fmt
-` replaces the lines with everything the command prints, stderr included):
a text that cannot be formatted comes back unchanged on stdout, with exit
status 1, and its diagnostics go to stderr only with `--errors`. Files
named on the command line are never written when they have errors, and
their diagnostics are always shown."""
from __future__ import annotations

import sys
from pathlib import Path

from ..base.source import SourceFile
from ..diagnostics import Collector
from ..ide.fmt import FormatError, format_text


def _targets(names: list) -> list:
    """The files to format: each name, or the .epk files under a folder."""
    out = []
    for name in names:
        path = Path(name)
        if name != "-" and path.is_dir():
            out.extend(str(p) for p in sorted(path.rglob("*.epk")) if p.is_file())
        else:
            out.append(name)
    return out


def _read(name: str) -> tuple:
    """(text, E004 diagnostic or None, the bytes read from standard input or
    None) of a file or of standard input."""
    raw = None
    if name == "-":
        raw = sys.stdin.buffer.read()
        source, problem = SourceFile.from_bytes(raw, "<stdin>")
    else:
        source, problem = SourceFile.from_path(Path(name), name)
    if problem is None:
        return source, None, raw
    start, end, message = problem
    diags = Collector(source)
    diags.error("E004", source.span(start, end), message,
                help="save the file as UTF-8 text; rule files are plain text (.epk)")
    return source, diags.items, raw


def run(names: list, check: bool = False, diff: bool = False, colour: bool = False,
        errors: bool = False) -> int:
    """`epuckc fmt`: 0 when done (or, with --check, nothing would change),
    1 when a file has syntax errors or would change, 2 when one cannot be
    read or written. `errors`: show standard input's diagnostics too."""
    import difflib

    from ..base.output import OutputError
    from ..diagnostics import Report
    from ..diagnostics.render import render_report
    status = 0
    report = Report()
    for name in _targets(names):
        shown = "<stdin>" if name == "-" else name
        try:
            source, problem, raw = _read(name)
        except OSError as exc:
            print(f"epuckc: error: cannot read {name}: {exc.strerror or exc}", file=sys.stderr)
            status = max(status, 2)
            continue
        try:
            if problem:
                raise FormatError(problem)
            formatted = format_text(source.text, shown)
        except FormatError as exc:
            status = max(status, 1)
            if name == "-" and not check and not diff:
                sys.stdout.flush()
                sys.stdout.buffer.write(raw)        # the filter gives the text back
                if not errors:
                    continue
            report.sources[shown] = source
            report.extend(exc.diagnostics)
            continue
        original = source.text
        if name == "-" and not check and not diff:
            sys.stdout.write(formatted)
            continue
        if formatted == original:
            continue
        if diff:
            sys.stdout.writelines(difflib.unified_diff(
                original.splitlines(keepends=True), formatted.splitlines(keepends=True),
                fromfile=f"{shown} (original)", tofile=f"{shown} (formatted)"))
        if check:
            print(f"would reformat {shown}")
            status = max(status, 1)
        elif not diff:
            try:
                _write_in_place(Path(name), formatted)
            except OutputError as exc:
                print(f"epuckc: error: {exc}", file=sys.stderr)
                status = max(status, 2)
    if report.diagnostics:
        sys.stderr.write(render_report(report, "human", colour=colour))
    return status


def _write_in_place(path: Path, text: str):
    """Replace the file with `text` by output.py's rules: atomically,
    through a symbolic link to its target, keeping its permissions. The
    source's BOM is not kept."""
    from ..base.output import write_file
    write_file(path, text)
