"""`epuckc cache`: what epuckc's cache folder holds (`--info`, the default),
emptied (`--clear`) or trimmed to its bound now (`--trim`); the rules of
the folder are base/cache.py's. Exit status: 0 done, 1 the folder could
not be emptied (what is in the way is named)."""
from __future__ import annotations

import os
import sys

from ..base import cache
from ..base.output import describe_os_error
from ..base.resources import cache_dir
from .commands import EXIT_ERRORS, EXIT_OK, _error


def add_parser(sub, run):
    p = sub.add_parser(
        "cache", help="show, trim or empty epuckc's cache folder",
        description="epuckc keeps what it can rebuild (parse tables, checks, builds, runs, the "
                    "world runner) in its cache folder: $EPUCKC_CACHE_DIR, else "
                    "$XDG_CACHE_HOME/epuckc, else ~/.cache/epuckc. It is kept under a bound, "
                    "$EPUCKC_CACHE_MAX (such as 500M or 2G; default 1G), by evicting what was "
                    "used longest ago. Without an option: what each cache holds. Exit status: "
                    "0 done, 1 the folder could not be emptied.")
    what = p.add_mutually_exclusive_group()
    what.add_argument("--info", action="store_true",
                      help="what each cache holds, the folder and the bound (the default)")
    what.add_argument("--clear", action="store_true",
                      help="remove everything the cache holds (builds under way are left alone)")
    what.add_argument("--trim", action="store_true",
                      help="evict the entries used longest ago until the cache is within its "
                           "bound (epuckc does it by itself after writing, at most once a minute)")
    p.set_defaults(run=run)


def size_text(n: int) -> str:
    """Bytes for people: 0 B, 812 B, 3.4 KiB, 12.0 MiB, 1.0 GiB."""
    value = float(n)
    for unit in ("B", "KiB", "MiB", "GiB"):
        if value < 1024 or unit == "GiB":
            return f"{n} B" if unit == "B" else f"{value:.1f} {unit}"
        value /= 1024
    return f"{n} B"     # (not reached)


def _entries(n: int) -> str:
    return f"{n} entr{'y' if n == 1 else 'ies'}"


def cmd_cache(args) -> int:
    folder = cache_dir()
    if args.clear:
        try:
            removed, freed = cache.clear()
        except OSError as exc:
            _error(describe_os_error(exc, exc.filename or folder, "remove") + "; the rest of "
                   "the cache was removed")
            return EXIT_ERRORS
        print(f"removed {_entries(removed)} ({size_text(freed)}) "
              f"from {folder}")
        return EXIT_OK
    if args.trim:
        removed, freed = cache.trim()
        limit, why = cache.bound()
        print(f"evicted {_entries(removed)} ({size_text(freed)}); "
              f"the bound is {size_text(limit)} ({why})")
        return EXIT_OK
    return _info(folder)


def _info(folder) -> int:
    limit, why = cache.bound()
    exists = os.path.isdir(folder)
    writable = exists and os.access(folder, os.W_OK)
    state = "" if writable else (" (not there yet)" if not exists else " (read-only: not kept)")
    print(f"cache folder: {folder}{state}")
    rows, total = [], 0
    for name, what in cache.AREAS.items():
        found = cache.entries(name)
        size = sum(e.size for e in found) + cache.temporary_size(name)
        total += size
        rows.append((name, _entries(len(found)), size_text(size), what))
    others = cache.others()
    if others:
        size = sum(e.size for e in others)
        total += size
        rows.append(("(older)", _entries(len(others)), size_text(size),
                     "an older epuckc's parse tables (evicted first)"))
    widths = [max(len(r[i]) for r in rows) for i in range(3)]
    for name, count, size, what in rows:
        print(f"  {name:<{widths[0]}}  {count:<{widths[1]}}  {size:>{widths[2]}}  {what}")
    print(f"total {size_text(total)} of a bound of {size_text(limit)} ({why})")
    sys.stdout.flush()
    return EXIT_OK
