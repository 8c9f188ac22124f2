"""Running cases and blessing their expected files.

A case is checked here (its diagnostics, without colour, the file named
relative to its folder) and, when it has no errors, run as `epuckc run
NAME.epk` in a child process started in the case's folder: standard output
is the readable trace exactly as a user sees it, and a JSON-lines trace
is written on the side for the property checks. A case whose run was
recorded on a robot (`recorded = "run.jsonl"`, by `epuckc monitor`) is
not run: the recording is its JSON trace, and the readable trace is what
the monitor printed of it. Cases run in parallel on
the machine's processors (threads, each waiting for its child); the build
cache makes a second run of an unchanged program cheap. Outcomes come
back in the order of the cases."""
from __future__ import annotations

import json
import os
import re
import subprocess
import sys
import tempfile
import threading
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass, field
from pathlib import Path
from typing import Optional

from .case import Case
from .compare import divergence, first_difference, trimmed_diff

PASSED, FAILED, SKIPPED = "passed", "failed", "skipped"
# what produced each expected file, in the order they are compared
KINDS = {".diag": "the diagnostics", ".trace": "the readable trace", ".c": "the generated C"}

_FRONT_END = threading.Lock()       # the checker keeps module state: one file at a time


@dataclass
class Outcome:
    case: Case
    status: str = PASSED
    problems: list = field(default_factory=list)     # text blocks, each one failure
    written: list = field(default_factory=list)      # with bless: "NAME.trace (new)", ...
    reason: str = ""                                  # why skipped
    records: Optional[list] = None                    # the run's JSON trace (the studio's replay)


@dataclass
class Produced:
    """What a case produces now: the text of each kind (None: nothing)."""
    texts: dict
    records: Optional[list] = None
    has_errors: bool = False
    run_problem: Optional[str] = None
    skipped: Optional[str] = None


def _package_root() -> str:
    """The folder that holds the epuckc package this process runs, for the
    children to run the same one."""
    return str(Path(__file__).resolve().parents[2])


def _program_name(path: Path) -> str:
    import re
    return re.sub(r"[^A-Za-z0-9_-]", "_", path.stem) or "program"


def _front_end(case: Case):
    """(diagnostics text, generated C or None, has errors, the names of
    its trace or None)."""
    from ..check.frontend import InputError, check_file
    from ..diagnostics import Report
    from ..diagnostics.render import render_report
    report = Report()
    with _FRONT_END:
        try:
            text = None
            if case.constants:      # as `epuckc run -D NAME=VALUE` gives them
                from ..check.defines import DefineError, apply_defines
                try:
                    text = apply_defines(case.path.read_text(encoding="utf-8"), case.constants,
                                         case.path.name)
                except (DefineError, UnicodeDecodeError, OSError) as exc:
                    return f"{case.path.name}: error: {exc}\n", None, True, None
            result = check_file(case.path, report, shown_name=case.path.name, text=text)
        except InputError as exc:
            report.diagnostics.append(exc.diagnostic(case.path.name))
            return render_report(report, "human", colour=False), None, True, None
        text = render_report(report, "human", colour=False)
        if result.checked is None or report.error_count:
            return text, None, True, None
        c_text = names = None
        if case.compare_c or case.recorded is not None:
            from ..emit.program import emit_program
            generated = emit_program(result.checked, result.source.text,
                                     _program_name(case.path))
            c_text = generated.c_text if case.compare_c else None
            names = generated.names
    return text, c_text, False, names


def _recorded(case: Case, names: dict, produced: Produced) -> None:
    """A robot's recorded trace as the case's run: its records, and the
    readable trace `epuckc monitor` printed of them (the steps' texts from
    the program's names)."""
    from ..sim.readable import readable_trace
    try:
        lines = case.recorded.read_text(encoding="utf-8").splitlines()
        produced.records = [json.loads(line) for line in lines if line.strip()]
        steps = names.get("steps", {})
        produced.texts[".trace"] = readable_trace(produced.records,
                                                  lambda a: steps.get(str(a), []))
    except (OSError, UnicodeDecodeError, ValueError, KeyError, TypeError) as exc:
        produced.run_problem = (f"the recorded trace {case.recorded.name} is not a trace that "
                                f"`epuckc monitor --trace` writes ({exc})")


