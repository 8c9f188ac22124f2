#!/usr/bin/env python3
"""Long `else if` chains (issue 42, point 2): the CPU time of `check`,
`compile` (check + lowering + the C) and a language-server edit (the
analysis of the document after one branch's condition changed, the one
before analysed), for one rule of 100 to 10,000 branches, side by side in
one run, and each per branch: linear when the per-branch figure stays
flat. The chain is tests/check/test_chain_linear.py's (a variable the
branches assign and a reading in each condition), which counts the work
instead of timing it.

    python3 bench/chain_bench.py [--sizes 100,1000,3000,10000]

Recorded figures: docs/performance.md, "Issue 42: long else-if chains"."""
from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

REPO = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(REPO))

from epuckc.check.frontend import check_file  # noqa: E402
from epuckc.diagnostics import Report  # noqa: E402
from epuckc.emit.program import emit_program  # noqa: E402
from epuckc.ide.incremental import Analyzer  # noqa: E402
from tests.check.test_chain_linear import chain  # noqa: E402


def cpu(f) -> float:
    start = time.process_time()
    f()
    return time.process_time() - start


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--sizes", default="100,1000,3000,10000")
    args = parser.parse_args()
    print(f"{'branches':>9} {'check s':>8} {'compile s':>9} {'edit s':>7}"
          f" {'check ms/br':>11} {'compile ms/br':>13} {'edit ms/br':>10}")
    for n in map(int, args.sizes.split(",")):
        text = chain(n)

        def check():
            return check_file(Path("c.epk"), Report(), shown_name="c.epk", text=text)
        checking = cpu(check)
        compiling = cpu(lambda: emit_program(check().checked, text, "c"))
        analyzer = Analyzer("c.epk")
        analyzer.analyse(text)
        editing = cpu(lambda: analyzer.analyse(chain(n, 1)))
        print(f"{n:>9} {checking:>8.2f} {compiling:>9.2f} {editing:>7.2f} "
              f"{1000 * checking / n:>11.3f} {1000 * compiling / n:>13.3f} "
              f"{1000 * editing / n:>10.3f}", flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
