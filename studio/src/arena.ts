// The arena: the world of a run drawn in SVG (walls, boxes, cylinders), each
// robot at the cursor's time with its heading and LEDs, its path so far and
// where rules fired, and the messages of the last half second. The world's
// y axis points up; the picture's down.
import { Trace } from "./trace";

const NS = "http://www.w3.org/2000/svg";
const COLOURS = ["#1f77b4", "#d62728", "#2ca02c", "#9467bd", "#ff7f0e", "#17becf",
                 "#8c564b", "#e377c2"];
const MESSAGE_SHOWN_MS = 500;
const FILL: Record<string, string> = { red: "#e61e1e", yellow: "#e6dc28", green: "#28be3c",
  cyan: "#28c8d2", blue: "#2846dc", magenta: "#d228c8", white: "#f0f0f0", grey: "#b0b0b0",
  black: "#222" };

function el(name: string, attrs: Record<string, string | number> = {}): SVGElement {
  const e = document.createElementNS(NS, name);
  for (const [k, v] of Object.entries(attrs)) e.setAttribute(k, String(v));
  return e;
}

type Drawn = { g: SVGGElement; path: SVGPolylineElement; marks: SVGGElement;
               ring: SVGElement[]; body: SVGElement; front: SVGElement; shown: number;
               label: SVGElement; radius: number };

export class Arena {
  readonly svg: SVGSVGElement;
  private layer: SVGGElement;
  private robots: Map<string, Drawn> = new Map();
  private messages: SVGGElement;
  private frame = { x0: 0, y0: 0, w: 1000, h: 700 };
  private worldDrawn = false;

  constructor(parent: HTMLElement) {
    this.svg = el("svg", { id: "arena-svg", preserveAspectRatio: "xMidYMid meet" }) as SVGSVGElement;
    this.layer = el("g") as SVGGElement;
    this.messages = el("g", { class: "messages" }) as SVGGElement;
    this.svg.append(this.layer, this.messages);
    parent.append(this.svg);
    this.reset();
  }

  reset() {
    this.layer.replaceChildren();
    this.messages.replaceChildren();
    this.robots.clear();
    this.worldDrawn = false;
    this.setFrame(0, 0, 1000, 700);
  }

  private setFrame(x0: number, y0: number, w: number, h: number) {
    this.frame = { x0, y0, w, h };
    this.svg.setAttribute("viewBox", `${x0} ${-(y0 + h)} ${w} ${h}`);
  }

  // world (x, y) in mm to the picture's (x, -y)
  private p(x: number, y: number): string { return `${x.toFixed(1)},${(-y).toFixed(1)}`; }

  private drawWorld(trace: Trace) {
    const w = trace.world;
    if (!w || this.worldDrawn) return;
    this.worldDrawn = true;
    if (w.arena) {
      this.setFrame(-20, -20, w.arena.width_mm + 40, w.arena.height_mm + 40);
      this.layer.append(el("rect", { class: "arena", x: 0, y: -w.arena.height_mm,
        width: w.arena.width_mm, height: w.arena.height_mm }));
    }
    for (const b of w.boxes || []) {
      this.layer.append(el("rect", { class: "box", x: -b.length_mm / 2, y: -b.width_mm / 2,
        width: b.length_mm, height: b.width_mm, fill: FILL[b.colour || "grey"] || FILL.grey,
        transform: `translate(${this.p(b.x_mm, b.y_mm)}) rotate(${-b.angle_deg})` }));
    }
    for (const c of w.cylinders || [])
      this.layer.append(el("circle", { class: "cylinder", cx: c.x_mm, cy: -c.y_mm, r: c.radius_mm,
        fill: FILL[c.colour || "grey"] || FILL.grey }));
  }

  private fit(trace: Trace) {
    // without an arena: the ground the robots have covered, and some room
    if (trace.world && trace.world.arena) return;
    let minX = Infinity, minY = Infinity, maxX = -Infinity, maxY = -Infinity;
    for (const track of trace.tracks.values())
      for (const [, x, y] of track.poses) {
        minX = Math.min(minX, x); maxX = Math.max(maxX, x);
        minY = Math.min(minY, y); maxY = Math.max(maxY, y);
      }
    if (minX === Infinity) return;
    const margin = 150;
    const w = Math.max(maxX - minX + 2 * margin, 400), h = Math.max(maxY - minY + 2 * margin, 300);
    const f = this.frame;
    if (minX - margin / 2 < f.x0 || minY - margin / 2 < f.y0 || maxX + margin / 2 > f.x0 + f.w
        || maxY + margin / 2 > f.y0 + f.h)
      this.setFrame((minX + maxX - w) / 2, (minY + maxY - h) / 2, w, h);
  }

