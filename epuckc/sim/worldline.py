"""The words of a world file's lines (sim/world.py, and the floor and the
sound sources it reads with sim/floor.py and sim/sound.py): its tokens, a
cursor over one line's with quantities in their units, and diagnostics
that point into the line (`file:line:col: error: ...`, the line, a caret,
a help line).
"""
from __future__ import annotations

import math
import re
from typing import Optional

from ..base.records import record

LENGTH_UNITS = {"mm": 1.0, "cm": 10.0, "m": 1000.0}
MAX_LENGTH_MM = 100_000.0       # 100 m
# The words of world lines: a bare number followed by one of them has no
# unit (`at 20, 30 size ...` says so), by any other word takes it as its unit.
KEYWORDS = {"at", "size", "x", "angle", "height", "radius", "heading", "program", "none",
            "range", "loss", "interval", "emitter", "receiver", "range_noise", "colour",
            "from", "to", "width", "closed", "frequency", "level", "image", "enki", "chipmunk",
            "selector", "scenario"}
# What the camera sees of each colour a world may give (r, g, b, 0..255):
# the six the camera tells apart (stdlib COLOURS) and three it does not.
COLOURS = {"red": (230, 30, 30), "yellow": (230, 220, 40), "green": (40, 190, 60),
           "cyan": (40, 200, 210), "blue": (40, 70, 220), "magenta": (210, 40, 200),
           "white": (240, 240, 240), "grey": (128, 128, 128), "black": (20, 20, 20)}
DEFAULT_COLOUR = "grey"         # walls, boxes, cylinders and robots without one


class WorldError(Exception):
    """A problem in a world file; str() is the whole diagnostic."""


_TOKEN = re.compile(r"\s*(?:(?P<num>[-+]?(?:\d+\.?\d*|\.\d+))(?P<unit>[A-Za-z%]+)?"
                    r"|(?P<str>\"[^\"]*\"?)|(?P<word>[^\s,]+)|(?P<comma>,))")


@record
class Tok:
    """A token: a number (with the unit written against it), a word, or a
    quoted text (`"my track.png"`: `text` without its quotes)."""
    text: str
    col: int
    number: Optional[float] = None
    unit: Optional[str] = None
    quoted: bool = False


def tokens(line: str) -> list:
    out = []
    pos = 0
    while pos < len(line):
        m = _TOKEN.match(line, pos)
        if m is None or m.end() == pos:
            break
        start = m.start(m.lastgroup) + 1
        if m.group("num") is not None:
            out.append(Tok(m.group(0).strip(), start, float(m.group("num")), m.group("unit")))
        elif m.group("str") is not None:
            out.append(Tok(m.group("str").strip('"'), start, quoted=True))
        elif m.group("word") is not None:
            out.append(Tok(m.group("word"), start))
        pos = m.end()
    return out


class Line:
    """A cursor over one line's tokens, with diagnostics that point into it."""

    def __init__(self, path: str, lineno: int, text: str):
        self.path, self.lineno, self.text = path, lineno, text
        self.toks = tokens(text)
        self.i = 0

    def error(self, message: str, tok: Optional[Tok] = None, help: str = "") -> WorldError:
        col = tok.col if tok is not None else len(self.text.rstrip()) + 1
        text = f"{self.path}:{self.lineno}:{col}: error: {message}"
        text += f"\n {self.lineno} | {self.text.rstrip()}\n"
        text += " " * (len(str(self.lineno)) + 1) + " | " + " " * (col - 1) + "^"
        if help:
            text += f"\nhelp: {help}"
        return WorldError(text)

    def at_end(self) -> bool:
        return self.i >= len(self.toks)

    def peek(self) -> Optional[Tok]:
        return self.toks[self.i] if self.i < len(self.toks) else None

    def next(self, what: str) -> Tok:
        tok = self.peek()
        if tok is None:
            raise self.error(f"expected {what} here, at the end of the line")
        self.i += 1
        return tok

    def keyword(self, word: str) -> bool:
        tok = self.peek()
        if tok is not None and tok.number is None and not tok.quoted and tok.text.lower() == word:
            self.i += 1
            return True
        return False

    def expect(self, word: str, example: str):
        if not self.keyword(word):
            tok = self.peek()
            found = f"`{tok.text}`" if tok is not None else "the end of the line"
            raise self.error(f"expected `{word}`, found {found}", tok, f"write it as: {example}")

    def _quantity(self, units: dict, kind: str, example: str) -> float:
        tok = self.next(f"a {kind} such as {example}")
        if tok.number is None:
            raise self.error(f"expected a {kind} such as {example}, found `{tok.text}`", tok)
        unit = tok.unit
        if unit is None:
            nxt = self.peek()
            if (nxt is not None and nxt.number is None
                    and (nxt.text in units or nxt.text.lower() not in KEYWORDS)):
                unit = nxt.text
                self.i += 1
        if unit is None:
            raise self.error(f"the {kind} {tok.text} has no unit", tok,
                             f"add one of {', '.join(units)}, e.g. {example}")
        if unit not in units:
            raise self.error(f"`{unit}` is not a unit of {kind}", tok,
                             f"use one of {', '.join(units)}, e.g. {example}")
        value = tok.number * units[unit]
        if not math.isfinite(value):
            raise self.error(f"the {kind} {tok.text} is not a number", tok)
        return value

    def length(self, what: str = "length", positive: bool = False) -> float:
        tok = self.peek()
        v = self._quantity(LENGTH_UNITS, "length", "20 cm")
        if abs(v) > MAX_LENGTH_MM:
            raise self.error(f"the {what} is larger than 100 m", tok)
        if positive and v <= 0:
            raise self.error(f"the {what} must be positive", tok)
        return v

    def whole(self, what: str, most: int, message: str) -> int:
        """A whole number from 0 to `most`, else `message`."""
        tok = self.next(what)
        if tok.number is None or tok.unit or not tok.text.isdigit() or int(tok.text) > most:
            raise self.error(message, tok)
        return int(tok.text)

    def angle(self) -> float:
        return self._quantity({"deg": 1.0}, "angle", "90 deg")

    def point(self):
        x = self.length("x coordinate")
        y = self.length("y coordinate")
        return x, y

    def end(self):
        tok = self.peek()
        if tok is not None:
            raise self.error(f"unexpected `{tok.text}`", tok, "each item takes one line; "
                             "see docs/world.md for what may follow")


def colour(ln: Line) -> str:
    """A colour's name, after `colour`."""
    tok = ln.next("a colour")
    name = tok.text.lower()
    if tok.number is not None or name not in COLOURS:
        raise ln.error(f"`{tok.text}` is not a colour of a world", tok,
                       "the colours are " + ", ".join(COLOURS))
    return name
