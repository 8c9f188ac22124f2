"""`epuckc check` of many files, again and again: a file is parsed and
checked again only when something its diagnostics depend on changed.

After a rule file is checked, `check_cached` keeps its diagnostics in
the cache's `check` area (base/cache.py), one entry per file (its path as given, its name as
shown, the target), replaced when the file changes. The entry holds a key
made of everything the diagnostics depend on, compared whole (the file's
bytes are in it):

  - the file's bytes, its path as given (the folder of its extern C files,
    which E040's help names), its name as shown, the target (E070);
  - epuckc itself: its version, Python's, and the size and modification
    time of every file of the front end (base/fingerprint.py), so an
    edited compiler never reuses an old result;

and, asked again at each hit, what the check asked outside the file:
whether each extern C file the program names exists and is a file (all
E040 asks, externs.extern_file_problem) and, for a program with externs,
what the C compiler and the runtime's headers declare (the names an
extern may not take, cnames.names_key). A hit adds the diagnostics as
they were, in the same order, with the file's text for showing them, so
what `check` prints is byte for byte what a check prints
(tests/cli/test_check_cache.py compares them over random changes).

Within one run, the fingerprint and the compiler's names are found once
for all the files, and a run whose files are all hits never imports the
parser or the checker. `EPUCKC_NO_CACHE` (or `check --no-cache`) checks every
file; an entry that cannot be read or written is a miss, never an error.
"""
from __future__ import annotations

import os
from pathlib import Path
from typing import Optional

from ..base import cache
from ..base.fingerprint import front_end_fingerprint
from ..base.source import SourceFile, Span
from ..diagnostics import Diagnostic, Fix, Note, Report

FORMAT = 1


def check_cached(path: Path, report: Report, shown_name: str, target: str = "host",
                 use: bool = True, world: bool = True) -> None:
    """check_file(path, report, shown_name, target=target, world=world), from the cache
    when nothing the result depends on changed (see the module's doc), and
    kept for the next time otherwise. `use` False (or EPUCKC_NO_CACHE):
    neither read nor written."""
    # (the front end is imported only for a file that is checked: a run
    # whose files are all in the cache starts without it)
    if not use or os.environ.get("EPUCKC_NO_CACHE"):
        from .frontend import check_file
        check_file(path, report, shown_name=shown_name, target=target, world=world)
        return
    try:
        data = path.read_bytes()
    except OSError as exc:
        from .frontend import read_error
        raise read_error(shown_name, exc) from None
    for_run = target if world else f"{target} without a world"      # (W070)
    entry = _entry_path(path, shown_name, for_run)
    key = _key(path, shown_name, for_run, data)
    diagnostics = _lookup(entry, key, path) if key is not None else None
    if diagnostics is not None:
        source, _ = SourceFile.from_bytes(data, shown_name)
        report.sources[source.name] = source
        report.extend(diagnostics)
        return
    from .frontend import check_file
    first = len(report.diagnostics)
    result = check_file(path, report, shown_name=shown_name, target=target, data=data,
                        world=world)
    if key is not None:
        _record(entry, key, path, result.program, report.diagnostics[first:])


def _entry_path(path: Path, shown_name: str, target: str) -> Path:
    """The file's entry (a name that is another file's too is a miss: the
    key inside is compared whole)."""
    name = f"{path}\0{shown_name}\0{target}".encode("utf-8", "surrogateescape")
    return cache.area("check") / f"{cache.key_name(name)}.marshal"


def _key(path: Path, shown_name: str, target: str, data: bytes) -> Optional[bytes]:
    """Everything the file's diagnostics depend on but the file system
    around it, as bytes (the file's own at the end), compared whole;
    None when epuckc's files cannot be read."""
    try:
        fingerprint = front_end_fingerprint()
    except OSError:
        return None
    head = f"format {FORMAT}\0{fingerprint}\0target {target}\0path {path}\0shown {shown_name}\0"
    return head.encode("utf-8", "surrogateescape") + data


def _outside(path: Path, files) -> Optional[tuple]:
    """What the check asked outside the rule file: the problem of each
    extern C file (None: none), and the C names' key when it has externs."""
    if not files:
        return (), None
    from .cnames import names_key
    from .externs import extern_file_problem
    try:
        problems = tuple(extern_file_problem(path.parent / f) for f in files)
        return problems, names_key()
    except (OSError, ValueError):
        return None


def _lookup(entry: Path, key: bytes, path: Path) -> Optional[list]:
    try:
        fmt, stored, files, outside, diagnostics = cache.load(entry)
        if fmt != FORMAT or stored != key or _outside(path, files) != outside:
            return None
        return [_decode(d) for d in diagnostics]
    except (OSError, EOFError, ValueError, TypeError):
        return None


def _record(entry: Path, key: bytes, path: Path, program, diagnostics: list) -> None:
    """Keep a check's diagnostics; a cache that cannot be written is not an
    error (the next run checks again)."""
    from ..syntax import ast
    files = tuple(s.file for s in program.statements if isinstance(s, ast.ExternDef)) \
        if program is not None else ()
    outside = _outside(path, files)
    if outside is None:
        return
    cache.store(entry, (FORMAT, key, files, outside, tuple(map(_encode, diagnostics))))


def _span(span) -> Optional[tuple]:
    return None if span is None else tuple(span)


def _encode(d: Diagnostic) -> tuple:
    return (d.code, d.severity, d.message, d.file, tuple(d.span), d.help,
            tuple((n.message, _span(n.span)) for n in d.notes),
            tuple((tuple(f.span), f.text, f.help) for f in d.fixes))


def _decode(t: tuple) -> Diagnostic:
    code, severity, message, file, span, help, notes, fixes = t
    return Diagnostic(code, severity, message, file, Span(*span), help,
                      tuple(Note(m, None if s is None else Span(*s)) for m, s in notes),
                      tuple(Fix(Span(*s), text, h) for s, text, h in fixes))
