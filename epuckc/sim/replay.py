"""`epuckc run ... --html replay.html`: one self-contained page (no network)
that replays a run: the picture of plot.py (arena, obstacles, paths,
timeline) with every robot moving along its path, play/pause, a time
slider, and at the cursor the rules that fired last and the variables'
values (every declared variable from 0 s with its initial value, when the
run passes them, then the trace's `set` records); each robot's LEDs (ring,
body, front: leds.py) lit as they were at the cursor. `#t=MS` after the
page's address opens it at that moment (`#t=MS&select=NAME` with that
robot selected), `#play` plays it. Each robot is drawn once, moving, in
its world colour, with its name beside it (the picture's final pose gives
way); the rules fired last are listed each once, with how often it fired
since it began (`every 20 ms` is one line); the picture and the panel sit
side by side in a 1200 x 800 window; the poses are thinned to those it can
show (thin.py). Each message
delivered in the last MESSAGE_SHOWN_MS is a line from its sender to its
receiver, fading with its age; the world's sound sources are lit while they
play (pale otherwise); its floor is the picture's. With more than MANY_ROBOTS robots the page
stays readable: each robot draws only its trail of the last TRAIL_MS over
its pale path, and a robot's rule labels show while the pointer is over it
or when it is selected (a click on the moving robot; again: unselected).

The page carries the trace's poses, firings and variable changes as JSON
and a small script; the picture's map frame and timeline axis come from
its `data-frame` and `data-axis` attributes, so the script draws nothing
the picture does not already place. tests/sim/test_replay.py plays it in
headless Chromium.
"""
from __future__ import annotations

import html
import json
import re
from typing import Optional

from .leds import BODY_ON, FRONT_ON, OFF_STROKE, RING_ON, local_geometry
from .plot import (DEFAULT_ROBOT_RADIUS_MM, MANY_ROBOTS, MESSAGE_COLOUR, parse_trace, plot_trace,
                   robot_colours)
from .thin import thin_poses