def _run(case: Case, trace_path: Path) -> subprocess.CompletedProcess:
    command = [sys.executable, "-m", "epuckc", "run", case.path.name,
               "--time-limit", f"{case.time_limit_ms}ms", "--seed", str(case.seed),
               "--trace", str(trace_path)]
    for name, value in case.constants.items():
        command += ["-D", f"{name}={value}"]
    if case.scenario is not None:
        command += ["--scenario", os.path.relpath(case.scenario, case.folder)]
    if case.world is not None:
        command += ["--world", os.path.relpath(case.world, case.folder)]
    env = dict(os.environ)
    root = _package_root()
    if not {"site-packages", "dist-packages"} & set(Path(root).parts):
        # a checkout (python3 -m epuckc from it): the child runs the same one
        env["PYTHONPATH"] = os.pathsep.join([root] + [p for p in
                                            env.get("PYTHONPATH", "").split(os.pathsep) if p])
    env["NO_COLOR"] = "1"
    for setting in ("EPUCK_QUIET", "EPUCK_SEED", "EPUCK_POSE_MS"):
        env.pop(setting, None)
    return subprocess.run(command, cwd=case.folder, env=env, capture_output=True,
                          text=True, encoding="utf-8", errors="replace")


def produce(case: Case) -> Produced:
    """Check and run the case; what it produces now."""
    diag, c_text, has_errors, names = _front_end(case)
    texts = {".diag": diag or None, ".trace": None, ".c": c_text}
    produced = Produced(texts, has_errors=has_errors)
    if has_errors or not (case.compare_trace or case.expect):
        return produced
    if case.recorded is not None:
        _recorded(case, names, produced)
        return produced
    if case.world is not None:
        from ..sim.enki import ENKI_MISSING, enki_available
        if not enki_available():
            produced.skipped = ENKI_MISSING
            return produced
    with tempfile.TemporaryDirectory(prefix="epuckc-test-") as tmp:
        trace_path = Path(tmp) / "trace.jsonl"
        proc = _run(case, trace_path)
        if proc.returncode not in (0, 3):
            produced.run_problem = (f"`epuckc run {case.path.name}` failed (exit status "
                                    f"{proc.returncode}):\n" + _tail(proc.stderr))
            return produced
        texts[".trace"] = proc.stdout
        try:
            produced.records = [json.loads(line) for line in
                                trace_path.read_text(encoding="utf-8").splitlines() if line]
        except (OSError, ValueError) as exc:
            produced.run_problem = f"the run wrote no readable JSON trace ({exc})"
    return produced


def _tail(text: str, lines: int = 20) -> str:
    rows = text.rstrip("\n").splitlines()
    if len(rows) > lines:
        rows = [f"... ({len(rows) - lines} lines above)"] + rows[-lines:]
    return "\n".join("    " + r for r in rows)


def _wanted(case: Case, kind: str, produced: Produced) -> bool:
    """Whether the expected file of this kind takes part in the case."""
    if kind == ".trace":
        return case.compare_trace
    if kind == ".c":
        return case.compare_c
    return case.compare_diag


def _compare(case: Case, kind: str, expected: Optional[str], actual: Optional[str],
             bless_hint: str) -> Optional[str]:
    name = case.expected(kind).name
    if expected is None and actual is None:
        return None
    if expected is None:
        return (f"{name} is missing ({KINDS[kind]} of this run has no expected file to be "
                f"compared with); {bless_hint} writes it from this run: read it before you "
                "commit it")
    if actual is None:
        why = ("the program has errors, so it does not run" if kind in (".trace", ".c")
               else "this run has no diagnostics")
        return f"{name} is there but {why}; {bless_hint} removes it"
    tolerance = case.tolerance if kind == ".trace" else None
    a, b = expected.splitlines(), actual.splitlines()
    index = first_difference(a, b, tolerance)
    if index is None:
        if tolerance is not None or expected == actual:
            return None
        index = 0
    header = f"{KINDS[kind]} differs from {name}"
    if kind == ".trace":
        header += f"\n  {divergence(a, b, index)}"
    diff = trimmed_diff(expected, actual, f"{name} (expected)", f"{case.path.name} (this run)",
                        index)
    return header + "\n" + diff


_INPUT_LINE = re.compile(r"\[ *\d+ ms\] input ")


