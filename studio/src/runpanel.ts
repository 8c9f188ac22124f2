// Run: the program in the chosen world or scenario, streamed into the arena
// as the simulation writes its trace (epuckc/studio/runs.py), then scrubbed
// and replayed; Stop; the trace to download. Monitor's robot trace comes the
// same way (epuckc/studio/robots.py).
import { socketURL, withToken } from "./api";
import { Arena } from "./arena";
import { Trace } from "./trace";

export type RunState = "idle" | "starting" | "running" | "ended" | "stopped" | "refused";
const SPEEDS = [1, 4, 10];

function h<K extends keyof HTMLElementTagNameMap>(tag: K, attrs: Record<string, string> = {},
                                                  ...children: (Node | string)[]) {
  const e = document.createElement(tag);
  for (const [k, v] of Object.entries(attrs)) e.setAttribute(k, v);
  e.append(...children);
  return e;
}

export class RunPanel {
  trace = new Trace();
  state: RunState = "idle";
  runId = 0;
  status: number | null = null;
  cursor = 0;
  live = true;
  firstPoseMs: number | null = null;     // Run to the first pose a robot wrote, in the page
  startedAt = 0;
  playing = false;
  stderr = "";
  private socket: WebSocket | null = null;
  private arena: Arena;
  readonly world = h("select", { id: "run-world", title: "the world or scenario of the run" });
  readonly limit = h("input", { id: "run-limit", type: "number", min: "1", max: "600",
                                value: "20", title: "simulated seconds" }) as HTMLInputElement;
  readonly runButton = h("button", { id: "run", type: "button" }, "Run");
  readonly stopButton = h("button", { id: "stop", type: "button", disabled: "" }, "Stop");
  readonly download = h("a", { id: "download", class: "disabled" }, "trace") as HTMLAnchorElement;
  readonly playButton = h("button", { id: "play", type: "button" }, "Play");
  readonly speed = h("select", { id: "speed" }) as HTMLSelectElement;
  readonly slider = h("input", { id: "slider", type: "range", min: "0", max: "0", value: "0",
                                 step: "1" }) as HTMLInputElement;
  readonly clock = h("span", { id: "clock" }, "0.000 s");
  readonly fired = h("ul", { id: "fired" });
  readonly vars = h("ul", { id: "vars" });
  readonly console = h("pre", { id: "run-console" });
  private scheduled = false;
  program: () => string | null = () => null;
  beforeRun: () => Promise<void> = async () => {};

  constructor(parent: HTMLElement) {
    for (const s of SPEEDS) this.speed.append(h("option", { value: String(s) }, `${s}×`));
    const controls = h("div", { class: "run-controls" },
      h("label", {}, "in ", this.world), h("label", {}, "for ", this.limit, " s"),
      this.runButton, this.stopButton, this.download);
    const arenaBox = h("div", { id: "arena" });
    const scrub = h("div", { class: "scrub" }, this.playButton, this.speed, this.slider, this.clock);
    const panels = h("div", { class: "run-panels" },
      h("div", {}, h("b", {}, "rules fired"), this.fired),
      h("div", {}, h("b", {}, "variables"), this.vars));
    parent.append(controls, arenaBox, scrub, panels, this.console);
    this.arena = new Arena(arenaBox);
    this.runButton.addEventListener("click", () => void this.run());
    this.stopButton.addEventListener("click", () => this.stop());
    this.slider.addEventListener("input", () => {
      this.live = false;
      this.pause();
      this.seek(Number(this.slider.value));
    });
    this.playButton.addEventListener("click", () => this.playing ? this.pause() : this.play());
  }

  setInputs(worlds: string[], scenarios: string[], preferred: string | null) {
    const keep = this.world.value;
    this.world.replaceChildren(h("option", { value: "" }, "no world"),
      ...worlds.map(w => h("option", { value: "world:" + w }, w)),
      ...scenarios.map(s => h("option", { value: "scenario:" + s }, s)));
    const want = preferred ?? keep;
    if ([...this.world.options].some(o => o.value === want)) this.world.value = want;
  }

  private connect(): Promise<WebSocket> {
    if (this.socket && this.socket.readyState === WebSocket.OPEN) return Promise.resolve(this.socket);
    return new Promise((resolve, reject) => {
      const ws = new WebSocket(socketURL("/ws/run"));
      ws.onopen = () => { this.socket = ws; resolve(ws); };
      ws.onerror = () => reject(new Error("the run socket failed"));
      ws.onmessage = e => this.receive(JSON.parse(String(e.data)));
      ws.onclose = () => { if (this.socket === ws) this.socket = null; };
    });
  }

  load(text: string) {
    // a trace shown as a finished run (a Check's replay)
    this.pause();
    this.trace = new Trace();
    this.arena.reset();
    for (const line of text.split("\n")) this.trace.add(line);
    this.state = "ended";
    this.live = false;
    this.slider.max = String(this.trace.end);
    this.seek(0);
  }

