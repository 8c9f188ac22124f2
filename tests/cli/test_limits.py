"""Inputs at the limits: every one gets a clear diagnostic or usage error
and a non-zero exit, never exit 4 ("internal error") or a traceback. The
property tests at the end keep the class closed: any value of a command-line
number or a robot setting is answered without an internal error."""
from __future__ import annotations

import json
import os
from pathlib import Path

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from epuckc import cli

from tests.support.cli import run_cli

INTERNAL = cli.EXIT_INTERNAL


@pytest.fixture
def work(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    monkeypatch.setenv("EPUCKC_CACHE_DIR", str(tmp_path / "cache"))
    (tmp_path / "ok.epk").write_text("on immediate do start_straight(300, 10 cm)\n"
                                     "on stop_motor do exit_main\n")
    return tmp_path


def _assert_clean(status, out, err):
    assert status != INTERNAL, err
    assert "internal error" not in err and "Traceback" not in err


# ---- chains: resolved without recursion ---------------------------------------------

@pytest.mark.parametrize("n", [493, 495, 5000])
def test_a_long_chain_of_constants(work, capsys, n):
    """c_i = -c_(i-1) for odd i: the sign flips n // 2 times down the chain."""
    lines = ["const c0 = 300"] + [f"const c{i} = {'-' if i % 2 else ''}c{i - 1}"
                                  for i in range(1, n)]
    lines.append(f"on immediate do start_straight(c{n - 1}, 10 cm), start_straight(-c{n - 2}, 1 cm)")
    (work / "chain.epk").write_text("\n".join(lines) + "\n")
    status, out, err = run_cli(["compile", "chain.epk", "-o", "-"], capsys)
    assert status == 0, err
    last = -300 if (n // 2) % 2 else 300
    before = -300 if ((n - 1) // 2) % 2 else 300
    assert f"{{{last}, " in out and f"{{{-before}, " in out, out[-1500:]


@pytest.mark.parametrize("n", [330, 5000])
def test_a_long_chain_of_named_actions(work, capsys, n):
    lines = ["action a0 = start_straight(300, 10 cm)"]
    lines += [f"action a{i} = a{i - 1}" for i in range(1, n)]
    lines.append(f"on immediate do a{n - 1}")
    (work / "chain.epk").write_text("\n".join(lines) + "\n")
    status, out, err = run_cli(["compile", "chain.epk", "-o", "-"], capsys)
    assert status == 0, err
    assert "start_straight" in out


def test_long_cycles_are_one_error_each(work, capsys):
    n = 3000
    lines = [f"action a{i} = a{i + 1}" for i in range(n)] + [f"action a{n} = a0"]
    lines += [f"const c{i} = c{i + 1}" for i in range(n)] + [f"const c{n} = c0"]
    lines += ["on immediate do a0, start_straight(c0, 10 cm)"]
    (work / "cycle.epk").write_text("\n".join(lines) + "\n")
    status, out, err = run_cli(["check", "--format", "json", "cycle.epk"], capsys)
    assert status == 1
    assert [d["code"] for d in json.loads(out)] == ["E023", "E023"]


def test_a_constant_used_many_times_is_resolved_once(work, capsys, monkeypatch):
    from epuckc.check import checker
    calls = []
    real = checker.Checker._const_chain

    def counting(self, name):
        calls.append(name)
        return real(self, name)
    monkeypatch.setattr(checker.Checker, "_const_chain", counting)
    lines = ["const c0 = 300"] + [f"const c{i} = c{i - 1}" for i in range(1, 400)]
    lines += ["on immediate do start_straight(c399, 10 cm)"] * 50
    (work / "uses.epk").write_text("\n".join(lines) + "\n")
    status, _, err = run_cli(["check", "--max-actions", "100", "--max-events", "100",
                              "uses.epk"], capsys)
    assert status == 0, err
    # one walk down the chain, then each use is a look-up
    assert len(calls) == 50
    assert "c0" not in calls      # every use looked c399 up; none walked again


# ---- numbers ----------------------------------------------------------------------------

@pytest.mark.parametrize("value", ["0." + "0" * 310 + "1 mm", "0." + "0" * 330 + "1 mm",
                                   "0." + "0" * 400 + "1 m", "1" + "0" * 400 + " mm",
                                   "0.0001 mm", "99999999999 mm"])
@pytest.mark.parametrize("setting", ["wheel_circumference", "wheel_diameter", "axle"])
def test_robot_lengths_out_of_range(work, capsys, setting, value):
    (work / "r.epk").write_text(f"robot {{ {setting}: {value} }}\n"
                                "on immediate do start_curve(0 mm, 90 deg, 300)\n")
    status, out, err = run_cli(["compile", "r.epk", "-o", "-"], capsys)
    assert status == 1
    _assert_clean(status, out, err)
    assert "E037" in err or "E034" in err


def test_robot_steps_per_rev_beyond_a_long(work, capsys):
    (work / "r.epk").write_text("robot { steps_per_rev: 99999999999 }\n"
                                "on immediate do stop_motor\n")
    status, out, err = run_cli(["check", "r.epk"], capsys)
    # the runtime's limit (EPUCK_MAX_STEPS_PER_REV), within a long
    assert status == 1 and "E037" in err and "give 1 to 1000000" in err


def test_time_limit_with_400_digits(work, capsys):
    with pytest.raises(SystemExit) as exit_info:
        cli.main(["run", "ok.epk", "--time-limit", "9" * 400 + "s"])
    assert exit_info.value.code == 2
    err = capsys.readouterr().err
    assert "too long" in err and "Traceback" not in err


@pytest.mark.parametrize("value", ["5", "60", "0.5"])
def test_time_limit_without_a_unit_is_refused(work, capsys, value):
    with pytest.raises(SystemExit) as exit_info:
        cli.main(["run", "ok.epk", "--time-limit", value])
    assert exit_info.value.code == 2
    assert f"write {value}s for seconds or {value}ms" in capsys.readouterr().err


@settings(max_examples=300, deadline=None)
@given(whole=st.text("0123456789", min_size=1, max_size=12),
       fraction=st.none() | st.text("0123456789", min_size=1, max_size=8),
       unit=st.sampled_from(["ms", "s", "min"]))
def test_time_limit_is_read_exactly(whole, fraction, unit):
    """--time-limit in whole numbers of ms, against exact fractions: the
    value if it is whole and from 1 ms to the harness's limit, else the
    matching usage error."""
    import argparse
    from fractions import Fraction
    from epuckc.cli import args
    text = whole + ("" if fraction is None else "." + fraction) + unit
    exact = Fraction(whole + ("" if fraction is None else "." + fraction)) * \
        {"ms": 1, "s": 1000, "min": 60000}[unit]
    if 1 <= exact <= args.MAX_TIME_LIMIT_MS and exact.denominator == 1:
        assert args._duration_ms(text) == exact
        return
    with pytest.raises(argparse.ArgumentTypeError) as error:
        args._duration_ms(text)
    why = str(error.value)
    if exact < 1:
        assert "at least 1 ms" in why
    elif exact > args.MAX_TIME_LIMIT_MS:
        assert "too long" in why
    else:
        assert "not a whole number of milliseconds" in why


@pytest.mark.parametrize("command", ["check", "compile", "build", "run"])
@pytest.mark.parametrize("value", ["99999999999999999999", "0", "-3", "32768", "1e3", "x"])
def test_capacities_are_bounded(work, capsys, command, value):
    with pytest.raises(SystemExit) as exit_info:
        cli.main([command, "ok.epk", f"--max-events={value}"])
    assert exit_info.value.code == 2
    assert "--max-events" in capsys.readouterr().err


def test_capacity_at_the_bound_is_accepted(work, capsys):
    status, _, err = run_cli(["check", "--max-events", "32767", "ok.epk"], capsys)
    assert status == 0, err


# ---- files ------------------------------------------------------------------------------

def test_extern_path_longer_than_name_max(work, capsys):
    (work / "x.epk").write_text(f'extern action spin() from "{"s" * 300}.c"\n'
                                "on immediate do spin\n")
    status, out, err = run_cli(["compile", "x.epk"], capsys)
    assert status == 1 and "E040" in err and "too long" in err


def test_rule_file_name_that_is_not_utf8(work, capsys):
    name = os.fsdecode(b"r\xff\xfe.epk")
    (work / name).write_text("on immediate do start_straight(300, 10 cm)\n")
    status, out, err = run_cli(["compile", name], capsys)
    assert status == 0, err
    c_text = (work / os.fsdecode(b"r\xff\xfe.c")).read_text(encoding="utf-8")
    # non-ASCII reaches C escaped: \uFFFD in comments, UTF-8 octal in strings
    assert c_text.isascii() and "r\\uFFFD\\uFFFD.epk" in c_text
    (work / name).write_text("on immediate do strat(300, 10 cm)\n")
    for fmt in ("human", "json"):
        status, out, err = run_cli(["check", "--format", fmt, name], capsys)
        shown = json.loads(out)[0]["file"] if fmt == "json" else err
        assert status == 1 and "r\ufffd\ufffd.epk" in shown


def test_scenario_that_is_a_directory(work, capsys):
    (work / "scenes").mkdir()
    status, out, err = run_cli(["run", "ok.epk", "--scenario", "scenes"], capsys)
    assert status == 2 and "scenes is a directory" in err


def test_missing_scenario(work, capsys):
    status, out, err = run_cli(["run", "ok.epk", "--scenario", "nope.scn"], capsys)
    assert status == 2 and "nope.scn: the file does not exist" in err


# ---- the property: no internal error, whatever the numbers --------------------------------

_NUMBER_TEXT = st.one_of(
    st.integers(min_value=0, max_value=10**30).map(str),
    st.builds(lambda a, zeros, b: f"{a}.{'0' * zeros}{b}",
              st.integers(0, 10**6), st.integers(0, 500), st.integers(0, 10**6)),
    st.text("0123456789", min_size=1, max_size=500),
)
_UNITS = st.sampled_from(["", " mm", " cm", " m", " steps", " steps/s", " mm/s", " deg", " s"])


@settings(max_examples=150, deadline=None,
          suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(setting=st.sampled_from(["wheel_circumference", "wheel_diameter", "axle",
                                "steps_per_rev", "max_speed"]),
       number=_NUMBER_TEXT, unit=_UNITS, negative=st.booleans(),
       speed=_NUMBER_TEXT, distance=_NUMBER_TEXT)
def test_property_robot_numbers_never_crash(tmp_path_factory, setting, number, unit, negative,
                                            speed, distance):
    folder = tmp_path_factory.mktemp("prop")
    path = folder / "p.epk"
    value = ("-" if negative else "") + number + unit
    path.write_text(f"robot {{ {setting}: {value} }}\n"
                    f"on immediate do start_straight({speed}, {distance} mm), "
                    f"start_curve(radius: {distance} mm, degrees: {speed} deg, speed: 100)\n"
                    f"on stop_motor do exit_main\n")
    import io
    import contextlib
    err = io.StringIO()
    out = io.StringIO()
    with contextlib.redirect_stderr(err), contextlib.redirect_stdout(out):
        status = cli.main(["compile", str(path), "-o", "-"])
    _assert_clean(status, out.getvalue(), err.getvalue())
    assert status in (0, 1)


_CLI_VALUES = st.one_of(
    st.text(min_size=0, max_size=60),
    st.integers(min_value=-10**25, max_value=10**25).map(str),
    st.builds(lambda n, u: f"{n}{u}", st.text("0123456789.", min_size=1, max_size=420),
              st.sampled_from(["", "s", "ms", "min", " s", "h", "e3"])),
)


@settings(max_examples=150, deadline=None,
          suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(option=st.sampled_from(["--time-limit", "--max-events", "--max-actions"]),
       command=st.sampled_from(["check", "compile", "run"]), value=_CLI_VALUES)
def test_property_cli_numbers_never_crash(tmp_path_factory, option, command, value):
    folder = tmp_path_factory.mktemp("cli")
    path = folder / "p.epk"
    path.write_text("on immediate do start_straight(300, 10 cm)\n")
    if command != "run" and option == "--time-limit":
        command = "run"
    argv = [command, str(path), f"{option}={value}"]
    if command == "compile":
        argv += ["-o", str(folder / "p.c")]
    if command == "run" and option != "--max-actions":
        # parsing the option is what is under test, not a run of hours
        argv.append("--max-actions=0")
    import io
    import contextlib
    err = io.StringIO()
    with contextlib.redirect_stderr(err), contextlib.redirect_stdout(io.StringIO()):
        try:
            status = cli.main(argv)
        except SystemExit as exc:
            status = exc.code
    _assert_clean(status, "", err.getvalue())
