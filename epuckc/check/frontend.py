"""The front end as one call: read a file, parse it, check it."""
from __future__ import annotations

import gc
from pathlib import Path
from typing import Optional

from .program import CheckedProgram
from ..diagnostics import ERROR, Collector, Diagnostic, Report
from ..base.records import record
from ..base.source import SourceFile, Span


@record
class FrontEndResult:
    source: Optional[SourceFile]
    checked: Optional[CheckedProgram]      # None when there are errors
    program: object = None                 # the ast.Program (None if the file is not text)


class InputError(Exception):
    """The file cannot be read at all (missing, a directory, no permission)."""

    def __init__(self, message: str, reason: str = "", help: Optional[str] = None):
        super().__init__(message)
        self.reason = reason or message
        self.help = help

    def diagnostic(self, shown_name: str) -> Diagnostic:
        """The same problem as a diagnostic (E005), so that `check` reports
        it in every format and goes on with the other files."""
        return Diagnostic("E005", ERROR, f"cannot read this file: {self.reason}", shown_name,
                          Span(1, 1, 1, 1), self.help)


def read_error(name: str, exc: OSError) -> InputError:
    import errno
    reason = exc.strerror or str(exc)
    help = {errno.ENOENT: "check the file's name and the folder you run epuckc in",
            errno.EISDIR: "give a rule file (.epk), not a folder",
            errno.EACCES: "you may not read it: check its permissions",
            errno.ENAMETOOLONG: "the name is too long for the file system"}.get(exc.errno)
    return InputError(f"cannot read {name}: {reason}", reason, help)


def check_file(path: Path, report: Report, shown_name: Optional[str] = None,
               text: Optional[str] = None, target: str = "host",
               data: Optional[bytes] = None, world: bool = True) -> FrontEndResult:
    """Parse and check one rule file, adding its diagnostics to `report`.
    `text` replaces the file's contents (an editor's unsaved buffer);
    `data` is the file's bytes when they were read already (check/cache.py);
    `target` the robot it is for (devices it lacks are E070); `world`
    False: it is to run without a world (devices only a world gives are
    W070)."""
    name = shown_name if shown_name is not None else str(path)
    if text is not None:
        source, problem = SourceFile(name, text), None
    elif data is not None:
        source, problem = SourceFile.from_bytes(data, name)
    else:
        try:
            source, problem = SourceFile.from_path(path, name)
        except OSError as exc:
            raise read_error(name, exc) from None
    report.sources[source.name] = source
    diags = Collector(source)
    if problem is not None:
        start, end, message = problem
        # A byte that cannot be decoded is not in the text: the span is empty
        # where it starts; a NUL is (one character).
        diags.error("E004", source.span(start, end), message,
                    help="save the file as UTF-8 text; rule files are plain text (.epk)")
        report.extend(diags.items)
        return FrontEndResult(source, None)
    # (the parser and checker are imported here: `check` of files that are
    # all in its cache, check/cache.py, runs without them)
    from .checker import check
    from ..syntax.parser import parse
    # The AST has no reference cycles, and the cyclic garbage collector,
    # run again and again over a growing heap of nodes, doubled the time
    # of large files; it is paused while they are built.
    collecting = gc.isenabled()
    gc.disable()
    try:
        program = parse(source, diags)
        checked = check(program, diags,
                        base_dir=path.parent if text is None or path.exists() else None,
                        target=target, world=world)
    finally:
        if collecting:
            gc.enable()
    report.extend(diags.items)
    return FrontEndResult(source, None if diags.has_errors else checked, program)
