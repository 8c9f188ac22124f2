"""The floor of a world (`floor` lines): what the robots' ground sensors
read, and what the pictures draw under the robots.

    floor "track.png"                  an image spanning the arena (or `floor image FILE`)
    floor colour grey                  the floor's own colour (default white)
    floor line from 10 cm, 10 cm to 50 cm, 10 cm [to ...] [closed] width 2 cm [colour C]
    floor polygon from X, Y to X, Y to X, Y [width W] [colour C]
    floor circle at X, Y radius R [width W] [colour C]
    floor ellipse at X, Y size A x B [angle D] [width W] [colour C]
    floor rectangle at X, Y size L x W [angle D] [width W] [colour C]

A shape with a `width` is a line of that width along its outline (a
track); without, it is filled (a region). Shapes are painted in the
file's order over the image or the colour, in black unless a colour is
given. A floor spans the arena: it needs an `arena W x H` line.

The floor becomes one raster (Pillow) of the arena at MM_PER_PX: the
texture the world runner hands Enki (`texture`, written for the runner by
`write_texture`), and a smaller PNG of it for the trace's world record
(`picture`), which the SVG and the replay draw (`draw`). docs/world.md,
"The floor and the ground sensors", is the reference.
"""
from __future__ import annotations

import base64
import io
import math
from pathlib import Path
from typing import Optional

from ..base.records import field, record
from .worldline import COLOURS, Line, Tok, colour

MM_PER_PX = 2.0             # the texture's resolution (Enki's ground sensor samples every 2.5 mm)
MAX_TEXTURE_PX = 4096       # per side: a larger arena gets a coarser texture
MAX_IMAGE_PX = 8192         # an image file wider or higher is refused
PICTURE_PX = 640            # the trace's picture of the floor, its longer side at most
FLOOR_COLOUR = "white"      # without `floor colour`: white paper
SHAPE_COLOUR = "black"      # a shape without `colour`: black tape or ink
WHITE = (255, 255, 255)
SHAPES = ("line", "polygon", "circle", "ellipse", "rectangle")
EXAMPLE = "floor line from 10 cm, 10 cm to 50 cm, 10 cm width 2 cm"


@record
class Shape:
    kind: str                       # one of SHAPES
    points: tuple                   # line, polygon: its corners; the others: (centre,)
    size: tuple = ()                # circle (r, r), ellipse (a, b) and rectangle (l, w): mm
    angle_deg: float = 0.0
    width_mm: Optional[float] = None    # a line this wide along the outline; None: filled
    colour: str = SHAPE_COLOUR
    closed: bool = True             # a line's outline joins its last point to its first
    line: int = 0

    def outline(self) -> list:
        """The shape's outline as points (mm): a line's own, the others'
        turned by their angle; a circle's and an ellipse's with a point
        every 2 mm or so."""
        if self.kind in ("line", "polygon"):
            return list(self.points)
        (cx, cy), (a, b) = self.points[0], self.size
        if self.kind == "rectangle":
            local = [(-a / 2, -b / 2), (a / 2, -b / 2), (a / 2, b / 2), (-a / 2, b / 2)]
        else:
            rx, ry = (a, b) if self.kind == "circle" else (a / 2, b / 2)
            n = max(64, int(math.pi * (rx + ry) / MM_PER_PX))
            local = [(rx * math.cos(2 * math.pi * k / n), ry * math.sin(2 * math.pi * k / n))
                     for k in range(n)]
        t = math.radians(self.angle_deg)
        c, s = math.cos(t), math.sin(t)
        return [(cx + x * c - y * s, cy + x * s + y * c) for x, y in local]


@record
class Floor:
    colour: str = FLOOR_COLOUR
    image: Optional[Path] = None
    shapes: list = field(default_factory=list)
    line: int = 0                   # the first `floor` line
    image_line: int = 0
    colour_line: int = 0


# ---- parsing ----------------------------------------------------------------------

def parse(world, ln: Line, path: Path, lineno: int) -> None:
    """One `floor` line (its `floor` read) into world.floor."""
    floor = world.floor
    if floor is None:
        floor = world.floor = Floor(line=lineno)
    tok = ln.peek()
    if tok is None:
        raise ln.error("`floor` needs an image, a colour or a shape", None,
                       f'for example: floor "track.png", floor colour grey, or {EXAMPLE}')
    word = tok.text.lower() if not tok.quoted and tok.number is None else ""
    if tok.quoted or word == "image" or word.endswith(".png"):
        ln.i += 1
        if word == "image":
            tok = ln.next('an image file such as "track.png"')
        if floor.image_line:
            raise ln.error(f"a second floor image (the first is line {floor.image_line})",
                           tok, "a floor has one image; draw more on it with shapes")
        floor.image = _image_path(ln, tok, path)
        floor.image_line = lineno
    elif word == "colour":
        ln.i += 1
        if floor.colour_line:
            raise ln.error(f"a second floor colour (the first is line {floor.colour_line})",
                           tok, "a floor has one colour; paint regions with shapes")
        floor.colour = colour(ln)
        floor.colour_line = lineno
    elif word in SHAPES:
        ln.i += 1
        floor.shapes.append(_shape(ln, word, lineno))
    else:
        raise ln.error(f"unknown floor item `{tok.text}`", tok,
                       'a floor line gives an image ("track.png"), `colour C`, or a shape: '
                       + ", ".join(SHAPES))


