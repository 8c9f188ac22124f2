"""A class folder: its exercises, and Check.

An exercise is a folder that holds an `epuckc-test.toml` (docs/testing.md,
"A teacher's workflow"): its checks apply to every rule file below it, the
students' files, down to the next folder with its own. The folder the
studio opened may be one exercise or hold many. An exercise's title is the
first comment line of its `epuckc-test.toml` (`# Lab 3: leave the box`),
else its folder's name.

Check is `epuckc test` on the files asked for, run as a child process
(`python -m epuckc.studio.exercises FILE...`, which prints JSON): the
testing package's runner, with the same comparison, diffs and property
checks, and the JSON trace of each case's run kept for its replay.
"""
from __future__ import annotations

import json
import os
import sys
from pathlib import Path

from .workspace import PathRefused, Workspace

OPTIONS = "epuckc-test.toml"


def _title(options: Path, fallback: str) -> str:
    try:
        for line in options.read_text(encoding="utf-8").splitlines():
            if line.startswith("#"):
                return line.lstrip("#").strip() or fallback
            if line.strip():
                break
    except (OSError, UnicodeDecodeError):
        pass
    return fallback


def exercises(workspace: Workspace) -> list:
    """[{"folder", "title", "files"}] for each exercise, by folder."""
    files = workspace.files()
    folders = sorted({f.rpartition("/")[0] for f in files if f.rpartition("/")[2] == OPTIONS})
    found = []
    for folder in folders:
        inner = [f for f in folders if f != folder and (folder == "" or f.startswith(folder + "/"))]
        mine = [f for f in files if f.endswith(".epk")
                and (folder == "" or f.startswith(folder + "/"))
                and not any(f.startswith(i + "/") for i in inner)]
        options = workspace.root / folder / OPTIONS
        found.append({"folder": folder, "title": _title(options, folder or workspace.root.name),
                      "files": mine})
    return found


def check_command(workspace: Workspace, paths: list) -> list:
    """The child's argv for a Check of these files or exercise folders."""
    argv = [sys.executable, "-m", "epuckc.studio.exercises"]
    for rel in paths:
        path = workspace.resolve(rel) if rel else workspace.root
        if path.is_file() and path.suffix != ".epk":
            raise PathRefused(f"{rel!r}: Check takes rule files (.epk) and exercise folders")
        argv.append(str(path))
    return argv


def _records_text(records) -> str:
    return "".join(json.dumps(r) + "\n" for r in records or ())


def run_check(paths: list, root: Path) -> list:
    """What the child does: the outcomes of the cases under the paths."""
    from ..testing.case import UsageError, discover
    from ..testing.runner import describe, run_cases
    try:
        cases = discover(paths)
    except UsageError as exc:
        return [{"file": "", "status": "error", "report": str(exc)}]
    # the folder's own files only: a link to a rule file elsewhere is not the class's
    cases = [c for c in cases if root in Path(os.path.realpath(c.path)).parents]
    outcomes = run_cases(cases, jobs=min(2, os.cpu_count() or 1))
    return [{"file": Path(o.case.path).resolve().relative_to(root).as_posix(),
             "status": o.status, "report": describe(o), "problems": o.problems,
             "trace": _records_text(o.records)} for o in outcomes]


def main(argv: list) -> int:
    root = Path(os.path.realpath(os.getcwd()))
    print(json.dumps(run_check(argv, root)))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
