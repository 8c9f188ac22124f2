"""The optional C accelerator of the front end (epuckc/syntax/_front*.c).

`front()` is the compiled module, or None when epuckc runs on Python
alone: when it was not built (it is optional: `pip install` builds it when
a C compiler is there), when a C source beside it changed after it was
built (in a checkout), or when EPUCKC_PURE_PYTHON is set. Both ways give
the same results; tests/syntax/test_front_accel.py compares them.
"""
from __future__ import annotations

import os
from functools import lru_cache

# The extension's files, as setup.py lists them (a test keeps the two equal).
SOURCES = ("_front.c", "_front_lex.c", "_front_make.c")
HEADERS = ("_front.h",)


@lru_cache(maxsize=1)
def front():
    if os.environ.get("EPUCKC_PURE_PYTHON"):
        return None
    try:
        from . import _front
    except ImportError:
        return None
    return None if stale(_front.__file__) else _front


def stale(built: str) -> bool:
    """Whether a C source or header beside a built module (in a checkout,
    not in a wheel) was changed after the build: a stale build is not used,
    and tests/syntax/test_front_accel.py says to rebuild it."""
    try:
        built_at = os.stat(built).st_mtime
    except OSError:
        return False
    folder = os.path.dirname(built)
    for name in SOURCES + HEADERS:
        try:
            if os.stat(os.path.join(folder, name)).st_mtime > built_at:
                return True
        except OSError:
            continue
    return False
