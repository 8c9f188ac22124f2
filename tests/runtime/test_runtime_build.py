"""Building: the Makefile (CC/CFLAGS honoured, concurrent-safe), the paper's
figure 2 built by hand, strict warnings, sanitizers, the 16-bit check, the
harness's settings and errors, determinism."""
import os
import re
import stat
import subprocess
import sys
from pathlib import Path

from epuckc.base.resources import (RUNTIME_CORE, RUNTIME_DEVICES, RUNTIME_DSPIC_DEVICES,
                                   RUNTIME_SIMULATED, RUNTIME_TRACE, RUNTIME_TRACE_CHIBIOS,
                                   RUNTIME_TRACE_UART1)
import pytest

from conftest import REPO, require_tool
from rt_helpers import (INCLUDES, PROGRAMS, RUNTIME, SOURCES, STRICT, build,  # noqa: F401
                        build_and_run, cc, registration, run)


def make(*args, env=None):
    require_tool("make")
    res = subprocess.run(["make", "-C", str(RUNTIME), *args], capture_output=True,
                         text=True, env=env)
    assert res.returncode == 0, res.stdout + res.stderr
    return res


def test_paper_figure_2_verbatim(tmp_path):
    """Figure 2 of the paper, copied verbatim, built the documented way."""
    make()      # runtime_c/build/libepuckrt.a
    exe = tmp_path / "fig2"
    res = subprocess.run([cc(), "-Iruntime_c", str(PROGRAMS.parent / "paper_fig2.c"),
                          "runtime_c/build/libepuckrt.a", "-o", str(exe)],
                         cwd=REPO, capture_output=True, text=True)
    assert res.returncode == 0, res.stderr
    r = run(exe, tmp_path)
    assert r.returncode == 0, r.stderr
    seq = [(x["kind"], x["name"]) for x in r.trace]
    assert seq == [("event", "immediate"), ("action", "start_straight"),
                   ("motors", "immediate"), ("motors", "free"),
                   ("event", "event_stop_motor"), ("action", "exit_main"),
                   ("exit", "exit_main")]
    # the motors are immediate's from its start_straight to the motion's end,
    # and the stop_motor event fires in the poll that ended it
    assert r.trace[2]["t_ms"] == r.trace[1]["t_ms"]
    assert 3000 <= r.trace[3]["t_ms"] == r.trace[4]["t_ms"] <= 3200
    assert abs(r.trace[-1]["x_mm"] - 100.0) < 0.5
    assert "event_stop_motor" in r.stdout and "exit at" in r.stdout


def test_paper_figure_2_is_clean_but_for_its_own_style(tmp_path):
    """The verbatim figure leaves e1/e2 unused: only that warning is
    disabled; `{250, 100}` fills the paper's struct exactly."""
    res = subprocess.run([cc(), *STRICT, "-Wno-unused-but-set-variable", *INCLUDES, "-c",
                          str(PROGRAMS.parent / "paper_fig2.c"), "-o",
                          str(tmp_path / "fig2.o")], capture_output=True, text=True)
    assert res.returncode == 0, res.stderr


def test_every_runtime_file_compiles_strictly(tmp_path):
    files = [*SOURCES, RUNTIME / "platform" / "platform_robot.c", *sorted(PROGRAMS.glob("*.c"))]
    for f in files:
        res = subprocess.run([cc(), *STRICT, *INCLUDES, "-c", str(f), "-o",
                              str(tmp_path / "x.o")], capture_output=True, text=True)
        assert res.returncode == 0, f"{f}:\n{res.stderr}"
    # every e-puck API header stands alone
    for h in sorted((RUNTIME / "epuck_api").rglob("*.h")):
        src = tmp_path / "h.c"
        src.write_text(f'#include "{h.relative_to(RUNTIME / "epuck_api")}"\nint x;\n')
        res = subprocess.run([cc(), *STRICT, *INCLUDES, "-c", str(src), "-o",
                              str(tmp_path / "h.o")], capture_output=True, text=True)
        assert res.returncode == 0, f"{h}:\n{res.stderr}"


