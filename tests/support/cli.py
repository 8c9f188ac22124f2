"""Helpers shared by the front-end tests."""
from __future__ import annotations

import shlex
from pathlib import Path

from epuckc import cli

CASES = Path(__file__).resolve().parents[1] / "check" / "cases"


def case_args(path: Path) -> list:
    """Extra command-line options a case asks for on its first line:
    `# args: --max-actions 2 --werror`."""
    first = path.read_bytes().split(b"\n", 1)[0].decode("utf-8", "replace")
    prefix = "# args:"
    return shlex.split(first[len(prefix):]) if first.startswith(prefix) else []


def run_cli(argv, capsys) -> tuple:
    """Run `epuckc ARGV` in-process: (exit status, stdout, stderr)."""
    capsys.readouterr()
    status = cli.main(list(argv))
    out = capsys.readouterr()
    return status, out.out, out.err
