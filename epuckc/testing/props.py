"""Property checks of a case (`expect = [...]` in NAME.toml), for cases
whose exact trace is not the point: each is one sentence, checked on the
run's JSON trace.

    exit                      the program reaches exit_main
    exit within 5 s           ... at 5 s or before
    timeout                   the run reaches its time limit
    no contact                in a world: no collision at all
    x > 100 mm at exit        x, y (mm, cm, m), heading (deg), left_steps,
    heading <= 10 deg at end  right_steps (steps) at exit (the program must
                              exit) or at end (exit or time limit);
                              operators < <= > >= == !=
    rule avoid fires          the rule named `avoid` fires at least once
    rule avoid never fires
    rule avoid fires within 2 s

In a world every robot must satisfy the check, or the one named first:
`r2: exit within 10 s`.
"""
from __future__ import annotations

import operator
import re
from dataclasses import dataclass
from decimal import Decimal
from typing import Optional

from ..sim.contacts import steps_in_contact


class PropertyError(Exception):
    """A sentence that is not a property check."""


_OPS = {"<": operator.lt, "<=": operator.le, ">": operator.gt, ">=": operator.ge,
        "==": operator.eq, "!=": operator.ne}
_LENGTH = {"mm": 1, "cm": 10, "m": 1000}
_QUANTITIES = {"x": ("x_mm", _LENGTH), "y": ("y_mm", _LENGTH),
               "heading": ("heading_deg", {"deg": 1}),
               "left_steps": ("left_steps", {"steps": 1, "": 1}),
               "right_steps": ("right_steps", {"steps": 1, "": 1})}
_TIME = {"ms": 1, "s": 1000, "min": 60_000}
_DURATION = r"([0-9]+(?:\.[0-9]+)?)\s*(ms|s|min)"
FORMS = ("exit", "exit within 5 s", "timeout", "no contact", "x > 100 mm at exit",
         "heading <= 10 deg at end", "rule NAME fires", "rule NAME never fires",
         "rule NAME fires within 2 s")


@dataclass
class Property:
    text: str
    robot: Optional[str]
    kind: str
    args: tuple


def _ms(number: str, unit: str) -> int:
    return int(Decimal(number) * _TIME[unit])


def parse_property(text: str) -> Property:
    sentence = " ".join(text.split())
    robot = None
    m = re.match(r"([A-Za-z_][\w-]*):\s*(.*)", sentence)
    if m:
        robot, sentence = m.group(1), m.group(2)
    if sentence == "exit":
        return Property(text, robot, "exit", (None,))
    m = re.fullmatch(r"exit within " + _DURATION, sentence)
    if m:
        return Property(text, robot, "exit", (_ms(m.group(1), m.group(2)),))
    if sentence == "timeout":
        return Property(text, robot, "timeout", ())
    if sentence in ("no contact", "no contacts", "no collision"):
        return Property(text, robot, "no_contact", ())
    m = re.fullmatch(r"rule ([A-Za-z_]\w*) (fires|never fires)(?: within " + _DURATION + ")?",
                     sentence)
    if m and not (m.group(2) == "never fires" and m.group(3)):
        limit = _ms(m.group(3), m.group(4)) if m.group(3) else None
        return Property(text, robot, "fires" if m.group(2) == "fires" else "never",
                        (m.group(1), limit))
    m = re.fullmatch(r"(\w+)\s*(<=|>=|==|!=|<|>)\s*(-?[0-9]+(?:\.[0-9]+)?)\s*([a-z]*)\s+"
                     r"at (exit|end)", sentence)
    if m:
        name, op, number, unit, when = m.groups()
        if name not in _QUANTITIES:
            raise PropertyError(f"`{text}`: unknown quantity `{name}`; the quantities are "
                                f"{', '.join(_QUANTITIES)}")
        field, units = _QUANTITIES[name]
        if unit not in units:
            raise PropertyError(f"`{text}`: `{name}` is measured in "
                                f"{' or '.join(u for u in units if u)}, not `{unit or 'a bare number'}`")
        value = float(Decimal(number) * units[unit])
        return Property(text, robot, "compare", (name, field, op, value, when))
    raise PropertyError(f"`{text}` is not a property check; the forms are: "
                        + "; ".join(f"`{f}`" for f in FORMS))


def _robots(records: list) -> list:
    names = []
    for r in records:
        name = r.get("robot", "")
        if name not in names and r.get("kind") != "world":
            names.append(name)
    return names or [""]


def _final(records: list, robot: str):
    last = None
    for r in records:
        if r.get("robot", "") == robot and r.get("kind") in ("exit", "timeout"):
            last = r
    return last


def _who(robot: str) -> str:
    return f"{robot}: " if robot else ""


def _check_one(prop: Property, records: list, robot: str, world: bool) -> Optional[str]:
    mine = [r for r in records if r.get("robot", "") == robot]
    final = _final(records, robot)
    if prop.kind == "exit":
        if final is None or final["kind"] != "exit":
            end = f"reached the time limit at {final['t_ms']} ms" if final else "did not end"
            return f"{_who(robot)}the program {end} without exit_main"
        limit = prop.args[0]
        if limit is not None and final["t_ms"] > limit:
            return f"{_who(robot)}the program exited at {final['t_ms']} ms, after {limit} ms"
        return None
    if prop.kind == "timeout":
        if final is not None and final["kind"] == "exit":
            return f"{_who(robot)}the program exited at {final['t_ms']} ms, before the time limit"
        return None
    if prop.kind == "no_contact":
        if not world:
            return "`no contact` needs a world (NAME.world): without one nothing can be touched"
        for r in mine:
            if r.get("kind") == "contacts":
                total = steps_in_contact(r)
                if total:
                    return (f"{_who(robot)}collisions in {total} physics steps, the first at "
                            f"{r['first_ms']} ms")
        return None
    if prop.kind in ("fires", "never"):
        name, limit = prop.args
        pattern = re.compile(r"\brule " + re.escape(name) + r":")
        times = [r["t_ms"] for r in mine if r.get("kind") == "event"
                 and pattern.search(str(r.get("name", "")))]
        if prop.kind == "never":
            return (f"{_who(robot)}rule `{name}` fired at {times[0]} ms" if times else None)
        if not times:
            return f"{_who(robot)}rule `{name}` never fired"
        if limit is not None and times[0] > limit:
            return f"{_who(robot)}rule `{name}` first fired at {times[0]} ms, after {limit} ms"
        return None
    name, field, op, value, when = prop.args
    if final is None:
        return f"{_who(robot)}the run has no final record"
    if when == "exit" and final["kind"] != "exit":
        return (f"{_who(robot)}the program did not exit (time limit at {final['t_ms']} ms), so "
                f"`{name}` at exit has no value; write `at end` for the pose at the time limit")
    actual = final[field]
    if not _OPS[op](actual, value):
        return f"{_who(robot)}{name} is {actual:g} at {when} ({final['t_ms']} ms)"
    return None


def check_properties(props: list, records: list) -> list:
    """The failures: (property text, why) for each check that does not hold."""
    world = any(r.get("kind") == "world" for r in records)
    robots = _robots(records)
    failures = []
    for prop in props:
        if prop.robot is not None:
            if prop.robot not in robots or not world:
                failures.append((prop.text, f"there is no robot `{prop.robot}` in this run "
                                            f"(robots: {', '.join(r for r in robots if r) or 'one, unnamed'})"))
                continue
            targets = [prop.robot]
        else:
            targets = robots
        for robot in targets:
            why = _check_one(prop, records, robot, world)
            if why:
                failures.append((prop.text, why))
                break
    return failures
