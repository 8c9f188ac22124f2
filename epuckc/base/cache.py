"""The cache folder (resources.cache_dir()): one set of rules for every cache.

Each cache has an area, a folder of its own under the cache folder
(`AREAS` names them and who keeps them); an entry is one file or one folder
directly inside an area, named by a key made of the cache's inputs (each
cache knows what its result depends on: `key_name` turns those bytes into a
name).

- Written whole or not at all: a file entry is written aside and renamed
  (`store`, `write_entry`); a folder entry is built in a temporary folder
  (`temporary_folder`) and renamed into place (`commit_folder`). A reader
  sees all of an entry or none of it.
- Marked when used: a hit calls `used(entry)`, which sets the entry's
  modification time to now (one system call); the least recently used
  entries are the ones evicted.
- Bounded: the whole folder is kept under `bound()` bytes
  (`EPUCKC_CACHE_MAX`, e.g. `500M` or `2G`; `DEFAULT_BOUND` without it).
  After a new entry, at most once every `TRIM_EVERY_S` seconds for all the
  processes sharing the folder, the process that wrote it trims the cache
  (`added`, `trim`): the entries used longest ago go first.
- Never pulled from under another process: an entry used in the last
  `GRACE_S` seconds is never evicted (the process that looked it up uses
  it within a build's time), each entry is looked at again just before it
  goes, and a folder is renamed aside in one step before it is removed, so
  that nobody finds half of one. An entry that vanished anyway is a miss.
- Never an error: a cache folder that cannot be read or written (read-only,
  full, not a folder) makes every entry a miss and every write a no-op;
  the command does its work without it.

`epuckc cache --info` shows the areas and the bound, `--clear` empties the
folder, `--trim` trims it now (cli/commands.py, cmd_cache).
"""
from __future__ import annotations

import marshal
import os
import re
import time
import zlib
from pathlib import Path
from typing import Optional

from .output import TEMP_PREFIX
from .resources import cache_dir

# area -> what it holds (and the module that keeps it)
AREAS = {
    "tables": "parse tables of an edited grammar (syntax/lalr.py)",
    "cnames": "the C names an extern may not take (check/cnames.py)",
    "check": "`epuckc check`'s diagnostics of each file (check/cache.py)",
    "host": "harness executables, by their C (build/host.py)",
    "runtime": "the runtime's objects, by their flags (build/host.py)",
    "run": "`epuckc run`'s builds, by their inputs (build/runcache.py)",
    "enki": "the Enki world runner and the robots' shared objects (sim/enki.py)",
    "int16": "the simavr runner of `run --int16` (sim/int16.py)",
    "experiment": "an experiment's programs on a worker (experiment/task.py)",
}

DEFAULT_BOUND = 1 << 30         # 1 GiB
GRACE_S = 600.0                 # an entry used this recently is never evicted
TRIM_EVERY_S = 60.0             # the cache is trimmed at most this often
STAMP = ".trimmed"              # its modification time: when it last was


def area(name: str) -> Path:
    """The folder of one cache."""
    assert name in AREAS, name
    return cache_dir() / name


def key_name(key: bytes) -> str:
    """A file name for an entry from the bytes of its key: two checksums
    and the length (a file entry keeps its key and compares it whole, so a
    collision is a miss; hashlib, ~3 ms to import, is not needed)."""
    return f"{zlib.crc32(key):08x}{zlib.adler32(key):08x}{len(key) & 0xffff:04x}"


# ---- reading and writing entries -------------------------------------------------------

# The entries this process wrote or looked up: its own trims never evict
# them (other processes' spare them for GRACE_S seconds).
_held = set()


def used(entry: Path) -> bool:
    """Mark an entry as used now; False when it is gone (a miss). A cache
    that cannot be written keeps its old times (nothing evicts there)."""
    try:
        os.utime(entry)
        _held.add(str(entry))
        return True
    except FileNotFoundError:
        return False
    except OSError:
        return os.path.exists(entry)


def load(entry: Path):
    """The marshalled payload of a file entry, marked used; None for a
    missing or unreadable one."""
    try:
        with open(entry, "rb") as f:
            data = marshal.load(f)
    except (OSError, EOFError, ValueError, TypeError):
        return None
    used(entry)
    return data


def store(entry: Path, payload) -> None:
    """`payload` marshalled into a file entry (see write_entry)."""
    try:
        data = marshal.dumps(payload)
    except ValueError:
        return
    write_entry(entry, data)


def write_entry(entry: Path, data: bytes) -> bool:
    """A file entry written aside and renamed, so that a parallel run reads
    all of it or nothing; False (and nothing left behind) when the cache
    cannot be written, which is not an error."""
    tmp = entry.with_name(f"{TEMP_PREFIX}{os.getpid()}-{entry.name}")
    try:
        entry.parent.mkdir(parents=True, exist_ok=True)
        with open(tmp, "wb") as f:
            f.write(data)
        os.replace(tmp, entry)
        _held.add(str(entry))
    except OSError:
        try:
            os.unlink(tmp)
        except OSError:
            pass
        return False
    added()
    return True


