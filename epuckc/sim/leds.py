"""The e-puck's LEDs in the pictures of a run: their state at any time, from
the trace's `led` records, and where each is drawn on the robot's disc.

The ring's eight LEDs are numbered clockwise seen from above, led0 at the
front (led2 on the right, led4 at the back, led6 on the left); the body LED
lights the whole body (drawn as a ring inside the disc) and the front LED
sits at the front, inside the ring. One geometry serves the SVG (the robot
at its final pose, plot.py) and the replay page (the robot as it moves,
replay.py): `local_geometry` gives each LED's place in the robot's own
frame, front along +x and y down as in SVG, which the page turns with the
robot and `draw_leds` turns by the heading itself.

Drawn pieces: `g.leds` (`data-t-ms`: the time of the state it shows) with
`circle.led.ring-led` (`data-led` 0..7), `circle.led.body-led`,
`circle.led.front-led`, each `data-on` "1" or "0".
"""
from __future__ import annotations

import bisect
import math

RING_ON = "#ff2020"         # off: an outline only, so that a label under it shows
BODY_ON = "#2ecc40"
FRONT_ON = "#ff2020"
OFF_STROKE = "#7a2a2a"

# (t_ms, ring "10000001" led0 first, body 0/1, front 0/1); before the first
# record every LED is off, as the robot starts
ALL_OFF = (0, "00000000", 0, 0)


def led_state(rec: dict):
    """The state after a `led` record: (t_ms, ring, body, front)."""
    ring = str(rec.get("ring", "00000000"))
    if len(ring) != 8 or set(ring) - {"0", "1"}:
        ring = "00000000"
    return (int(rec["t_ms"]), ring, 1 if rec.get("body") else 0, 1 if rec.get("front") else 0)


def state_at(states: list, t_ms: int):
    """The LEDs as they were at t_ms: the last state recorded at or before it."""
    i = bisect.bisect_right([s[0] for s in states], t_ms)
    return states[i - 1] if i else ALL_OFF


def local_geometry(radius_px: float) -> dict:
    """Each LED's place on a robot disc of radius_px, in the robot's frame
    (front along +x, y down): the ring's centres, their radius, the body
    ring's radius and width, the front LED's centre and radius."""
    ring_r = 0.78 * radius_px
    led_r = max(0.8, 0.16 * radius_px)
    ring = [(round(ring_r * math.cos(math.radians(45 * i)), 2),
             round(ring_r * math.sin(math.radians(45 * i)), 2)) for i in range(8)]
    return {"ring": ring, "led_r": round(led_r, 2),
            "body_r": round(0.5 * radius_px, 2), "body_w": round(max(0.8, 0.14 * radius_px), 2),
            "front": (round(0.5 * radius_px, 2), 0.0), "front_r": round(max(0.7, 0.11 * radius_px), 2)}


def _turn(point, heading_deg: float):
    """A point of the robot's frame turned to the heading (SVG frame: a
    heading counter-clockwise in the world is clockwise on screen)."""
    c, s = math.cos(math.radians(heading_deg)), math.sin(math.radians(heading_deg))
    x, y = point
    return x * c + y * s, -x * s + y * c


def draw_leds(dwg, cx: float, cy: float, radius_px: float, heading_deg: float, state):
    """The LEDs of a robot drawn at (cx, cy) px with its heading, lit as
    `state` (t_ms, ring, body, front) says: a group (svg.py)."""
    geo = local_geometry(radius_px)
    t_ms, ring, body, front = state
    g = dwg.g(class_="leds")
    g["data-t-ms"] = str(t_ms)
    b = dwg.circle(center=(round(cx, 1), round(cy, 1)), r=geo["body_r"], fill="none",
                   stroke=BODY_ON if body else "#000", stroke_opacity=0.9 if body else 0.08,
                   stroke_width=geo["body_w"], class_="led body-led")
    b["data-on"] = str(body)
    g.add(b)
    fx, fy = _turn(geo["front"], heading_deg)
    f = dwg.circle(center=(round(cx + fx, 1), round(cy + fy, 1)), r=geo["front_r"],
                   fill=FRONT_ON if front else "none", stroke=OFF_STROKE, stroke_width=0.4,
                   class_="led front-led")
    f["data-on"] = str(front)
    g.add(f)
    for i, point in enumerate(geo["ring"]):
        lx, ly = _turn(point, heading_deg)
        on = ring[i] == "1"
        c = dwg.circle(center=(round(cx + lx, 1), round(cy + ly, 1)), r=geo["led_r"],
                       fill=RING_ON if on else "none", stroke=OFF_STROKE, stroke_width=0.5,
                       class_="led ring-led")
        c["data-led"] = str(i)
        c["data-on"] = "1" if on else "0"
        g.add(c)
    return g
