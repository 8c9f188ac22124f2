// The page of `epuckc studio` (docs/studio.md): the files of the folder, an
// editor with the language server's diagnostics, quick fixes, hover,
// completion and formatting, saving that never overwrites a change made
// outside, Run into the arena, the generated C, a class folder's exercises
// with Check, and Flash and Monitor of a robot. `window.studio` holds the
// page's state for tests and the curious.
import { EditorState, Extension } from "@codemirror/state";
import { EditorView, keymap, lineNumbers, highlightActiveLine, drawSelection } from "@codemirror/view";
import { defaultKeymap, history, historyKeymap, indentWithTab } from "@codemirror/commands";
import { syntaxHighlighting, defaultHighlightStyle, bracketMatching } from "@codemirror/language";
import { lintGutter, lintKeymap, forEachDiagnostic } from "@codemirror/lint";
import { autocompletion, closeBrackets } from "@codemirror/autocomplete";
import { LSPClient, formatDocument } from "@codemirror/lsp-client";
import { api, Info } from "./api";
import { epuckHighlighting, epuckLanguage } from "./highlight";
import { connect, diagnosticsShown, listeners } from "./lsp";
import { RunPanel } from "./runpanel";
import { Exercises } from "./exercises";
import { RobotPanel } from "./robot";

type Open = { path: string; state: EditorState; version: string | null; saved: string };

const $ = (id: string) => document.getElementById(id)!;

class Studio {
  info!: Info;
  client: LSPClient | null = null;
  view!: EditorView;
  files: Map<string, Open> = new Map();
  current: Open | null = null;
  run!: RunPanel;
  exercises!: Exercises;
  robot!: RobotPanel;
  ready = false;
  diagnosticsAt = 0;        // when diagnostics were last drawn (performance.now)
  fixesAt = 0;              // and when their quick fixes were added
  notice = "";
  conflict: { path: string; version: string | null } | null = null;

  uri(path: string): string { return this.info.root_uri + "/" + path.split("/").map(encodeURIComponent).join("/"); }

  async start() {
    this.info = await api<Info>("GET", "/api/info");
    $("folder").textContent = this.info.name;
    document.title = `${this.info.name} — epuckc studio`;
    this.run = new RunPanel($("run-panel"));
    this.run.program = () => this.current && /\.(epk|c)$/.test(this.current.path) ? this.current.path : null;
    this.run.beforeRun = async () => { if (this.dirty()) await this.save(); };
    this.exercises = new Exercises($("exercises"), this);
    this.view = new EditorView({ parent: $("editor") });
    try {
      this.client = await connect(this.info.root_uri);
    } catch (e) {
      this.say(`the language server is not there: ${e}`);
    }
    this.listFiles();
    this.exercises.show(this.info.exercises);
    this.bind();
    const first = this.info.files.find(f => f.endsWith(".epk"));
    if (first) await this.open(first);
    window.setInterval(() => void this.watch(), 1500);
    window.addEventListener("focus", () => void this.watch());
    // the robot link: buttons that appear when the server offers them (pyserial there)
    this.robot = new RobotPanel(this.run, this.run.program, this.run.beforeRun);
    $("flash").hidden = !this.info.flash;
    $("monitor").hidden = !this.info.monitor;
    this.ready = true;
    document.body.dataset.ready = "1";
  }

  extensions(path: string): Extension[] {
    const base: Extension[] = [lineNumbers(), highlightActiveLine(), drawSelection(), history(),
      bracketMatching(), closeBrackets(), syntaxHighlighting(defaultHighlightStyle),
      keymap.of([...defaultKeymap, ...historyKeymap, ...lintKeymap, indentWithTab,
                 { key: "Mod-s", run: () => { void this.save(); return true; }, preventDefault: true }]),
      EditorView.updateListener.of(u => { if (u.docChanged) this.showDirty(); })];
    if (path.endsWith(".epk")) {
      base.push(epuckLanguage, epuckHighlighting, lintGutter(), autocompletion());
      if (this.client) base.push(this.client.plugin(this.uri(path), "epuck"));
    }
    return base;
  }

  listFiles() {
    const list = $("files");
    list.replaceChildren(...this.info.files.map(f => {
      const li = document.createElement("li");
      li.textContent = f;
      li.dataset.path = f;
      li.addEventListener("click", () => void this.open(f));
      return li;
    }));
    const worlds = this.info.files.filter(f => f.endsWith(".world"));
    const scenarios = this.info.files.filter(f => f.endsWith(".scn"));
    this.run.setInputs(worlds, scenarios, this.preferredWorld(worlds, scenarios));
  }

  preferredWorld(worlds: string[], scenarios: string[]): string | null {
    // NAME.world or NAME.scn beside NAME.epk, as `epuckc test` finds them
    if (!this.current) return null;
    const stem = this.current.path.replace(/\.epk$/, "");
    if (worlds.includes(stem + ".world")) return "world:" + stem + ".world";
    if (scenarios.includes(stem + ".scn")) return "scenario:" + stem + ".scn";
    return null;
  }

  async open(path: string) {
    if (this.current) this.current.state = this.view.state;
    let file = this.files.get(path);
    if (!file) {
      const { text, version } = await api<{ text: string; version: string }>(
        "GET", `/api/file?path=${encodeURIComponent(path)}`);
      file = { path, version, saved: text,
               state: EditorState.create({ doc: text, extensions: this.extensions(path) }) };
      this.files.set(path, file);
    }
    this.current = file;
    this.view.setState(file.state);
    for (const li of $("files").children)
      li.classList.toggle("current", (li as HTMLElement).dataset.path === path);
    $("current").textContent = path;
    const worlds = this.info.files.filter(f => f.endsWith(".world"));
    const scenarios = this.info.files.filter(f => f.endsWith(".scn"));
    const preferred = this.preferredWorld(worlds, scenarios);
    if (preferred) this.run.world.value = preferred;
    this.showDirty();
  }

