"""World files (`.world`): the arena, obstacles and robots of an Enki run.

One item per line, `#` starts a comment, lengths take a unit (mm, cm, m),
angles `deg`, and a comma may separate the two coordinates of a point:

    arena 120 cm x 80 cm          # walls around the floor; (0, 0) is its bottom-left corner
    arena none                    # open ground, no walls (the default)
    box at 40 cm, 30 cm size 20 cm x 5 cm angle 30 deg
    cylinder at 90 cm, 50 cm radius 6 cm colour red
    robot at 20 cm, 20 cm heading 45 deg colour blue
    robot bob at 60 cm, 60 cm heading 180 deg program wall_follow.epk
    robot eve at 20 cm, 60 cm program main.c demo.c     (a C main and its other files)
    seed 7                        # Enki's random generator (default 1)
    noise 5 %                     # wheel speed noise, +- (default 5 %, Enki's e-puck)
    step 10 ms                    # physics step (default 10 ms)
    messages range 22.5 cm loss 5 % interval 100 ms emitter 60 deg receiver 60 deg
                                  # the IR message channel (these are the defaults)

docs/world.md is the reference. `parse_world` returns a `World` in
millimetres and degrees, or raises `WorldError` with `file:line:col: error:
what is wrong`, and how to fix it.
"""
from __future__ import annotations

import math
import re
from pathlib import Path
from typing import Optional

from ..base.records import field, record

ROBOT_RADIUS_MM = 37.0          # Enki's e-puck body
DEFAULT_HEIGHT_MM = 50.0        # boxes and cylinders: taller than the IR sensors (25 mm)
LENGTH_UNITS = {"mm": 1.0, "cm": 10.0, "m": 1000.0}
MAX_ROBOTS = 1000
MAX_LENGTH_MM = 100_000.0       # 100 m
NAME_RE = re.compile(r"[A-Za-z_][A-Za-z0-9_-]*\Z")
KEYWORDS = {"at", "size", "x", "angle", "height", "radius", "heading", "program", "none",
            "range", "loss", "interval", "emitter", "receiver", "range_noise", "colour"}
# What the camera sees of each colour a world may give (r, g, b, 0..255):
# the six the camera tells apart (stdlib COLOURS) and three it does not.
COLOURS = {"red": (230, 30, 30), "yellow": (230, 220, 40), "green": (40, 190, 60),
           "cyan": (40, 200, 210), "blue": (40, 70, 220), "magenta": (210, 40, 200),
           "white": (240, 240, 240), "grey": (128, 128, 128), "black": (20, 20, 20)}
DEFAULT_COLOUR = "grey"         # walls, boxes, cylinders and robots without one


@record
class Messages:
    """The IR message channel (runtime_c/enki/world_channel.h); the defaults
    and where they come from are in docs/world.md."""
    range_mm: float = 225.0
    loss_percent: float = 5.0
    interval_ms: int = 100
    emitter_deg: float = 60.0
    receiver_deg: float = 60.0
    range_noise_percent: float = 10.0


class WorldError(Exception):
    """A problem in a world file; str() is the whole diagnostic."""


@record
class Box:
    x_mm: float
    y_mm: float
    length_mm: float        # along the box's own x axis (at angle 0: the world's x)
    width_mm: float
    angle_deg: float = 0.0
    height_mm: float = DEFAULT_HEIGHT_MM
    line: int = 0
    colour: str = DEFAULT_COLOUR


@record
class Cylinder:
    x_mm: float
    y_mm: float
    radius_mm: float
    height_mm: float = DEFAULT_HEIGHT_MM
    line: int = 0
    colour: str = DEFAULT_COLOUR


@record
class RobotPlacement:
    name: str
    x_mm: float
    y_mm: float
    heading_deg: float = 0.0
    program: Optional[Path] = None      # None: the program given on the command line
    line: int = 0
    colour: str = DEFAULT_COLOUR
    more_c: tuple = ()                  # a C program's other files, after its main