def temporary_folder(parent: Path) -> Path:
    """A new folder in `parent` (an area) to build a folder entry in; its
    name says whose it is, so that one a killed run left is swept
    (build/host.py sweep_stale). Raises OSError."""
    import tempfile
    parent.mkdir(parents=True, exist_ok=True)
    return Path(tempfile.mkdtemp(prefix=f"{TEMP_PREFIX}{os.getpid()}-", dir=parent))


def commit_folder(tmp: Path, final: Path, complete) -> None:
    """The folder built in `tmp` takes its place as the entry `final` in one
    rename; when a parallel build got there first, its entry stays if
    `complete(final)` says it is whole, else it is replaced. `tmp` is gone
    afterwards. Raises OSError."""
    try:
        os.rename(tmp, final)
    except OSError:
        if not complete(final):
            _remove_folder(final)
            os.rename(tmp, final)
    finally:
        if tmp.exists():
            _remove_folder(tmp)
    _held.add(str(final))
    added()


FULL_BELOW = 32 << 20          # a cache folder with less free space is full


def problem(folder: Path) -> Optional[str]:
    """Why no entry can be written in `folder` (an area), or None: it cannot
    be made or written in, or its disk is (almost) full."""
    try:
        folder.mkdir(parents=True, exist_ok=True)
        temporary_folder(folder).rmdir()
        st = os.statvfs(folder)
    except OSError as exc:
        from .output import describe_os_error
        return describe_os_error(exc, exc.filename or folder, "write in")
    free = st.f_bavail * st.f_frsize
    if free < FULL_BELOW:
        return f"cannot write in {folder}: the disk is full ({free >> 10} KiB free)"
    return None


_scratch = {}


def writable_area(name: str) -> Path:
    """The area to build a new entry in: the cache's, or, when it cannot
    take one (see `problem`), a temporary folder of this process, removed
    when it ends, with one line on standard error saying so."""
    folder = area(name)
    reason = problem(folder)
    if reason is None:
        return folder
    if name not in _scratch:
        import atexit
        import sys
        import tempfile
        _scratch[name] = Path(tempfile.mkdtemp(prefix=f"{TEMP_PREFIX}{os.getpid()}-{name}-"))
        atexit.register(_remove_folder, _scratch[name])
        print(f"epuckc: note: building in a temporary folder, the cache is unusable ({reason}); "
              "set EPUCKC_CACHE_DIR to a writable folder", file=sys.stderr)
    return _scratch[name]


def usable(folder: Path) -> Optional[Path]:
    """`folder` (an area) when it can take new entries, else None."""
    return folder if problem(folder) is None else None


def _remove_folder(folder: Path) -> None:
    import shutil
    shutil.rmtree(folder, ignore_errors=True)


# ---- the bound ---------------------------------------------------------------------------

_SUFFIXES = {"": 1, "K": 1 << 10, "M": 1 << 20, "G": 1 << 30, "T": 1 << 40}


def parse_size(text: str) -> int:
    """`123`, `500K`, `500M`, `2G` (binary multiples; a trailing `B` or
    `iB` allowed) as bytes; ValueError otherwise."""
    t = text.strip().upper()
    for tail in ("IB", "B"):
        if t.endswith(tail) and len(t) > len(tail):
            t = t[: -len(tail)]
            break
    suffix = t[-1:] if t[-1:] in _SUFFIXES else ""
    number = t[: len(t) - len(suffix)].strip()
    try:
        value = float(number)
    except ValueError:
        raise ValueError(f"`{text}` is not a size (like 500M or 2G)") from None
    if not number or value < 0 or value != value:
        raise ValueError(f"`{text}` is not a size (like 500M or 2G)")
    return int(value * _SUFFIXES[suffix])


def bound() -> tuple:
    """(the bound in bytes, why it is what it is): EPUCKC_CACHE_MAX, or the
    default when it is unset or not a size."""
    text = os.environ.get("EPUCKC_CACHE_MAX")
    if text is None or not text.strip():
        return DEFAULT_BOUND, "the default"
    try:
        return parse_size(text), f"EPUCKC_CACHE_MAX={text}"
    except ValueError as exc:
        return DEFAULT_BOUND, f"the default: EPUCKC_CACHE_MAX {exc}"


def _seconds(variable: str, default: float) -> float:
    try:
        return max(0.0, float(os.environ.get(variable, default)))
    except ValueError:
        return default


def added() -> None:
    """A new entry was written: trim the cache if no process did it in the
    last TRIM_EVERY_S seconds (EPUCKC_CACHE_TRIM_EVERY, for tests). The
    stamp is renewed first, so that parallel writers do not all trim."""
    stamp = cache_dir() / STAMP
    now = time.time()
    try:
        if now - os.stat(stamp).st_mtime < _seconds("EPUCKC_CACHE_TRIM_EVERY", TRIM_EVERY_S):
            return
    except FileNotFoundError:
        pass
    except OSError:
        return
    try:
        with open(stamp, "ab"):
            pass
        os.utime(stamp)
    except OSError:
        return
    trim()


