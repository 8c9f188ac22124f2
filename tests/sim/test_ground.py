"""The readings of GCtronic's ground-sensor module (issue 46): `ground0`..
`ground2` and `ground[i]` on the stub harness from a scenario's `groundN=V`
lines (white paper until then), the same on the 16-bit path, the device
every target has (the e-puck's project carries the module's API over the
library's I2C bus), and what the checker tells the world runner."""
import json
from pathlib import Path

import pytest

from conftest import require_tool
from epuckc.check.frontend import check_file
from epuckc.diagnostics import Report
from tests.support.programs import epuckc

PROGRAM = """\
var left = 0
var centre = 0
var right = 0
var i = 0
every 10 ms do i = (i + 1) % 3, left = ground0, centre = ground[1], right = ground[i]
rule dark: when ground1 < 300 do led_on(body)
after 500 ms do exit_main
"""
SCENARIO = "0 ms ground0=900\n100 ms ground1=120 ground2=40\n300 ms ground1=1000\n"


def _values(records):
    return [(r["t_ms"], r["var"], r["value"]) for r in records if r["kind"] == "set"]


def _run(tmp_path, *extra):
    trace = tmp_path / "g.jsonl"
    result = epuckc("run", tmp_path / "g.epk", "--scenario", tmp_path / "g.scn",
                    "--trace", trace, *extra)
    assert result.returncode == 0, result.stdout + result.stderr
    return [json.loads(line) for line in trace.read_text().splitlines()]


@pytest.fixture
def program(tmp_path):
    (tmp_path / "g.epk").write_text(PROGRAM)
    (tmp_path / "g.scn").write_text(SCENARIO)
    return tmp_path


def test_a_scenario_sets_the_ground_readings(program):
    records = _run(program)
    sets = _values(records)
    at = {}
    for t, var, value in sets:
        at.setdefault(var, []).append((t, value))
    assert at["left"] == [(11, 900)]
    # white paper under all three until the scenario says otherwise
    assert at["centre"] == [(11, 1000), (101, 120), (301, 1000)]
    # ground[i] with i computed: 1, 2, 0, 1, ... each poll of the rule
    assert {value for t, value in at["right"] if 100 < t < 300} == {900, 120, 40}
    [dark] = [r for r in records if r["kind"] == "event" and "rule dark" in r["name"]]
    assert dark["t_ms"] == 100
    inputs = [(r["name"], r["value"]) for r in records if r["kind"] == "input"]
    assert inputs[:3] == [("ground0", 900), ("ground1", 120), ("ground2", 40)]


def test_the_16_bit_path_reads_them_as_the_host_does(program):
    require_tool("avr-gcc")
    require_tool("simavr")
    if not Path("/usr/include/simavr/sim_avr.h").exists():
        require_tool("libsimavr-dev (the simavr headers)")
    assert _values(_run(program, "--int16")) == _values(_run(program))


def test_every_target_has_the_module_and_the_world_knows_who_reads_it(tmp_path):
    path = tmp_path / "g.epk"
    path.write_text(PROGRAM)
    for target in ("host", "dspic", "epuck2"):
        report = Report()
        result = check_file(path, report, target=target)
        assert report.error_count == 0, (target, report)
        assert "ground" in result.checked.devices
    # an element of the array alone (a computed index) is a reading of the module too
    only = tmp_path / "only.epk"
    only.write_text("var i = 0\nvar v = 0\nevery 10 ms do i = (i + 1) % 3, v = ground[i]\n")
    assert "ground" in check_file(only, Report()).checked.devices
    plain = tmp_path / "plain.epk"
    plain.write_text("every 10 ms do led_toggle(body)\n")
    assert "ground" not in check_file(plain, Report()).checked.devices


def test_the_e_pucks_project_carries_the_modules_api(tmp_path):
    (tmp_path / "g.epk").write_text(PROGRAM)
    out = tmp_path / "proj"
    result = epuckc("build", "--target", "dspic", tmp_path / "g.epk", "-o", out,
                    env={"XC16_DIR": str(tmp_path / "none"), "PATH": "/usr/bin:/bin"})
    assert result.returncode == 3, result.stderr            # written, XC16 missing
    header = (out / "runtime" / "sensors" / "ground.h").read_text()
    assert "int get_ground_prox(unsigned int sensor_number);" in header
    makefile = (out / "Makefile").read_text()
    assert "runtime/rt_ground.c" in makefile and "runtime/ground_i2c.c" in makefile
    assert "$(LIB)/I2C/e_I2C_master_module.c" in makefile
