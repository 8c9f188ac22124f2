"""The sound sources of a world (`sound` lines), which the robots' three
microphones hear through Enki's microphone model (runtime_c/enki/
world_sound.h), as they hear the robots that play a sound:

    sound at 60 cm, 50 cm frequency 1000 Hz level 80 dB from 1 s to 3 s
    sound at 20 cm, 20 cm level 90 dB from 2 s to 2.2 s from 6 s to 6.2 s
    sound at 90 cm, 10 cm                    (1000 Hz, 80 dB, on all the time)

A source is a point on the floor; its level is the sound pressure level
(dB SPL) 1 m from it, and it is on during each `from T [to T]` (from T to
the end when `to` is left out; always without any). docs/world.md,
"Sound", is the reference; `spec_lines` hands them to the world runner,
`to_json` to the trace's world record, which the pictures draw (`draw`).
"""
from __future__ import annotations

from ..base.records import record
from .worldline import Line

FREQUENCY_HZ = 1000.0       # without `frequency`
LEVEL_DB = 80.0             # without `level`: dB SPL at 1 m, a loud voice or a radio
MAX_SOUNDS = 64
EXAMPLE = "sound at 60 cm, 50 cm frequency 1000 Hz level 80 dB from 1 s to 3 s"
DURATION_UNITS = {"ms": 1.0, "s": 1000.0, "min": 60000.0}
MAX_MS = 1_000_000_000


@record
class Sound:
    x_mm: float
    y_mm: float
    frequency_hz: float = FREQUENCY_HZ
    level_db: float = LEVEL_DB
    intervals: tuple = ()           # (on ms, off ms or None: to the end); (): always on
    line: int = 0


def _time(ln: Line) -> int:
    tok = ln.peek()
    ms = ln._quantity(DURATION_UNITS, "time", "2 s")
    if ms < 0 or ms > MAX_MS or ms != int(ms):
        raise ln.error("a time is a whole number of ms from 0 to 1000000000", tok)
    return int(ms)


def parse(world, ln: Line, lineno: int) -> None:
    """One `sound` line (its `sound` read) into world.sounds."""
    ln.expect("at", EXAMPLE)
    x, y = ln.point()
    sound = Sound(x, y, line=lineno)
    intervals = []
    seen = set()
    while not ln.at_end():
        tok = ln.peek()
        if ln.keyword("frequency") or ln.keyword("level"):
            word = tok.text.lower()
            if word in seen:
                raise ln.error(f"a second `{word}`", tok, "a source has one; delete one")
            seen.add(word)
            value_tok = ln.peek()
            if word == "frequency":
                value = ln._quantity({"Hz": 1.0, "kHz": 1000.0}, "frequency", "1000 Hz")
                if not 20 <= value <= 20000:
                    raise ln.error("a frequency is from 20 Hz to 20 kHz", value_tok)
                sound.frequency_hz = value
            else:
                value = ln._quantity({"dB": 1.0}, "level", "80 dB")
                if not 0 <= value <= 140:
                    raise ln.error("a level is from 0 dB to 140 dB (the sound pressure level "
                                   "1 m from the source)", value_tok)
                sound.level_db = value
        elif ln.keyword("from"):
            on = _time(ln)
            off = None
            if ln.keyword("to"):
                to_tok = ln.peek()
                off = _time(ln)
                if off <= on:
                    raise ln.error(f"the sound goes off at {off} ms, not after it comes on "
                                   f"at {on} ms", to_tok, "write from T1 to T2 with T2 > T1")
            if intervals and (intervals[-1][1] is None or on < intervals[-1][1]):
                raise ln.error("this interval begins before the one before it ends", tok,
                               "give the times in order: from 1 s to 2 s from 4 s to 5 s")
            intervals.append((on, off))
        else:
            raise ln.error(f"unexpected `{tok.text}`", tok,
                           f"a sound takes `frequency F Hz`, `level L dB` and `from T1 to T2`, "
                           f"e.g. {EXAMPLE}")
    sound.intervals = tuple(intervals)
    if len(world.sounds) == MAX_SOUNDS:
        raise ln.error(f"more than {MAX_SOUNDS} sound sources", None)
    world.sounds.append(sound)


def check(world, lines: list, shown: str) -> list:
    """Every source inside the arena: the problems found, as diagnostics."""
    problems = []
    for s in world.sounds:
        if world.walled and not (0 <= s.x_mm <= world.width_mm and 0 <= s.y_mm <= world.height_mm):
            text = lines[s.line - 1].rstrip()
            col = len(text) - len(text.lstrip()) + 1
            problems.append(
                f"{shown}:{s.line}:{col}: error: this sound source is outside the arena\n"
                f" {s.line} | {text}\n" + " " * (len(str(s.line)) + 1) + " | " + " " * (col - 1)
                + f"^\nhelp: the arena spans 0..{world.width_mm:g} mm x 0..{world.height_mm:g} mm")
    return problems


def spec_lines(world) -> list:
    """`sound X Y HZ DB N ON OFF ...` (cm, ms; OFF -1: to the end) for the
    world runner."""
    out = []
    for s in world.sounds:
        times = " ".join(f"{on} {-1 if off is None else off}" for on, off in s.intervals)
        out.append(f"sound {float(s.x_mm / 10)!r} {float(s.y_mm / 10)!r} "
                   f"{float(s.frequency_hz)!r} {float(s.level_db)!r} {len(s.intervals)}"
                   + (f" {times}" if times else ""))
    return out


def to_json(world) -> list:
    return [{"x_mm": round(s.x_mm, 1), "y_mm": round(s.y_mm, 1),
             "frequency_hz": s.frequency_hz, "level_db": s.level_db,
             "on_ms": [[on, off] for on, off in s.intervals]} for s in world.sounds]


def describe(record: dict) -> str:
    """`1000 Hz, 80 dB, from 1 s to 3 s`: a source in words (its tooltip)."""
    def t(ms):
        return f"{ms / 1000:g} s"
    times = ", ".join(f"from {t(on)}" + ("" if off is None else f" to {t(off)}")
                      for on, off in record.get("on_ms", [])) or "all the time"
    return f"sound {record['frequency_hz']:g} Hz, {record['level_db']:g} dB at 1 m, {times}"


def draw(dwg, group, record: dict, px, scale: float) -> None:
    """Each source of a trace's world record on the SVG's map: a speaker's
    mark (`g.sound`, `data-on-ms`: its intervals, for the replay), its
    tooltip saying what it plays and when."""
    for s in record.get("sounds", []):
        cx, cy = px(s["x_mm"], s["y_mm"])
        g = dwg.g(class_="sound")
        g["data-on-ms"] = " ".join(f"{on}:{'' if off is None else off}" for on, off in s["on_ms"])
        g.set_desc(title=describe(s))
        r = max(12.0 * scale, 3.0)
        g.add(dwg.circle(center=(cx, cy), r=round(r, 1), fill="#f9a825", stroke="#8d5b00",
                         stroke_width=1))
        for k in (1.6, 2.3):
            g.add(dwg.circle(center=(cx, cy), r=round(r * k, 1), fill="none", stroke="#f9a825",
                             stroke_width=1, stroke_opacity=0.6))
        group.add(g)
