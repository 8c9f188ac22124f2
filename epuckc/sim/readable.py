"""The readable trace of JSON trace records: the lines `epuckc run` prints
(runtime_c/platform/platform_host.c prints them as the harness runs; this is
the same text from the records), for a trace that did not come from the
harness: the robot's, decoded by `epuckc monitor`, and a recorded robot
trace that `epuckc test` checks. The JSON has no texts of a sequence's
steps: `step_names(action_id)` gives them (the program's trace table)."""
from __future__ import annotations

import json
from typing import Callable, Optional

# the keys of a record before its kind's own (platform/platform_host.c record_extra)
_BASE = ("t_ms", "kind", "name", "id", "left_steps", "right_steps", "x_mm", "y_mm",
         "heading_deg", "step", "steps", "robot")


def _pose(r: dict) -> str:
    return f"pose ({r.get('x_mm', 0.0):.1f}, {r.get('y_mm', 0.0):.1f}) {r.get('heading_deg', 0.0):.1f} deg"


def _extra(r: dict) -> str:
    """The kind's own keys as the harness writes them: `"key": value, ...`."""
    return ", ".join(f"{json.dumps(k)}: {json.dumps(v)}" for k, v in r.items() if k not in _BASE)


def readable_line(r: dict, step_names: Optional[Callable[[int], list]] = None) -> Optional[str]:
    """The line of one record, or None for a record the readable trace
    leaves out (pose, motors)."""
    t, kind = f"[{r['t_ms']:6d} ms]", r.get("kind")
    if kind == "event":
        return f"{t} event  #{r['id']} {r['name']:<23} {_pose(r)}"
    if kind == "action":
        line = f"{t} action #{r['id']} {r['name']}"
        if "step" in r:
            line += f" step {r['step']} of {r['steps']}"
            names = step_names(r["id"]) if step_names else []
            if 0 < r["step"] <= len(names):
                line += f": {names[r['step'] - 1]}"
        return line
    if kind == "set":
        return f"{t} set       {r['var']} = {r['value']}"
    if kind == "suppressed":
        return (f"{t} suppressed {r['command']} of #{r['id']} {r['name']} (priority "
                f"{r['priority']}); motors owned by #{r['owner']} {r['owner_name']} (priority "
                f"{r['owner_priority']})")
    if kind == "mode":
        return f"{t} mode      {r['name']}"
    if kind == "led":
        return (f"{t} led       {r['name']:<5} {'on' if r['state'] else 'off':<3} ring "
                f"{r['ring']} body {r['body']} front {r['front']}")
    if kind == "sound":
        return f"{t} sound     {r['name']}"
    if kind == "send":
        return f"{t} send      {r['value']}"
    if kind == "message":
        # as host/stub_devices.c stub_ircom_receive prints it; a robot's
        # trace (link/stream.py) knows neither the sender nor the sensor
        sender = f" from {r['from']}" if "from" in r else ""
        sensor = f" (sensor {r['sensor']})" if "sensor" in r else ""
        return (f"{t} message   {r['value']}{sender}, bearing {r['bearing_deg']:.1f} deg, "
                f"range {r['range_mm']:.1f} mm{sensor}")
    if kind == "input":
        return f"{t} input     {r['name']}={r['value']}"
    if kind in ("exit", "timeout"):
        return f"{t} {kind:<9} {_pose(r)}"
    if kind == "lost":
        if r["frames"] == 0:
            line = f"{t} lost      no frame: {r['bytes']} bytes of noise on the link"
        else:
            line = (f"{t} lost      {r['frames']} frame{'s' if r['frames'] != 1 else ''} "
                    f"({r['bytes']} bytes damaged or cut on the link)")
        if r.get("before_start"):
            return line + ", before the run's first hello"
        return line + (f", before {r['until_ms']} ms" if "until_ms" in r else ", at the end")
    if kind == "dropped":
        return (f"{t} dropped   {r['count']} record{'s' if r['count'] != 1 else ''}: the "
                f"robot's link was full ({r['total']} so far)")
    if kind in ("pose", "motors", "world", "contacts"):
        return None
    return f"{t} {kind:<9}{(' ' + _extra(r)) if _extra(r) else ''}"


def summary_line(records: list) -> Optional[str]:
    """`exit at ...` / `timeout at ...`, as the harness ends its trace."""
    if not records or records[-1].get("kind") not in ("exit", "timeout"):
        return None
    end = records[-1]
    events = sum(r.get("kind") == "event" for r in records)
    actions = sum(r.get("kind") == "action" and "step" not in r for r in records)
    steps = sum(r.get("kind") == "action" and "step" in r for r in records)
    return (f"{end['kind']} at {end['t_ms']} ms: {_pose(end)}, {events} events fired, "
            f"{actions} actions run, {steps} sequence steps")


def readable_trace(records: list, step_names: Optional[Callable[[int], list]] = None) -> str:
    """The whole readable trace, the summary line at the end."""
    lines = [line for line in (readable_line(r, step_names) for r in records) if line is not None]
    end = summary_line(records)
    if end is not None:
        lines.append(end)
    return "".join(line + "\n" for line in lines)
