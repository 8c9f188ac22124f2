#!/usr/bin/env python3
"""Where a language server's edit goes, step by step: the CPU time of
each step of the analysis (the split, each whole-program check, the
replay of the rules, the diagnostics in real lines) and of the server's
conversion, per edit, on lsp_bench.py's expression program.

    python3 bench/lsp_phases.py [--rules 1000] [--edits 40] [--kind error|number|interval]

The steps are timed by wrapping them (CPU time of the thread), which adds
about a microsecond a call: `_rule` is called once a rule, so its figure
is high by that much. Figures in docs/performance.md (issue 31).
"""
from __future__ import annotations

import argparse
import collections
import random
import sys
import time
from pathlib import Path

REPO = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(REPO))
sys.path.insert(0, str(REPO / "bench"))

import lsp_bench as lb  # noqa: E402

from epuckc.check import checker as checker_module  # noqa: E402
from epuckc.ide import documents, incremental, recheck  # noqa: E402
from epuckc.ide.lsp import Document, EpuckServer  # noqa: E402

STEPS = ("_declarations", "_declare", "_robot", "_var_ranges", "_resolve_actions", "_rules",
         "_rule", "_never_fire", "_unused", "_no_warnings_beside_errors", "_modes_program")


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--rules", type=int, default=1000)
    ap.add_argument("--edits", type=int, default=40)
    ap.add_argument("--kind", choices=["error", "number", "interval"], default="error")
    args = ap.parse_args(argv)
    spent = collections.Counter()

    def timed(owner, name, label):
        real = getattr(owner, name)

        def step(*a, **k):
            t0 = time.thread_time()
            try:
                return real(*a, **k)
            finally:
                spent[label] += time.thread_time() - t0
        setattr(owner, name, step)

    for name in STEPS:
        timed(recheck.IncrementalChecker, name, name)
    timed(checker_module.races, "check_program", "races (W009)")
    timed(incremental.Analyzer, "_chunks", "split and parse (_chunks)")
    timed(incremental.Pieces, "place", "pieces placed (pieces.py)")
    timed(incremental.Analyzer, "_finish", "real lines (_finish)")
    timed(documents.Conversions, "all", "the server's LSP forms (documents.py)")
    timed(incremental.Analyzer, "_analyse", "= analysis")
    timed(recheck.IncrementalChecker, "check", "= check")
    text = lb.expression_program(args.rules)
    server = EpuckServer()
    doc = Document("file:///bench/bench.epk", text, 1, server)
    analysis = doc.analyse()        # opened and published
    lb.published(server, doc, analysis)
    edits = {"error": lb.error_edits, "number": lb.edits,
             "interval": lb.interval_edits}[args.kind](text, random.Random(1), args.edits)
    spent.clear()
    total = sum(lb.server_edit(server, doc, *e) for e in edits)
    n = len(edits)
    print(f"{args.rules} rules, {n} edits ({args.kind}): {total / n * 1000:.2f} ms an edit "
          f"(CPU), of which:")
    for label, seconds in spent.most_common():
        print(f"  {label:32s} {seconds / n * 1000:7.2f} ms")
    return 0


if __name__ == "__main__":
    sys.exit(main())