SANITIZED = {
    "straight.c": {}, "curve.c": {"defines": ["RADIUS=30", "DEGREES=-200", "SPEED=-700"]},
    "wrap.c": {}, "sequence.c": {}, "sequence_abandon.c": {}, "ordering.c": {},
    "registry.c": {}, "capacity.c": {"defines": ["MAX_ACTIONS=3", "MAX_EVENTS=4"]},
    "sensor_edge.c": {}, "sensor_off.c": {}, "timer_periodic.c": {},
    "timer_reset.c": {"time_limit": 500}, "stop_action.c": {}, "stop_restart.c": {},
    "zero_motion.c": {}, "overflow.c": {}, "sequence_self.c": {}, "static_table.c": {},
    "priority.c": {}, "modes.c": {}, "devices.c": {}, "static_ranked.c": {},
    "mode_reentry.c": {}, "hold.c": {},
}


def test_sanitized_list_covers_all_programs():
    assert set(SANITIZED) == {p.name for p in PROGRAMS.glob("*.c")}


@pytest.mark.parametrize("name", sorted(SANITIZED))
@pytest.mark.usefixtures("registration")
def test_runs_clean_under_sanitizers(tmp_path, name):
    opts = SANITIZED[name]
    r = build_and_run(tmp_path, name, defines=opts.get("defines", ()),
                      time_limit=opts.get("time_limit"), sanitize=True,
                      env={"EPUCK_QUIET": "1"})
    assert r.returncode == (3 if "time_limit" in opts else 0), r.stderr
    assert "runtime error" not in r.stderr and "Sanitizer" not in r.stderr


@pytest.mark.usefixtures("registration")
def test_deterministic(tmp_path):
    exe = build(tmp_path, PROGRAMS / "sequence.c")
    a = run(exe, tmp_path)
    b = run(exe, tmp_path)
    assert a.trace_bytes == b.trace_bytes and a.stdout == b.stdout
    assert a.trace_bytes


def test_makefile_honours_cc_and_cflags(tmp_path):
    """CFLAGS with -DMAX_ACTIONS=2 must reach the core (a program sees the
    third registration fail), and CC must be the compiler used (a wrapper
    logs its calls).  Built into a temporary BUILD directory."""
    log = tmp_path / "cc.log"
    wrapper = tmp_path / "mycc"
    wrapper.write_text(f'#!/bin/sh\necho "$@" >> "{log}"\nexec {cc()} "$@"\n')
    wrapper.chmod(wrapper.stat().st_mode | stat.S_IEXEC)
    build_dir = tmp_path / "build"
    make(f"BUILD={build_dir}", f"CC={wrapper}", "CFLAGS=-std=c99 -O0 -DMAX_ACTIONS=2")
    calls = log.read_text()
    assert "-DMAX_ACTIONS=2" in calls and all(name in calls for name in RUNTIME_CORE)
    lib = build_dir / "libepuckrt.a"
    assert lib.exists()
    src = tmp_path / "p.c"
    src.write_text('#include <stdio.h>\n#include "epuckrt.h"\nint main(void){\n'
                   'int a = register_action(exit_main, NULL);\n'
                   'int b = register_action(exit_main, NULL);\n'
                   'int c = register_action(exit_main, NULL);\n'
                   'printf("%d %d %d\\n", a, b, c);\nreturn 0;}\n')
    exe = tmp_path / "p"
    res = subprocess.run([cc(), f"-I{RUNTIME}", str(src), str(lib), "-o", str(exe)],
                         capture_output=True, text=True)
    assert res.returncode == 0, res.stderr
    out = subprocess.run([str(exe)], capture_output=True, text=True).stdout
    assert out == "0 1 -1\n"
    # changing CFLAGS rebuilds; the same flags do not
    log.write_text("")
    make(f"BUILD={build_dir}", f"CC={wrapper}", "CFLAGS=-std=c99 -O0 -DMAX_ACTIONS=2")
    assert log.read_text() == ""
    make(f"BUILD={build_dir}", f"CC={wrapper}", "CFLAGS=-std=c99 -O0 -DMAX_ACTIONS=3")
    assert "-DMAX_ACTIONS=3" in log.read_text()