_PAGE = """<!doctype html>
<html lang="en"><head><meta charset="utf-8"><title>{title}</title>
<style>
body {{ font-family: sans-serif; margin: 12px 16px; color: #222; }}
#controls {{ display: flex; gap: 12px; align-items: center; margin: 0 0 8px; }}
#slider {{ width: 480px; }}
#main {{ display: flex; gap: 16px; align-items: flex-start; }}
#picture {{ flex: 0 1 auto; min-width: 0; }}
#picture svg {{ display: block; width: auto; height: auto; max-width: 100%;
  max-height: calc(100vh - 64px); }}
#panel {{ flex: 1 0 260px; max-width: 420px; max-height: calc(100vh - 64px); overflow: auto;
  font-size: 13px; }}
#panel ul {{ margin: 4px 0 12px; padding-left: 18px; }}
.replay-robot {{ cursor: pointer; }}
</style></head>
<body data-errors="">
<div id="controls"><button id="play" type="button">play</button>
<input id="slider" type="range" min="0" max="{end}" step="1" value="0">
<span id="clock">0.000 s</span></div>
<div id="main"><div id="picture">{svg}</div>
<div id="panel"><div><b>last rules fired</b><ul id="fired"></ul></div>
<div><b>variables</b><ul id="vars"></ul></div></div></div>
<script id="run-data" type="application/json">{data}</script>
<script>
window.addEventListener("error", e => {{ document.body.dataset.errors += e.message + ";"; }});
(function () {{
  const run = JSON.parse(document.getElementById("run-data").textContent);
  const svg = document.querySelector("#picture svg");
  const NS = "http://www.w3.org/2000/svg";
  const [x0, y1, scale, margin, top] = document.getElementById("world").dataset.frame
    .split(" ").map(Number);
  const [tLeft, tRight, span, tTop, tBottom] = document.getElementById("timeline").dataset.axis
    .split(" ").map(Number);
  const px = (x, y) => [margin + (x - x0) * scale, top + (y1 - y) * scale];
  const runs = new Map([...svg.querySelectorAll("g.robot-run")].map(e => [e.dataset.robot, e]));
  const many = run.robots.length > {many};
  const layer = document.createElementNS(NS, "g");
  layer.setAttribute("id", "replay-messages"); svg.appendChild(layer);
  const robots = run.robots.map(r => {{
    let trail = null;
    if (many) {{
      trail = document.createElementNS(NS, "polyline");
      trail.setAttribute("class", "trail"); trail.setAttribute("fill", "none");
      trail.setAttribute("stroke", r.colour); trail.setAttribute("stroke-width", "2");
      svg.appendChild(trail);
    }}
    const g = document.createElementNS(NS, "g");
    g.setAttribute("class", "replay-robot");
    g.dataset.robot = r.name;
    const c = document.createElementNS(NS, "circle");
    c.setAttribute("r", Math.max(run.radius * scale, 3));
    c.setAttribute("fill", r.colour); c.setAttribute("fill-opacity", "0.6");
    c.setAttribute("stroke", "#000");
    const h = document.createElementNS(NS, "line");
    h.setAttribute("x2", Math.max(run.radius * scale, 3)); h.setAttribute("stroke", "#000");
    g.appendChild(c); g.appendChild(h);
    // the LEDs, where leds.py places them in the robot's frame
    const geo = run.leds, dot = (x, y, rad, cls) => {{
      const e = document.createElementNS(NS, "circle");
      e.setAttribute("cx", x); e.setAttribute("cy", y); e.setAttribute("r", rad);
      e.setAttribute("class", cls); e.setAttribute("stroke", "{off_stroke}");
      e.setAttribute("stroke-width", "0.5"); g.appendChild(e); return e;
    }};
    const body = dot(0, 0, geo.body_r, "led body-led");
    body.setAttribute("fill", "none"); body.setAttribute("stroke-width", geo.body_w);
    const front = dot(geo.front[0], geo.front[1], geo.front_r, "led front-led");
    const ring = geo.ring.map(([x, y], i) => {{
      const e = dot(x, y, geo.led_r, "led ring-led"); e.dataset.led = i; return e;
    }});
    svg.appendChild(g);
    let label = null;
    if (r.name) {{
      label = document.createElementNS(NS, "text");
      label.setAttribute("class", "replay-name"); label.setAttribute("font-family", "sans-serif");
      label.setAttribute("font-size", "10"); label.textContent = r.name;
      svg.appendChild(label);
    }}
    // a click selects the robot: its labels stay shown
    g.addEventListener("click", () => {{
      const e = runs.get(r.name); if (!e) return;
      e.classList.toggle("selected"); g.classList.toggle("selected", e.classList.contains("selected"));
    }});
    return {{ poses: r.poses, leds: r.leds, g: g, body: body, front: front, ring: ring,
             trail: trail, label: label }};
  }});
  function trailAt(poses, t) {{
    const pts = [];
    for (const p of poses) {{
      if (p[0] > t) break;
      if (p[0] >= t - {trail_ms}) pts.push(px(p[1], p[2]).map(v => v.toFixed(1)).join(","));
    }}
    return pts.join(" ");
  }}
  function showMessages(t) {{
    let lo = 0, hi = run.messages.length;
    while (lo < hi) {{ const mid = (lo + hi) >> 1; if (run.messages[mid][0] <= t - {shown_ms}) lo = mid + 1; else hi = mid; }}
    const recent = [];
    for (let i = lo; i < run.messages.length && run.messages[i][0] <= t; i++) recent.push(run.messages[i]);
    while (layer.childNodes.length < recent.length) {{
      const l = document.createElementNS(NS, "line");
      l.setAttribute("class", "replay-message"); l.setAttribute("stroke", "{message_colour}");
      l.setAttribute("stroke-width", "1.5"); layer.appendChild(l);
    }}
    while (layer.childNodes.length > recent.length) layer.removeChild(layer.lastChild);
    recent.forEach((m, i) => {{
      const l = layer.childNodes[i], [ax, ay] = px(m[1], m[2]), [bx, by] = px(m[3], m[4]);
      l.setAttribute("x1", ax.toFixed(1)); l.setAttribute("y1", ay.toFixed(1));
      l.setAttribute("x2", bx.toFixed(1)); l.setAttribute("y2", by.toFixed(1));
      l.setAttribute("stroke-opacity", (1 - (t - m[0]) / {shown_ms}).toFixed(2));
      l.dataset.from = m[5]; l.dataset.to = m[6];
    }});
  }}
  // each robot is drawn once: the moving one (its LEDs at the cursor, its name beside it)
  svg.querySelectorAll(".final-pose").forEach(e => e.setAttribute("display", "none"));
  svg.querySelectorAll(".final-pose .leds").forEach(e => e.setAttribute("display", "none"));
  const size = Math.max(run.radius * scale, 3);
  function light(e, on, colour) {{
    e.dataset.on = on ? "1" : "0"; e.setAttribute("fill", on ? colour : "none");
  }}
  const cursor = document.createElementNS(NS, "line");
  cursor.setAttribute("id", "cursor"); cursor.setAttribute("stroke", "#c00");
  cursor.setAttribute("y1", tTop - 4); cursor.setAttribute("y2", tBottom + 4);
  svg.appendChild(cursor);
  const slider = document.getElementById("slider"), clock = document.getElementById("clock");
  const button = document.getElementById("play");
  function poseAt(poses, t) {{
    let lo = 0, hi = poses.length - 1;
    while (lo < hi) {{ const mid = (lo + hi + 1) >> 1; if (poses[mid][0] <= t) lo = mid; else hi = mid - 1; }}
    return poses[lo];
  }}
  // the world's sound sources (plot.py's g.sound): lit while they play
  const sounds = [...svg.querySelectorAll("g.sound")].map(e => [e, e.dataset.onMs
    ? e.dataset.onMs.split(" ").map(w => w.split(":").map(v => v === "" ? Infinity : Number(v)))
    : []]);
  function showSounds(t) {{
    for (const [e, on] of sounds) {{
      const playing = !on.length || on.some(([a, b]) => a <= t && t < b);
      e.dataset.playing = playing ? "1" : "0";
      e.setAttribute("opacity", playing ? "1" : "0.25");
    }}
  }}
  function show(t) {{
    showMessages(t);
    showSounds(t);
    for (const r of robots) {{
      if (r.trail) r.trail.setAttribute("points", trailAt(r.poses, t));
      const [, x, y, heading] = poseAt(r.poses, t);
      const [cx, cy] = px(x, y);
      r.g.setAttribute("transform", `translate(${{cx.toFixed(1)}} ${{cy.toFixed(1)}}) rotate(${{(-heading).toFixed(1)}})`);
      if (r.label) {{
        r.label.setAttribute("x", (cx + size + 2).toFixed(1));
        r.label.setAttribute("y", (cy + 4).toFixed(1));
      }}
      const [ledT, ring, body, front] = r.leds.length && r.leds[0][0] <= t ? poseAt(r.leds, t)
        : [0, "00000000", 0, 0];
      r.g.dataset.ledsT = ledT;
      r.ring.forEach((e, i) => light(e, ring[i] === "1", "{ring_on}"));
      light(r.front, front, "{front_on}");
      r.body.dataset.on = body ? "1" : "0";
      r.body.setAttribute("stroke", body ? "{body_on}" : "none");
    }}
    const cx = tLeft + (tRight - tLeft) * Math.min(t, span) / span;
    cursor.setAttribute("x1", cx.toFixed(1)); cursor.setAttribute("x2", cx.toFixed(1));
    clock.textContent = (t / 1000).toFixed(3) + " s";
    document.getElementById("fired").innerHTML = lastFired(t).map(g =>
      `<li>${{(g.last / 1000).toFixed(3)}} s ${{g.robot ? g.robot + ": " : ""}}${{escape(g.rule)}}` +
      (g.count > 1 ? ` <span class="repeats">\u00d7${{g.count}}${{g.more ? "+" : ""}} since ` +
       `${{(g.first / 1000).toFixed(3)}} s</span>` : "") + "</li>").join("");
    const values = new Map();
    for (const v of run.sets) {{ if (v[0] > t) break; values.set(v[1] + "\\u0000" + v[2], v); }}
    document.getElementById("vars").innerHTML = [...values.values()].map(v =>
      `<li>${{v[1] ? v[1] + ": " : ""}}${{escape(v[2])}} = ${{v[3]}}</li>`).join("") || "<li>none</li>";
  }}
  // the last FIRED_SHOWN rules fired by the cursor, each once with how often it fired since it
  // began (`every 20 ms` is one line, not the whole list), looked at over the last FIRED_SCAN
  function lastFired(t) {{
    let lo = 0, hi = run.firings.length;
    while (lo < hi) {{ const mid = (lo + hi) >> 1; if (run.firings[mid][0] <= t) lo = mid + 1; else hi = mid; }}
    const groups = new Map(), order = [];
    let i = lo - 1;
    for (; i >= 0 && i >= lo - {fired_scan}; i--) {{
      const f = run.firings[i], key = f[1] + "\u0000" + f[2];
      let g = groups.get(key);
      if (!g) {{
        if (order.length === {fired_shown}) break;
        g = {{ robot: f[1], rule: f[2], last: f[0], first: f[0], count: 0, more: false }};
        groups.set(key, g); order.push(g);
      }}
      g.first = f[0]; g.count++;
    }}
    if (i >= 0 && i < lo - {fired_scan}) order.forEach(g => {{ g.more = true; }});
    return order;
  }}
  function escape(s) {{
    return String(s).replace(/[&<>]/g, c => ({{"&": "&amp;", "<": "&lt;", ">": "&gt;"}})[c]);
  }}
  // a frame every 40 ms by the clock (timers, not animation frames, which
  // a hidden or headless page may not paint)
  let playing = false, last = 0;
  function frame() {{
    if (!playing) return;
    const now = performance.now();
    const t = Math.min(Number(slider.value) + Math.max(0, now - last) * run.speed, run.end);
    last = now; slider.value = t; show(t);
    if (t >= run.end) {{ playing = false; button.textContent = "play"; return; }}
    setTimeout(frame, 40);
  }}
  function play() {{
    if (Number(slider.value) >= run.end) slider.value = 0;
    playing = true; button.textContent = "pause"; last = performance.now();
    setTimeout(frame, 40);
  }}
  button.addEventListener("click", () => {{
    if (playing) {{ playing = false; button.textContent = "play"; }} else play();
  }});
  slider.addEventListener("input", () => show(Number(slider.value)));
  // #t=MS shows that moment, #play plays from the start
  const at = /^#t=([0-9]+)(?:&select=([A-Za-z0-9_-]+))?$/.exec(location.hash);
  if (at) slider.value = Math.min(Number(at[1]), run.end);
  if (at && at[2]) {{        // #t=MS&select=NAME: that robot selected
    const i = run.robots.findIndex(r => r.name === at[2]);
    if (i >= 0) robots[i].g.dispatchEvent(new Event("click"));
  }}
  show(Number(slider.value));
  if (location.hash === "#play") play();
}})();
</script></body></html>
"""

