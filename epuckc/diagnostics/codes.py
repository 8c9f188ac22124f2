"""The stable diagnostic codes and their long explanations (`epuckc explain`).

A code never changes meaning once released; retired codes stay listed."""
from __future__ import annotations

from pathlib import Path

CODES = {
    # the text itself
    "E001": "syntax error",
    "E002": "unexpected character",
    "E003": "unterminated string",
    "E004": "the file is not UTF-8 text",
    "E005": "the file cannot be read",
    "E006": "a C file given to `check`",
    "E007": "number written with an exponent",
    "E008": "name with letters that are not ASCII",
    "E009": "hexadecimal or binary number with a bad digit",
    # names
    "E010": "unknown event",
    "E011": "unknown action",
    "E012": "unknown rule",
    "E013": "unknown constant (or, in an expression, variable or reading)",
    "E014": "unknown parameter",
    "E015": "name defined twice",
    "E016": "too many arguments",
    "E017": "missing argument",
    "E018": "argument given twice",
    "E019": "quantity of the wrong kind",
    "E020": "unknown unit",
    "E021": "positional argument after a named one",
    "E022": "bad robot block",
    "E023": "action defined in terms of itself",
    "E024": "condition in the wrong place",
    "E025": "sensor listed twice",
    "E026": "unknown type",
    "E027": "extern name reserved in C",
    # values
    "E030": "speed above the robot's maximum",
    "E031": "unknown sensor",
    "E032": "threshold out of range",
    "E033": "duration not positive",
    "E034": "value too large for a 16-bit int",
    "E035": "curve's inner wheel too fast",
    "E036": "negative radius",
    "E037": "impossible robot geometry",
    "E038": "whole number expected",
    "E039": "more actions or events than the runtime holds (no longer reported)",
    "E040": "extern source file not found",
    "E041": "unknown LED, sound or key",
    "E042": "value out of range",
    # modes
    "E043": "unknown mode",
    "E044": "`on enter` outside a mode",
    "E045": "`cancel` of a rule of another mode",
    "E046": "two initial modes",
    # expressions and variables
    "E048": "kinds that do not combine",
    "E049": "division by zero",
    "E050": "a condition where a number is needed, or the other way round",
    "E051": "assignment to something that is not a variable",
    "E052": "a changing value where a fixed one is needed",
    "E054": "unknown function",
    "E055": "`repeat` on `every` or `after`",
    "E056": "nested too deeply (operators, calls, indexes, `if`s, named actions spliced in)",
    "E061": "array index outside the array, or an array of no (or too many) elements",
    "E062": "an array where one value is wanted, or an index of what is not an array",
    "E063": "`dot` of arrays of different sizes",
    "E070": "a device the target does not have",
    "E080": "`then` inside an `if` branch",
    # Aseba's constructs (syntax/aseba.py)
    "E090": "Aseba's `while` or `for` loop",
    "E091": "`++` or `--`",
    "E092": "Aseba's `sub` or `callsub`",
    "E093": "Aseba's `onevent`",
    "E094": "Aseba's `emit`",
    "E095": "Aseba's `call` of a native function",
    "E096": "`sort`",
    # warnings
    "W001": "timer rule that can never fire",
    "W002": "sensor rule that can never fire",
    "W003": "stop_motor rule that can never fire",
    "W004": "`immediate repeat` runs at every poll",
    "W005": "action never used",
    "W006": "program with no rules",
    "W007": "constant never used",
    "W008": "bare duration that is very likely meant in seconds",
    "W009": "same-priority rules race for the motors",
    "W010": "mode never entered",
    "W011": "steps after `enter` never run",
    "W012": "a negative speed and a negative distance drive forward",
    "W013": "a motor command can leave the robot's range",
    "W014": "a divisor that can be 0",
    "W015": "variable never used",
    "W016": "condition that never changes",
    "W017": "variable never assigned",
    "W020": "a value that can leave its range and saturate",
    "W022": "an array index that can leave the array",
    "W030": "a value that can leave the range its action carries",
    "W070": "a device only a world gives, in a run without one",
    "W080": "an `if` branch that never runs",
}

_EXPLANATIONS = Path(__file__).resolve().parent / "explanations"


def normalise(code: str) -> str:
    code = code.strip().upper()
    if code[:1] in ("E", "W") and code[1:].isascii() and code[1:].isdigit():
        return code[0] + str(int(code[1:])).zfill(3)      # e12, E0012 -> E012
    return code


def explanation_path(code: str) -> Path | None:
    """The shipped Markdown file that explains a code (what `epuckc
    explain` prints; the language server links diagnostics to it)."""
    code = normalise(code)
    if code not in CODES:
        return None
    path = _EXPLANATIONS / f"{code}.md"
    return path if path.is_file() else None


def explanation(code: str) -> str | None:
    path = explanation_path(code)
    return path.read_text(encoding="utf-8") if path is not None else None