  dirty(): boolean {
    return !!this.current && this.view.state.doc.toString() !== this.current.saved;
  }

  showDirty() {
    $("current").classList.toggle("dirty", this.dirty());
  }

  say(text: string) {
    this.notice = text;
    $("notice").textContent = text;
  }

  async save(force = false): Promise<boolean> {
    const file = this.current;
    if (!file) return false;
    const text = this.view.state.doc.toString();
    const base = force && this.conflict ? this.conflict.version : file.version;
    try {
      const { version } = await api<{ version: string }>("PUT", "/api/file",
        { path: file.path, text, version: base });
      file.version = version;
      file.saved = text;
      this.conflict = null;
      $("conflict").hidden = true;
      this.say(`saved ${file.path}`);
      this.showDirty();
      return true;
    } catch (e: any) {
      if (e.status === 409) {
        this.conflict = { path: file.path, version: e.data.version ?? null };
        this.showConflict(`${file.path} changed on disk since it was opened: it was not saved.`);
      } else this.say(`not saved: ${e.message}`);
      return false;
    }
  }

  showConflict(text: string) {
    $("conflict-text").textContent = text;
    $("conflict").hidden = false;
  }

  async reload() {
    const file = this.current;
    if (!file) return;
    const { text, version } = await api<{ text: string; version: string }>(
      "GET", `/api/file?path=${encodeURIComponent(file.path)}`);
    file.version = version;
    file.saved = text;
    this.view.dispatch({ changes: { from: 0, to: this.view.state.doc.length, insert: text } });
    this.conflict = null;
    $("conflict").hidden = true;
    this.say(`reloaded ${file.path} from disk`);
    this.showDirty();
  }

  async watch() {
    // a change made outside the page is noticed: reloaded when the page has
    // none of its own, else offered, never overwritten
    const file = this.current;
    if (!file || file.version === null) return;
    let version: string | null;
    try {
      ({ version } = await api<{ version: string | null }>(
        "GET", `/api/version?path=${encodeURIComponent(file.path)}`));
    } catch { return; }
    if (file !== this.current || version === file.version) return;
    if (this.conflict && this.conflict.version === version) return;
    if (!this.dirty() && version !== null) await this.reload();
    else {
      this.conflict = { path: file.path, version };
      this.showConflict(`${file.path} changed on disk, and it has changes of yours here.`);
    }
  }

  async showC() {
    const file = this.current;
    if (!file || !file.path.endsWith(".epk")) return;
    const line = this.view.state.doc.lineAt(this.view.state.selection.main.head).number;
    const panel = $("c-code");
    $("c-panel").hidden = false;
    try {
      const r = await api<{ c: string; parts: string[]; line: number }>("POST", "/api/c",
        { path: file.path, text: this.view.state.doc.toString(), line });
      $("c-title").textContent = r.parts.length ? `the C of line ${r.line}` : "the generated C";
      panel.textContent = r.parts.length ? r.parts.join("\n\n") : r.c;
      panel.dataset.whole = r.c;
    } catch (e: any) {
      $("c-title").textContent = "no C: the program has errors";
      panel.textContent = e.data?.diagnostics || e.message;
    }
  }

  async newWorld() {
    const name = prompt("the new world's file name", "arena.world");
    if (!name) return;
    const path = name.endsWith(".world") ? name : name + ".world";
    try {
      await api("POST", "/api/world", { path });
    } catch (e: any) { this.say(`no new world: ${e.message}`); return; }
    this.info = await api<Info>("GET", "/api/info");
    this.listFiles();
    await this.open(path);
  }

  bind() {
    $("save").addEventListener("click", () => void this.save());
    $("format").addEventListener("click", () => { formatDocument(this.view); });
    $("show-c").addEventListener("click", () => void this.showC());
    $("c-whole").addEventListener("click", () => {
      $("c-code").textContent = $("c-code").dataset.whole || "";
    });
    $("c-close").addEventListener("click", () => { $("c-panel").hidden = true; });
    $("new-world").addEventListener("click", () => void this.newWorld());
    $("reload").addEventListener("click", () => void this.reload());
    $("overwrite").addEventListener("click", () => void this.save(true));
  }

  // what tests read: the diagnostics shown in the editor, with their fixes
  diagnostics() {
    const out: { from: number; to: number; severity: string; message: string; fixes: string[] }[] = [];
    forEachDiagnostic(this.view.state, (d, from, to) => out.push({
      from, to, severity: d.severity, message: d.message,
      fixes: (d.actions || []).map(a => a.name) }));
    return out;
  }

  applyFix(index: number, which = 0) {
    const all: any[] = [];
    forEachDiagnostic(this.view.state, (d, from, to) => all.push({ d, from, to }));
    const item = all[index];
    if (!item || !item.d.actions || !item.d.actions[which]) return false;
    item.d.actions[which].apply(this.view, item.from, item.to);
    return true;
  }

  text(): string { return this.view.state.doc.toString(); }
}

const studio = new Studio();
(window as any).studio = studio;
(window as any).studioShown = diagnosticsShown;
listeners.push((uri, withFixes) => {
  if (withFixes) studio.fixesAt = performance.now();
  else studio.diagnosticsAt = performance.now();
  document.body.dataset.diagnostics = String(studio.diagnostics().length);
});
studio.start().catch(e => {
  document.body.dataset.error = String(e);
  studio.say(`the studio could not start: ${e.message || e}`);
});