  private robot(trace: Trace, name: string): Drawn {
    let d = this.robots.get(name);
    if (d) return d;
    const colour = COLOURS[this.robots.size % COLOURS.length];
    const radius = trace.world?.robot_radius_mm ?? 37;
    const path = el("polyline", { class: "path", fill: "none", stroke: colour,
                                  "stroke-width": 3, "stroke-opacity": 0.6 }) as SVGPolylineElement;
    const marks = el("g", { class: "firings", fill: colour }) as SVGGElement;
    const g = el("g", { class: "robot", "data-robot": name }) as SVGGElement;
    g.append(el("circle", { r: radius, fill: colour, "fill-opacity": 0.35, stroke: "#000",
                            "stroke-width": 2 }),
             el("line", { x1: 0, y1: 0, x2: radius, y2: 0, stroke: "#000", "stroke-width": 3 }));
    const body = el("circle", { class: "led body-led", r: radius * 0.5, fill: "none",
                                "stroke-width": radius * 0.14 });
    const front = el("circle", { class: "led front-led", cx: radius * 0.5, cy: 0,
                                 r: radius * 0.11, stroke: "#7a2a2a" });
    const ring: SVGElement[] = [];
    for (let i = 0; i < 8; i++) {
      const a = (Math.PI / 4) * i;
      const e = el("circle", { class: "led ring-led", "data-led": i, r: radius * 0.16,
        cx: (0.78 * radius * Math.cos(a)).toFixed(1), cy: (0.78 * radius * Math.sin(a)).toFixed(1),
        stroke: "#7a2a2a", "stroke-width": 1 });
      ring.push(e);
    }
    g.append(body, front, ...ring);
    const label = el("text", { class: "robot-name" });
    label.textContent = name;
    this.layer.append(path, marks, g, label);
    d = { g, path, marks, ring, body, front, shown: 0, label, radius };
    this.robots.set(name, d);
    return d;
  }

  show(trace: Trace, t: number) {
    this.drawWorld(trace);
    this.fit(trace);
    for (const [name, track] of trace.tracks) {
      const pose = trace.poseAt(name, t);
      if (!pose) continue;
      const d = this.robot(trace, name);
      const [, x, y, heading] = pose;
      d.g.setAttribute("transform", `translate(${this.p(x, y)}) rotate(${(-heading).toFixed(1)})`);
      d.label.setAttribute("x", (x + d.radius + 4).toFixed(1));
      d.label.setAttribute("y", (-y - d.radius).toFixed(1));
      d.g.dataset.x = x.toFixed(1);
      d.g.dataset.y = y.toFixed(1);
      const points: string[] = [];
      for (const p of track.poses) { if (p[0] > t) break; points.push(this.p(p[1], p[2])); }
      d.path.setAttribute("points", points.join(" "));
      // a dot where each rule fired, up to the cursor
      const fired = track.firings.filter(f => f[0] <= t).length;
      if (fired !== d.shown) {
        d.marks.replaceChildren();
        let lastT = -1;
        for (const [ft] of track.firings.slice(0, fired)) {
          if (ft - lastT < 100) continue;      // one dot per 100 ms is enough to see
          lastT = ft;
          const at = trace.poseAt(name, ft);
          if (at) d.marks.append(el("circle", { cx: at[1].toFixed(1), cy: (-at[2]).toFixed(1), r: 6 }));
        }
        d.shown = fired;
      }
      const [, ring, body, front] = trace.ledsAt(name, t);
      d.ring.forEach((e, i) => {
        e.dataset.on = ring[i] === "1" ? "1" : "0";
        e.setAttribute("fill", ring[i] === "1" ? "#ff2020" : "none");
      });
      d.front.setAttribute("fill", front ? "#ff2020" : "none");
      d.body.setAttribute("stroke", body ? "#2ecc40" : "none");
    }
    this.messages.replaceChildren(...trace.messagesAround(t, MESSAGE_SHOWN_MS).map(m =>
      el("line", { class: "message", x1: m[1], y1: -m[2], x2: m[3], y2: -m[4], stroke: "#e67e22",
                   "stroke-width": 3,
                   "stroke-opacity": (1 - (t - m[0]) / MESSAGE_SHOWN_MS).toFixed(2) })));
  }
}