def _image_path(ln: Line, tok: Tok, world_path: Path) -> Path:
    """The image file of `floor FILE`, relative to the world file's folder:
    a PNG that Pillow reads (checked now, so that a run never starts with
    one it cannot)."""
    image = Path(tok.text)
    if not image.is_absolute():
        image = Path(world_path).parent / image
    if not image.is_file():
        raise ln.error(f"the image {tok.text} does not exist", tok,
                       "the path is relative to the world file's folder")
    try:
        from PIL import Image, UnidentifiedImageError
    except ImportError:         # pragma: no cover - Pillow is a dependency
        raise ln.error("reading a floor image needs Pillow (pip install Pillow)", tok) from None
    try:
        with Image.open(image) as im:
            size, fmt = im.size, im.format
    except (UnidentifiedImageError, OSError) as exc:
        raise ln.error(f"{tok.text} is not an image Pillow can read ({exc})", tok,
                       "give a PNG file (the floor's picture, spanning the arena)") from None
    if fmt != "PNG":
        raise ln.error(f"{tok.text} is a {fmt} image, not a PNG", tok,
                       "save it as PNG (lossless: a line's edges stay sharp)")
    if max(size) > MAX_IMAGE_PX:
        raise ln.error(f"{tok.text} is {size[0]} x {size[1]} pixels, more than "
                       f"{MAX_IMAGE_PX} on a side", tok,
                       f"scale it down: the floor is sampled every {MM_PER_PX:g} mm")
    return image


def _shape(ln: Line, kind: str, lineno: int) -> Shape:
    example = {"line": EXAMPLE,
               "polygon": "floor polygon from 10 cm, 10 cm to 30 cm, 10 cm to 20 cm, 30 cm",
               "circle": "floor circle at 50 cm, 40 cm radius 20 cm width 2 cm",
               "ellipse": "floor ellipse at 50 cm, 40 cm size 60 cm x 40 cm width 2 cm",
               "rectangle": "floor rectangle at 50 cm, 40 cm size 30 cm x 20 cm"}[kind]
    if kind in ("line", "polygon"):
        ln.expect("from", example)
        points = [ln.point()]
        while ln.keyword("to"):
            points.append(ln.point())
        least = 2 if kind == "line" else 3
        if len(points) < least:
            raise ln.error(f"a floor {kind} needs at least {least} points, "
                           f"`from X, Y to X, Y`{' to X, Y' if least == 3 else ''}",
                           ln.peek(), f"write it as: {example}")
        shape = Shape(kind, tuple(points), line=lineno, closed=kind == "polygon")
    else:
        ln.expect("at", example)
        centre = ln.point()
        if kind == "circle":
            ln.expect("radius", example)
            r = ln.length("radius", positive=True)
            size = (r, r)
        else:
            ln.expect("size", example)
            a = ln.length(f"{kind}'s length", positive=True)
            ln.expect("x", example)
            size = (a, ln.length(f"{kind}'s width", positive=True))
        shape = Shape(kind, (centre,), size, line=lineno)
    while not ln.at_end():
        tok = ln.peek()
        if ln.keyword("width"):
            shape.width_mm = ln.length("line's width", positive=True)
        elif ln.keyword("colour"):
            shape.colour = colour(ln)
        elif kind == "line" and ln.keyword("closed"):
            shape.closed = True
        elif kind in ("ellipse", "rectangle") and ln.keyword("angle"):
            shape.angle_deg = ln.angle()
        else:
            raise ln.error(f"unexpected `{tok.text}`", tok,
                           f"a floor {kind} takes "
                           + ("`closed`, " if kind == "line" else "")
                           + ("`angle A`, " if kind in ("ellipse", "rectangle") else "")
                           + f"`width W` and `colour C`, e.g. {example}")
    if kind == "line" and shape.width_mm is None:
        raise ln.error("a floor line needs a width", None, f"write it as: {example}")
    return shape


