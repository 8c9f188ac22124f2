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
    robot sam at 60 cm, 20 cm selector 5 scenario sam.scn
                                  # its selector at start, its inputs at set times
    scenario knocks.scn           # the inputs of every robot without a scenario of its own
    seed 7                        # Enki's random generator (default 1)
    noise 5 %                     # wheel speed noise, +- (default 5 %, Enki's e-puck)
    step 10 ms                    # physics step (default 10 ms)
    messages range 22.5 cm loss 5 % interval 100 ms emitter 60 deg receiver 60 deg
                                  # the IR message channel (these are the defaults)
    floor "track.png"             # the floor the ground sensors read (sim/floor.py), or
    floor line from 20 cm, 20 cm to 80 cm, 20 cm width 2 cm       drawn shapes
    sound at 60 cm, 50 cm frequency 1000 Hz level 80 dB from 1 s to 3 s    (sim/sound.py)
    physics chipmunk              # enki (the default up to 200 robots) or chipmunk (sim/physics.py)

The words of a line and their diagnostics are sim/worldline.py's.
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
from . import floor as floor_lines, physics as physics_line, sound as sound_lines
from .spacing import overlapping
# (COLOURS, LENGTH_UNITS, MAX_LENGTH_MM and WorldError are this module's too)
from .worldline import (COLOURS, DEFAULT_COLOUR, KEYWORDS, LENGTH_UNITS, MAX_LENGTH_MM,  # noqa: F401
                        WorldError, colour as _colour, Line as _Line, tokens)

ROBOT_RADIUS_MM = 37.0          # Enki's e-puck body
DEFAULT_HEIGHT_MM = 50.0        # boxes and cylinders: taller than the IR sensors (25 mm)
MAX_ROBOTS = 100_000
NAME_RE = re.compile(r"[A-Za-z_][A-Za-z0-9_-]*\Z")


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
    selector: Optional[int] = None      # the selector's position at start
    scenario: Optional[Path] = None     # its inputs at set times (a scenario file)


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
    floor: Optional[floor_lines.Floor] = None   # None: white paper, nothing drawn
    sounds: list = field(default_factory=list)  # sound.Sound: the sound sources
    physics: Optional[str] = None       # the `physics` line's; None: by the robot count
    physics_line: int = 0
    scenario: Optional[Path] = None     # the inputs of the robots without their own

    @property
    def walled(self) -> bool:
        return self.width_mm is not None

    @property
    def resolved_physics(self) -> str:
        """Its `physics` line's, else by its robot count (sim/physics.py)."""
        return physics_line.resolved(self)

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
            "physics": self.resolved_physics,
            "messages": {"range_mm": r1(self.messages.range_mm),
                         "loss_percent": self.messages.loss_percent,
                         "interval_ms": self.messages.interval_ms,
                         "emitter_deg": self.messages.emitter_deg,
                         "receiver_deg": self.messages.receiver_deg,
                         "range_noise_percent": self.messages.range_noise_percent},
            # (a floor and sound sources only when the world has them)
            **({"floor": floor_lines.picture(self)} if self.floor else {}),
            **({"sounds": sound_lines.to_json(self)} if self.sounds else {}),
        }


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
        lines = text.splitlines()
        errors = (_check_placement(world, lines, shown) + floor_lines.check(world, lines, shown)
                  + sound_lines.check(world, lines, shown)
                  + physics_line.check(world, lines, shown))
    if errors:
        count = f"{len(errors)} error{'s' if len(errors) > 1 else ''}"
        raise WorldError("\n\n".join(errors) + f"\n\n{count} in {shown}")
    return world


