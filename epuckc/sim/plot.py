"""Pictures of a run: a trace (JSON lines) drawn as SVG (svg.py).

Above, the map (world frame, millimetres, +y up): the arena's walls, boxes
and cylinders (from the trace's `world` record, when the run had a world),
a scale bar, each robot's path through its poses (the `pose` records and
the pose of every other record), a marker where a rule fired, labelled with
the rule's name (or its event), the modes entered, LEDs switched and the
first contact, and the robot at its final pose with its name and LEDs.
Below, a timeline: bands of who holds the motors and when the robot is
still, one row per rule (and for modes, LEDs and contacts), a tick at each
firing, time in seconds. Labels are laid out so that none covers
another or a robot's name and none leaves the picture (a label with no
free place is left to the marker's tooltip); tests/sim/test_plot_layout.py
measures that in a browser.

The drawing is made of named pieces that tests and tools can find again:
`g#world` (`rect.arena`, `image.floor`, `rect.box`, `circle.cylinder`,
`g.sound`, `g.scale-bar`),
`g.robot-run` (`data-robot`) with `polyline.path`, `circle.firing`
(`data-t-ms`, `data-label`: the rule's `file:line`; `text.firing-label`),
`polygon.mode-change`, `circle.led-change`, `path.contact`,
`g.final-pose` (with the LEDs' `g.leds`: leds.py); `g.messages` with a
`line.message` (`data-t-ms`, `data-from`, `data-to`) from sender to
receiver for each pair that exchanged messages in each second; with more
than MANY_ROBOTS robots each robot's labels are in its `g.labels`, shown
when the pointer is over the robot's run (or, in the replay, for the robot
selected) and the paths are pale; `g#timeline` with the
bands of who holds the motors and when the robot is still
(`g.timeline-band`: timeline.py) and `g.timeline-row` (`data-label`: a
rule's `file:line`, or `mode`, `led`, `contact`) holding `line.tick`
(`data-t-ms`).
"""
from __future__ import annotations

import json
import math
import re
from dataclasses import dataclass, field
from typing import Optional

from . import floor as floor_lines
from . import leds as leds_mod
from . import sound as sound_lines
from . import timeline as bands
from .contacts import contact_words
from .svg import Drawing
from .thin import thin_points
from .world import COLOURS as WORLD_COLOURS

MAP_WIDTH_PX = 640.0
MAP_MAX_HEIGHT_PX = 520.0
MARGIN_PX = 24.0
ROW_PX = 18.0
LABEL_COLUMN_PX = 200.0
ROW_LABEL_CHARS = 40
COLOURS = ["#1f77b4", "#d62728", "#2ca02c", "#9467bd", "#ff7f0e", "#8c564b", "#e377c2",
           "#17becf", "#7f7f7f", "#bcbd22"]
DEFAULT_ROBOT_RADIUS_MM = 37.0
_FILE_LINE = re.compile(r"^(\S+:\d+)(?:\s|$)")


class PlotError(Exception):
    pass


@dataclass
class Firing:
    t_ms: int
    label: str          # file:line, or the event's name: what tells rules apart
    title: str          # the whole record name
    x: float
    y: float
    shown: str = ""     # the words on the map: the rule's name, or its event


@dataclass
class Mark:
    """A mode entered, an LED switched, the first contact: a point of a path."""
    kind: str           # "mode" | "led" | "contact"
    t_ms: int
    text: str
    x: float
    y: float


@dataclass
class RobotRun:
    name: str
    poses: list = field(default_factory=list)       # (t_ms, x, y, heading)
    firings: list = field(default_factory=list)
    marks: list = field(default_factory=list)
    leds: list = field(default_factory=list)        # (t_ms, ring, body, front): leds.py
    holds: list = field(default_factory=list)       # (t_ms, rule label or None, name)
    # messages it received: (t_ms, sender's x, y, its own x, y, sender, value)
    messages: list = field(default_factory=list)


