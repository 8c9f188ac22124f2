// A run's JSON-lines trace (docs/runtime.md, docs/world.md) as the arena
// reads it: each robot's poses, LEDs and rules fired, the variables set,
// the messages delivered. Lines come in as the run streams them.
export type Pose = [number, number, number, number];          // t, x, y, heading
export type Leds = [number, string, number, number];          // t, ring, body, front
export type Firing = [number, string];                         // t, the event's name
export type Message = [number, number, number, number, number, string, string];

export type Box = { x_mm: number; y_mm: number; length_mm: number; width_mm: number;
                    angle_deg: number; colour?: string };
export type Cylinder = { x_mm: number; y_mm: number; radius_mm: number; colour?: string };
export type World = {
  arena?: { width_mm: number; height_mm: number } | null;
  boxes?: Box[]; cylinders?: Cylinder[];
  robots?: { name: string; x_mm: number; y_mm: number; heading_deg: number }[];
  robot_radius_mm?: number;
};

export class Track {
  poses: Pose[] = [];
  leds: Leds[] = [];
  firings: Firing[] = [];
  constructor(readonly name: string) {}
}

function before<T extends unknown[]>(items: T[], t: number): number {
  // the index of the last item at or before t (items by time), -1: none
  let lo = 0, hi = items.length - 1, found = -1;
  while (lo <= hi) {
    const mid = (lo + hi) >> 1;
    if ((items[mid][0] as number) <= t) { found = mid; lo = mid + 1; } else hi = mid - 1;
  }
  return found;
}

export class Trace {
  world: World | null = null;
  tracks: Map<string, Track> = new Map();
  sets: [number, string, string, number][] = [];
  messages: Message[] = [];
  end = 0;
  lines = 0;
  robotPoses = 0;           // the records with a pose that robots wrote (not the world's placements)
  exits: Map<string, string> = new Map();

  track(name: string): Track {
    let t = this.tracks.get(name);
    if (!t) { t = new Track(name); this.tracks.set(name, t); }
    return t;
  }

  add(line: string) {
    if (!line) return;
    let rec: Record<string, any>;
    try { rec = JSON.parse(line); } catch { return; }
    this.lines++;
    if (rec.kind === "world") {
      this.world = rec as World;
      for (const r of this.world.robots || [])
        this.track(r.name).poses.push([0, r.x_mm, r.y_mm, r.heading_deg]);
      return;
    }
    const t = Number(rec.t_ms);
    if (!Number.isFinite(t)) return;
    const robot = String(rec.robot ?? "");
    const track = this.track(robot);
    this.end = Math.max(this.end, t);
    if (typeof rec.x_mm === "number") {
      this.robotPoses++;
      const last = track.poses[track.poses.length - 1];
      const pose: Pose = [t, rec.x_mm, rec.y_mm, rec.heading_deg];
      if (last && last[0] === t) track.poses[track.poses.length - 1] = pose;
      else track.poses.push(pose);
    }
    switch (rec.kind) {
      case "event": track.firings.push([t, String(rec.name)]); break;
      case "led": track.leds.push([t, String(rec.ring ?? "00000000"), rec.body ? 1 : 0,
                                   rec.front ? 1 : 0]); break;
      case "set": this.sets.push([t, robot, String(rec.var), Number(rec.value)]); break;
      case "message":
        if (typeof rec.from_x_mm === "number")
          this.messages.push([t, rec.from_x_mm, rec.from_y_mm, rec.x_mm, rec.y_mm,
                              String(rec.from ?? ""), robot]);
        break;
      case "exit": case "timeout": case "watchdog": this.exits.set(robot, rec.kind); break;
    }
  }

  poseAt(name: string, t: number): Pose | null {
    const track = this.tracks.get(name);
    if (!track || !track.poses.length) return null;
    const i = before(track.poses, t);
    return track.poses[Math.max(i, 0)];
  }

  ledsAt(name: string, t: number): Leds {
    const track = this.tracks.get(name);
    const i = track ? before(track.leds, t) : -1;
    return i >= 0 ? track!.leds[i] : [0, "00000000", 0, 0];
  }

  firedUntil(t: number, count: number): [number, string, string][] {
    const all: [number, string, string][] = [];
    for (const track of this.tracks.values()) {
      const i = before(track.firings, t);
      for (let k = Math.max(0, i - count + 1); k <= i; k++)
        all.push([track.firings[k][0], track.name, track.firings[k][1]]);
    }
    return all.sort((a, b) => b[0] - a[0]).slice(0, count);
  }

  variablesAt(t: number): Map<string, [string, string, number]> {
    const values = new Map<string, [string, string, number]>();
    for (const [time, robot, name, value] of this.sets) {
      if (time > t) break;
      values.set(robot + "\u0000" + name, [robot, name, value]);
    }
    return values;
  }

  messagesAround(t: number, shownMs: number): Message[] {
    const out: Message[] = [];
    for (let i = before(this.messages, t); i >= 0 && this.messages[i][0] > t - shownMs; i--)
      out.push(this.messages[i]);
    return out;
  }
}
