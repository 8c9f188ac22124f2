"""Comparing what a case produced with what it should: exactly, or with
tolerances on the numbers of a readable trace (pose, heading, times); a
unified diff trimmed to the first difference with its context; and the
point where two readable traces diverge, in words."""
from __future__ import annotations

import difflib
import re
from typing import Optional

from .case import Tolerance

CONTEXT = 3
MAX_DIFF_LINES = 40

# Numbers of a readable trace line that physics moves: times in ms, the
# pose and the heading. Everything else in a line must be equal.
_TIME = re.compile(r"(\[\s*)(-?\d+)( ms\])|(\bat )(-?\d+)( ms\b)")
_POSE = re.compile(r"(pose \()(-?\d+(?:\.\d+)?)(, )(-?\d+(?:\.\d+)?)(\) )(-?\d+(?:\.\d+)?)( deg)")


def _shape(line: str):
    """The line with its times and pose replaced by holes, and the values."""
    times, poses = [], []

    def time(m):
        if m.group(2) is not None:
            times.append(int(m.group(2)))
            return m.group(1).rstrip() + "#T" + m.group(3)
        times.append(int(m.group(5)))
        return m.group(4) + "#T" + m.group(6)

    def pose(m):
        poses.append((float(m.group(2)), float(m.group(4)), float(m.group(6))))
        return "pose (#X, #Y) #H deg"
    shaped = _POSE.sub(pose, _TIME.sub(time, line))
    return shaped, times, poses


def _angle(a: float, b: float) -> float:
    d = abs(a - b) % 360.0
    return min(d, 360.0 - d)


def lines_match(expected: str, actual: str, tolerance: Optional[Tolerance]) -> bool:
    if expected == actual:
        return True
    if tolerance is None or not tolerance.any():
        return False
    s1, t1, p1 = _shape(expected)
    s2, t2, p2 = _shape(actual)
    if s1 != s2 or len(t1) != len(t2) or len(p1) != len(p2):
        return False
    eps = 1e-9
    if any(abs(a - b) > tolerance.time_ms + eps for a, b in zip(t1, t2)):
        return False
    for (x1, y1, h1), (x2, y2, h2) in zip(p1, p2):
        if ((x1 - x2) ** 2 + (y1 - y2) ** 2) ** 0.5 > tolerance.pose_mm + eps:
            return False
        if _angle(h1, h2) > tolerance.heading_deg + eps:
            return False
    return True


def first_difference(expected: list, actual: list, tolerance: Optional[Tolerance] = None):
    """The index of the first line that differs, or None when they match."""
    for i, (a, b) in enumerate(zip(expected, actual)):
        if not lines_match(a, b, tolerance):
            return i
    if len(expected) != len(actual):
        return min(len(expected), len(actual))
    return None


def trimmed_diff(expected: str, actual: str, expected_name: str, actual_name: str,
                 start: int = 0) -> str:
    """A unified diff from the hunk that holds line `start` on, at most
    MAX_DIFF_LINES lines; what is cut is counted."""
    a, b = expected.splitlines(), actual.splitlines()
    lines = list(difflib.unified_diff(a, b, expected_name, actual_name, n=CONTEXT, lineterm=""))
    head, body = lines[:2], lines[2:]
    # skip hunks that end before the first real difference (tolerated ones)
    hunks, current = [], []
    for line in body:
        if line.startswith("@@") and current:
            hunks.append(current)
            current = []
        current.append(line)
    if current:
        hunks.append(current)
    kept = []
    for hunk in hunks:
        m = re.match(r"@@ -(\d+)(?:,(\d+))?", hunk[0])
        first = int(m.group(1)) if m else 1
        length = int(m.group(2)) if m and m.group(2) is not None else 1
        if first + length - 1 >= start + 1 - CONTEXT or not kept and hunk is hunks[-1]:
            kept.append(hunk)
    out = head + [line for hunk in kept for line in hunk]
    if len(out) > MAX_DIFF_LINES:
        rest = len(out) - MAX_DIFF_LINES
        out = out[:MAX_DIFF_LINES] + [f"... ({rest} more diff line{'s' if rest > 1 else ''})"]
    return "\n".join(out)


_LINE = re.compile(r"^(?:(?P<robot>[\w-]+): )?\[\s*(?P<t>-?\d+) ms\] (?P<kind>\w+)\s+(?P<rest>.*)$")
_SUMMARY = re.compile(r"^(?:(?P<robot>[\w-]+): )?(?P<kind>exit|timeout) at (?P<t>\d+) ms: ")


def _describe(line: str):
    """(time or None, words) for a readable trace line."""
    m = _LINE.match(line)
    if m is None:
        s = _SUMMARY.match(line)
        if s:
            return int(s.group("t")), f"the run ended ({line.strip()})"
        return None, f"`{line.strip()}`"
    who = f"robot {m.group('robot')}: " if m.group("robot") else ""
    kind, rest = m.group("kind"), m.group("rest")
    rest = re.sub(r"\s*pose \(.*$", "", rest)
    if kind == "event":
        rest = re.sub(r"^#\d+\s+", "", rest)
        named = re.search(r"\brule (\w+):", rest)
        if named:
            what = f"rule `{named.group(1)}` fired"
        else:
            where = rest.split(" ", 1)
            what = (f"the rule at {where[0]} (`{where[1]}`) fired" if len(where) == 2
                    else f"event `{rest}` fired")
    elif kind == "action":
        what = f"action `{re.sub(r'^#[0-9]+ ', '', rest)}` ran"
    elif kind == "exit":
        what = "the program exited"
    elif kind == "timeout":
        what = "the time limit was reached"
    else:
        what = f"{kind} {rest}".strip()
    return int(m.group("t")), who + what


def divergence(expected: list, actual: list, index: int) -> str:
    """Where behaviour first diverged, in words: the time, and what happened
    there in each trace."""
    if index >= len(expected):
        t, what = _describe(actual[index])
        at = f"at {t:,} ms " if t is not None else ""
        return f"{at}this run goes on where the expected trace ends: {what}"
    if index >= len(actual):
        t, what = _describe(expected[index])
        at = f"at {t:,} ms " if t is not None else ""
        return f"{at}this run has ended where the expected trace goes on: {what}"
    t1, what1 = _describe(expected[index])
    t2, what2 = _describe(actual[index])
    if t1 is not None and t1 == t2 and what1 == what2:
        # the same thing at the same time: what differs is where
        p1, p2 = _POSE.search(expected[index]), _POSE.search(actual[index])
        if p1 and p2:
            return (f"at {t1:,} ms {what1} in both traces, at {p1.group(0)} in the expected "
                    f"one, {p2.group(0)[5:]} in this one")
        return f"at {t1:,} ms {what1} in both traces, but the lines differ"
    if t1 is not None and t1 == t2:
        return f"at {t1:,} ms {what1} in the expected trace, {what2} in this one"
    if t1 is not None and t2 is not None:
        return (f"the expected trace has at {t1:,} ms: {what1}; this one at {t2:,} ms: {what2} "
                f"(first difference from {min(t1, t2):,} ms)")
    return f"line {index + 1}: {what1} in the expected trace, {what2} in this one"