SHOWN_CHARS = 24        # a label on the map; the timeline and the tooltip say it all
# A rule that fires more often than this in a run (`every 10 ms`: continuous
# control) has no markers on the map and one band on the timeline.
DENSE = 50
# More robots than this: labels on demand (hover, selection), pale paths.
MANY_ROBOTS = 10
MESSAGE_BUCKET_MS = 1000    # one line per pair of robots per second
MESSAGE_COLOUR = "#7b1fa2"
_MANY_CSS = ("g.robot-run g.labels { display: none; } "
             "g.robot-run:hover g.labels, g.robot-run.selected g.labels { display: inline; }")


def rule_label(name: str) -> str:
    """`prog.epk:12` for a rule's event (its trace name starts with it);
    the name itself otherwise (hand-written C)."""
    m = _FILE_LINE.match(name)
    return m.group(1) if m else name


def shown_label(name: str) -> str:
    """What the map writes beside a firing: the rule's name (`avoid`), else
    its event (`on sensor(ir0 > 300)`), cut to SHOWN_CHARS."""
    m = _FILE_LINE.match(name)
    rest = name[m.end():].strip() if m else name
    named = re.match(r"rule (\w+):", rest)
    text = named.group(1) if named else rest
    return text if len(text) <= SHOWN_CHARS else text[:SHOWN_CHARS - 1] + "\u2026"


def parse_trace(text: str, source: str = "trace"):
    """The world record (or None) and the robots' runs, in first-seen order."""
    world = None
    runs = {}
    end_ms = 0
    contacts = []
    for lineno, line in enumerate(text.splitlines(), 1):
        if not line.strip():
            continue
        try:
            rec = json.loads(line)
        except json.JSONDecodeError as exc:
            raise PlotError(f"{source}:{lineno}: not a JSON trace record ({exc.msg})") from None
        if not isinstance(rec, dict) or "kind" not in rec:
            raise PlotError(f"{source}:{lineno}: not a trace record (no \"kind\")")
        if rec["kind"] == "world":
            world = rec
            continue
        if "x_mm" not in rec:
            if rec["kind"] == "contacts" and int(rec.get("first_ms", -1)) >= 0:
                contacts.append((str(rec.get("robot", "")), int(rec["first_ms"]), rec))
            continue        # contacts: counts, no pose
        try:
            t, x, y, h = int(rec["t_ms"]), float(rec["x_mm"]), float(rec["y_mm"]), \
                float(rec["heading_deg"])
        except (KeyError, TypeError, ValueError):
            raise PlotError(f"{source}:{lineno}: a record without t_ms, x_mm, y_mm and "
                            f"heading_deg") from None
        name = str(rec.get("robot", ""))
        run = runs.setdefault(name, RobotRun(name))
        run.poses.append((t, x, y, h))
        end_ms = max(end_ms, t)
        if rec["kind"] == "event":
            ev = str(rec.get("name", ""))
            run.firings.append(Firing(t, rule_label(ev), ev, x, y, shown_label(ev)))
        elif rec["kind"] == "mode":
            run.marks.append(Mark("mode", t, f"mode {rec.get('name', '')}", x, y))
        elif rec["kind"] == "led":
            state = "on" if rec.get("state") else "off"
            run.leds.append(leds_mod.led_state(rec))
            run.marks.append(Mark("led", t, f"{rec.get('name', 'LED')} {state} (ring "
                                  f"{run.leds[-1][1]})", x, y))
        elif rec["kind"] == "message" and "from_x_mm" in rec:
            run.messages.append((t, float(rec["from_x_mm"]), float(rec["from_y_mm"]), x, y,
                                 str(rec.get("from", "")), rec.get("value")))
        elif rec["kind"] == "motors":
            owner = str(rec.get("name", ""))
            run.holds.append((t, None if owner == "free" else rule_label(owner), owner))
    if not runs:
        raise PlotError(f"{source}: the trace has no record with a pose")
    for robot, first_ms, rec in contacts:
        run = runs.get(robot)
        if run is None:
            continue
        # where the robot was at its first contact: the last pose before it
        before = [p for p in run.poses if p[0] <= first_ms] or run.poses[:1]
        t, x, y, _ = before[-1]
        words = contact_words(rec)
        run.marks.append(Mark("contact", first_ms, "contact" if words == "no contact" else words,
                              x, y))
    return world, list(runs.values()), end_ms


