"""The tune file's [search]: objectives read by their own parser (never
Python's eval), ranges and settings, each problem at its line and column
with the file's others."""
from __future__ import annotations

import math

import pytest

from epuckc.experiment.spec import ExperimentError, read_experiment
from epuckc.tune.objective import ObjectiveError, RunValueError, aggregate, parse
from epuckc.tune.space import Param, plain, read_search
from tests.experiment.helpers import make

ROW = {"distance_mm": 800.0, "contacts": 3, "coverage_cells": 21, "var:hits": 4,
       "contacts_walls": 2}


@pytest.mark.parametrize("text, value", [
    ("distance - 500 * min(contacts, 1)", 300.0),
    ("coverage - contacts / 100", 20.97),
    ("-distance ^ 0.5", -math.sqrt(800)),
    ("(1 + 2) * 3 - 4 / 2", 7.0),
    ("2 ^ 3 ^ 2", 512.0),
    ("max(var:hits, contacts_walls) + abs(-1.5) + log(exp(2)) + sqrt(16)", 11.5),
    ("1e3 - distance_mm", 200.0),
])
def test_objectives_evaluate(text, value):
    assert math.isclose(parse(text).value(ROW), value)


def test_the_metrics_an_objective_needs():
    obj = parse("coverage - contacts_walls / 10 + distance + mean:speed")
    assert obj.columns == ["coverage_cells", "contacts_walls", "distance_mm", "mean:speed"]
    assert obj.metrics == ["coverage", "contacts", "distance", "mean:speed"]


@pytest.mark.parametrize("text, column, words", [
    ("coverage - contcts", 12, "did you mean `contacts`?"),
    ("__import__(distance)", 1, "`__import__` is not a metric"),
    ("distance + 'os'", 12, "`'` has no meaning"),
    ("distance +", 11, "ends too soon"),
    ("(distance", 1, "not closed"),
    ("distance contacts", 10, "unexpected `contacts`"),
    ("min(distance)", 1, "min takes 2 arguments"),
    ("distance; 1", 9, "`;` has no meaning"),
    ("", 1, "empty"),
])
def test_bad_objectives(text, column, words):
    with pytest.raises(ObjectiveError) as info:
        parse(text)
    assert words in str(info.value) + " " + info.value.help
    assert info.value.column == column


def test_a_run_without_a_value():
    for text, row in (("distance / contacts", {"distance_mm": 1.0, "contacts": 0}),
                      ("log(distance)", {"distance_mm": -1.0}),
                      ("distance", {"distance_mm": ""})):
        with pytest.raises(RunValueError):
            parse(text).value(row)


def test_aggregates():
    values = [4.0, 1.0, 3.0, 2.0, 10.0]
    assert aggregate(values, ("mean",)) == 4.0
    assert aggregate(values, ("median",)) == 3.0
    assert aggregate(values, ("quantile", 0.25)) == 2.0
    assert aggregate(values, ("quantile", 0.1)) == pytest.approx(1.4)     # numpy's default
    assert aggregate([5.0], ("quantile", 0.9)) == 5.0


def test_values_as_the_language_writes_them():
    assert Param("K", "int", 0, 128, unit="steps/s").text(37) == "37 steps/s"
    assert Param("G", "float", 0.01, 10, log=True).text(0.012345678) == "0.0123457"
    assert Param("D", "float", 1, 3, unit="cm").toml(2.5) == '"2.5 cm"'
    assert Param("N", "int", 1, 9).toml(4) == "4"
    assert plain(123456.789) == "123457" and plain(0.5) == "0.5" and plain(-2.0) == "-2"


BASE = """program = "brait.epk"
world = "arena.world"
duration = "1 s"
seeds = 4
"""


def _read(tmp_path, text):
    return read_experiment(make(tmp_path, text), "t.toml",
                           extensions={"search": read_search}).extra["search"]


def test_a_search_reads(tmp_path):
    s = _read(tmp_path, BASE + """[search]
K = { low = "0 steps/s", high = "8 steps/s" }
CRUISE = { low = 100, high = 900, step = 100 }
GAIN = { low = 0.01, high = 10, log = true }
MODE = { choices = [1, "2 cm"] }
objective = "coverage - contacts / 100"
direction = "minimise"
aggregate = "quantile 0.25"
budget = "10 min"
sampler_seed = 11
test_seeds = [40, 41]
""")
    k, cruise, gain, mode = s.params
    assert (k.kind, k.low, k.high, k.unit) == ("int", 0, 8, "steps/s")
    assert (cruise.kind, cruise.step) == ("int", 100) and (gain.kind, gain.log) == ("float", True)
    assert mode.choices == ["1", "2 cm"]
    assert s.direction == "minimize" and s.aggregate == ("quantile", 0.25)
    assert s.budget_runs is None and s.budget_s == 600 and s.sampler_seed == 11
    assert s.test_seeds == [40, 41]


@pytest.mark.parametrize("lines, where, words", [
    ('K = { low = 1, high = 8 }\nobjectiv = "distance"\n', "t.toml:7:12:",
     "did you mean `objective`?"),
    ('K = { low = 1, high = 8 }\nobjective = "distance + speed"\n', "t.toml:7:25:",
     "`speed` is not a metric"),
    ('K = { low = "1 cm", high = "8 mm" }\nobjective = "distance"\n', "t.toml:6:5:",
     "different units"),
    ('K = { low = 0, high = 8, log = true }\nobjective = "distance"\n', "t.toml:6:5:",
     "log scale needs a low above 0"),
    ('K = { low = 8, high = 1 }\nobjective = "distance"\n', "t.toml:6:5:", "not below its high"),
    ('K = { low = 1, high = 8 }\nobjective = "distance"\nbudget = 3\n', "t.toml:8:10:",
     "does not cover one candidate on the 4 design seeds"),
    ('K = { low = 1, high = 8 }\nobjective = "distance"\ndirection = "up"\n', "t.toml:8:13:",
     "maximize"),
    ('objective = "distance"\n', "t.toml:5:1:", "gives no constant to search"),
    ('K = { low = 1, high = 8 }\n', "t.toml:5:1:", "has no objective"),
])
def test_bad_searches(tmp_path, lines, where, words):
    with pytest.raises(ExperimentError) as info:
        _read(tmp_path, BASE + "[search]\n" + lines)
    message = str(info.value)
    # the errors come in the file's order: the one meant is at its place
    assert any(e.startswith(where) and words in e for e in message.split("\n\n")), message


def test_every_problem_of_a_tune_file_at_once(tmp_path):
    with pytest.raises(ExperimentError) as info:
        _read(tmp_path, BASE.replace('"1 s"', '"1"') + '[search]\nK = { low = 1 }\n'
              'objective = "distanse"\n')
    message = str(info.value)
    assert "t.toml:3:" in message and "t.toml:6:" in message and "t.toml:7:" in message
    assert message.endswith("3 errors in t.toml")


def test_without_optuna_the_command_says_so(tmp_path, capsys, monkeypatch):
    import sys
    from tests.support.cli import run_cli
    monkeypatch.setitem(sys.modules, "optuna", None)
    exp = make(tmp_path, BASE + '[search]\nK = { low = 1, high = 8 }\nobjective = "distance"\n')
    status, _, err = run_cli(["tune", str(exp)], capsys)
    assert status == 1 and "pip install 'epuckc[tune]'" in err
    assert not (tmp_path / "exp-tune").exists()
