"""The physics a world runs on (a `physics` line), which chooses the world
runner's provider (runtime_c/enki/physics.h):

    physics enki        Enki, the reference: every pair of objects is tested
    physics chipmunk    Chipmunk 7, a 2-D engine with a broad phase: large worlds

Without the line a world of more than CHIPMUNK_ABOVE robots runs on
Chipmunk (faster from there on: docs/performance.md, "Large worlds"), any
other on Enki. Enki is refused above MAX_ENKI_ROBOTS robots. docs/world.md,
"Large worlds", is the reference; sim/enki.py builds the runner of each.
"""
from __future__ import annotations

from .worldline import Line

PHYSICS = ("enki", "chipmunk")
CHIPMUNK_ABOVE = 200
MAX_ENKI_ROBOTS = 1000          # Enki steps every pair of objects: beyond, hours per minute


def parse(world, ln: Line, lineno: int) -> None:
    """One `physics` line (its `physics` read) into world.physics."""
    tok = ln.next("the physics: enki or chipmunk")
    if tok.number is not None or tok.text.lower() not in PHYSICS:
        raise ln.error(f"`{tok.text}` is not a physics of a world", tok,
                       "write `physics enki` (the reference) or `physics chipmunk` "
                       "(large worlds)")
    world.physics = tok.text.lower()
    world.physics_line = lineno


def resolved(world) -> str:
    """The world's `physics` line's, else Enki up to CHIPMUNK_ABOVE robots."""
    if world.physics is not None:
        return world.physics
    return "chipmunk" if len(world.robots) > CHIPMUNK_ABOVE else "enki"


def check(world, lines: list, shown: str) -> list:
    """Enki's limit on robots, at the `physics enki` line: the problems
    found, as diagnostics."""
    if world.physics != "enki" or len(world.robots) <= MAX_ENKI_ROBOTS:
        return []
    line = world.physics_line
    text = lines[line - 1].rstrip()
    col = len(text) - len(text.lstrip()) + 1
    return [f"{shown}:{line}:{col}: error: {len(world.robots):,} robots on Enki: it steps every "
            f"pair of objects, and runs at most {MAX_ENKI_ROBOTS:,} robots\n"
            f" {line} | {text}\n" + " " * (len(str(line)) + 1) + " | " + " " * (col - 1)
            + "^\nhelp: write `physics chipmunk`, the physics for large worlds (docs/world.md)"]