  async run() {
    const [kind, file] = this.world.value ? this.world.value.split(/:(.*)/s) : ["", ""];
    const seconds = Math.max(1, Math.min(600, Number(this.limit.value) || 20));
    await this.start({ type: "run", time_limit_ms: Math.round(seconds * 1000),
                       ...(kind ? { [kind]: file } : {}) });
  }

  async monitor(port: string) {
    // a robot's own run: `epuckc monitor PORT --program P --trace -`, shown as a run
    await this.start({ type: "monitor", port });
  }

  private async start(request: Record<string, unknown>) {
    const program = this.program();
    if (!program) return;
    await this.beforeRun();
    const ws = await this.connect();
    this.pause();
    this.trace = new Trace();
    this.arena.reset();
    this.state = "starting";
    this.status = null;
    this.live = true;
    this.firstPoseMs = null;
    this.stderr = "";
    this.console.textContent = "";
    this.startedAt = performance.now();
    this.download.classList.add("disabled");
    this.download.removeAttribute("href");
    this.runButton.setAttribute("disabled", "");
    this.stopButton.removeAttribute("disabled");
    ws.send(JSON.stringify({ ...request, program }));
  }

  stop() {
    if (this.socket && (this.state === "running" || this.state === "starting"))
      this.socket.send(JSON.stringify({ type: "stop" }));
  }

  private receive(m: any) {
    switch (m.type) {
      case "started":
        this.runId = m.run; this.state = "running";
        this.console.textContent = `$ ${m.command}\n`;
        break;
      case "records":
        if (m.run !== this.runId) return;
        for (const line of m.lines) this.trace.add(line);
        if (this.firstPoseMs === null && this.trace.robotPoses > 0)
          this.firstPoseMs = performance.now() - this.startedAt;
        this.slider.max = String(this.trace.end);
        if (this.live) this.schedule();
        break;
      case "stderr":
        this.stderr += m.text;
        this.say(m.text);
        break;
      case "refused":
        this.state = "refused";
        this.console.textContent = m.error;
        this.finish();
        break;
      case "end":
        if (m.run !== this.runId) return;
        this.state = m.stopped ? "stopped" : "ended";
        this.status = m.status;
        this.download.href = withToken(m.trace);
        this.download.setAttribute("download", `trace-${m.run}.jsonl`);
        this.download.classList.remove("disabled");
        this.slider.max = String(this.trace.end);
        if (this.live) this.seek(this.trace.end);
        this.say(m.stopped ? "stopped\n" : `exit status ${m.status}\n`);
        this.finish();
        break;
    }
  }

  private say(text: string) {
    // appended, not rewritten (a program's warnings can be many lines)
    this.console.append(document.createTextNode(text));
    while (this.console.childNodes.length > 400) this.console.firstChild!.remove();
    this.console.scrollTop = this.console.scrollHeight;
  }

  private finish() {
    this.runButton.removeAttribute("disabled");
    this.stopButton.setAttribute("disabled", "");
  }

  private schedule() {
    // the arena follows the run as it comes, a frame at most every 30 ms
    if (this.scheduled) return;
    this.scheduled = true;
    window.setTimeout(() => {
      this.scheduled = false;
      if (this.live) this.seek(this.trace.end);
    }, 30);
  }

  seek(t: number) {
    this.cursor = Math.max(0, Math.min(t, this.trace.end));
    this.slider.value = String(this.cursor);
    this.clock.textContent = (this.cursor / 1000).toFixed(3) + " s";
    this.arena.show(this.trace, this.cursor);
    const named = this.trace.tracks.size > 1;
    this.fired.replaceChildren(...this.trace.firedUntil(this.cursor, 8).map(([ft, robot, name]) =>
      h("li", {}, `${(ft / 1000).toFixed(3)} s ${named && robot ? robot + ": " : ""}${name}`)));
    const values = [...this.trace.variablesAt(this.cursor).values()];
    this.vars.replaceChildren(...(values.length ? values.map(([robot, name, value]) =>
      h("li", {}, `${named && robot ? robot + ": " : ""}${name} = ${value}`))
      : [h("li", {}, "none")]));
  }

  play() {
    if (this.state === "running" || this.state === "starting") {
      this.live = true;         // back to following the run as it comes
      this.seek(this.trace.end);
      return;
    }
    if (this.cursor >= this.trace.end) this.seek(0);
    this.playing = true;
    this.live = false;
    this.playButton.textContent = "Pause";
    let last = performance.now();
    const frame = () => {
      if (!this.playing) return;
      const now = performance.now();
      this.seek(this.cursor + (now - last) * Number(this.speed.value));
      last = now;
      if (this.cursor >= this.trace.end) { this.pause(); return; }
      window.setTimeout(frame, 40);
    };
    window.setTimeout(frame, 40);
  }

  pause() {
    this.playing = false;
    this.playButton.textContent = "Play";
  }
}
