#!/usr/bin/env python3
"""How fast `epuckc lsp` has new diagnostics after an edit, side by side with
a full check of the same text in the same process.

    python3 bench/lsp_bench.py [--rules 1000] [--edits 40]

The file is bench/check_bench.py's generated program. Each edit changes one
rule the way typing does (a misspelt action, a changed number, a new line
inside the rule, the change undone), then the server's work for a
`didChange` is timed: splice the change into the text, analyse it
(epuckc/ide/incremental.py) and turn the diagnostics into LSP objects. The
reference is `frontend.check_file` on the same text (parse and check
everything; what `epuckc check` does after start-up). Edits to a
declaration (a constant), after which every rule is checked again, are
timed too. Times are CPU time of this thread (`time.thread_time`), so
other processes on the machine do not count; figures go in
docs/performance.md.
"""
from __future__ import annotations

import argparse
import os
import platform
import random
import statistics
import sys
import time
from pathlib import Path

REPO = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(REPO))
sys.path.insert(0, str(REPO / "bench"))

from check_bench import generate  # noqa: E402

from epuckc.diagnostics import Report  # noqa: E402
from epuckc.check.frontend import check_file  # noqa: E402
from epuckc.ide.lsp import Document, EpuckServer, Lines  # noqa: E402
from lsprotocol import types as lsp  # noqa: E402


def full_check(text: str) -> float:
    start = time.thread_time()
    check_file(Path("bench.epk"), Report(), text=text)
    return time.thread_time() - start


def server_edit(server, doc, start: int, end: int, new: str) -> float:
    """What the server does for one didChange (apply the change) and, once
    the debounce expires, to publish its diagnostics."""
    lines = Lines(doc.text, server.encoding)      # the client's view
    change = lsp.TextDocumentContentChangePartial(
        range=lsp.Range(lines.position(start), lines.position(end)), text=new)
    t0 = time.thread_time()
    doc.apply(change, server.encoding)
    analysis = doc.analyse()
    [server.diagnostic(doc, analysis, d) for d in analysis.diagnostics]
    return time.thread_time() - t0


def edits(text: str, rng: random.Random, count: int):
    """(start, end, new text) of one-rule edits, each undone by the next."""
    lines = text.split("\n")
    offsets = [0]
    for line in lines:
        offsets.append(offsets[-1] + len(line) + 1)
    rules = [i for i, line in enumerate(lines) if line.startswith(("on ", "rule "))]
    out = []
    while len(out) < count:
        i = rng.choice(rules)
        line = lines[i]
        for old, new in (("stop_motor", "stop_motr"), ("300", "310"), ("do ", "do\n  ")):
            at = line.find(old)
            if at >= 0:
                start = offsets[i] + at
                out.append((start, start + len(old), new))
                out.append((start, start + len(new), old))      # and back
                break
    return out[:count]


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--rules", type=int, default=1000)
    ap.add_argument("--edits", type=int, default=40)
    args = ap.parse_args(argv)
    text = generate(args.rules)
    server = EpuckServer()
    doc = Document("file:///bench/bench.epk", text, 1, server)
    doc.analyse()                   # opening the file: everything is parsed once
    rng = random.Random(1)
    rule_times = [server_edit(server, doc, *e) for e in edits(text, rng, args.edits)]
    full_times = [full_check(doc.text) for _ in range(max(5, args.edits // 4))]
    const_at = doc.text.index("const dist_")
    const_at = doc.text.index("cm", const_at)
    const_times = []
    for i in range(6):
        new, old = ("mm", "cm") if i % 2 == 0 else ("cm", "mm")
        const_times.append(server_edit(server, doc, const_at, const_at + 2, new))
    ms = lambda xs: f"median {statistics.median(xs) * 1000:6.1f} ms, max {max(xs) * 1000:6.1f} ms"
    print(f"python {platform.python_version()} on {platform.machine()}, {os.cpu_count()} cpus; "
          f"{args.rules} rules, {text.count(chr(10))} lines, {len(text)} bytes (CPU time)")
    print(f"full check (parse + check)      : {ms(full_times)}  ({len(full_times)} runs)")
    print(f"server, one-rule edit           : {ms(rule_times)}  ({len(rule_times)} edits)")
    print(f"server, edit to a constant      : {ms(const_times)}  ({len(const_times)} edits)")
    print(f"one-rule edit / full check      : "
          f"{statistics.median(rule_times) / statistics.median(full_times) * 100:.1f} %")
    return 0


if __name__ == "__main__":
    sys.exit(main())