def _parse_line(world: World, path: Path, shown: str, lineno: int, raw: str, seen: dict,
                names: set):
    """One item of a world file into `world`, or a WorldError."""
    body = raw.split("#", 1)[0]
    ln = _Line(shown, lineno, raw)
    ln.toks = tokens(body)
    if ln.at_end():
        return
    head = ln.next("an item")
    kind = head.text.lower() if head.number is None else ""
    if kind in ("arena", "seed", "noise", "step", "messages", "physics", "scenario"):
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
            elif ln.keyword("selector"):
                robot.selector = ln.whole("the selector's position, 0 .. 15", 15,
                                          "the selector's position is a whole number from 0 to 15")
            elif ln.keyword("scenario"):
                robot.scenario = _scenario(ln, path)
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
                        and ln.peek().text.endswith((".c", ".s")):
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
            raise ln.error(f"more than {MAX_ROBOTS:,} robots", head)
        world.robots.append(robot)
    elif kind == "seed":
        world.seed = ln.whole("a whole number", 2**32 - 1,
                              "the seed is a whole number from 0 to 4294967295")
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
    elif kind == "floor":
        floor_lines.parse(world, ln, path, lineno)
    elif kind == "sound":
        sound_lines.parse(world, ln, lineno)
    elif kind == "physics":
        physics_line.parse(world, ln, lineno)
    elif kind == "scenario":
        world.scenario = _scenario(ln, path)
    else:
        raise ln.error(f"unknown item `{head.text}`", head,
                       "a line starts with arena, box, cylinder, robot, seed, noise, step, "
                       "messages, floor, sound, physics or scenario")
    ln.end()


def _scenario(ln: _Line, path: Path) -> Path:
    """A scenario file named by the world (relative to its folder): its
    inputs at set times for what physics does not give, checked now (each
    problem at the scenario's own file:line:col)."""
    from .scenario import world_scenario_problems
    tok = ln.next("a scenario file (.scn)")
    scenario = Path(tok.text)
    if not scenario.is_absolute():
        scenario = Path(path).parent / scenario
    if not scenario.is_file():
        raise ln.error(f"the scenario {tok.text} does not exist", tok,
                       "the path is relative to the world file's folder")
    try:
        problems = world_scenario_problems(scenario, tok.text)
    except OSError as exc:
        raise ln.error(f"cannot read the scenario {tok.text}: {exc.strerror or exc}", tok) \
            from None
    if problems:
        raise WorldError("\n\n".join(problems) + "\n" + str(ln.error(
            f"the scenario {tok.text} of this line has "
            f"{len(problems)} error{'s' if len(problems) > 1 else ''} (above)", tok)))
    return scenario


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
            if box_distance(b, robot.x_mm, robot.y_mm) < r:
                fail(robot.line, f"robot {robot.name} overlaps the box of line {b.line}",
                     "move the robot or the box")
    for i, j in overlapping(world.robots, 2 * r):
        a, b = world.robots[i], world.robots[j]
        fail(b.line, f"robot {b.name} overlaps robot {a.name}",
             f"robots' centres must be at least {2 * r:g} mm apart")
    if world.walled:
        for obj in world.boxes + world.cylinders:
            if not (0 <= obj.x_mm <= world.width_mm and 0 <= obj.y_mm <= world.height_mm):
                fail(obj.line, "this obstacle's centre is outside the arena",
                     f"the arena spans 0..{world.width_mm:g} mm x 0..{world.height_mm:g} mm")
    return problems


def box_distance(b: Box, x: float, y: float) -> float:
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


def runner_spec(world: World, robots: list, floor_file: Optional[Path] = None) -> str:
    """The world for runtime_c/enki/world_runner.cpp: lengths in cm, angles
    in radians, colours as r g b in 0..1. `robots` gives, in the world's
    order, (library path, {setting: value}[, devices]) for each robot:
    `devices` (stdlib DEVICES; None or left out: all) says which of the
    costly ones it reads, "camera" (Enki's camera on its body), "tof"
    (the distance ray, cast at every step) and "ground" (Enki's ground
    sensors over the floor). A world with a floor has its texture written
    to `floor_file` (sim/floor.py)."""
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
    if world.floor is not None:
        if floor_file is None:
            raise ValueError("the world has a floor: runner_spec needs a floor_file")
        out.append(floor_lines.write_texture(world, floor_file))
    out.extend(sound_lines.spec_lines(world))
    for placement, (lib, settings, *rest) in zip(world.robots, robots):
        devices = rest[0] if rest and rest[0] is not None else ("camera", "tof", "ground")
        out.append(f"robot {placement.name} {f(placement.x_mm / 10)} {f(placement.y_mm / 10)} "
                   f"{f(math.radians(placement.heading_deg))}")
        out.append(f"lib {lib}")
        out.append(f"colour {_rgb(placement.colour)}")
        out.extend(device for device in ("camera", "tof", "ground") if device in devices)
        for name, value in settings.items():
            out.append(f"setting {name} {value}")
    return "\n".join(out) + "\n"
