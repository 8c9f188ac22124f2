// A class folder's exercises (epuckc/studio/exercises.py): each with its
// files, Check on one file or on the whole exercise (`epuckc test` on them),
// the results with their diffs, and each case's run replayed in the arena.
import { api, withToken } from "./api";

type Result = { file: string; status: string; report: string; problems?: string[];
                trace: number | null };
type Exercise = { folder: string; title: string; files: string[] };
type Host = { open(path: string): Promise<void>; save(): Promise<boolean>; dirty(): boolean;
              run: { load(text: string): void }; say(text: string): void };

function h<K extends keyof HTMLElementTagNameMap>(tag: K, attrs: Record<string, string> = {},
                                                  ...children: (Node | string)[]) {
  const e = document.createElement(tag);
  for (const [k, v] of Object.entries(attrs)) e.setAttribute(k, v);
  e.append(...children);
  return e;
}

export class Exercises {
  results: Result[] = [];
  checking = false;
  constructor(private parent: HTMLElement, private host: Host) {}

  show(exercises: Exercise[]) {
    this.parent.hidden = exercises.length === 0;
    this.parent.replaceChildren(h("h2", {}, "Exercises"), ...exercises.map(ex => {
      const check = h("button", { type: "button", class: "check-all",
                                  "data-folder": ex.folder }, "Check all");
      check.addEventListener("click", () => void this.check([ex.folder]));
      const files = h("ul", {}, ...ex.files.map(f => {
        const open = h("span", { class: "file" }, f.slice(ex.folder ? ex.folder.length + 1 : 0));
        open.addEventListener("click", () => void this.host.open(f));
        const one = h("button", { type: "button", class: "check", "data-path": f }, "Check");
        one.addEventListener("click", () => void this.check([f]));
        return h("li", {}, open, " ", one);
      }));
      return h("section", { class: "exercise", "data-folder": ex.folder },
               h("h3", {}, ex.title, " ", check), files);
    }), h("div", { id: "check-results" }));
  }

  async check(paths: string[]) {
    if (this.host.dirty()) await this.host.save();
    this.checking = true;
    const box = document.getElementById("check-results")!;
    box.textContent = "checking…";
    try {
      const { results } = await api<{ results: Result[] }>("POST", "/api/check", { paths });
      this.results = results;
      box.replaceChildren(...results.map(r => this.result(r)));
    } catch (e: any) {
      box.textContent = `Check failed: ${e.message}`;
    } finally {
      this.checking = false;
    }
  }

  private result(r: Result): HTMLElement {
    const replay = h("button", { type: "button", class: "replay" }, "Replay");
    replay.hidden = r.trace === null;
    replay.addEventListener("click", async () => {
      const response = await fetch(withToken(`/api/trace/${r.trace}`));
      this.host.run.load(await response.text());
    });
    return h("div", { class: `result ${r.status}`, "data-file": r.file, "data-status": r.status },
      h("b", {}, r.status === "passed" ? "PASS" : r.status === "failed" ? "FAIL" : r.status.toUpperCase()),
      ` ${r.file} `, replay, r.report ? h("pre", { class: "report" }, r.report) : "");
  }
}