def check(world, lines: list, shown: str) -> list:
    """A floor needs an arena to span: the problems found, as diagnostics."""
    floor = world.floor
    if floor is None or world.walled:
        return []
    text = lines[floor.line - 1].rstrip()
    col = len(text) - len(text.lstrip()) + 1
    return [f"{shown}:{floor.line}:{col}: error: a floor spans the arena, and this world has "
            f"none\n {floor.line} | {text}\n" + " " * (len(str(floor.line)) + 1) + " | "
            + " " * (col - 1) + "^\nhelp: give the world an arena: `arena 120 cm x 80 cm`"]


# ---- the raster ---------------------------------------------------------------------

def _grid(world) -> tuple:
    """(width px, height px, mm a pixel) of the world's texture."""
    mm = max(MM_PER_PX, max(world.width_mm, world.height_mm) / MAX_TEXTURE_PX)
    return max(1, round(world.width_mm / mm)), max(1, round(world.height_mm / mm)), mm


def raster(world):
    """The floor as a Pillow RGB image of the arena, its top row at the
    arena's far edge (y = height)."""
    from PIL import Image, ImageDraw
    floor = world.floor
    w, h, _ = _grid(world)
    sx, sy = w / world.width_mm, h / world.height_mm
    base = COLOURS[floor.colour] if floor.colour != "white" else WHITE
    im = Image.new("RGB", (w, h), base)
    if floor.image is not None:
        with Image.open(floor.image) as picture:
            picture = picture.convert("RGBA")
            backing = Image.new("RGBA", picture.size, base + (255,))
            picture = Image.alpha_composite(backing, picture).convert("RGB")
            im.paste(picture.resize((w, h), Image.Resampling.BILINEAR))
    draw = ImageDraw.Draw(im)

    def px(p):
        return (p[0] * sx, (world.height_mm - p[1]) * sy)

    for shape in floor.shapes:
        fill = COLOURS[shape.colour] if shape.colour != "white" else WHITE
        points = [px(p) for p in shape.outline()]
        if shape.width_mm is None:
            draw.polygon(points, fill=fill)
            continue
        _stroke(draw, points, max(1.0, shape.width_mm * sx), fill, shape.closed)
    return im


def _stroke(draw, points: list, width: float, fill, closed: bool) -> None:
    """A line `width` pixels wide along the points: a quadrilateral along
    each segment and a disc at each point (round joins and ends, as tape
    laid down), filled, so that it has no gaps at the joins."""
    r = width / 2
    segments = list(zip(points, points[1:] + points[:1] if closed else points[1:]))
    for (x0, y0), (x1, y1) in segments:
        length = math.hypot(x1 - x0, y1 - y0)
        if length == 0:
            continue
        nx, ny = -(y1 - y0) / length * r, (x1 - x0) / length * r
        draw.polygon([(x0 + nx, y0 + ny), (x1 + nx, y1 + ny), (x1 - nx, y1 - ny),
                      (x0 - nx, y0 - ny)], fill=fill)
    for x, y in points:
        draw.ellipse((x - r, y - r, x + r, y + r), fill=fill)


def texture(world) -> tuple:
    """(width px, height px, RGB bytes with the row of y = 0 first): Enki's
    ground texture (World::GroundTexture, scanlines from the arena's
    origin)."""
    from PIL import Image
    im = raster(world).transpose(Image.Transpose.FLIP_TOP_BOTTOM)
    return im.width, im.height, im.tobytes()


def write_texture(world, path: Path) -> str:
    """Writes the texture for the world runner; its spec line."""
    w, h, data = texture(world)
    Path(path).write_bytes(data)
    return f"floor {w} {h} {path}"


def picture(world) -> dict:
    """The floor in the trace's world record: a PNG (as a data URL) of the
    arena, its longer side PICTURE_PX pixels at most."""
    im = raster(world)
    scale = min(1.0, PICTURE_PX / max(im.width, im.height))
    if scale < 1.0:
        from PIL import Image
        im = im.resize((max(1, round(im.width * scale)), max(1, round(im.height * scale))),
                       Image.Resampling.BOX)
    buf = io.BytesIO()
    im.save(buf, format="PNG", optimize=True)
    return {"image": "data:image/png;base64," + base64.b64encode(buf.getvalue()).decode("ascii"),
            "colour": world.floor.colour}


def draw(dwg, group, record: dict, px) -> None:
    """The floor of a trace's world record (`picture`) on the SVG's map,
    under everything else: `image.floor`, spanning the arena."""
    floor, arena = record.get("floor"), record.get("arena")
    if not floor or not arena or not str(floor.get("image", "")).startswith("data:image/png"):
        return
    (ax, ay), (bx, by) = px(0, arena["height_mm"]), px(arena["width_mm"], 0)
    image = dwg.image(href=floor["image"], insert=(ax, ay), size=(round(bx - ax, 1),
                                                                    round(by - ay, 1)),
                      class_="floor")
    image["preserveAspectRatio"] = "none"
    group.add(image)
