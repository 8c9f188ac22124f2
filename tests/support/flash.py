"""Running `epuckc flash` as a user does, in a subprocess, always bounded
in time (a flash waits on robots; a test never waits forever)."""
from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

REPO = Path(__file__).resolve().parents[2]
TIMEOUT = 120


def flash(*args, env=None, timeout=TIMEOUT):
    full = dict(os.environ)
    full["PYTHONPATH"] = str(REPO) + os.pathsep + full.get("PYTHONPATH", "")
    full.update(env or {})
    return subprocess.run([sys.executable, "-m", "epuckc", "flash", *map(str, args)],
                          env=full, capture_output=True, text=True, timeout=timeout)
