// Flash and Monitor (epuckc/studio/robots.py, docs/robots.md): the robot's
// serial port (the ports found offered, another typed), Flash as `epuckc
// flash` on the open program, Monitor as the robot's own run in the arena.
import { api } from "./api";
import { RunPanel } from "./runpanel";

type Port = { device: string; kind: string; robot_id: number | null; description: string;
              uses: string[] };

type Flashed = { status: number; command: string; output: string };

const $ = (id: string) => document.getElementById(id)!;

export class RobotPanel {
  mode: "flash" | "monitor" = "flash";
  ports: Port[] = [];
  busy = false;
  lastFlash: Flashed | null = null;
  readonly panel = $("robot");
  readonly port = $("robot-port") as HTMLInputElement;
  readonly target = $("robot-target") as HTMLSelectElement;
  readonly number = $("robot-id") as HTMLInputElement;
  readonly trace = $("robot-trace") as HTMLInputElement;
  readonly go = $("robot-go") as HTMLButtonElement;
  readonly output = $("robot-output");

  constructor(private run: RunPanel, private program: () => string | null,
              private beforeFlash: () => Promise<void>) {
    $("flash").addEventListener("click", () => void this.open("flash"));
    $("monitor").addEventListener("click", () => void this.open("monitor"));
    $("robot-close").addEventListener("click", () => { this.panel.hidden = true; });
    this.go.addEventListener("click", () => void (this.mode === "flash" ? this.flash() : this.monitor()));
    this.port.addEventListener("change", () => this.chosen());
  }

  async open(mode: "flash" | "monitor") {
    this.mode = mode;
    this.panel.hidden = false;
    this.panel.dataset.mode = mode;
    $("robot-title").textContent = mode === "flash" ? "Flash the open program to a robot"
      : "Monitor a robot running the open program (built with its trace)";
    this.go.textContent = mode === "flash" ? "Flash" : "Monitor";
    for (const id of ["robot-target-label", "robot-id-label", "robot-trace-label"])
      $(id).hidden = mode !== "flash";
    try {
      ({ ports: this.ports } = await api<{ ports: Port[] }>("GET", "/api/ports"));
    } catch (e: any) { this.ports = []; this.output.textContent = e.message; }
    const usable = this.ports.filter(p => p.device && p.uses.includes(mode));
    $("robot-ports").replaceChildren(...usable.map(p => {
      const o = document.createElement("option");
      o.value = p.device;
      o.textContent = `${p.kind === "epuck2" ? "e-puck2" : "e-puck"}${p.robot_id !== null ? " " + p.robot_id : ""}: ${p.description}`;
      return o;
    }));
    if (!this.port.value && usable.length) { this.port.value = usable[0].device; this.chosen(); }
    if (!usable.length && !this.output.textContent)
      this.output.textContent = "no robot's port was found: type it (docs/robots.md says how to connect a robot)";
  }

  chosen() {
    // what the port found says of its robot
    const p = this.ports.find(q => q.device === this.port.value);
    if (!p) return;
    this.target.value = p.kind;
    if (p.robot_id !== null) this.number.value = String(p.robot_id);
  }

  async flash() {
    const program = this.program();
    if (!program || this.busy || !this.port.value) return;
    await this.beforeFlash();
    const built = /\.(hex|elf)$/.test(program);
    const body: Record<string, unknown> = { program, port: this.port.value, trace: this.trace.checked };
    if (!built) body.target = this.target.value;
    if (this.number.value !== "" && (built ? program.endsWith(".hex") : this.target.value === "epuck"))
      body.robot_id = Number(this.number.value);
    this.busy = true;
    this.go.disabled = true;
    this.output.textContent = (built ? program.endsWith(".hex") : this.target.value === "epuck")
      ? "flashing: press the e-puck's reset button when asked…\n" : "flashing…\n";
    try {
      const done = await api<Flashed>("POST", "/api/flash", body);
      this.lastFlash = done;
      this.output.textContent = `$ ${done.command}\n${done.output}` +
        (done.status === 0 ? "" : `exit status ${done.status}\n`);
    } catch (e: any) {
      this.lastFlash = null;
      this.output.textContent = `not flashed: ${e.message}`;
    } finally {
      this.busy = false;
      this.go.disabled = false;
    }
  }

  async monitor() {
    if (!this.port.value) return;
    this.output.textContent = "";
    await this.run.monitor(this.port.value);
  }
}
