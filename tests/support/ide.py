"""Helpers of the language features' tests (tests/ide)."""
from __future__ import annotations


def where(text: str, needle: str, offset: int = 0, nth: int = 0) -> tuple:
    """(line, column) from 1 of the nth (from 0) `needle` in text, plus
    offset characters."""
    i = -1
    for _ in range(nth + 1):
        i = text.index(needle, i + 1)
    i += offset
    line = text.count("\n", 0, i) + 1
    return line, i - (text.rfind("\n", 0, i) + 1) + 1
