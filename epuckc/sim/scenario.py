"""Scenario files (`--scenario x.scn`), checked before anything is built.

The host harness reads them (runtime_c/host/scenario.c, host_load_scenario)
and stops at the first problem; this module applies the same rules to the
whole file first and reports every problem with its line, column and a
caret, so a run never starts with a broken scenario. The two are held to
the same verdicts by tests/sim/test_scenario.py, which runs the harness on
the same good and broken files.

One line per change: `<time> [ms|s|min] NAME=V ...`, `#` starts a comment;
lines end with LF, CRLF or a lone CR; a UTF-8 byte-order mark is skipped.
"""
from __future__ import annotations

import re
from pathlib import Path
from typing import Optional

MAX_SCENARIO_MS = 1_000_000_000         # MAX_SCENARIO_MS in host/host_harness.h
MAX_ITEMS = 64                          # tokens on a line
EXAMPLE = '"1200 ms ir0=850"'

# name prefix -> (count of indexes, largest value); rot's values are signed
_INPUTS = {"ir": (8, 4095), "amb": (8, 4095), "mic": (3, 4095), "acc": (3, 4095),
           "rot": (3, 1000), "selector": (1, 15), "key": (1, 127), "ground": (3, 4095)}
KEY_NAMES = {"standby": 12, "mute": 13, "vol_up": 16, "vol_down": 17, "chan_up": 32,
             "chan_down": 33}
EXPECTED_ITEM = ("expected irN=V or ambN=V (N 0..7), micN=V (N 0..2) or mic=V, accx=V, accy=V "
                 "or accz=V, groundN=V (N 0..2) (V 0..4095), rotx=V, roty=V or rotz=V "
                 "(V -1000..1000 degrees/s), selector=V (0..15), or key=K (0..127 or standby, "
                 "mute, vol_up, vol_down, chan_up, chan_down)")
_BLANKS = re.compile(r"[^ \t\f\v]+")
_LINE_ENDS = re.compile(r"\r\n|\r|\n")


class ScenarioProblem(Exception):
    def __init__(self, message: str, column: int, help: str = ""):
        super().__init__(message)
        self.message, self.column, self.help = message, column, help
        self.time_ms: Optional[int] = None     # the line's time, when it was read


def _time(tokens: list) -> tuple:
    """(ms, tokens used) of a line's time, or ScenarioProblem."""
    text, col = tokens[0]
    m = re.match(r"([0-9]*)(?:\.([0-9]*))?(.*)\Z", text, re.S)
    whole, frac, unit = m.group(1), m.group(2), m.group(3)
    if not whole:
        raise ScenarioProblem('expected a time ("<number> ms", "<number> s" or "<number> min")',
                              col, f"a line starts with its time: {EXAMPLE}")
    if len(whole) > 9:
        raise ScenarioProblem("time too large", col)
    if frac is not None and len(frac) > 3:
        raise ScenarioProblem("time finer than 1 ms", col)
    used = 1
    if unit == "" and len(tokens) > 1 and tokens[1][0] in ("ms", "s", "min"):
        unit, used = tokens[1][0], 2
    if unit not in ("", "ms", "s", "min"):
        raise ScenarioProblem("unknown time unit (use ms, s or min)", col + len(text) - len(unit))
    fraction = int((frac or "").ljust(3, "0")[:3] or 0)
    if unit in ("s", "min"):
        limit = MAX_SCENARIO_MS // (1000 if unit == "s" else 60000)
        if int(whole) > limit:
            raise ScenarioProblem("time too large", col)
        ms = int(whole) * 1000 + fraction if unit == "s" else int(whole) * 60000 + fraction * 60
    else:
        if frac is not None:
            raise ScenarioProblem("milliseconds must be a whole number", col,
                                  "write 1.5 s, or 1500 ms")
        ms = int(whole)
    if ms > MAX_SCENARIO_MS:
        raise ScenarioProblem("time too large", col)
    return ms, used


def _assignment(text: str) -> bool:
    """Whether `text` is one of the inputs with a value in its range."""
    name, eq, value = text.partition("=")
    if not eq or not name or len(name) >= 16:
        return False
    name = name.lower()
    for prefix, (count, largest) in _INPUTS.items():
        if not name.startswith(prefix):
            continue
        rest = name[len(prefix):]
        if count == 1 and rest == "":
            pass
        elif prefix in ("acc", "rot") and rest in ("x", "y", "z"):
            pass
        elif prefix == "mic" and rest == "":
            pass
        elif count > 1 and prefix not in ("acc", "rot") and len(rest) == 1 \
                and "0" <= rest < str(count):
            pass
        else:
            continue
        if prefix == "key" and value in KEY_NAMES:
            return True
        if prefix == "rot" and value[:1] == "-":
            value = value[1:]
        return (value.isascii() and value.isdigit() and len(value) <= 5
                and int(value) <= largest)
    return False


