"""Running epuckc and the programs it builds, for the code generation tests."""
from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

REPO = Path(__file__).resolve().parents[2]
EXAMPLES = REPO / "examples"


def epuckc(*args, cwd=None, env=None, check=False):
    """Run the CLI as a user does, in a subprocess."""
    full_env = dict(os.environ)
    full_env["PYTHONPATH"] = str(REPO) + os.pathsep + full_env.get("PYTHONPATH", "")
    full_env.update(env or {})
    result = subprocess.run([sys.executable, "-m", "epuckc", *map(str, args)], cwd=cwd,
                            env=full_env, capture_output=True, text=True)
    if check and result.returncode != 0:
        raise AssertionError(f"epuckc {' '.join(map(str, args))} failed ({result.returncode}):\n"
                             f"{result.stdout}\n{result.stderr}")
    return result


def run_program(path, tmp_path, *extra, expect=0):
    """`epuckc run` a program; returns (records of the JSON trace, stdout)."""
    trace = tmp_path / f"{Path(path).stem}.jsonl"
    result = epuckc("run", path, "--trace", trace, *extra)
    assert result.returncode == expect, result.stdout + result.stderr
    records = [json.loads(line) for line in trace.read_text().splitlines()]
    return records, result.stdout


def events(records, name_part=""):
    return [r for r in records if r["kind"] == "event" and name_part in r["name"]]
