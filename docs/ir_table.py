#!/usr/bin/env python3
"""Prints docs/world.md's table of what the IR sensors read against the
gap between the robot's body and a box's face, measured in an Enki world by the
runtime itself: one robot per gap, each facing its own box (the wall
ahead: `ir0`, front right; `ir7` reads the same) and with another box
beside it (the wall on its right: `ir2`), far from the others. The same
model, seed and rounding as every world run, so a wall follower's
thresholds can be read off it; tests/sim/test_ir_table.py fails when the
committed table differs from what this prints.

    python3 docs/ir_table.py          # the table, in Markdown

Needs Enki (libenki-dev) and a C++ compiler, as `epuckc run --world` does.
"""
import json
import os
import subprocess
import sys
import tempfile
from pathlib import Path

REPO = Path(__file__).resolve().parent.parent
GAPS_MM = (2, 5, 10, 15, 20, 30, 40, 50, 60, 70, 80, 100)
RADIUS_MM = 37                  # Enki's e-puck
SPACING_MM = 400                # between the robots: none sees another
SAMPLES = 8                     # readings averaged (Enki's sensor noise: a few units); 8 x 4095 fits
PROGRAM = f"""var n = 0
var ahead = 0
var beside = 0
every 10 ms if n < {SAMPLES} do ahead += ir0, beside += ir2, n += 1
after {10 * SAMPLES + 50} ms do exit_main
"""


def world_text() -> str:
    """Two robots per gap, 40 cm from any other, heading +x: `a` with a
    box ahead (its face `gap` from the body), `s` with a box on its right
    (its face `gap` below the body), each box 10 cm long."""
    lines = ["arena none", "noise 0 %"]
    for k, gap in enumerate(GAPS_MM):
        x = 2 * SPACING_MM * k
        lines.append(f"robot a{gap} at {x} mm, 0 mm heading 0 deg")
        lines.append(f"box at {x + RADIUS_MM + gap + 10} mm, 0 mm size 20 mm x 100 mm")
        x += SPACING_MM
        lines.append(f"robot s{gap} at {x} mm, 0 mm heading 0 deg")
        lines.append(f"box at {x} mm, {-(RADIUS_MM + gap + 10)} mm size 100 mm x 20 mm")
    return "\n".join(lines) + "\n"


def measure() -> dict:
    """gap mm -> (ir0, ir2): the mean of SAMPLES readings of the program's."""
    env = dict(os.environ, PYTHONPATH=str(REPO) + os.pathsep + os.environ.get("PYTHONPATH", ""),
               EPUCK_QUIET="1")
    with tempfile.TemporaryDirectory() as tmp:
        folder = Path(tmp)
        (folder / "read.epk").write_text(PROGRAM)
        (folder / "gaps.world").write_text(world_text())
        result = subprocess.run([sys.executable, "-m", "epuckc", "run", "read.epk", "--world",
                                 "gaps.world", "--trace", "t.jsonl"], cwd=folder, env=env,
                                capture_output=True, text=True)
        if result.returncode != 0:
            raise SystemExit(f"epuckc run failed:\n{result.stderr}")
        values: dict = {}
        for line in (folder / "t.jsonl").read_text().splitlines():
            rec = json.loads(line)
            if rec["kind"] == "set":
                values.setdefault(rec["robot"], {})[rec["var"]] = rec["value"]
    return {gap: (round(values.get(f"a{gap}", {}).get("ahead", 0) / SAMPLES),
                  round(values.get(f"s{gap}", {}).get("beside", 0) / SAMPLES)) for gap in GAPS_MM}


def table(measured: dict) -> str:
    rows = ["| gap to the face | wall ahead: `ir0` (and `ir7`) | wall on the right: `ir2` "
            "(on the left: `ir5`) |", "|---|---|---|"]
    rows += [f"| {gap} mm | {ahead} | {beside} |" for gap, (ahead, beside) in measured.items()]
    return "\n".join(rows) + "\n"


if __name__ == "__main__":
    sys.stdout.write(table(measure()))