@record
class World:
    path: Path
    width_mm: Optional[float] = None    # None: open ground
    height_mm: Optional[float] = None
    boxes: list = field(default_factory=list)
    cylinders: list = field(default_factory=list)
    robots: list = field(default_factory=list)
    seed: int = 1
    noise_percent: float = 5.0
    step_ms: int = 10
    messages: Messages = field(default_factory=Messages)
    wall_colour: str = DEFAULT_COLOUR

    @property
    def walled(self) -> bool:
        return self.width_mm is not None

    def to_json(self) -> dict:
        """The world as the first record of a trace (what `epuckc plot` draws)."""
        def r1(v):
            return round(float(v), 1)
        return {
            "kind": "world",
            "arena": ({"width_mm": r1(self.width_mm), "height_mm": r1(self.height_mm),
                       "colour": self.wall_colour} if self.walled else None),
            "boxes": [{"x_mm": r1(b.x_mm), "y_mm": r1(b.y_mm), "length_mm": r1(b.length_mm),
                       "width_mm": r1(b.width_mm), "angle_deg": r1(b.angle_deg),
                       "colour": b.colour} for b in self.boxes],
            "cylinders": [{"x_mm": r1(c.x_mm), "y_mm": r1(c.y_mm), "radius_mm": r1(c.radius_mm),
                           "colour": c.colour} for c in self.cylinders],
            "robots": [{"name": r.name, "x_mm": r1(r.x_mm), "y_mm": r1(r.y_mm),
                        "heading_deg": r1(r.heading_deg), "colour": r.colour}
                       for r in self.robots],
            "robot_radius_mm": ROBOT_RADIUS_MM,
            "seed": self.seed,
            "noise_percent": self.noise_percent,
            "step_ms": self.step_ms,
            "messages": {"range_mm": r1(self.messages.range_mm),
                         "loss_percent": self.messages.loss_percent,
                         "interval_ms": self.messages.interval_ms,
                         "emitter_deg": self.messages.emitter_deg,
                         "receiver_deg": self.messages.receiver_deg,
                         "range_noise_percent": self.messages.range_noise_percent},
        }


# ---- tokens ---------------------------------------------------------------------

_TOKEN = re.compile(r"\s*(?:(?P<num>[-+]?(?:\d+\.?\d*|\.\d+))(?P<unit>[A-Za-z%]+)?"
                    r"|(?P<word>[^\s,]+)|(?P<comma>,))")


@record
class _Tok:
    text: str
    col: int
    number: Optional[float] = None
    unit: Optional[str] = None


def _tokens(line: str) -> list:
    out = []
    pos = 0
    while pos < len(line):
        m = _TOKEN.match(line, pos)
        if m is None or m.end() == pos:
            break
        start = m.start(m.lastgroup) + 1
        if m.group("num") is not None:
            out.append(_Tok(m.group(0).strip(), start, float(m.group("num")), m.group("unit")))
        elif m.group("word") is not None:
            out.append(_Tok(m.group("word"), start))
        pos = m.end()
    return out


class _Line:
    """A cursor over one line's tokens, with diagnostics that point into it."""

    def __init__(self, path: str, lineno: int, text: str):
        self.path, self.lineno, self.text = path, lineno, text
        self.toks = _tokens(text)
        self.i = 0

    def error(self, message: str, tok: Optional[_Tok] = None, help: str = "") -> WorldError:
        col = tok.col if tok is not None else len(self.text.rstrip()) + 1
        text = f"{self.path}:{self.lineno}:{col}: error: {message}"
        text += f"\n {self.lineno} | {self.text.rstrip()}\n"
        text += " " * (len(str(self.lineno)) + 1) + " | " + " " * (col - 1) + "^"
        if help:
            text += f"\nhelp: {help}"
        return WorldError(text)

    def at_end(self) -> bool:
        return self.i >= len(self.toks)

    def peek(self) -> Optional[_Tok]:
        return self.toks[self.i] if self.i < len(self.toks) else None

    def next(self, what: str) -> _Tok:
        tok = self.peek()
        if tok is None:
            raise self.error(f"expected {what} here, at the end of the line")
        self.i += 1
        return tok

    def keyword(self, word: str) -> bool:
        tok = self.peek()
        if tok is not None and tok.number is None and tok.text.lower() == word:
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


# ---- parsing ----------------------------------------------------------------------

def parse_world(path: Path, text: Optional[str] = None, shown: Optional[str] = None) -> World:
    shown = shown or str(path)
    if text is None:
        try:
            text = Path(path).read_text(encoding="utf-8")
        except FileNotFoundError:
            raise WorldError(f"the world file {shown} does not exist") from None
        except (OSError, UnicodeDecodeError) as exc:
            raise WorldError(f"cannot read the world file {shown}: "
                             f"{getattr(exc, 'strerror', None) or exc}") from None
    world = World(Path(path))
    seen = {}
    names = set()
    errors = []         # every line's first error: all of a file's at once
    for lineno, raw in enumerate(text.splitlines(), 1):
        try:
            _parse_line(world, path, shown, lineno, raw, seen, names)
        except WorldError as exc:
            errors.append(str(exc))
    if not errors:
        errors = _check_placement(world, text.splitlines(), shown)
    if errors:
        count = f"{len(errors)} error{'s' if len(errors) > 1 else ''}"
        raise WorldError("\n\n".join(errors) + f"\n\n{count} in {shown}")
    return world


