"""Thinning a robot's dense path for the pictures: every trace record
carries a pose, so a variable set every 20 ms puts 50 points a second on
the path, most of them on the line between their neighbours. The SVG
keeps the points a reader can see (Ramer-Douglas-Peucker within
PATH_TOLERANCE_PX of the path drawn), the replay the poses it can show
(one every REPLAY_POSE_MS of the run, and every turn of the heading by
REPLAY_TURN_DEG), both deterministic."""
from __future__ import annotations

import math

PATH_TOLERANCE_PX = 0.5         # no point kept closer than this to the line drawn
REPLAY_POSE_MS = 50             # the replay's frames move 400 ms of the run (speed 10)
REPLAY_TURN_DEG = 5.0


def _distance(p, a, b) -> float:
    """Of point p from the segment a-b."""
    (px, py), (ax, ay), (bx, by) = p, a, b
    dx, dy = bx - ax, by - ay
    length2 = dx * dx + dy * dy
    if length2 == 0:
        return math.hypot(px - ax, py - ay)
    t = max(0.0, min(1.0, ((px - ax) * dx + (py - ay) * dy) / length2))
    return math.hypot(px - ax - t * dx, py - ay - t * dy)


def thin_points(points: list, tolerance: float = PATH_TOLERANCE_PX) -> list:
    """The points of a polyline that keep it within `tolerance` of itself:
    the first, the last and each farther than `tolerance` from the line
    through the ones kept around it (a stack, not recursion)."""
    if len(points) <= 2:
        return list(points)
    keep = [False] * len(points)
    keep[0] = keep[-1] = True
    stack = [(0, len(points) - 1)]
    while stack:
        first, last = stack.pop()
        worst, at = -1.0, -1
        for i in range(first + 1, last):
            d = _distance(points[i], points[first], points[last])
            if d > worst:
                worst, at = d, i
        if worst > tolerance:
            keep[at] = True
            stack.append((first, at))
            stack.append((at, last))
    return [p for p, k in zip(points, keep) if k]


def thin_poses(poses: list) -> list:
    """(t_ms, x, y, heading) poses for the replay: the first and the last,
    and each one REPLAY_POSE_MS after the last kept or turned by
    REPLAY_TURN_DEG from it."""
    if len(poses) <= 2:
        return list(poses)
    out = [poses[0]]
    for pose in poses[1:-1]:
        t, _, _, h = pose
        last_t, _, _, last_h = out[-1]
        turned = abs((h - last_h + 180) % 360 - 180)
        if t - last_t >= REPLAY_POSE_MS or turned >= REPLAY_TURN_DEG:
            out.append(pose)
    out.append(poses[-1])
    return out
