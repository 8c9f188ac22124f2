"""Running a host harness executable: the environment that tells it the
time limit, the scenario, where to write the trace and how often to add
pose records."""
from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path
from typing import Optional


def run_executable(exe: Path, scenario: Optional[str], time_limit_ms: int,
                   trace: Optional[str], pose_ms: Optional[int] = None) -> int:
    """Run the executable, its trace going to our stdout; its exit status.
    Raises OSError when it cannot be started."""
    env = dict(os.environ)
    env["EPUCK_TIME_LIMIT_MS"] = str(time_limit_ms)
    for setting in ("EPUCK_SCENARIO", "EPUCK_TRACE", "EPUCK_POSE_MS"):
        env.pop(setting, None)
    if pose_ms:
        env["EPUCK_POSE_MS"] = str(pose_ms)
    # The harness names the options typed here in its messages, not its
    # environment variables.
    env["EPUCK_FRONTEND"] = "epuckc"
    if scenario:
        env["EPUCK_SCENARIO"] = scenario     # as typed: the messages show it
    if trace == "-":            # JSON lines on stdout, instead of the readable trace
        env["EPUCK_TRACE"] = "/dev/stdout"
        env["EPUCK_QUIET"] = "1"
    elif trace:
        env["EPUCK_TRACE"] = trace
    sys.stdout.flush()
    return subprocess.run([str(exe)], env=env).returncode
