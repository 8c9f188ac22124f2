#!/usr/bin/env python3
"""The studio in the browser, timed where the student sees it: a keystroke
to its diagnostics in the page, and Run to the first robot pose streamed
into the arena, for a 200-rule program; each beside its reference measured
in the same run.

    python3 bench/studio_bench.py [--rules 200] [--keys 30] [--runs 5]

- Keystroke: the page (Debian's Chromium, driven by Playwright) has the
  program open; a key that makes or mends an error (`set_timer` <->
  `set_timerx`) is pressed, and the time from its keydown event to the
  changed diagnostics drawn in the editor is read from the page's own clock.
  The reference is what the language server does for that edit in this
  process (ide/: apply the change, analyse, convert the diagnostics), the
  floor under the page's figure. Goal: under 100 ms.
- Run: the page's Run button to the first pose record in the page (warm:
  the program was run once before, so its build is cached); the reference
  is `epuckc run PROG --world W --trace -` started from this process to the
  first pose line on its stdout, which is what the studio starts. Goal:
  under 500 ms.

Wall-clock times (the machine may be shared: figures move); medians and the
90th percentile. Figures go in docs/performance.md.
"""
from __future__ import annotations

import argparse
import os
import shutil
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

REPO = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(REPO))
sys.path.insert(0, str(REPO / "bench"))

from check_bench import generate  # noqa: E402

ARGS = ["--headless=new", "--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
        "--disable-background-networking", "--disable-component-update", "--disable-sync"]


def summary(xs: list) -> str:
    xs = sorted(xs)
    p90 = xs[min(len(xs) - 1, int(round(0.9 * (len(xs) - 1))))]
    return f"median {statistics.median(xs):7.1f} ms   p90 {p90:7.1f} ms   (n={len(xs)})"


def server_reference(text: str, keys: int) -> list:
    """ide/'s work for the same edits, in this process."""
    from lsprotocol import types as lsp
    from epuckc.ide.lsp import Document, EpuckServer, Lines
    server = EpuckServer()
    doc = Document("file:///bench/prog.epk", text, 1, server)
    doc.analyse()
    at = text.rindex("set_timer") + len("set_timer")
    times = []
    for i in range(keys):
        lines = Lines(doc.text, server.encoding)
        start, end, new = (at, at, "x") if i % 2 == 0 else (at, at + 1, "")
        change = lsp.TextDocumentContentChangePartial(
            range=lsp.Range(lines.position(start), lines.position(end)), text=new)
        t0 = time.perf_counter()
        doc.apply(change, server.encoding)
        analysis = doc.analyse()
        server.diagnostics(doc, analysis)
        times.append((time.perf_counter() - t0) * 1000)
    return times


def cli_reference(folder: Path, runs: int) -> list:
    env = dict(os.environ, PYTHONPATH=str(REPO))
    argv = [sys.executable, "-m", "epuckc", "run", "prog.epk", "--world", "arena.world",
            "--trace", "-", "--pose-interval", "50ms", "--time-limit", "20s"]
    subprocess.run(argv, cwd=folder, env=env, capture_output=True)     # warm the cache
    times = []
    for _ in range(runs):
        t0 = time.perf_counter()
        proc = subprocess.Popen(argv, cwd=folder, env=env, stdout=subprocess.PIPE,
                                stderr=subprocess.DEVNULL, text=True)
        for line in proc.stdout:
            if '"x_mm"' in line and '"kind": "world"' not in line:
                times.append((time.perf_counter() - t0) * 1000)
                break
        proc.kill()
        proc.wait()
    return times


def page_figures(url: str, keys: int, runs: int) -> tuple:
    from playwright.sync_api import sync_playwright
    with sync_playwright() as p:
        browser = p.chromium.launch(executable_path=shutil.which("chromium") or "/usr/bin/chromium",
                                    args=ARGS)
        page = browser.new_page(viewport={"width": 1400, "height": 860}, bypass_csp=True)
        page.goto(url)
        page.wait_for_function("document.body.dataset.ready === '1'", timeout=60000)
        page.wait_for_function("studio.current && studio.current.path === 'prog.epk'")
        page.evaluate("""() => { window.benchKey = 0;
            document.addEventListener('keydown', e => { window.benchKey = performance.now(); },
                                      true); }""")
        # the cursor after the last `set_timer`
        page.evaluate("""() => { const at = studio.text().lastIndexOf('set_timer') + 9;
            studio.view.dispatch({selection: {anchor: at}}); studio.view.focus(); }""")
        page.wait_for_timeout(500)
        key_times = []
        for i in range(keys + 2):           # the first two: the analysis warms up
            before = page.evaluate("studio.diagnostics().length")
            page.keyboard.press("x" if i % 2 == 0 else "Backspace")
            page.wait_for_function("n => studio.diagnostics().length !== n", arg=before,
                                   timeout=10000)
            if i >= 2:
                key_times.append(page.evaluate("studio.diagnosticsAt - window.benchKey"))
            page.wait_for_timeout(50)
        # Run, warm: once to build, then timed
        page.select_option("#run-world", "world:arena.world")
        page.fill("#run-limit", "20")
        run_times = []
        for i in range(runs + 1):
            page.click("#run")
            page.wait_for_function("studio.run.state === 'ended' || studio.run.state === 'stopped'",
                                   timeout=300000)
            if i:
                run_times.append(page.evaluate("studio.run.firstPoseMs"))
        browser.close()
    return key_times, run_times


def main() -> int:
    ap = argparse.ArgumentParser()
    ap.add_argument("--rules", type=int, default=200)
    ap.add_argument("--keys", type=int, default=30)
    ap.add_argument("--runs", type=int, default=5)
    args = ap.parse_args()
    import re
    import signal
    with tempfile.TemporaryDirectory(prefix="studio-bench-") as tmp:
        folder = Path(tmp)
        text = generate(args.rules)
        (folder / "prog.epk").write_text(text, encoding="utf-8")
        shutil.copy(REPO / "examples" / "arena.world", folder / "arena.world")
        # the studio as a student starts it: a process of its own
        studio = subprocess.Popen([sys.executable, "-m", "epuckc", "studio", str(folder),
                                   "--no-browser", "--port", "0"], stdout=subprocess.PIPE,
                                  text=True, env=dict(os.environ, PYTHONPATH=str(REPO)))
        try:
            url = next(m.group(1) for line in studio.stdout
                       for m in [re.search(r"open (http://\S+)", line)] if m)
            key_times, run_times = page_figures(url, args.keys, args.runs)
        finally:
            studio.send_signal(signal.SIGINT)
            studio.wait(30)
        reference_keys = server_reference(text, args.keys)
        reference_runs = cli_reference(folder, args.runs)
    print(f"{args.rules}-rule program, {os.cpu_count()} CPUs")
    print(f"keystroke to diagnostics, page:        {summary(key_times)}   (goal < 100 ms)")
    print(f"  the language server's work alone:    {summary(reference_keys)}")
    print(f"Run to the first streamed pose, page:  {summary(run_times)}   (goal < 500 ms)")
    print(f"  `epuckc run --trace -` alone:        {summary(reference_runs)}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
