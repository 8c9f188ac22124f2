"""Two bands of the timeline of a run, computed from the trace: who holds
the motors, and when the robot stands still.

**Who holds the motors**: the trace's `motors` records (the runtime writes
one whenever the holder changes: the event whose action started the motion
in progress, `main`, or `free`) cut the run into intervals; each is
labelled with the owner's rule (`file:line`, as the timeline's rows are)
and coloured with the rule's colour, which a small key beside the rule's
row repeats. Changes at the same millisecond count as their last (a
sequence's next step takes the motors in the ms its previous one ended).

**Still**: the robot is still at time `a` when every pose within the next
second, [a, a + 1 s] (cut at the end of the run), lies less than 5 mm from
its pose at `a`, poses taken on the path drawn through the trace's poses
(straight between records); times are tried every 10 ms (coarser for runs
over 200 s, 20 000 tries at most). A still interval runs from the first of
a series of still times to the last one's window end, and is drawn when it
lasts more than 2 s. Turning on the spot counts as still: the robot gets
nowhere.

Drawn pieces, in `g#timeline`: `g.timeline-band` (`data-label` `motors` or
`still`) holding `rect.hold` (`data-label`: the owner's `file:line`, or
`main`; `data-from-ms`, `data-to-ms`, `data-robot`) or `rect.still`
(`data-from-ms`, `data-to-ms`, `data-robot`); `rect.hold-key`
(`data-label`) beside a rule's row.
"""
from __future__ import annotations

import bisect
import math

STILL_MM = 5.0
WINDOW_MS = 1000
STILL_MIN_MS = 2000
STEP_MS = 10
MAX_TRIES = 20000
RULE_COLOURS = ["#aec7e8", "#ffbb78", "#98df8a", "#ff9896", "#c5b0d5", "#c49c94",
                "#f7b6d2", "#dbdb8d", "#9edae5", "#c7c7c7"]


def hold_intervals(holds: list, end_ms: int) -> list:
    """(from_ms, to_ms, label, title) of each interval some rule held the
    motors, from the run's holds [(t_ms, label or None when free, title)]."""
    last = {}
    for t, label, title in holds:
        last[t] = (label, title)            # the last change of each ms counts
    changes = sorted(last.items())
    out = []
    for i, (t, (label, title)) in enumerate(changes):
        to = changes[i + 1][0] if i + 1 < len(changes) else end_ms
        if label is None or to <= t:
            continue
        if out and out[-1][2] == label and out[-1][1] == t:
            out[-1] = (out[-1][0], to, label, out[-1][3])
        else:
            out.append((t, to, label, title))
    return out


def _path(poses: list):
    """Times and points of a path, one point per ms (the last one of it)."""
    by_t = {}
    for t, x, y, _ in poses:
        by_t[t] = (x, y)
    ts = sorted(by_t)
    return ts, [by_t[t] for t in ts]


def _at(ts: list, pts: list, t: float):
    i = bisect.bisect_right(ts, t)
    if i == 0:
        return pts[0]
    if i == len(ts):
        return pts[-1]
    t0, t1 = ts[i - 1], ts[i]
    (x0, y0), (x1, y1) = pts[i - 1], pts[i]
    k = (t - t0) / (t1 - t0)
    return x0 + (x1 - x0) * k, y0 + (y1 - y0) * k


def still_intervals(poses: list, end_ms: int) -> list:
    """(from_ms, to_ms) of each interval of more than 2 s during which the
    robot moved less than 5 mm in any 1 s (the module's words)."""
    if not poses:
        return []
    ts, pts = _path(poses)
    step = max(STEP_MS, math.ceil(end_ms / MAX_TRIES / STEP_MS) * STEP_MS)
    out = []
    first = last = None
    for a in range(ts[0], end_ms + 1, step):
        b = min(a + WINDOW_MS, end_ms)
        x0, y0 = _at(ts, pts, a)
        lo, hi = bisect.bisect_right(ts, a), bisect.bisect_right(ts, b)
        near = all(math.hypot(x - x0, y - y0) < STILL_MM
                   for x, y in pts[lo:hi] + [_at(ts, pts, b)])
        if near:
            if first is None:
                first = a
            last = a
        if (not near or a + step > end_ms) and first is not None:
            to = min(last + WINDOW_MS, end_ms)
            if to - first > STILL_MIN_MS:
                out.append((first, to))
            first = None
    return out


def rule_colours(runs: list, rows: list) -> dict:
    """A colour for each rule that ever held the motors, in the order of
    the timeline's rows (`main` after them)."""
    held = {label for run in runs for _, label, _ in run.holds if label is not None}
    order = [r for r in rows if r in held] + sorted(held - set(rows))
    return {label: RULE_COLOURS[i % len(RULE_COLOURS)] for i, label in enumerate(order)}


def band_rows(runs: list) -> list:
    """The bands the timeline gets: (label, title)."""
    rows = []
    if any(run.holds for run in runs):
        rows.append(("motors", "motors held by (rule's colour)"))
    rows.append(("still", f"still (< {STILL_MM:g} mm in 1 s, > {STILL_MIN_MS // 1000} s)"))
    return rows


def draw_bands(dwg, tl, runs: list, end_ms: int, rows: list, colours: dict, top: float,
               row_px: float, label_x: float, tx, robot_colours: list):
    """Adds the bands to the timeline group `tl`, from y = top, one row of
    row_px each; tx maps ms to x. A row shares its height between the robots."""
    for k, (label, title) in enumerate(band_rows(runs)):
        y = top + k * row_px
        g = dwg.g(class_="timeline-band")
        g["data-label"] = label
        text = dwg.text(title, insert=(label_x, round(y + 12, 1)), font_family="sans-serif",
                        font_size=9, class_="row-label")
        g.add(text)
        strip = (row_px - 6) / max(len(runs), 1)
        for i, run in enumerate(runs):
            sy = round(y + 3 + i * strip, 1)
            if label == "motors":
                spans = [(a, b, lab, t) for a, b, lab, t in hold_intervals(run.holds, end_ms)]
            else:
                spans = [(a, b, None, None) for a, b in still_intervals(run.poses, end_ms)]
            for a, b, lab, t in spans:
                fill = colours.get(lab, "#999") if label == "motors" else robot_colours[i]
                r = dwg.rect(insert=(tx(a), sy), size=(round(max(tx(b) - tx(a), 1.0), 1),
                                                       round(max(strip, 1.0), 1)),
                             fill=fill, fill_opacity=1.0 if label == "motors" else 0.5,
                             class_="hold" if label == "motors" else "still")
                r["data-from-ms"] = str(a)
                r["data-to-ms"] = str(b)
                if run.name:
                    r["data-robot"] = run.name
                who = f"{run.name}: " if run.name else ""
                if label == "motors":
                    r["data-label"] = lab
                    r.set_desc(title=f"{who}{a} ms to {b} ms: motors held by {t}")
                else:
                    r.set_desc(title=f"{who}{a} ms to {b} ms: still")
                g.add(r)
        tl.add(g)
    for label, colour in colours.items():
        if label in rows:
            y = top + (len(band_rows(runs)) + rows.index(label)) * row_px
            key = dwg.rect(insert=(round(label_x - 14, 1), round(y + 5, 1)), size=(8, 8),
                           fill=colour, class_="hold-key")
            key["data-label"] = label
            tl.add(key)