def _parse_line(world: World, path: Path, shown: str, lineno: int, raw: str, seen: dict,
                names: set):
    """One item of a world file into `world`, or a WorldError."""
    body = raw.split("#", 1)[0]
    ln = _Line(shown, lineno, raw)
    ln.toks = _tokens(body)
    if ln.at_end():
        return
    head = ln.next("an item")
    kind = head.text.lower() if head.number is None else ""
    if kind in ("arena", "seed", "noise", "step", "messages"):
        if kind in seen:
            raise ln.error(f"a second `{kind}` line (the first is line {seen[kind]})", head,
                           "a world has one of each; delete one")
        seen[kind] = lineno
    if kind == "arena":
        if ln.keyword("none"):
            pass
        else:
            world.width_mm = ln.length("arena's width", positive=True)
            ln.expect("x", "arena 120 cm x 80 cm")
            world.height_mm = ln.length("arena's height", positive=True)
            if ln.keyword("colour"):
                world.wall_colour = _colour(ln)
    elif kind == "box":
        ln.expect("at", "box at 40 cm, 30 cm size 20 cm x 5 cm")
        x, y = ln.point()
        ln.expect("size", "box at 40 cm, 30 cm size 20 cm x 5 cm")
        length = ln.length("box's length", positive=True)
        ln.expect("x", "box at 40 cm, 30 cm size 20 cm x 5 cm")
        width = ln.length("box's width", positive=True)
        box = Box(x, y, length, width, line=lineno)
        while not ln.at_end():
            if ln.keyword("angle"):
                box.angle_deg = ln.angle()
            elif ln.keyword("height"):
                box.height_mm = ln.length("box's height", positive=True)
            elif ln.keyword("colour"):
                box.colour = _colour(ln)
            else:
                ln.end()
        world.boxes.append(box)
    elif kind == "cylinder":
        ln.expect("at", "cylinder at 90 cm, 50 cm radius 6 cm")
        x, y = ln.point()
        ln.expect("radius", "cylinder at 90 cm, 50 cm radius 6 cm")
        cyl = Cylinder(x, y, ln.length("radius", positive=True), line=lineno)
        while not ln.at_end():
            if ln.keyword("height"):
                cyl.height_mm = ln.length("cylinder's height", positive=True)
            elif ln.keyword("colour"):
                cyl.colour = _colour(ln)
            else:
                ln.end()
        world.cylinders.append(cyl)
    elif kind == "robot":
        name = f"r{len(world.robots) + 1}"
        tok = ln.peek()
        if tok is not None and tok.number is None and tok.text.lower() != "at":
            ln.i += 1
            if not NAME_RE.match(tok.text) or tok.text.lower() in KEYWORDS:
                raise ln.error(f"`{tok.text}` cannot name a robot", tok,
                               "a name is a letter or _ followed by letters, digits, _ or -")
            name = tok.text
        if name in names:
            raise ln.error(f"a second robot named `{name}`", tok or head,
                           "give each robot its own name")
        names.add(name)
        ln.expect("at", "robot at 20 cm, 20 cm heading 45 deg")
        x, y = ln.point()
        robot = RobotPlacement(name, x, y, line=lineno)
        while not ln.at_end():
            if ln.keyword("heading"):
                robot.heading_deg = ln.angle()
            elif ln.keyword("colour"):
                robot.colour = _colour(ln)
            elif ln.keyword("program"):
                ptok = ln.next("a program file (.epk or .c)")
                program = Path(ptok.text)
                if not program.is_absolute():
                    program = Path(path).parent / program
                if not program.is_file():
                    raise ln.error(f"the program {ptok.text} does not exist", ptok,
                                   "the path is relative to the world file's folder")
                robot.program = program
                more = []
                while program.suffix == ".c" and ln.peek() is not None \
                        and ln.peek().text.endswith(".c"):
                    ctok = ln.next("a C file")
                    extra = Path(ctok.text)
                    if not extra.is_absolute():
                        extra = Path(path).parent / extra
                    if not extra.is_file():
                        raise ln.error(f"the C file {ctok.text} does not exist", ctok,
                                       "the path is relative to the world file's folder")
                    more.append(extra)
                robot.more_c = tuple(more)
            else:
                ln.end()
        if len(world.robots) == MAX_ROBOTS:
            raise ln.error(f"more than {MAX_ROBOTS} robots", head)
        world.robots.append(robot)
    elif kind == "seed":
        tok = ln.next("a whole number")
        if tok.number is None or tok.unit or not tok.text.isdigit() or int(tok.text) >= 2**32:
            raise ln.error("the seed is a whole number from 0 to 4294967295", tok)
        world.seed = int(tok.text)
    elif kind == "noise":
        tok = ln.peek()
        value = ln._quantity({"%": 1.0}, "noise", "5 %")
        if not 0 <= value <= 50:
            raise ln.error("the noise is from 0 % to 50 %", tok)
        world.noise_percent = value
    elif kind == "step":
        tok = ln.peek()
        value = ln._quantity({"ms": 1.0, "s": 1000.0}, "duration", "10 ms")
        if value != int(value) or not 1 <= value <= 100:
            raise ln.error("the physics step is a whole number of ms from 1 to 100", tok)
        world.step_ms = int(value)
    elif kind == "messages":
        _messages(world.messages, ln)
    else:
        raise ln.error(f"unknown item `{head.text}`", head,
                       "a line starts with arena, box, cylinder, robot, seed, noise, step or "
                       "messages")
    ln.end()


