"""The size of a run's outputs: past LARGE_BYTES (each of the JSON trace,
the SVG and the replay page), what fills the trace and the option that
leaves it out. Ten robots with a counter set every 20 ms gave 79 MB of
trace, a 16.8 MB SVG and a 33 MB page, and nothing said so."""
from __future__ import annotations

import re
from pathlib import Path
from typing import Optional

LARGE_BYTES = 10_000_000        # 10 MB (docs/world.md, Output)
_KIND = re.compile(r'"kind": "(\w+)"')
_VAR = re.compile(r'"var": "((?:[^"\\]|\\.)*)"')
_NAME = re.compile(r'"name": "((?:[^"\\]|\\.)*)"')


def _shares(trace: Path) -> tuple:
    """(bytes by kind, bytes of `set` records by variable, bytes of
    `event` records by rule, all bytes)."""
    kinds: dict = {}
    variables: dict = {}
    rules: dict = {}
    total = 0
    with open(trace, "rb") as f:
        for raw in f:
            total += len(raw)
            line = raw.decode("utf-8", "replace")
            m = _KIND.search(line)
            kind = m.group(1) if m else "other"
            kinds[kind] = kinds.get(kind, 0) + len(raw)
            if kind == "set":
                v = _VAR.search(line)
                name = v.group(1) if v else "?"
                variables[name] = variables.get(name, 0) + len(raw)
            elif kind == "event":
                n = _NAME.search(line)
                name = n.group(1) if n else "?"
                rules[name] = rules.get(name, 0) + 1
    return kinds, variables, rules, total


def _narrowing(trace: Optional[Path]) -> str:
    """What fills the trace, and how to leave it out."""
    if trace is None or not trace.is_file():
        return ("shorten the run (--time-limit), leave variables out of the trace "
                "(--trace-vars NAMES, or none), or write poses less often (--pose-interval)")
    kinds, variables, rules, total = _shares(trace)
    if not total:
        return "shorten the run (--time-limit)"
    top = max(kinds, key=kinds.get)
    share = round(100 * kinds[top] / total)
    if top == "set":
        ranked = sorted(variables, key=lambda n: (-variables[n], n))
        heavy = [n for n in ranked if variables[n] >= 0.2 * kinds["set"]] or ranked[:1]
        keep = sorted({n.split("[", 1)[0] for n in ranked} - {n.split("[", 1)[0] for n in heavy})
        named = ", ".join(f"`{n}`" for n in heavy)
        return (f"the changes of {named} are {share} % of the trace: leave "
                f"{'them' if len(heavy) > 1 else 'it'} out with "
                + (f"--trace-vars {','.join(keep)} (the variables kept)" if keep
                   else "--trace-vars none") + " or a shorter --time-limit")
    if top == "pose":
        return (f"pose records are {share} % of the trace: write them less often "
                f"(--pose-interval 500ms) or run shorter (--time-limit)")
    if top in ("event", "action") and rules:
        rule = max(rules, key=lambda n: (rules[n], n))
        share = round(100 * (kinds.get("event", 0) + kinds.get("action", 0)) / total)
        return (f"the rules' firings are {share} % of the trace ({rules[rule]} of `{rule}`): "
                f"a rule that fires this often writes each firing; run shorter (--time-limit), "
                f"or without --trace (--svg and --html alone keep no trace file)")
    return (f"`{top}` records are {share} % of the trace: run shorter (--time-limit), or leave "
            f"variables out (--trace-vars)")


def large_outputs_warning(files: list, trace: Optional[Path]) -> Optional[str]:
    """The warning for the outputs past LARGE_BYTES, or None."""
    big = [(p, p.stat().st_size) for p in files if p.stat().st_size > LARGE_BYTES]
    if not big:
        return None
    sizes = ", ".join(f"{p.name} {n / 1e6:.1f} MB" for p, n in big)
    return (f"the run wrote large output ({sizes}; more than {LARGE_BYTES // 1_000_000} MB "
            f"each): {_narrowing(trace)}")