# Virtual time runs this many times faster than real time: a minute's run
# plays in six seconds.
SPEED = 10.0
FIRED_SHOWN = 8             # rules in "last rules fired", each once with its repeats
FIRED_SCAN = 5000           # firings looked at for them, back from the cursor
MESSAGE_SHOWN_MS = 500      # a message's line fades out over this
TRAIL_MS = 5000             # with many robots, each one's trail


def replay_html(text: str, title: str = "", source: str = "trace",
                variables: Optional[dict] = None) -> str:
    """The replay page of a trace (deterministic). `variables`: each
    robot's declared variables by its name ("" without a world), as
    (name, initial value) in declared order: the panel lists them from 0 s."""
    world, runs, end_ms = parse_trace(text, source)
    robots, firings, sets, messages = [], [], [], []
    colours = robot_colours(world, runs)
    for i, run in enumerate(runs):
        robots.append({"name": run.name, "colour": colours[i],
                       "poses": [[t, round(x, 1), round(y, 1), round(h, 1)]
                                 for t, x, y, h in thin_poses(run.poses)],
                       "leds": [list(state) for state in run.leds]})
        firings += [[f.t_ms, run.name, f.shown] for f in run.firings]
        messages += [[t, round(fx, 1), round(fy, 1), round(x, 1), round(y, 1), sender, run.name]
                     for t, fx, fy, x, y, sender, _ in run.messages]
        sets += [[0, run.name, name, value] for name, value in (variables or {}).get(run.name, ())]
    for line in text.splitlines():
        if '"set"' in line:
            rec = json.loads(line)
            if rec.get("kind") == "set":
                sets.append([int(rec["t_ms"]), str(rec.get("robot", "")), str(rec["var"]),
                             rec["value"]])
    firings.sort(key=lambda f: f[0])
    messages.sort(key=lambda m: m[0])
    sets.sort(key=lambda s: s[0])       # stable: the declared values first
    radius = float((world or {}).get("robot_radius_mm", DEFAULT_ROBOT_RADIUS_MM))
    svg = plot_trace(text, title=title, source=source)
    scale = float(re.search(r'data-frame="\S+ \S+ (\S+) ', svg).group(1))
    data = {"robots": robots, "firings": firings, "sets": sets, "messages": messages,
            "end": end_ms, "speed": SPEED,
            "radius": radius, "leds": local_geometry(max(radius * scale, 3.0))}
    payload = json.dumps(data, separators=(",", ":")).replace("</", "<\\/")
    svg = svg[svg.index("<svg"):]
    return _PAGE.format(title=html.escape(title or "epuckc replay"), end=end_ms, svg=svg,
                        data=payload, ring_on=RING_ON, front_on=FRONT_ON, body_on=BODY_ON,
                        off_stroke=OFF_STROKE, many=MANY_ROBOTS, trail_ms=TRAIL_MS,
                        shown_ms=MESSAGE_SHOWN_MS, message_colour=MESSAGE_COLOUR,
                        fired_shown=FIRED_SHOWN, fired_scan=FIRED_SCAN)