def _bounds(world: Optional[dict], runs: list, radius: float):
    if world is not None and world.get("arena"):
        return 0.0, 0.0, float(world["arena"]["width_mm"]), float(world["arena"]["height_mm"])
    xs = [p[1] for r in runs for p in r.poses]
    ys = [p[2] for r in runs for p in r.poses]
    if world is not None:
        for b in world.get("boxes", []):
            half = math.hypot(b["length_mm"], b["width_mm"]) / 2
            xs += [b["x_mm"] - half, b["x_mm"] + half]
            ys += [b["y_mm"] - half, b["y_mm"] + half]
        for c in world.get("cylinders", []):
            xs += [c["x_mm"] - c["radius_mm"], c["x_mm"] + c["radius_mm"]]
            ys += [c["y_mm"] - c["radius_mm"], c["y_mm"] + c["radius_mm"]]
    pad = radius + 20.0
    x0, x1, y0, y1 = min(xs) - pad, max(xs) + pad, min(ys) - pad, max(ys) + pad
    # at least 200 mm each way, so a short run is not blown up
    if x1 - x0 < 200:
        c = (x0 + x1) / 2
        x0, x1 = c - 100, c + 100
    if y1 - y0 < 200:
        c = (y0 + y1) / 2
        y0, y1 = c - 100, c + 100
    return x0, y0, x1, y1


LABEL_H = 11.0          # a 9 px label's box, descenders included (the browser's is ~10.5)
BASELINE = 8.5          # from the top of a label's box
CHAR_W = 5.6            # a 9 px sans-serif character, wide ones included (kept above the truth)


def _text_width(text: str, size: float = 9.0) -> float:
    return CHAR_W * size / 9.0 * len(text)


def _label_box(label: str, x: float, y: float, placed: list, width: float):
    """Where the label of a marker at (x, y) goes: right of it (left of it
    near the picture's right edge), above, below or further down; None when
    every place covers a placed label. Boxes are (x, y, w, h, text), y the top."""
    w = _text_width(label)
    if any(text == label and abs(bx - x - 5) < 40 and abs(by - y) < 2 * LABEL_H + 6
           for bx, by, _, _, text in placed):
        return None
    left = x + 5 if x + 5 + w <= width - 2 else x - 5 - w
    if left < 2:
        return None
    for dy in (-LABEL_H - 2, 2.0, -2 * LABEL_H - 4, LABEL_H + 4):
        box = (_r(left), _r(y + dy), w, LABEL_H, label)
        if not any(box[0] < bx + bw and bx < box[0] + w and box[1] < by + bh and by < box[1] + LABEL_H
                   for bx, by, bw, bh, _ in placed):
            return box
    return None


def _scale_length(scale: float) -> float:
    """A round length (mm) that the map draws 40 px long or more."""
    for mm in (10, 20, 50, 100, 200, 500, 1000, 2000, 5000, 10000, 20000, 50000):
        if mm * scale >= 40:
            return float(mm)
    return 100000.0


def _length_text(mm: float) -> str:
    return f"{mm / 1000:g} m" if mm >= 1000 else f"{mm / 10:g} cm"


def _r(v: float) -> float:
    return round(v, 1)


def _nice_step(span_s: float) -> float:
    for step in (0.1, 0.2, 0.5, 1, 2, 5, 10, 15, 30, 60, 120, 300, 600, 1800, 3600):
        if span_s / step <= 12:
            return step
    return 3600 * math.ceil(span_s / 3600 / 12)


def _fill(obstacle: dict) -> str:
    """An obstacle's colour on the map: its world colour (what the camera
    sees), or the map's brown for the default grey."""
    colour = obstacle.get("colour", "grey")
    if colour == "grey" or colour not in WORLD_COLOURS:
        return "#b0a08a"
    return "#%02x%02x%02x" % WORLD_COLOURS[colour]


