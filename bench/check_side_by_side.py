#!/usr/bin/env python3
"""CPU time of one in-process check (parse + check, what `epuckc check` does
after start-up) of generated programs, for this checkout and a reference
checkout side by side in the same run, alternating, so that the machine's
load falls on both alike.

    python3 bench/check_side_by_side.py --reference DIR [--rules 1000] [--runs 7]

DIR is another checkout of epuckc (e.g. `git worktree add /tmp/ref COMMIT`).
The programs: check_bench.py's mixed program, a program of sensor rules
that all command the motors at one priority (W009's worst case), and
lsp_bench.py's program of variables and expressions. Figures go in
docs/performance.md."""
from __future__ import annotations

import argparse
import json
import statistics
import subprocess
import sys
import tempfile
from pathlib import Path

REPO = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(REPO / "bench"))

from check_bench import generate  # noqa: E402
from lsp_bench import expression_program  # noqa: E402

MEASURE = """
import json, sys, time
from pathlib import Path
from epuckc.check.frontend import check_file
from epuckc.diagnostics import Report
text = Path(sys.argv[1]).read_text()
check_file(Path("b.epk"), Report(), text=text)          # warm
times = []
for _ in range(int(sys.argv[2])):
    t = time.thread_time()
    check_file(Path("b.epk"), Report(), text=text)
    times.append(time.thread_time() - t)
print(json.dumps(times))
"""


def sensor_program(rules: int) -> str:
    lines = ["on immediate do start_sensor"]
    for i in range(rules):
        lines.append(f"on sensor(ir{i % 8} > {100 + i}) repeat do start_curve(0 mm, 90 deg, 300)")
    return "\n".join(lines) + "\n"


def measure(tree: Path, program: Path, runs: int) -> list:
    out = subprocess.run([sys.executable, "-c", MEASURE, str(program), str(runs)], cwd=tree,
                         capture_output=True, text=True, check=True)
    return json.loads(out.stdout)


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--reference", required=True, type=Path)
    ap.add_argument("--rules", type=int, default=1000)
    ap.add_argument("--runs", type=int, default=7)
    args = ap.parse_args()
    folder = Path(tempfile.mkdtemp(prefix="epuckc-side-"))
    programs = {"mixed": generate(args.rules), "sensor rules, one priority":
                sensor_program(args.rules), "variables and expressions":
                expression_program(args.rules)}
    print(f"{args.rules} rules, CPU ms of one check, median of {args.runs} "
          f"(reference {args.reference})")
    print(f"{'program':<28} {'this':>8} {'reference':>10} {'ratio':>7}")
    for name, text in programs.items():
        path = folder / f"{name.split()[0]}.epk"
        path.write_text(text, encoding="utf-8")
        this, ref = [], []
        for _ in range(2):          # alternate, so that load falls on both
            this += measure(REPO, path, args.runs)
            ref += measure(args.reference, path, args.runs)
        a, b = statistics.median(this) * 1000, statistics.median(ref) * 1000
        print(f"{name:<28} {a:>8.1f} {b:>10.1f} {a / b:>6.2f}x")
    return 0


if __name__ == "__main__":
    sys.exit(main())