def _colour(ln: _Line) -> str:
    tok = ln.next("a colour")
    name = tok.text.lower()
    if tok.number is not None or name not in COLOURS:
        raise ln.error(f"`{tok.text}` is not a colour of a world", tok,
                       "the colours are " + ", ".join(COLOURS))
    return name


def _messages(m: Messages, ln: _Line):
    """`messages [range L] [loss P %] [interval T ms] [emitter A deg]
    [receiver A deg] [range_noise P %]`, any of them, in any order."""
    example = "messages range 22.5 cm loss 5 % interval 100 ms"
    if ln.at_end():
        raise ln.error("`messages` needs a setting: range, loss, interval, emitter, receiver "
                       "or range_noise", None, f"for example: {example}")
    while not ln.at_end():
        tok = ln.peek()
        if ln.keyword("range"):
            m.range_mm = ln.length("message range", positive=True)
        elif ln.keyword("loss") or ln.keyword("range_noise"):
            value = ln._quantity({"%": 1.0}, "percentage", "5 %")
            if not 0 <= value <= 100:
                raise ln.error(f"the {tok.text} is from 0 % to 100 %", tok)
            if tok.text.lower() == "loss":
                m.loss_percent = value
            else:
                m.range_noise_percent = value
        elif ln.keyword("interval"):
            value = ln._quantity({"ms": 1.0, "s": 1000.0}, "duration", "100 ms")
            if value != int(value) or not 1 <= value <= 60_000:
                raise ln.error("the interval is a whole number of ms from 1 to 60000", tok)
            m.interval_ms = int(value)
        elif ln.keyword("emitter") or ln.keyword("receiver"):
            value = ln.angle()
            if not 0 < value <= 360:
                raise ln.error(f"the {tok.text} cone's width is from 0 to 360 deg", tok)
            if tok.text.lower() == "emitter":
                m.emitter_deg = value
            else:
                m.receiver_deg = value
        else:
            raise ln.error(f"unknown setting `{tok.text}` of messages", tok,
                           "the settings are range, loss, interval, emitter, receiver and "
                           f"range_noise, e.g. {example}")