def test_makefile_concurrent_builds(tmp_path):
    require_tool("make")
    build_dir = tmp_path / "build"
    procs = [subprocess.Popen(["make", "-C", str(RUNTIME), f"BUILD={build_dir}"],
                              stdout=subprocess.PIPE, stderr=subprocess.STDOUT)
             for _ in range(3)]
    for p in procs:
        out, _ = p.communicate()
        assert p.returncode == 0, out.decode()
    assert (build_dir / "libepuckrt.a").exists()
    assert not list(build_dir.glob("*.tmp.*"))


def test_check16_with_avr_gcc():
    require_tool("avr-gcc")
    res = make("check16")
    assert "check16: OK" in res.stdout


def test_check16_really_is_16_bit(tmp_path):
    """check16.c must reject a 32-bit int target (so check16 cannot pass
    vacuously)."""
    res = subprocess.run([cc(), "-std=c99", "-c", str(RUNTIME / "check16.c"), "-o",
                          str(tmp_path / "c.o")], capture_output=True, text=True)
    assert res.returncode != 0 and "int_is_16_bits" in res.stderr


# ---- harness settings ------------------------------------------------------

def test_scenario_errors_name_file_and_line(tmp_path):
    exe = build(tmp_path, PROGRAMS / "straight.c")
    bad = tmp_path / "bad.scn"
    bad.write_text("# fine\n0 ms ir0=5\n100xs ir1=3\n")
    r = run(exe, tmp_path, scenario=bad)
    assert r.returncode == 2
    assert f"{bad}:3:" in r.stderr and "unit" in r.stderr
    for text, what in [("0 ms ir8=1\n", "irN=V"), ("0 ms ir0=5000\n", "irN=V"),
                       ("100 ms\n50 ms ir0=1\n", "before"), ("1.5 ms\n", "whole"),
                       ("abc\n", "expected a time")]:
        bad.write_text(text)
        r = run(exe, tmp_path, scenario=bad)
        assert r.returncode == 2 and what in r.stderr and f"{bad}:" in r.stderr, text
    r = run(exe, tmp_path, scenario=tmp_path / "missing.scn")
    assert r.returncode == 2 and "missing.scn" in r.stderr


def test_bad_time_limit(tmp_path):
    exe = build(tmp_path, PROGRAMS / "straight.c")
    for bad in ["abc", "-5", "0", "12ms"]:
        r = run(exe, tmp_path, time_limit=bad)
        assert r.returncode == 2 and "EPUCK_TIME_LIMIT_MS" in r.stderr, bad


@pytest.mark.usefixtures("registration")
def test_time_limit_timeout(tmp_path):
    exe = build(tmp_path, PROGRAMS / "straight.c")
    r = run(exe, tmp_path, time_limit=1000)
    assert r.returncode == 3
    assert r.trace[-1]["kind"] == "timeout" and r.trace[-1]["t_ms"] == 1000
    assert r.trace[-1]["left_steps"] == 249     # 250 steps/s for 999 ms
    assert "timeout at 1000 ms" in r.stdout


def test_default_time_limit_is_60s(tmp_path):
    exe = build(tmp_path, PROGRAMS / "straight.c", defines=["SPEED=1000", "DIST=0",
                                                             "STEPS=30000"])
    r = run(exe, tmp_path, env={"EPUCK_QUIET": "1"})
    assert r.returncode == 0 and r.stdout == ""
    exe = build(tmp_path, PROGRAMS / "straight.c", defines=["SPEED=1000", "DIST=0",
                                                             "STEPS=61000"])
    r = run(exe, tmp_path, env={"EPUCK_QUIET": "1"})
    assert r.returncode == 3 and r.trace[-1]["t_ms"] == 60000


@pytest.mark.usefixtures("registration")
def test_scenario_time_formats(tmp_path):
    exe = build(tmp_path, PROGRAMS / "sensor_edge.c")
    scn = "0 ir0=0\n100ms ir0=900\n0.2 s ir0=0\n0.3s ir0=900 IR7=1\n"
    r = run(exe, tmp_path, scenario=scn)
    assert r.returncode == 0, r.stderr
    assert r.times("event", "sensor") == [2, 100, 200, 300]   # read from the poll after start_sensor


