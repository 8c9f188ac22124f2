"""The optional C accelerator of the front end (epuckc/syntax/_front.c).

`front()` is the compiled module, or None when epuckc runs on Python
alone: when it was not built (it is optional: `pip install` builds it when
a C compiler is there), when the C source beside it changed after it was
built (in a checkout), or when EPUCKC_PURE_PYTHON is set. Both ways give
the same results; tests/syntax/test_front_accel.py compares them.
"""
from __future__ import annotations

import os
from functools import lru_cache


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
    """Whether the C source beside a built module (in a checkout, not in a
    wheel) was changed after the build: a stale build is not used, and
    tests/syntax/test_front_accel.py says to rebuild it."""
    try:
        return os.stat(os.path.join(os.path.dirname(built), "_front.c")).st_mtime > \
            os.stat(built).st_mtime
    except OSError:
        return False