# ---- looking at the entries --------------------------------------------------------------

class Entry:
    """One entry: its path, its size in bytes (a folder's files together),
    when it was last used, and whether it is a folder."""
    __slots__ = ("path", "size", "used", "folder")

    def __init__(self, path: Path, size: int, used: float, folder: bool):
        self.path, self.size, self.used, self.folder = path, size, used, folder


def _folder_size(path: str) -> int:
    total = 0
    try:
        with os.scandir(path) as it:
            for item in it:
                try:
                    if item.is_dir(follow_symlinks=False):
                        total += _folder_size(item.path)
                    else:
                        total += item.stat(follow_symlinks=False).st_size
                except OSError:
                    pass
    except OSError:
        pass
    return total


def entries(name: str) -> list:
    """The entries of one area (temporary ones, being written, left out)."""
    out = []
    try:
        with os.scandir(cache_dir() / name) as it:
            items = list(it)
    except OSError:
        return out
    for item in items:
        if item.name.startswith(TEMP_PREFIX):
            continue
        try:
            st = item.stat(follow_symlinks=False)
            folder = item.is_dir(follow_symlinks=False)
        except OSError:
            continue
        size = _folder_size(item.path) if folder else st.st_size
        out.append(Entry(Path(item.path), size, st.st_mtime, folder))
    return out


def temporary_size(name: str) -> int:
    """The bytes of an area's temporary files and folders (builds under
    way, or left by killed runs until they are swept)."""
    total = 0
    try:
        with os.scandir(cache_dir() / name) as it:
            for item in it:
                if item.name.startswith(TEMP_PREFIX):
                    try:
                        total += _folder_size(item.path) if item.is_dir(follow_symlinks=False) \
                            else item.stat(follow_symlinks=False).st_size
                    except OSError:
                        pass
    except OSError:
        pass
    return total


# What older epuckcs left directly in the cache folder: evicted first. Any
# other file there is not epuckc's (EPUCKC_CACHE_DIR may name a folder that
# holds more): it is never removed.
LEGACY = re.compile(r"tables-[0-9a-f]{8}\.marshal")


def others() -> list:
    """What older epuckcs left in the cache folder (LEGACY), as entries:
    they count, and go first."""
    out = []
    try:
        with os.scandir(cache_dir()) as it:
            items = list(it)
    except OSError:
        return out
    for item in items:
        if not LEGACY.fullmatch(item.name):
            continue
        try:
            folder = item.is_dir(follow_symlinks=False)
            size = _folder_size(item.path) if folder else item.stat(follow_symlinks=False).st_size
        except OSError:
            continue
        out.append(Entry(Path(item.path), size, 0.0, folder))
    return out


# ---- eviction ----------------------------------------------------------------------------

def evict(entry: Entry, grace: float) -> bool:
    """Remove one entry unless it was used in the last `grace` seconds,
    looked at again now, or one this process holds; False when it stays
    (or cannot go)."""
    if str(entry.path) in _held:
        return False
    try:
        if time.time() - os.stat(entry.path, follow_symlinks=False).st_mtime < grace:
            return False
        _remove(entry)
    except OSError:
        return False
    return True


def _remove(entry: Entry) -> None:
    """A file is unlinked; a folder is renamed aside first (one step, so
    that nobody finds half of it), then removed. Raises OSError."""
    path = entry.path
    if not entry.folder:
        os.unlink(path)
        return
    aside = path.with_name(f"{TEMP_PREFIX}{os.getpid()}-evicted-{path.name}")
    os.rename(path, aside)
    _remove_folder(aside)


def trim(limit: Optional[int] = None) -> tuple:
    """Evict the least recently used entries until the cache holds at most
    `limit` bytes (bound() without it), sparing those used in the last
    GRACE_S seconds (EPUCKC_CACHE_GRACE, for tests); (entries evicted,
    bytes freed)."""
    if limit is None:
        limit = bound()[0]
    grace = _seconds("EPUCKC_CACHE_GRACE", GRACE_S)
    found = others() + sorted((e for name in AREAS for e in entries(name)),
                              key=lambda e: e.used)
    total = sum(e.size for e in found) + sum(temporary_size(name) for name in AREAS)
    removed = freed = 0
    for entry in found:
        if total <= limit:
            break
        if evict(entry, grace):
            total -= entry.size
            removed += 1
            freed += entry.size
    return removed, freed


def clear() -> tuple:
    """Remove every entry of every area, and what else the folder holds
    (temporary folders of builds under way stay); (entries, bytes).
    Raises OSError when an entry cannot be removed (after trying all)."""
    removed = freed = 0
    problem = None
    for entry in others() + [e for name in AREAS for e in entries(name)]:
        try:
            _remove(entry)
        except FileNotFoundError:
            continue
        except OSError as exc:
            problem = problem or exc
            continue
        removed += 1
        freed += entry.size
    if problem is not None:
        raise problem
    return removed, freed
