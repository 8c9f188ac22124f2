"""Bad experiment files: every problem as file:line:col with the line and
a caret, before anything runs; the grid and the statistics."""
from __future__ import annotations

import math

import pytest

from epuckc.experiment.plan import grid
from epuckc.experiment.spec import ExperimentError, read_experiment
from epuckc.experiment.stats import describe, t975
from tests.experiment.helpers import make
from tests.support.cli import run_cli

GOOD = """program = "brait.epk"
world = "arena.world"
duration = "1 s"
seeds = 2
"""


def _errors(tmp_path, text):
    exp = make(tmp_path, text)
    with pytest.raises(ExperimentError) as info:
        read_experiment(exp, "exp.toml")
    return str(info.value)


@pytest.mark.parametrize("text, where, words", [
    (GOOD + "seed = 3\n", "exp.toml:5:8:", "unknown key `seed`"),
    (GOOD.replace('"1 s"', '"1"'), "exp.toml:3:12:", "duration is a time"),
    (GOOD.replace('"1 s"', '20'), "exp.toml:3:12:", "duration is a time"),
    (GOOD.replace("seeds = 2", "seeds = [1, 2, 1]"), "exp.toml:4:16:", "seed 1 is given twice"),
    (GOOD.replace("seeds = 2", "seeds = 0"), "exp.toml:4:9:", "seeds 1..N"),
    (GOOD.replace("brait.epk", "nowhere.epk"), "exp.toml:1:11:", "nowhere.epk does not exist"),
    (GOOD.replace("arena.world", "none.world"), "exp.toml:2:9:", "none.world does not exist"),
    (GOOD + 'metrics = ["distance", "speed"]\n', "exp.toml:5:24:", "unknown metric `speed`"),
    (GOOD + 'metrics = ["messages"]\n', "exp.toml:5:12:", "not a metric of their own"),
    (GOOD + "[params]\nK = [1, true]\n", "exp.toml:6:9:", "True is not a value"),
    (GOOD + '[params]\nK = ["3; x"]\n', "exp.toml:6:6:", "not a value of the language"),
    (GOOD + "duration2 = [1,\n", "exp.toml:5:16:", "this is not TOML"),
    (GOOD + "duration2 = 3 3\n", "exp.toml:5:15:", "this is not TOML"),
])
def test_bad_files(tmp_path, text, where, words):
    message = _errors(tmp_path, text)
    assert message.startswith(where), message
    assert words in message
    line = int(where.split(":")[1])
    col = int(where.split(":")[2])
    shown = text.splitlines()[line - 1] if line <= len(text.splitlines()) else ""
    assert f" {line} | {shown}\n" in message
    # the caret under the column
    caret_line = message.split("\n")[2]
    assert caret_line.index("^") - caret_line.index("|") - 2 == col - 1


@pytest.mark.parametrize("text, where, words, meant", [
    (GOOD + "seed = 3\n", "exp.toml:5:8:", "unknown key `seed`", "did you mean `seeds`?"),
    (GOOD + "[param]\nK = [1, 2]\n", "exp.toml:5:1:", "unknown table `param`",
     "did you mean `params`?"),
    (GOOD + 'metrics = ["distanse"]\n', "exp.toml:5:12:", "unknown metric `distanse`",
     "did you mean `distance`?"),
    (GOOD + "[params]\nKK = [1, 2]\n", "exp.toml:6:6:", "no program of the experiment has a "
     "constant KK", "did you mean `K`?"),
    (GOOD + 'metrics = ["var:left_nera"]\n', "exp.toml:5:12:", "declares a variable left_nera",
     "did you mean `left_near`?"),
])
def test_a_misspelt_name_is_found_at_its_line_with_the_one_meant(tmp_path, text, where, words,
                                                                  meant):
    """Issue 41: a wrong table was reported at 1:1, and no name was suggested."""
    message = _errors(tmp_path, text)
    assert message.startswith(where) and words in message, message
    assert f"help: {meant}" in message


def test_every_problem_at_once_in_the_file_s_order(tmp_path):
    """The spec's own problems and those of the names its programs
    declare, in one report (issue 41: they came in rounds)."""
    text = ("seed = 3\n" + GOOD + 'metrics = ["var:nope", "distanse"]\n'
            "[params]\nNOPE = [1, 2]\nK = [1, 1]\n")
    message = _errors(tmp_path, text)
    lines = [line.split(" error:")[0] for line in message.splitlines() if " error: " in line]
    assert lines == ["exp.toml:1:8:", "exp.toml:6:12:", "exp.toml:6:24:", "exp.toml:8:8:",
                     "exp.toml:9:9:"], message
    assert message.endswith("5 errors in exp.toml")


