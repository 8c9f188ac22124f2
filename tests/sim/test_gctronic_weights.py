"""Issue 25's measure of arrays and 32-bit intermediates: GCtronic's
avoider (`shock_neuron` of runbreitenberg_adv.c, its weight matrix summed
in `long`), written in the language with two weight arrays and `dot`, drives
exactly as GCtronic's own C does when both run on the simulated e-puck in
the same world with the same seed: the C, byte for byte from the checkout
EPUCK_LIB names, called every 65 ms (its agenda's period) through an extern
action; the rule program every 65 ms too. Every pose of the two runs is the
same; a port that rounds differently (dividing each term first, as a
16-bit port had to) drives differently."""
from __future__ import annotations

import json

import pytest

from conftest import REPO, require_enki, require_epuck_library
from tests.support.programs import epuckc

PORT = """\
# GCtronic's shock_neuron as two weight arrays
const M0 = [8, 4, 2, 0, 0, -4, -8, -16]
const M1 = [-16, -8, -4, 0, 0, 2, 4, 8]
var s0 = 0
var s1 = 0
every 65 ms
    do s0 = {sum0},
        s1 = {sum1},
        if s0 < 50 and s0 > -50 and s1 < 50 and s1 > -50 {{ s0 = s0 * 20, s1 = s1 * 20 }},
        set_speed(left: clamp(s1, -1000, 1000) * 1 steps/s,
            right: clamp(s0, -1000, 1000) * 1 steps/s)
"""
EXACT = {"sum0": "dot(M0, ir) / 4 + 550", "sum1": "dot(M1, ir) / 4 + 550"}
# each term divided first: what keeping every value in 16 bits made students write
DIVIDED = {"sum0": " + ".join(f"M0[{k}] * (ir[{k}] / 4)" for k in range(8)) + " + 550",
           "sum1": " + ".join(f"M1[{k}] * (ir[{k}] / 4)" for k in range(8)) + " + 550"}


def _poses(trace) -> dict:
    """t_ms -> (x, y, heading) at each event of the run."""
    out = {}
    for line in trace.read_text().splitlines():
        r = json.loads(line)
        if r.get("kind") == "event" and "x_mm" in r:
            out[r["t_ms"]] = (r["x_mm"], r["y_mm"], r["heading_deg"])
    return out


def _run(tmp_path, name, program, world, seconds=40):
    trace = tmp_path / f"{name}.jsonl"
    result = epuckc("run", program, "--world", world, "--time-limit", f"{seconds}s",
                    "--trace", trace)
    assert result.returncode == 3, result.stdout[-2000:] + result.stderr[-2000:]
    return _poses(trace)


@pytest.mark.parametrize("seed", [1, 3])
def test_the_weight_arrays_drive_as_gctronic_s_shock_neuron(tmp_path, seed):
    library = require_epuck_library("program/DemoGCtronic-complete")
    require_enki()
    demo = library / "program" / "DemoGCtronic-complete" / "runbreitenberg_adv.c"
    world = tmp_path / "arena.world"
    world.write_text((REPO / "examples" / "braitenberg.world").read_text()
                     .replace("seed 1", f"seed {seed}"))
    (tmp_path / "glue.c").write_text(
        "/* GCtronic's avoider, its file as it is, called as an extern action */\n"
        '#include "gctronic_externs.h"\n'
        f'#include "{demo}"\n\n'
        "void shock(void *param)\n{\n    (void)param;\n    shock_neuron();\n}\n")
    gctronic = tmp_path / "gctronic.epk"
    gctronic.write_text('extern action shock() from "glue.c"\nevery 65 ms do shock\n')
    port = tmp_path / "port.epk"
    port.write_text(PORT.format(**EXACT))
    divided = tmp_path / "divided.epk"
    divided.write_text(PORT.format(**DIVIDED))
    theirs = _run(tmp_path, "gctronic", gctronic, world)
    ours = _run(tmp_path, "port", port, world)
    assert len(theirs) > 500
    # it meets obstacles and turns away from them: the comparison is not of
    # straight lines
    assert max(abs(h) for _, _, h in theirs.values()) > 45
    assert ours == theirs
    assert _run(tmp_path, "divided", divided, world) != theirs
