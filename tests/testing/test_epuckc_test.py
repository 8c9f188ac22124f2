"""`epuckc test` through the command line (epuckc/testing/): bless, pass,
a change that fails with its diff and divergence point, a missing expected
file, a program with errors and its diagnostics golden, the C golden,
usage errors, the order of parallel cases."""
from __future__ import annotations

import re

from tests.support.programs import epuckc

PROGRAM = """const CRUISE = 300 steps/s
on immediate do start_sensor, start_straight(CRUISE, 50 cm)
rule avoid: on sensor(ir0 > 500, ir7 > 500) repeat priority 1
    do start_curve(radius: 0 mm, degrees: 90 deg, speed: CRUISE)
rule cruise: on stop_motor repeat do start_straight(CRUISE, 50 cm)
on timer(4 s) priority 2 do stop_motor, exit_main
""".replace("on immediate do start_sensor,", "on immediate do start_sensor, set_timer,")
SCENARIO = "0 ms ir0=0 ir7=0\n1200 ms ir0=900 ir7=900\n1300 ms ir0=0 ir7=0\n"


def make_case(folder, name="avoid", program=PROGRAM, scenario=SCENARIO, toml=None):
    folder.mkdir(parents=True, exist_ok=True)
    (folder / f"{name}.epk").write_text(program)
    if scenario is not None:
        (folder / f"{name}.scn").write_text(scenario)
    if toml is not None:
        (folder / f"{name}.toml").write_text(toml)
    return folder / f"{name}.epk"


def test_missing_expected_file_fails_and_says_how_to_bless(tmp_path):
    make_case(tmp_path / "cases")
    r = epuckc("test", tmp_path / "cases")
    assert r.returncode == 1, r.stdout + r.stderr
    assert "FAIL" in r.stdout and "avoid.trace is missing" in r.stdout
    assert "`epuckc test --bless` writes it" in r.stdout
    assert r.stdout.rstrip().endswith("0 passed, 1 failed")
    assert not (tmp_path / "cases" / "avoid.trace").exists()


def test_bless_writes_the_run_then_the_case_passes(tmp_path):
    make_case(tmp_path / "cases")
    r = epuckc("test", "--bless", "cases", cwd=tmp_path)
    assert r.returncode == 0, r.stdout + r.stderr
    assert "blessed cases/avoid.epk: avoid.trace (new)" in r.stdout
    trace = (tmp_path / "cases" / "avoid.trace").read_text()
    # the golden is what `epuckc run` prints, byte for byte
    run = epuckc("run", "avoid.epk", "--scenario", "avoid.scn", "--seed", "1",
                 cwd=tmp_path / "cases")
    assert trace == run.stdout
    assert "rule avoid:" in trace and trace.count("\n") > 4
    r = epuckc("test", "cases", cwd=tmp_path)
    assert (r.returncode, r.stdout) == (0, "1 passed, 0 failed\n"), r.stderr
    # blessing again changes nothing and says so
    r = epuckc("test", "--bless", "cases", cwd=tmp_path)
    assert r.stdout == "1 passed, 0 failed\n"


def test_a_change_fails_with_a_trimmed_diff_and_the_divergence_point(tmp_path):
    path = make_case(tmp_path)
    assert epuckc("test", "--bless", tmp_path).returncode == 0
    expected = (tmp_path / "avoid.trace").read_text()
    # the obstacle now comes later: `avoid` fires at 2,000 ms instead of 1,200
    (tmp_path / "avoid.scn").write_text(SCENARIO.replace("1200 ms", "2000 ms")
                                        .replace("1300 ms", "2100 ms"))
    r = epuckc("test", path)
    assert r.returncode == 1
    out = r.stdout
    assert "the readable trace differs from avoid.trace" in out
    m = re.search(r"the expected trace has at ([\d,]+) ms: rule `avoid` fired; this one at "
                  r"([\d,]+) ms: (.*?) \(first difference from ([\d,]+) ms\)", out)
    assert m, out
    assert m.group(1) == "1,200" and m.group(4) == "1,200"
    assert "--- avoid.trace (expected)" in out and "+++ avoid.epk (this run)" in out
    minus = [line for line in out.splitlines() if line.startswith("  -[")]
    assert minus and all(line[3:] in expected for line in minus)
    # trimmed: the unchanged first event is context, not repeated in full
    assert out.count("on immediate") <= 1
    assert (tmp_path / "avoid.trace").read_text() == expected     # never rewritten without --bless