def _check_placement(world: World, lines: list, shown: str) -> list:
    """Everything inside the arena, and no robot inside something else: the
    problems found, each a diagnostic's text."""
    problems = []

    def fail(line: int, message: str, help: str):
        text = lines[line - 1].rstrip()
        col = len(text) - len(text.lstrip()) + 1        # the item's first word
        problems.append(f"{shown}:{line}:{col}: error: {message}\n {line} | {text}\n"
                        + " " * (len(str(line)) + 1) + " | " + " " * (col - 1) + "^"
                        + f"\nhelp: {help}")

    if not world.robots:
        # one robot: the arena's centre, or the origin of open ground, facing +x
        if world.walled:
            world.robots.append(RobotPlacement("r1", world.width_mm / 2, world.height_mm / 2))
        else:
            world.robots.append(RobotPlacement("r1", 0.0, 0.0))
    r = ROBOT_RADIUS_MM
    for robot in world.robots:
        if robot.line == 0:
            continue
        if world.walled and not (r <= robot.x_mm <= world.width_mm - r
                                 and r <= robot.y_mm <= world.height_mm - r):
            fail(robot.line, f"robot {robot.name} at ({robot.x_mm:g} mm, {robot.y_mm:g} mm) is not "
                 f"inside the {world.width_mm:g} x {world.height_mm:g} mm arena",
                 f"its centre must be at least {r:g} mm (the e-puck's radius) from each wall")
        for c in world.cylinders:
            if math.hypot(robot.x_mm - c.x_mm, robot.y_mm - c.y_mm) < c.radius_mm + r:
                fail(robot.line, f"robot {robot.name} overlaps the cylinder of line {c.line}",
                     "move the robot or the cylinder")
        for b in world.boxes:
            if _box_distance(b, robot.x_mm, robot.y_mm) < r:
                fail(robot.line, f"robot {robot.name} overlaps the box of line {b.line}",
                     "move the robot or the box")
    for i, a in enumerate(world.robots):
        for b in world.robots[i + 1:]:
            if math.hypot(a.x_mm - b.x_mm, a.y_mm - b.y_mm) < 2 * r:
                fail(b.line, f"robot {b.name} overlaps robot {a.name}",
                     f"robots' centres must be at least {2 * r:g} mm apart")
    if world.walled:
        for obj in world.boxes + world.cylinders:
            if not (0 <= obj.x_mm <= world.width_mm and 0 <= obj.y_mm <= world.height_mm):
                fail(obj.line, "this obstacle's centre is outside the arena",
                     f"the arena spans 0..{world.width_mm:g} mm x 0..{world.height_mm:g} mm")
    return problems


def _box_distance(b: Box, x: float, y: float) -> float:
    """Distance from a point to a (rotated) box, 0 inside."""
    a = math.radians(b.angle_deg)
    dx, dy = x - b.x_mm, y - b.y_mm
    lx = dx * math.cos(a) + dy * math.sin(a)
    ly = -dx * math.sin(a) + dy * math.cos(a)
    ox = max(abs(lx) - b.length_mm / 2, 0.0)
    oy = max(abs(ly) - b.width_mm / 2, 0.0)
    return math.hypot(ox, oy)


def _rgb(colour: str) -> str:
    """A colour as Enki's components, 0..1."""
    return " ".join(repr(round(v / 255, 6)) for v in COLOURS[colour])


def runner_spec(world: World, robots: list) -> str:
    """The world for runtime_c/enki/world_runner.cpp: lengths in cm, angles
    in radians, colours as r g b in 0..1. `robots` gives, in the world's
    order, (library path, {setting: value}[, devices]) for each robot:
    `devices` (stdlib DEVICES; None or left out: all) says which of the
    costly ones it reads, "camera" (Enki's camera on its body) and "tof"
    (the distance ray, cast at every step)."""
    def f(v: float) -> str:
        return repr(float(v))
    out = []
    if world.walled:
        out.append(f"arena square {f(world.width_mm / 10)} {f(world.height_mm / 10)} "
                   f"{_rgb(world.wall_colour)}")
    else:
        out.append("arena none")
    out.append(f"seed {world.seed}")
    out.append(f"noise {f(world.noise_percent / 100)}")
    out.append(f"step_ms {world.step_ms}")
    m = world.messages
    out.append(f"messages {f(m.range_mm / 10)} {f(m.loss_percent / 100)} "
               f"{f(math.radians(m.emitter_deg))} {f(math.radians(m.receiver_deg))} "
               f"{f(m.range_noise_percent / 100)} {m.interval_ms}")
    for b in world.boxes:
        out.append(f"box {f(b.x_mm / 10)} {f(b.y_mm / 10)} {f(b.length_mm / 10)} "
                   f"{f(b.width_mm / 10)} {f(math.radians(b.angle_deg))} {f(b.height_mm / 10)} "
                   f"{_rgb(b.colour)}")
    for c in world.cylinders:
        out.append(f"cylinder {f(c.x_mm / 10)} {f(c.y_mm / 10)} {f(c.radius_mm / 10)} "
                   f"{f(c.height_mm / 10)} {_rgb(c.colour)}")
    for placement, (lib, settings, *rest) in zip(world.robots, robots):
        devices = rest[0] if rest and rest[0] is not None else ("camera", "tof")
        out.append(f"robot {placement.name} {f(placement.x_mm / 10)} {f(placement.y_mm / 10)} "
                   f"{f(math.radians(placement.heading_deg))}")
        out.append(f"lib {lib}")
        out.append(f"colour {_rgb(placement.colour)}")
        out.extend(device for device in ("camera", "tof") if device in devices)
        for name, value in settings.items():
            out.append(f"setting {name} {value}")
    return "\n".join(out) + "\n"
