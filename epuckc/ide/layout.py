"""The formatter's document and its printer: hard and soft lines, groups
that break together, indents and fills, laid out in a width the way
Wadler's "prettier printer" does. fmt.py builds the document."""
from __future__ import annotations

from dataclasses import dataclass, field

WIDTH = 88          # the longest line the formatter makes, when it can
INDENT = 4          # the hanging indent of a wrapped statement


class _Line:
    """A space when its group is flat, a new line when it is broken."""
    __slots__ = ()


class _Hard:
    """Always a new line; the groups around it are broken."""
    __slots__ = ()


@dataclass
class _Comment:
    """Comment text: printed as it is, but not counted when deciding whether
    a group fits (a long comment never rearranges the code around it)."""
    text: str


@dataclass
class _IfBreak:
    broken: str
    flat: str = ""


@dataclass
class _Group:
    items: list = field(default_factory=list)
    broken: bool = False


@dataclass
class _Indent:
    items: list = field(default_factory=list)


@dataclass
class _Fill:
    """Items separated by LINEs, broken only where the next item does not
    fit on the line (an argument list fills its lines)."""
    items: list = field(default_factory=list)


class _FillLine:
    """A LINE of a broken fill: a new line only when what follows it, up to
    the next line break, does not fit."""
    __slots__ = ()


FILL_LINE = _FillLine()
LINE, HARD = _Line(), _Hard()
_FLAT, _BREAK = 0, 1


def _propagate(doc) -> bool:
    """Mark every group that holds a hard line as broken; True if `doc` holds one."""
    if doc is HARD:
        return True
    if isinstance(doc, _Group):
        hard = False
        for item in doc.items:
            hard = _propagate(item) or hard
        doc.broken = doc.broken or hard
        return hard
    if isinstance(doc, (_Indent, _Fill)):
        hard = False
        for item in doc.items:
            hard = _propagate(item) or hard
        return hard
    return False


def _fits(command, rest: list, width: int) -> bool:
    """Does `command` (laid out flat) and what follows it up to the next line
    break fit in `width` columns?"""
    todo = [command]
    rest_index = len(rest)
    while width >= 0:
        if not todo:
            if rest_index == 0:
                return True
            rest_index -= 1
            todo.append(rest[rest_index])
            continue
        indent, mode, doc = todo.pop()
        if isinstance(doc, str):
            width -= len(doc)
        elif isinstance(doc, _Group):
            group_mode = _BREAK if doc.broken else mode
            todo.extend((indent, group_mode, item) for item in reversed(doc.items))
        elif isinstance(doc, (_Indent, _Fill)):
            todo.extend((indent, mode, item) for item in reversed(doc.items))
        elif doc is FILL_LINE:
            return True
        elif doc is LINE:
            if mode == _BREAK:
                return True
            width -= 1
        elif doc is HARD:
            return True
        elif isinstance(doc, _IfBreak):
            width -= len(doc.broken if mode == _BREAK else doc.flat)
    return False


def _render(doc, width: int) -> str:
    _propagate(doc)
    out: list = []
    column = 0
    stack = [(0, _BREAK, doc)]
    while stack:
        indent, mode, item = stack.pop()
        if isinstance(item, str):
            out.append(item)
            column += len(item)
        elif isinstance(item, _Comment):
            out.append(item.text)
            column += len(item.text)
        elif isinstance(item, _Group):
            if item.broken:
                group_mode = _BREAK
            elif mode == _FLAT:
                group_mode = _FLAT
            else:
                group_mode = _FLAT if _fits((indent, _FLAT, item), stack, width - column) else _BREAK
            stack.extend((indent, group_mode, x) for x in reversed(item.items))
        elif isinstance(item, _Indent):
            stack.extend((indent + INDENT, mode, x) for x in reversed(item.items))
        elif isinstance(item, _Fill):
            stack.extend((indent, mode, FILL_LINE if x is LINE and mode == _BREAK else x)
                         for x in reversed(item.items))
        elif item is FILL_LINE:
            if _fits((indent, _FLAT, " "), stack, width - column):
                out.append(" ")
                column += 1
            else:
                while out and out[-1].endswith(" "):
                    out[-1] = out[-1].rstrip(" ")
                out.append("\n" + " " * indent)
                column = indent
        elif item is HARD or (item is LINE and mode == _BREAK):
            while out and out[-1].endswith(" "):
                out[-1] = out[-1].rstrip(" ")
            out.append("\n" + " " * indent)
            column = indent
        elif item is LINE:
            out.append(" ")
            column += 1
        elif isinstance(item, _IfBreak):
            text = item.broken if mode == _BREAK else item.flat
            out.append(text)
            column += len(text)
    return "".join(out).rstrip(" ")