def test_same_time_divergence_names_both_rules(tmp_path):
    program = PROGRAM.replace("rule avoid: on sensor(ir0 > 500, ir7 > 500)",
                              "rule avoid: on sensor(ir0 > 500)")
    make_case(tmp_path, program=program)
    assert epuckc("test", "--bless", tmp_path).returncode == 0
    (tmp_path / "avoid.epk").write_text(program.replace("rule avoid:", "rule dodge:"))
    r = epuckc("test", tmp_path)
    assert r.returncode == 1
    assert "at 1,200 ms rule `avoid` fired in the expected trace, rule `dodge` fired in this one" \
        in r.stdout, r.stdout


def test_a_program_with_errors_has_a_diagnostics_golden(tmp_path):
    cases = tmp_path / "cases"
    make_case(cases, name="bad", program="on immediate do strat_straight(300, 2 m)\n",
              scenario=None)
    r = epuckc("test", cases)
    assert r.returncode == 1 and "bad.diag is missing" in r.stdout
    r = epuckc("test", "--bless", cases)
    assert r.returncode == 0 and "bad.diag (new)" in r.stdout
    diag = (cases / "bad.diag").read_text()
    # the human form without colour, the file named relative to its folder
    check = epuckc("check", "bad.epk", cwd=cases)
    assert diag == check.stderr
    assert diag.startswith("bad.epk:1:17: error[E011]") and "\x1b[" not in diag
    assert not (cases / "bad.trace").exists()
    assert epuckc("test", cases).returncode == 0
    # another error: the diagnostics differ, shown as a diff
    (cases / "bad.epk").write_text("on immediate do start_straight(300, 2 m), strat_x\n")
    r = epuckc("test", cases)
    assert r.returncode == 1 and "the diagnostics differs from bad.diag" in r.stdout
    assert "+bad.epk:1:43: error" in r.stdout.replace("  +", "+")


def test_a_trace_beside_a_program_with_errors_fails(tmp_path):
    make_case(tmp_path)
    assert epuckc("test", "--bless", tmp_path).returncode == 0
    (tmp_path / "avoid.epk").write_text("on immediate do nothing_here\n")
    r = epuckc("test", tmp_path)
    assert r.returncode == 1
    assert "avoid.trace is there but the program has errors" in r.stdout
    assert "avoid.diag is missing" in r.stdout
    r = epuckc("test", "--bless", tmp_path)
    assert "avoid.trace (removed)" in r.stdout and "avoid.diag (new)" in r.stdout
    assert not (tmp_path / "avoid.trace").exists()


def test_the_c_golden_is_opt_in(tmp_path):
    make_case(tmp_path, toml="c = true\n")
    r = epuckc("test", "--bless", tmp_path)
    assert "avoid.c (new)" in r.stdout, r.stdout + r.stderr
    compiled = epuckc("compile", "avoid.epk", "-o", "-", cwd=tmp_path).stdout
    assert (tmp_path / "avoid.c").read_text() == compiled
    other = tmp_path / "other"
    make_case(other)
    r = epuckc("test", "--bless", other)
    assert not (other / "avoid.c").exists()