def _as_recorded(expected: str, records) -> str:
    """The golden of a simulated run as a robot's recording can match it:
    the robot's tracer sends what the program did, not what its sensors
    read (the scenario's `input` lines are the simulation's), so they are
    left out unless the recording has inputs of its own."""
    if any(r.get("kind") == "input" for r in records or ()):
        return expected
    return "".join(line for line in expected.splitlines(True) if not _INPUT_LINE.match(line))


def _read(path: Path) -> Optional[str]:
    try:
        return path.read_text(encoding="utf-8")
    except FileNotFoundError:
        return None


def run_case(case: Case, bless: bool = False, bless_hint: str = "`epuckc test --bless`") -> Outcome:
    outcome = Outcome(case)
    produced = produce(case)
    outcome.records = produced.records
    if produced.skipped:
        outcome.status, outcome.reason = SKIPPED, produced.skipped
        return outcome
    if produced.run_problem:
        outcome.problems.append(produced.run_problem)
    for kind in KINDS:
        if not _wanted(case, kind, produced):
            continue
        path = case.expected(kind)
        expected = _read(path)
        actual = produced.texts[kind]
        if kind == ".trace" and produced.run_problem:
            continue        # nothing to compare with; the problem says why
        if kind == ".trace" and case.recorded is not None and expected is not None and not bless:
            expected = _as_recorded(expected, produced.records)
        if bless:
            _bless(path, expected, actual, outcome)
            continue
        problem = _compare(case, kind, expected, actual, bless_hint)
        if problem:
            outcome.problems.append(problem)
    if case.expect and produced.records is not None:
        from .props import check_properties
        for text, why in check_properties(case.expect, produced.records):
            outcome.problems.append(f"expect `{text}`: {why}")
    elif case.expect and produced.has_errors:
        problem = "the property checks need a run, but the program has errors"
        if not case.compare_diag:
            problem += ":\n" + "\n".join("  " + row if row else ""
                                          for row in (produced.texts[".diag"] or "").splitlines())
        outcome.problems.append(problem)
    if outcome.problems:
        outcome.status = FAILED
    return outcome


def _bless(path: Path, expected: Optional[str], actual: Optional[str], outcome: Outcome):
    from ..base.output import write_atomic
    if actual == expected:
        return
    if actual is None:
        path.unlink()
        outcome.written.append(f"{path.name} (removed)")
        return
    write_atomic(path, actual)
    outcome.written.append(f"{path.name} ({'new' if expected is None else 'changed'})")


def run_cases(cases: list, bless: bool = False, jobs: Optional[int] = None,
              bless_hint: str = "`epuckc test --bless`", on_done=None) -> list:
    """Every case, `jobs` at once (default: the processors); the outcomes
    in the cases' order. `on_done(outcome)` is called in that order too, as
    soon as each outcome and those before it are known."""
    jobs = jobs or os.cpu_count() or 1
    outcomes = [None] * len(cases)
    if not cases:
        return []
    with ThreadPoolExecutor(max_workers=min(jobs, len(cases))) as pool:
        futures = [pool.submit(run_case, case, bless, bless_hint) for case in cases]
        for i, future in enumerate(futures):
            outcomes[i] = future.result()
            if on_done is not None:
                on_done(outcomes[i])
    return outcomes


def summary(outcomes: list) -> str:
    passed = sum(o.status == PASSED for o in outcomes)
    failed = sum(o.status == FAILED for o in outcomes)
    skipped = sum(o.status == SKIPPED for o in outcomes)
    line = f"{passed} passed, {failed} failed"
    if skipped:
        line += f", {skipped} skipped"
    written = sum(len(o.written) for o in outcomes)
    if written:
        line += f"; {written} expected file{'s' if written > 1 else ''} written"
    return line


def describe(outcome: Outcome) -> str:
    """The report of one case: its name and status, and what went wrong."""
    shown = outcome.case.shown
    lines = []
    if outcome.status == SKIPPED:
        lines.append(f"SKIP {shown}: {outcome.reason}")
    elif outcome.status == FAILED:
        lines.append(f"FAIL {shown}")
        for problem in outcome.problems:
            lines.extend("  " + row if row else "" for row in problem.splitlines())
    for written in outcome.written:
        lines.append(f"blessed {shown}: {written}")
    return "\n".join(lines)