def check_scenario(path: Path, shown: Optional[str] = None, data: Optional[bytes] = None) -> list:
    """Every problem of a scenario file, each a diagnostic's text
    (`file:line:col: error: ...`, the line, a caret, a help line); [] when
    the harness will read it. OSError when it cannot be read."""
    shown = shown or str(path)
    data = Path(path).read_bytes() if data is None else data
    if data.startswith(b"\xef\xbb\xbf"):
        data = data[3:]
    text = data.decode("utf-8", errors="replace")
    problems, last_t = [], 0
    for lineno, line in enumerate(_LINE_ENDS.split(text), 1):
        try:
            last_t = _line(line, last_t)
        except ScenarioProblem as p:
            if p.time_ms is not None:           # the next lines' order is still checked
                last_t = p.time_ms
            shown_line = line.replace("\0", "\\0")
            col = len(line[:p.column - 1].replace("\0", "\\0")) + 1
            text_ = (f"{shown}:{lineno}:{p.column}: error: {p.message}\n"
                     f" {lineno} | {shown_line.rstrip()}\n"
                     + " " * (len(str(lineno)) + 1) + " | " + " " * (col - 1) + "^")
            if p.help:
                text_ += f"\nhelp: {p.help}"
            problems.append(text_)
    return problems


def world_scenario_problems(path: Path, shown: Optional[str] = None) -> list:
    """A world's scenario: check_scenario's problems, and each input that the
    world's physics gives (the proximity sensors, Enki's) refused where it
    is written. OSError when it cannot be read."""
    shown = shown or str(path)
    data = Path(path).read_bytes()
    problems = check_scenario(path, shown, data)
    if data.startswith(b"\xef\xbb\xbf"):
        data = data[3:]
    for lineno, line in enumerate(_LINE_ENDS.split(data.decode("utf-8", errors="replace")), 1):
        for m in _BLANKS.finditer(line.split("#", 1)[0]):
            if re.match(r"(?i)ir[0-7]=", m.group(0)):
                col = m.start() + 1
                problems.append(f"{shown}:{lineno}:{col}: error: in a world the proximity "
                                f"sensors read Enki's: `{m.group(0)}` cannot be a scenario's "
                                f"input there\n {lineno} | {line.rstrip()}\n"
                                + " " * (len(str(lineno)) + 1) + " | " + " " * (col - 1) + "^"
                                + "\nhelp: a world's scenario gives what its physics does not: "
                                  "selector, mic, key, acc (knocks, tilts), rot (a hand turning "
                                  "the robot), amb")
    return problems


def _line(line: str, last_t: int) -> int:
    for i, c in enumerate(line):
        if c == "\0":
            raise ScenarioProblem("a NUL byte: this is not a text file", i + 1,
                                  f"a scenario has lines such as {EXAMPLE}")
        if c < " " and c not in "\t\f\v":
            raise ScenarioProblem(f"control character 0x{ord(c):02x}: this is not a text file",
                                  i + 1, f"a scenario has lines such as {EXAMPLE}")
    body = line.split("#", 1)[0]
    tokens = [(m.group(0), m.start() + 1) for m in _BLANKS.finditer(body)]
    if not tokens:
        return last_t
    if len(tokens) > MAX_ITEMS:
        raise ScenarioProblem("too many items on one line", tokens[MAX_ITEMS][1],
                              "put the changes of one time on two lines")
    ms, used = _time(tokens)
    if ms < last_t:
        raise ScenarioProblem(f"time {ms} ms is before the previous line's {last_t} ms",
                              tokens[0][1], "lines go in the order of their times")
    for k in range(used, len(tokens)):
        item, col = tokens[k]
        problem = None
        if k == used == 1 and item[:1].isalpha() and "=" not in item:
            problem = ScenarioProblem(f"unknown time unit '{item}' (use ms, s or min)", col)
        elif not _assignment(item):
            problem = ScenarioProblem(f"{EXPECTED_ITEM}, got '{item}'", col)
        if problem is not None:
            problem.time_ms = ms
            raise problem
    return ms