def test_usage_errors_exit_2_with_file_line_col(tmp_path):
    r = epuckc("test", tmp_path / "nowhere")
    assert r.returncode == 2 and "no such file or folder" in r.stderr
    make_case(tmp_path, toml='seed = 3\ntime_limit = "5s\n')
    r = epuckc("test", tmp_path, cwd=tmp_path)
    assert r.returncode == 2
    assert re.search(r"avoid\.toml:2:\d+: error: not valid TOML", r.stderr), r.stderr
    (tmp_path / "avoid.toml").write_text('seed = 3\n\ntimelimit = "5s"\n')
    r = epuckc("test", tmp_path, cwd=tmp_path)
    assert r.returncode == 2 and "avoid.toml:3:1: error: unknown option `timelimit`" in r.stderr
    (tmp_path / "avoid.toml").write_text('time_limit = "5"\n')
    r = epuckc("test", tmp_path, cwd=tmp_path)
    assert r.returncode == 2 and "avoid.toml:1:1: error: `time_limit` must be" in r.stderr
    (tmp_path / "avoid.toml").write_text('expect = ["exit within 5 s", "x > 3 deg at exit"]\n')
    r = epuckc("test", tmp_path, cwd=tmp_path)
    assert r.returncode == 2
    assert "avoid.toml:1:30: error: `x > 3 deg at exit`: `x` is measured in mm or cm or m" \
        in r.stderr, r.stderr
    (tmp_path / "avoid.toml").write_text('scenario = "gone.scn"\n')
    r = epuckc("test", tmp_path, cwd=tmp_path)
    assert r.returncode == 2 and "the scenario file gone.scn does not exist" in r.stderr
    (tmp_path / "avoid.toml").unlink()
    (tmp_path / "notes.txt").write_text("x")
    r = epuckc("test", tmp_path / "notes.txt")
    assert r.returncode == 2 and "not a rule file" in r.stderr


def test_cases_run_in_parallel_and_report_in_a_stable_order(tmp_path):
    names = ["b_case", "a_case", "d_case", "c_case"]
    for i, name in enumerate(names):
        make_case(tmp_path / ("sub" if i % 2 else ""), name=name)
    first = epuckc("test", "-j", "4", tmp_path)
    assert first.returncode == 1
    fails = re.findall(r"^FAIL (\S+)", first.stdout, re.M)
    # sorted by path: the folder's own files, then its subfolders'
    assert [f.split(str(tmp_path) + "/")[-1] for f in fails] == [
        "b_case.epk", "d_case.epk", "sub/a_case.epk", "sub/c_case.epk"]
    one = epuckc("test", "-j", "1", tmp_path)
    assert one.stdout == first.stdout
    assert first.stdout.rstrip().endswith("0 passed, 4 failed")


def test_constants_of_a_case_are_the_runs_and_the_checkers(tmp_path):
    """`[constants]` in NAME.toml gives the program's constants as
    `epuckc run -D` does: the run drives at the new speed, a value of the
    wrong unit is the checker's error in the diagnostics golden, and a name
    the program lacks fails the case with what to fix."""
    make_case(tmp_path / "fast", toml='[constants]\nCRUISE = "600 steps/s"\n')
    r = epuckc("test", "--bless", "fast", cwd=tmp_path)
    assert r.returncode == 0, r.stdout + r.stderr
    trace = (tmp_path / "fast" / "avoid.trace").read_text()
    run = epuckc("run", "avoid.epk", "--scenario", "avoid.scn", "--seed", "1",
                 "-D", "CRUISE=600steps/s", cwd=tmp_path / "fast")
    assert trace == run.stdout
    default = epuckc("run", "avoid.epk", "--scenario", "avoid.scn", "--seed", "1",
                     cwd=tmp_path / "fast")
    assert trace != default.stdout          # the constant took effect
    make_case(tmp_path / "unit", toml='[constants]\nCRUISE = "20 cm"\n')
    r = epuckc("test", "--bless", "unit", cwd=tmp_path)
    diag = (tmp_path / "unit" / "avoid.diag").read_text()
    assert "error[E" in diag and "20 cm" in diag, diag
    make_case(tmp_path / "none", toml='[constants]\nSPEED = 3\n')
    r = epuckc("test", "none", cwd=tmp_path)
    assert r.returncode == 2 and "avoid.toml:2:1: error: avoid.epk has no constant SPEED" \
        in r.stdout + r.stderr, r.stdout + r.stderr
    make_case(tmp_path / "target", toml='target = "epuck2"\n')
    r = epuckc("test", "target", cwd=tmp_path)
    assert r.returncode == 2 and "avoid.toml:1:" in r.stderr + r.stdout