def robot_colours(world: Optional[dict], runs: list) -> list:
    """Each run's colour: its robot's world `colour` (darkened where it
    would not show on the white map, as white and yellow), else the
    palette's."""
    given = {r.get("name"): r.get("colour") for r in (world or {}).get("robots", [])}
    out = []
    for i, run in enumerate(runs):
        colour = given.get(run.name)
        if colour in WORLD_COLOURS and colour != "grey":
            rgb = WORLD_COLOURS[colour]
            light = (0.2126 * rgb[0] + 0.7152 * rgb[1] + 0.0722 * rgb[2]) / 255
            k = 0.55 / light if light > 0.7 else 1.0       # white, yellow: darker
            out.append("#%02x%02x%02x" % tuple(round(c * k) for c in rgb))
        else:
            out.append(COLOURS[i % len(COLOURS)])
    return out


def _draw_messages(dwg, runs: list, px):
    """A line from sender to receiver for each pair of robots that
    exchanged messages, once per MESSAGE_BUCKET_MS (where they were at the
    first), the tooltip naming the messages."""
    g = dwg.g(class_="messages")
    seen = {}
    for run in runs:
        for t, fx, fy, x, y, sender, value in run.messages:
            key = (sender, run.name, t // MESSAGE_BUCKET_MS)
            if key in seen:
                seen[key][1] += 1
                continue
            line = dwg.line(start=px(fx, fy), end=px(x, y), class_="message",
                            stroke=MESSAGE_COLOUR, stroke_width=0.8, stroke_opacity=0.35)
            line["data-t-ms"] = str(t)
            line["data-from"] = sender
            line["data-to"] = run.name
            seen[key] = [line, 1, t, value]
    for (sender, to, _), (line, count, t, value) in seen.items():
        line.set_desc(title=f"{sender} to {to}: {count} message{'s' if count > 1 else ''} "
                            f"from {t} ms (the first: {value})")
        g.add(line)
    if seen:
        dwg.add(g)


def plot_trace(text: str, title: str = "", source: str = "trace") -> str:
    """The SVG picture of a trace, as text (deterministic)."""
    world, runs, end_ms = parse_trace(text, source)
    radius = float((world or {}).get("robot_radius_mm", DEFAULT_ROBOT_RADIUS_MM))
    x0, y0, x1, y1 = _bounds(world, runs, radius)
    scale = min(MAP_WIDTH_PX / (x1 - x0), MAP_MAX_HEIGHT_PX / (y1 - y0))
    map_w, map_h = (x1 - x0) * scale, (y1 - y0) * scale
    top = MARGIN_PX + (22.0 if title else 0.0)

    def px(x: float, y: float):
        return _r(MARGIN_PX + (x - x0) * scale), _r(top + (y1 - y) * scale)

    rows = []
    row_titles = {}
    for run in runs:
        for f in run.firings:
            if f.label not in rows:
                rows.append(f.label)
                row_titles[f.label] = f.title
    mark_rows = [(kind, words) for kind, words in (("mode", "modes entered"),
                                                   ("led", "LEDs switched"),
                                                   ("contact", "first contact"))
                 if any(m.kind == kind for run in runs for m in run.marks)]
    for kind, words in mark_rows:
        rows.append(kind)
        row_titles[kind] = words
    timeline_top = top + map_h + 36.0
    n_bands = len(bands.band_rows(runs))
    timeline_h = (max(len(rows), 1) + n_bands) * ROW_PX
    width = max(MARGIN_PX * 2 + map_w, MARGIN_PX * 2 + LABEL_COLUMN_PX + 360.0)
    height = timeline_top + timeline_h + 40.0
    dwg = Drawing(size=(f"{_r(width)}", f"{_r(height)}"))
    dwg.viewbox(0, 0, _r(width), _r(height))
    dwg.add(dwg.rect(insert=(0, 0), size=(_r(width), _r(height)), fill="white", class_="background"))
    if title:
        room = int((width - 2 * MARGIN_PX) / (CHAR_W * 15 / 9))
        shown_title = title if len(title) <= room else title[:room - 1] + "\u2026"
        t = dwg.text(shown_title, insert=(MARGIN_PX, MARGIN_PX + 6), class_="title",
                     font_family="sans-serif", font_size=15)
        t.set_desc(title=title)
        dwg.add(t)

    # -- the world; its frame (mm -> px) for a page that moves the robots
    g = dwg.g(id="world")
    g["data-frame"] = f"{x0!r} {y1!r} {scale!r} {MARGIN_PX!r} {top!r}"
    if world is not None and world.get("arena"):
        a = world["arena"]
        (ax, ay), (bx, by) = px(0, a["height_mm"]), px(a["width_mm"], 0)
        wall = a.get("colour", "grey")
        g.add(dwg.rect(insert=(ax, ay), size=(_r(bx - ax), _r(by - ay)), class_="arena",
                       fill="#fafafa", stroke="#%02x%02x%02x" % WORLD_COLOURS[wall]
                       if wall in WORLD_COLOURS and wall != "grey" else "#444", stroke_width=4))
        floor_lines.draw(dwg, g, world, px)         # under everything else
    else:
        g.add(dwg.rect(insert=(MARGIN_PX, top), size=(_r(map_w), _r(map_h)), class_="ground",
                       fill="#fafafa", stroke="#ccc", stroke_width=1, stroke_dasharray="4,4"))
    for b in (world or {}).get("boxes", []):
        cx, cy = px(b["x_mm"], b["y_mm"])
        w, h = b["length_mm"] * scale, b["width_mm"] * scale
        rect = dwg.rect(insert=(_r(cx - w / 2), _r(cy - h / 2)), size=(_r(w), _r(h)), class_="box",
                        fill=_fill(b), stroke="#6b5b45")
        if b.get("angle_deg"):
            rect.rotate(-b["angle_deg"], center=(cx, cy))     # +y is up in the world
        g.add(rect)
    for c in (world or {}).get("cylinders", []):
        g.add(dwg.circle(center=px(c["x_mm"], c["y_mm"]), r=_r(c["radius_mm"] * scale),
                         class_="cylinder", fill=_fill(c), stroke="#6b5b45"))
    sound_lines.draw(dwg, g, world or {}, px, scale)
    # a scale bar in the map's lower left corner
    bar_mm = _scale_length(scale)
    bx0, by0 = MARGIN_PX + 8, _r(top + map_h - 10)
    bar = dwg.g(class_="scale-bar")
    bar["data-mm"] = f"{bar_mm:g}"
    bar.add(dwg.line(start=(bx0, by0), end=(_r(bx0 + bar_mm * scale), by0), stroke="#222",
                     stroke_width=2))
    for x_end in (bx0, _r(bx0 + bar_mm * scale)):
        bar.add(dwg.line(start=(x_end, _r(by0 - 3)), end=(x_end, _r(by0 + 3)), stroke="#222"))
    bar.add(dwg.text(_length_text(bar_mm), insert=(bx0, _r(by0 - 5)), font_family="sans-serif",
                     font_size=9, class_="scale-label"))
    g.add(bar)
    dwg.add(g)
    many = len(runs) > MANY_ROBOTS
    if many:
        dwg.defs.add(dwg.style(_MANY_CSS))
    _draw_messages(dwg, runs, px)

    # -- each robot's path, firings, marks and final pose: the robots' names
    # are placed first, so that no label covers them
    placed_labels = [(bx0, _r(by0 - 5 - LABEL_H), _text_width(_length_text(bar_mm)), LABEL_H,
                      "scale")]
    name_boxes = {}
    for run in runs:
        if run.name:
            _, fx, fy, _ = run.poses[-1]
            cx, cy = px(fx, fy)
            rr = max(radius * scale, 3.0)
            w = _text_width(run.name, 10)
            left = cx + rr + 2 if cx + rr + 2 + w <= width - 2 else cx - rr - 2 - w
            box = (_r(left), _r(cy + 4 - 10), w, 13.0, run.name)     # 10 px text
            name_boxes[run.name] = box
            placed_labels.append(box)
    base_labels = list(placed_labels)
    colours = robot_colours(world, runs)
    for i, run in enumerate(runs):
        colour = colours[i]
        rg = dwg.g(class_="robot-run")
        rg["data-robot"] = run.name or "robot"
        # many robots: each one's labels on demand, laid out among its own
        labels = dwg.g(class_="labels") if many else rg
        if many:
            placed_labels = list(base_labels)
        points = []
        for _, x, y, _ in run.poses:
            p = px(x, y)
            if not points or points[-1] != p:
                points.append(p)
        points = thin_points(points)        # what can be seen of a dense path (thin.py)
        if len(points) == 1:
            points.append(points[0])
        path = dwg.polyline(points, class_="path", fill="none", stroke=colour, stroke_width=1.5,
                            stroke_linejoin="round")
        if many:
            path["stroke-opacity"] = 0.35
        rg.add(path)
        sx, sy = px(run.poses[0][1], run.poses[0][2])
        rg.add(dwg.circle(center=(sx, sy), r=3, class_="start", fill="white", stroke=colour))
        counts: dict = {}
        for f in run.firings:
            counts[f.label] = counts.get(f.label, 0) + 1
        for f in run.firings:
            if counts[f.label] > DENSE:
                continue            # a rule of continuous control: its timeline bar says it
            fx, fy = px(f.x, f.y)
            marker = dwg.circle(center=(fx, fy), r=3.5, class_="firing", fill=colour,
                                stroke="white", stroke_width=0.8)
            marker["data-t-ms"] = str(f.t_ms)
            marker["data-label"] = f.label
            marker.set_desc(title=f"{run.name + ': ' if run.name else ''}{f.t_ms} ms {f.title}")
            rg.add(marker)
            # its label (the rule's name, or its event), unless that would
            # cover another label (the marker's tooltip still names it); the
            # same label at the same spot once
            box = _label_box(f.shown, fx, fy, placed_labels, width)
            if box is not None:
                placed_labels.append(box)
                t = dwg.text(f.shown, insert=(box[0], _r(box[1] + BASELINE)), class_="firing-label",
                             font_family="sans-serif", font_size=9, fill="#333")
                t["data-t-ms"] = str(f.t_ms)
                t["data-label"] = f.label
                labels.add(t)
        for m in run.marks:
            mx, my = px(m.x, m.y)
            if m.kind == "mode":
                shape = dwg.polygon([(mx, _r(my - 5)), (_r(mx + 5), my), (mx, _r(my + 5)),
                                     (_r(mx - 5), my)], class_="mode-change", fill="#ffd54f",
                                    stroke="#7a5c00")
            elif m.kind == "led":
                shape = dwg.circle(center=(mx, my), r=2.5, class_="led-change", fill="#66bb6a",
                                   stroke="#1b5e20", stroke_width=0.6)
            else:
                shape = dwg.path(d=f"M {_r(mx - 4)} {_r(my - 4)} L {_r(mx + 4)} {_r(my + 4)} "
                                   f"M {_r(mx - 4)} {_r(my + 4)} L {_r(mx + 4)} {_r(my - 4)}",
                                 class_="contact", stroke="#c62828", stroke_width=2, fill="none")
            shape["data-t-ms"] = str(m.t_ms)
            shape.set_desc(title=f"{run.name + ': ' if run.name else ''}{m.t_ms} ms {m.text}")
            rg.add(shape)
            if m.kind != "led":         # LEDs: the tooltip and the timeline
                box = _label_box(m.text, mx, my, placed_labels, width)
                if box is not None:
                    placed_labels.append(box)
                    t = dwg.text(m.text, insert=(box[0], _r(box[1] + BASELINE)),
                                 class_=f"{m.kind}-label", font_family="sans-serif", font_size=9,
                                 fill="#333")
                    labels.add(t)
        _, fx, fy, fh = run.poses[-1]
        cx, cy = px(fx, fy)
        fin = dwg.g(class_="final-pose")
        fin["data-x-mm"] = str(fx)
        fin["data-y-mm"] = str(fy)
        fin["data-heading-deg"] = str(fh)
        rr = radius * scale
        fin.add(dwg.circle(center=(cx, cy), r=_r(max(rr, 3.0)), fill=colour, fill_opacity=0.35,
                           stroke=colour, stroke_width=1.5))
        hx = cx + max(rr, 3.0) * math.cos(math.radians(fh))
        hy = cy - max(rr, 3.0) * math.sin(math.radians(fh))
        fin.add(dwg.line(start=(cx, cy), end=(_r(hx), _r(hy)), stroke="#000", stroke_width=1.5,
                         class_="heading"))
        fin.add(leds_mod.draw_leds(dwg, cx, cy, max(rr, 3.0), fh,
                                   leds_mod.state_at(run.leds, run.poses[-1][0])))
        if run.name:
            box = name_boxes[run.name]
            fin.add(dwg.text(run.name, insert=(box[0], _r(box[1] + 10)), font_family="sans-serif",
                             font_size=10, class_="robot-name"))
        rg.add(fin)
        if many:
            rg.add(labels)
        dwg.add(rg)

    # -- timeline
    tl = dwg.g(id="timeline")
    t_left = MARGIN_PX + LABEL_COLUMN_PX
    t_right = width - MARGIN_PX
    span_ms = max(end_ms, 1)
    tl["data-axis"] = f"{t_left!r} {t_right!r} {span_ms} {timeline_top!r} {timeline_top + timeline_h!r}"

    def tx(t_ms: int) -> float:
        return _r(t_left + (t_right - t_left) * t_ms / span_ms)

    tl.add(dwg.text("rules fired over time", insert=(MARGIN_PX, _r(timeline_top - 12)),
                    font_family="sans-serif", font_size=11, class_="timeline-title"))
    bands.draw_bands(dwg, tl, runs, end_ms, rows, bands.rule_colours(runs, rows), timeline_top,
                     ROW_PX, MARGIN_PX, tx, colours)
    for row, label in enumerate(rows):
        y = timeline_top + (row + n_bands) * ROW_PX
        rowg = dwg.g(class_="timeline-row")
        rowg["data-label"] = label
        text = row_titles[label]
        if len(text) > ROW_LABEL_CHARS:
            text = text[:ROW_LABEL_CHARS - 1] + "\u2026"
        row_label = dwg.text(text, insert=(MARGIN_PX, _r(y + 12)), font_family="sans-serif",
                             font_size=9, class_="row-label")
        row_label.set_desc(title=row_titles[label])
        rowg.add(row_label)
        rowg.add(dwg.line(start=(t_left, _r(y + ROW_PX / 2)), end=(t_right, _r(y + ROW_PX / 2)),
                          stroke="#ddd", stroke_width=1))
        for i, run in enumerate(runs):
            times = ([f.t_ms for f in run.firings if f.label == label]
                     + [m.t_ms for m in run.marks if m.kind == label])
            if len(times) > DENSE:
                # one band from the first firing to the last, not thousands of ticks
                band = dwg.rect(insert=(tx(times[0]), _r(y + 4)),
                                size=(_r(max(tx(times[-1]) - tx(times[0]), 1.5)), ROW_PX - 8),
                                fill=colours[i], class_="dense")
                band["data-count"] = str(len(times))
                band.set_desc(title=f"{len(times)} firings from {times[0]} ms to {times[-1]} ms")
                if run.name:
                    band["data-robot"] = run.name
                rowg.add(band)
                continue
            for t_ms in times:
                tick = dwg.line(start=(tx(t_ms), _r(y + 3)), end=(tx(t_ms), _r(y + ROW_PX - 3)),
                                stroke=colours[i], stroke_width=1.5, class_="tick")
                tick["data-t-ms"] = str(t_ms)
                if run.name:
                    tick["data-robot"] = run.name
                rowg.add(tick)
        tl.add(rowg)
    axis_y = _r(timeline_top + timeline_h + 4)
    tl.add(dwg.line(start=(t_left, axis_y), end=(t_right, axis_y), stroke="#444", class_="axis"))
    step = _nice_step(span_ms / 1000.0)
    k = 0
    while k * step * 1000 <= span_ms + 1e-6:
        t = k * step * 1000
        x = tx(t)
        tl.add(dwg.line(start=(x, axis_y), end=(x, _r(axis_y + 4)), stroke="#444"))
        tl.add(dwg.text(f"{k * step:g} s", insert=(_r(x - 8), _r(axis_y + 16)),
                        font_family="sans-serif", font_size=9, class_="axis-label"))
        k += 1
    dwg.add(tl)
    return dwg.tostring() + "\n"
