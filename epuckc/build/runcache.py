"""`epuckc run` of a rule file that was built before: straight to the
executable (or, with `--world`, to the robot's shared object), keyed on the
inputs rather than on the generated C.

The host build cache (build.py) is keyed on the generated C, so reaching it
means checking the file, lowering it and rendering the Jinja2 template,
which is most of a cached run's time. This cache sits in front of it: after
a successful build, `record` stores under a key made of everything that
decides the executable and the messages printed on the way,

  - the rule file: its bytes, its path (the folder of its extern C files)
    and its name as given (diagnostics show it),
  - epuckc itself: its version and the size and modification time of every
    file of the compiler (epuckc/*.py, the grammar, the templates), so an
    edited compiler never reuses an old build,
  - the runtime's sources (size and modification time),
  - the C compiler ($CC) and the capacities (--max-actions, --max-events),

  - what is built: the host's executable (`run`) or a robot of an Enki
    world (`run --world`), which are two entries,

the path of the executable (the shared object), the bytes of every extern C
file the program includes (compared whole on a hit), the diagnostics as
they were printed (warnings: only a program without errors is built), with
and without colour, and what a world run reads of the program besides
(`extra`: its devices and variables). `lookup` returns that entry when the
key matches and the executable and extern files are unchanged; the next run
prints the same warnings and runs the executable without importing the
front end or Jinja2. Anything unexpected (a missing or unreadable entry,
another format) is a miss: the normal path runs and records again.
"""
from __future__ import annotations

import os
import sys
from pathlib import Path
from typing import Optional

from .. import __version__
from ..base import cache
from ..base.fingerprint import PACKAGE as _PACKAGE, stat_lines
from ..base.resources import cache_dir, grammar_path, runtime_dir, templates_dir

FORMAT = 2
_stat_lines = stat_lines     # (base/fingerprint.py: shared with `check`'s cache)


def input_key(path: Path, data: bytes, shown_name: str, max_actions,
              max_events, kind: str = "host") -> Optional[bytes]:
    """Everything a `run` of this rule file depends on, as one byte string;
    None when some of it cannot be read (the normal path will say why).
    `kind`: what is built, "host" (the executable) or "world" (a robot)."""
    try:
        return _input_key(path, data, shown_name, max_actions, max_events, kind)
    except OSError:
        return None


def _input_key(path: Path, data: bytes, shown_name: str, max_actions, max_events,
               kind: str) -> bytes:
    parts = [f"format {FORMAT}", f"built {kind}", f"epuckc {__version__}", f"python {sys.version}",
             f"file {path.resolve()}", f"shown {shown_name}",
             f"cc {os.environ.get('CC') or 'cc'}",
             f"capacity {max_actions} {max_events}"]
    parts += _stat_lines(_PACKAGE, (".py", ".so"), recursive=True)
    parts.append(f"grammar {grammar_path()}")
    parts += _stat_lines(grammar_path().parent, (".lark",), recursive=False)
    parts += _stat_lines(templates_dir(), (".j2",), recursive=False)
    parts += _stat_lines(runtime_dir(), (".c", ".h"), recursive=True)
    return "\n".join(parts).encode("utf-8") + b"\n\0" + data


def _entry_path(key: bytes) -> Path:
    return cache.area("run") / f"{cache.key_name(key)}.marshal"


class Entry:
    """A recorded build: the executable, its extern files, what was printed."""

    def __init__(self, exe: str, user_files: tuple, shown: str, shown_colour: str,
                 warnings: int, extra: dict):
        self.exe = exe
        self.user_files = user_files        # ((absolute path, bytes), ...)
        self.shown = shown                  # the diagnostics, as printed
        self.shown_colour = shown_colour
        self.warnings = warnings
        self.extra = extra                  # what else a run reads of the program


def lookup(key: bytes) -> Optional[Entry]:
    data = cache.load(_entry_path(key))
    if not (isinstance(data, tuple) and len(data) == 8 and data[0] == FORMAT
            and data[1] == key):
        return None
    entry = Entry(*data[2:])
    # the executable's own entry (host/ or enki/) is used too: marked, so
    # that it is not evicted while this one is
    if not cache.used(Path(entry.exe).parent) or not os.access(entry.exe, os.X_OK):
        return None
    for name, content in entry.user_files:
        try:
            with open(name, "rb") as f:
                if f.read() != content:
                    return None
        except OSError:
            return None
    return entry


def record(key: bytes, exe: Path, user_files: list, shown: str, shown_colour: str,
           warnings: int, extra: Optional[dict] = None) -> None:
    """Remember a build; a cache that cannot be written is not an error."""
    try:
        exe = Path(exe).resolve()
        if cache_dir().resolve() not in exe.parents:
            return          # a build outside the cache (e.g. a temporary folder) does not last
        files = tuple((str(Path(p).resolve()), Path(p).read_bytes()) for p in user_files)
    except (OSError, ValueError):
        return
    cache.store(_entry_path(key), (FORMAT, key, str(exe), files, shown, shown_colour, warnings,
                             extra or {}))