def test_bench_robot_runs():
    """bench/robot_bench.py measures all three figures side by side with
    their references (10 rules only, to stay quick)."""
    for tool in ("valgrind", "avr-gcc", "avr-size", "simavr"):
        require_tool(tool)
    res = subprocess.run([sys.executable, str(REPO / "bench" / "robot_bench.py"), "--sizes", "10"],
                         capture_output=True, text=True)
    assert res.returncode == 0, res.stdout + res.stderr
    rows = [line.split() for line in res.stdout.splitlines() if line.startswith("    10 ")]
    assert len(rows) == 3, res.stdout
    instructions, reference = float(rows[0][1]), float(rows[0][2])
    assert 0 < reference < instructions
    assert int(rows[1][1]) > 0            # RAM bytes
    assert 0 < int(rows[2][1]) < 16000    # cycles per poll, 10 rules


def test_bench_of_the_language_runs_and_a_variable_is_two_bytes():
    """bench/robot_bench.py's `when` rules beside sensor rules and the
    reference chain, and the RAM of variables: a variable is an int, two
    bytes on a 16-bit target."""
    for tool in ("valgrind", "avr-gcc", "avr-size"):
        require_tool(tool)
    res = subprocess.run([sys.executable, str(REPO / "bench" / "robot_bench.py"), "--only",
                          "when,vars", "--sizes", "10,20"], capture_output=True, text=True)
    assert res.returncode == 0, res.stdout + res.stderr
    rows = [line.split() for line in res.stdout.splitlines() if line.startswith("    20 ")]
    assert len(rows) == 2, res.stdout
    sensor, when, levels, chain = map(float, rows[0][1:5])
    assert 0 < chain < sensor and when > 0 and levels > 0
    assert "marginal RAM per variable, 10 -> 20: 2.00 B" in res.stdout


# ---- scenario files as users write them ---------------------------------------

def _scenario_bytes(tmp_path, data: bytes):
    path = tmp_path / "s.scn"
    path.write_bytes(data)
    return path


@pytest.mark.parametrize("data", [
    b"\xef\xbb\xbf0 ir0=0\n100 ms ir0=900\n200 ms ir0=0\n300 ms ir0=900\n",   # a BOM
    b"0 ir0=0\r100 ms ir0=900\r200 ms ir0=0\r300 ms ir0=900\r",              # old Mac
    b"0 ir0=0\r\n100 ms ir0=900\r\n200 ms ir0=0\r\n300 ms ir0=900",           # Windows, no last end
    b"# caf\xc3\xa9\n0 ir0=0\n100 ms ir0=900\n0.2 s ir0=0\n0.005 min ir0=900\n",  # UTF-8, min
])
def test_scenario_line_ends_bom_and_minutes_are_accepted(tmp_path, data):
    exe = build(tmp_path, PROGRAMS / "sensor_edge.c")
    r = run(exe, tmp_path, scenario=_scenario_bytes(tmp_path, data))
    assert r.returncode == 0, r.stderr
    assert r.times("event", "sensor") == [2, 100, 200, 300]   # read from the poll after start_sensor


def test_scenario_in_minutes(tmp_path):
    exe = build(tmp_path, PROGRAMS / "straight.c")
    r = run(exe, tmp_path, scenario=_scenario_bytes(tmp_path, b"5 min ir0=1\n1.5min ir0=2\n"),
            time_limit=10)
    assert r.returncode == 2 and ":2: time 90000 ms is before the previous line's 300000 ms" \
        in r.stderr


@pytest.mark.parametrize("data, line, what", [
    (b"0 ir0=0\n100 ms \x00\x00ir0=1\n", 2, "a NUL byte: this is not a text file"),
    (b"\x7fELF\x02\x01\x01\x00\x00", 1, "this is not a text file"),
    (b"0 ir0=0\n\x1b[31m5 ms\n", 2, "control character 0x1b"),
    (b"5 h ir0=1\n", 1, "unknown time unit 'h' (use ms, s or min)"),
    (b"5h ir0=1\n", 1, "unknown time unit (use ms, s or min)"),
])
def test_scenario_binary_or_unknown_units_are_clear_errors(tmp_path, data, line, what):
    exe = build(tmp_path, PROGRAMS / "straight.c")
    path = _scenario_bytes(tmp_path, data)
    r = run(exe, tmp_path, scenario=path)
    assert r.returncode == 2
    assert f"{path}:{line}: " in r.stderr and what in r.stderr, r.stderr