def test_every_problem_at_once(tmp_path):
    message = _errors(tmp_path, GOOD.replace('"1 s"', '"1"').replace("seeds = 2", "seeds = 0"))
    assert "exp.toml:3:" in message and "exp.toml:4:" in message
    assert message.endswith("2 errors in exp.toml")


def test_command_line_errors(tmp_path, capsys):
    exp = make(tmp_path, GOOD + "[params]\nNOPE = [1, 2]\n")
    status, out, err = run_cli(["experiment", str(exp)], capsys)
    assert status == 2
    assert "exp.toml:6:8: error: no program of the experiment has a constant NOPE" in err
    # a value of the wrong unit: the checker's diagnostic, before anything runs
    exp = make(tmp_path, GOOD + '[params]\nK = ["2 steps/s", "3 cm"]\n')
    status, out, err = run_cli(["experiment", str(exp), "-o", str(tmp_path / "o")], capsys)
    assert status == 1
    assert "error[E048]" in err and "with K=3 cm; nothing was run" in err
    assert not (tmp_path / "o" / "runs").exists() or not any((tmp_path / "o" / "runs").iterdir())
    exp = make(tmp_path, GOOD + 'metrics = ["var:nothing"]\n')
    status, out, err = run_cli(["experiment", str(exp)], capsys)
    assert status == 2 and "no program of the experiment declares a variable nothing" in err
    assert "left_near" in err


def test_grid_order(tmp_path):
    exp = make(tmp_path, GOOD + '[params]\nK = ["1 steps/s", "2 steps/s"]\n'
                                'CRUISE = ["100 steps/s", "200 steps/s", "300 steps/s"]\n')
    points = grid(read_experiment(exp))
    assert [p.values for p in points][:4] == [
        {"K": "1 steps/s", "CRUISE": "100 steps/s"}, {"K": "1 steps/s", "CRUISE": "200 steps/s"},
        {"K": "1 steps/s", "CRUISE": "300 steps/s"}, {"K": "2 steps/s", "CRUISE": "100 steps/s"}]
    assert len(points) == 6 and [p.index for p in points] == list(range(6))


def test_statistics():
    assert t975(1) == 12.706 and t975(30) == 2.042
    assert abs(t975(35) - 2.030) < 0.001 and abs(t975(100) - 1.984) < 0.001
    assert abs(t975(10 ** 6) - 1.960) < 0.001
    s = describe([1.0, 2.0, 3.0, 4.0])
    assert s["mean"] == 2.5 and math.isclose(s["sd"], math.sqrt(5 / 3))
    assert math.isclose(s["ci_high"] - s["mean"], 3.182 * math.sqrt(5 / 3) / 2)
    assert describe([7.0])["sd"] is None and describe([])["n"] == 0


class _Terminal:
    def __init__(self, tty):
        self.text, self.tty = "", tty

    def isatty(self):
        return self.tty

    def write(self, s):
        self.text += s

    def flush(self):
        pass


def test_progress_on_a_terminal_and_in_a_log():
    from types import SimpleNamespace
    from epuckc.cli.experiment import Progress
    from epuckc.experiment.task import RunResult
    task = SimpleNamespace(values={"K": "1 steps/s"}, point=0, seed=3)
    good = RunResult("k", 0, 3, {}, rows=[{"robot": "r1", "error": ""}])
    bad = RunResult("k", 0, 3, {}, error="the watchdog", rows=[{"robot": "r1", "error": "x"}])
    term = _Terminal(True)
    p = Progress(4, 1, term)        # one run already done: resumed
    p.update(task, good)
    p.update(task, bad)
    assert term.text.startswith("\r[")
    assert "3/4 runs, 1 failed" in term.text and "s left" in term.text
    assert "\n" not in term.text
    p.update(task, good)
    assert term.text.endswith("\n") and "4/4 runs, 1 failed" in term.text
    log = _Terminal(False)
    p = Progress(2, 0, log)
    p.update(task, good)
    p.update(task, bad)
    lines = log.text.splitlines()
    assert lines[0].startswith("run 1/2 (point 0 K=1 steps/s, seed 3): ok; ")
    assert lines[1].startswith("run 2/2 (point 0 K=1 steps/s, seed 3): failed: the watchdog; ")
