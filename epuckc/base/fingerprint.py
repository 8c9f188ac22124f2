"""What epuckc's own code is, for the caches keyed on inputs (`epuckc run`'s,
build/runcache.py, and `epuckc check`'s, check/cache.py): the size and
modification time of every file of the compiler, so that an edited
compiler never reuses an old result (how the caches keep their entries:
cache.py)."""
from __future__ import annotations

import os
import sys
from functools import lru_cache
from pathlib import Path

from .. import __version__
from .resources import grammar_path

PACKAGE = Path(__file__).resolve().parent.parent     # epuckc/, every stage's folder


def stat_lines(folder: Path, suffixes: tuple, recursive: bool) -> list:
    """`relative path, size, mtime` of the files with these suffixes."""
    lines = []
    walker = os.walk(folder) if recursive else [(str(folder), [], os.listdir(folder))]
    for base, dirs, files in walker:
        dirs[:] = sorted(d for d in dirs if d not in ("build", "__pycache__"))
        for name in sorted(files):
            if name.endswith(suffixes):
                path = os.path.join(base, name)
                st = os.stat(path)
                lines.append(f"{os.path.relpath(path, folder)} {st.st_size} {st.st_mtime_ns}")
    return lines


@lru_cache(maxsize=1)
def front_end_fingerprint() -> str:
    """epuckc's version, Python's, and every file the front end is made of
    (the package's Python and C extension, the grammar), once per process;
    OSError when one cannot be read."""
    parts = [f"epuckc {__version__}", f"python {sys.version}"]
    parts += stat_lines(PACKAGE, (".py", ".so"), recursive=True)
    parts.append(f"grammar {grammar_path()}")
    parts += stat_lines(grammar_path().parent, (".lark",), recursive=False)
    return "\n".join(parts)