def test_scenario_of_80000_lines_loads_under_asan(tmp_path):
    """80,000 lines load cleanly under ASan/UBSan, and the last one holds.
    (The array grows geometrically; bench/scenario_load.py measures the
    loading time against the one-line-at-a-time version: 243 s before.)"""
    exe = build(tmp_path, PROGRAMS / "sensor_edge.c", sanitize=True)
    lines = "".join(f"{t} ms ir0={900 if 100 <= t < 200 or t >= 300 else 0} ir7={t % 4096}\n"
                    for t in range(80000))
    r = run(exe, tmp_path, scenario=lines, env={"EPUCK_QUIET": "1"})
    assert r.returncode == 0, r.stderr
    assert r.times("event", "sensor") == [2, 100, 200, 300]   # read from the poll after start_sensor


def test_harness_names_the_options_typed_when_run_by_epuckc(tmp_path):
    exe = build(tmp_path, PROGRAMS / "straight.c")
    env = {"EPUCK_FRONTEND": "epuckc", "EPUCK_TRACE": str(tmp_path / "no" / "t.jsonl")}
    r = run(exe, tmp_path, env=env)
    assert r.returncode == 2 and r.stderr.startswith("epuck host: --trace: cannot write")
    r = run(exe, tmp_path, time_limit="x", env={"EPUCK_FRONTEND": "epuckc"})
    assert r.returncode == 2 and "--time-limit:" in r.stderr
    assert "EPUCK_" not in r.stderr


def test_the_makefile_builds_the_runtime_the_compiler_builds():
    """runtime_c/Makefile's CORE lists the runtime's sources as
    epuckc.base.resources.RUNTIME_CORE does (the one list every build and test
    takes), and every file of the runtime is in it."""
    makefile = (RUNTIME / "Makefile").read_text()
    lists = {name: [line.split("=", 1)[1].split() for line in makefile.splitlines()
                    if line.startswith(f"{name} =")] for name in ("CORE", "SIMULATED", "TRACE")}
    assert lists["CORE"] == [list(RUNTIME_CORE)]
    assert lists["SIMULATED"] == [list(RUNTIME_SIMULATED)]
    assert lists["TRACE"] == [list(RUNTIME_TRACE + RUNTIME_TRACE_UART1)]
    top_level = {p.name for p in RUNTIME.glob("*.c")} - {"check16.c"}
    assert top_level == (set(RUNTIME_CORE) | set(RUNTIME_DEVICES) | set(RUNTIME_DSPIC_DEVICES)
                         | set(RUNTIME_SIMULATED)
                         | set(RUNTIME_TRACE + RUNTIME_TRACE_UART1 + RUNTIME_TRACE_CHIBIOS)), \
        "a runtime source missing from RUNTIME_CORE, _DEVICES, _DSPIC_DEVICES, _SIMULATED or " \
        "_TRACE*"


def test_the_platform_layers_are_in_one_folder():
    """Every implementation of rt_platform.h (a file that defines
    rt_platform_idle) is in runtime_c/platform/, which holds nothing else,
    and the builds take them from there (issue 44, point 4)."""
    defining = {p.relative_to(RUNTIME).as_posix() for p in RUNTIME.rglob("*.c")
                if re.search(r"^void rt_platform_idle\(void\)\s*\{", p.read_text(), re.M)}
    assert defining == {p.relative_to(RUNTIME).as_posix()
                        for p in (RUNTIME / "platform").glob("*.c")}
    assert len(defining) == 4, defining     # the e-puck, the e-puck2, the host, the 16-bit build
    from epuckc.build.common import HOST_SOURCES, ROBOT_COPIES
    from epuckc.build.epuck2 import EPUCK2_SOURCES
    assert "platform/platform_host.c" in HOST_SOURCES
    assert ROBOT_COPIES["platform_robot.c"] == "platform/platform_robot.c"
    assert "platform/platform_epuck2.c" in EPUCK2_SOURCES
