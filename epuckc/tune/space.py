"""The `[search]` table of a tune file: each constant's range, and the
settings of the search. Read as an extension of the experiment file
(experiment/spec.py's `extensions`), so that its problems are reported at
their lines with the file's others, all at once.

    [search]
    K_FRONT = { low = "0 steps/s", high = "64 steps/s" }    # a quantity, its unit kept
    GAIN = { low = 1, high = 8 }                            # whole numbers
    RATE = { low = 0.01, high = 10, log = true }            # a log scale
    STEP = { low = 10, high = 100, step = 10 }
    MODE = { choices = [1, 3, 5] }
    objective = "coverage - contacts / 100"
    direction = "maximize"          # or "minimize"
    aggregate = "mean"              # "median", "quantile 0.25"
    budget = 200                    # runs, or a wall-clock time: "30 min"
    sampler_seed = 7

docs/experiments.md ("Tuning") is the reference."""
from __future__ import annotations

import difflib
import math
import re
from dataclasses import dataclass, field
from typing import Optional

from .objective import Objective, ObjectiveError, parse

SETTINGS = ("objective", "direction", "aggregate", "budget", "sampler", "sampler_seed",
            "pruning", "parallel", "min_seeds", "test_seeds", "baseline")
RANGE_KEYS = ("low", "high", "step", "log", "choices")
MAX_BUDGET = 10_000_000
_QUANTITY = re.compile(r"\s*(-?(?:[0-9]+(?:\.[0-9]*)?|\.[0-9]+))\s*([A-Za-z%][A-Za-z/%]*"
                       r"(?:\s*/\s*[A-Za-z]+)?)?\s*\Z")


@dataclass
class Param:
    """One constant's range: `kind` int or float over [low, high] (in
    `unit`, "" for a plain number), or `choices` (value texts)."""
    name: str
    kind: str
    low: float = 0.0
    high: float = 0.0
    step: Optional[float] = None
    log: bool = False
    unit: str = ""
    choices: list = field(default_factory=list)

    def text(self, value) -> str:
        """A value the sampler gave, as the constant's -D text."""
        if self.kind == "choice":
            return value
        number = str(int(value)) if self.kind == "int" else plain(value)
        return f"{number} {self.unit}" if self.unit else number

    def toml(self, value) -> str:
        """The value as a TOML value of [params]."""
        text = self.text(value)
        return text if re.fullmatch(r"-?[0-9.]+", text) else f'"{text}"'


@dataclass
class Search:
    params: list
    objective: Objective
    direction: str = "maximize"
    aggregate: tuple = ("mean",)
    budget_runs: Optional[int] = 100
    budget_s: Optional[float] = None
    sampler: str = "tpe"
    sampler_seed: int = 1
    pruning: str = "median"
    parallel: int = 4
    min_seeds: int = 2
    test_seeds: object = None       # a count, a list, or None (as many as the design seeds)
    baseline: bool = True

    def better(self, a: float, b: float) -> bool:
        """a is a better value of the objective than b."""
        return a > b if self.direction == "maximize" else a < b


def plain(v: float) -> str:
    """A float without an exponent, six significant digits."""
    if v == 0:
        return "0"
    digits = max(0, 5 - math.floor(math.log10(abs(v))))
    text = f"{v:.{digits}f}"
    return text.rstrip("0").rstrip(".") if "." in text else text


def _quantity(value):
    """(number, unit text, whole) of a TOML value, or None."""
    if isinstance(value, bool):
        return None
    if isinstance(value, (int, float)):
        return (float(value), "", isinstance(value, int)) if math.isfinite(value) else None
    if isinstance(value, str):
        m = _QUANTITY.match(value)
        if m:
            unit = re.sub(r"\s+", "", m.group(2) or "")
            return float(m.group(1)), unit, "." not in m.group(1)
    return None


def read_search(data, pos, fail) -> Optional[Search]:
    """The [search] table as a Search (None when there are errors, each
    reported through `fail`)."""
    table = data.get("search")
    if table is None:
        fail((1, 1), "a tune needs a [search] table: the constants' ranges and the objective",
             '[search]\nGAIN = { low = 1, high = 8 }\nobjective = "coverage"')
        return None
    if not isinstance(table, dict):
        fail(pos.key("search"), "search is a table", "[search]")
        return None
    count = [0]

    def bad(where, message, help=""):
        count[0] += 1
        fail(where, message, help)

    params = []
    for name, value in table.items():
        if isinstance(value, dict):
            param = _param(name, value, pos.key(name, "search"), bad)
            if param is not None:
                params.append(param)
        elif name not in SETTINGS:
            close = difflib.get_close_matches(name, SETTINGS, n=1)
            bad(pos.key(name, "search"), f"unknown setting `{name}` of [search]",
                (f"did you mean `{close[0]}`? " if close else "")
                + f"a constant's range is a table: {name} = {{ low = 1, high = 8 }}")
    if not any(isinstance(v, dict) for v in table.values()):
        bad(pos.key(None, "search"), "[search] gives no constant to search", "GAIN = { low = 1, high = 8 }")
    search = Search(params, None)
    _settings(search, table, data, pos, bad)
    return None if count[0] else search


def _param(name, table, where, bad) -> Optional[Param]:
    from ..check.defines import NAME_RE
    if not NAME_RE.match(name) or name in ("program", "world", "robots"):
        bad(where, f"`{name}` is not a constant that a tune can search")
        return None
    for key in table:
        if key not in RANGE_KEYS:
            bad(where, f"unknown key `{key}` in the range of {name}",
                "a range has low, high and step or log, or else choices")
    if "choices" in table:
        from ..check.defines import DefineError, check_value, format_value
        choices = table["choices"]
        texts = []
        if not isinstance(choices, list) or not choices:
            bad(where, f"the choices of {name} are a list of values", f"{name} = "
                "{ choices = [1, 3, 5] }")
            return None
        for c in choices:
            try:
                if not isinstance(c, (int, float, str)):
                    raise DefineError(repr(c))
                text = format_value(c)
                check_value(name, text)
            except DefineError:
                bad(where, f"{c!r} is not a value of the language",
                    'give numbers, or values with their unit in quotes: ["10 cm", "20 cm"]')
                continue
            if text in texts:
                bad(where, f"{name} has the choice {text} twice")
            texts.append(text)
        return Param(name, "choice", choices=texts)
    ends = {}
    for key in ("low", "high"):
        if key not in table:
            bad(where, f"the range of {name} has no {key}", f"{name} = {{ low = 1, high = 8 }}")
            return None
        ends[key] = _quantity(table[key])
        if ends[key] is None:
            bad(where, f"the {key} of {name} is a number, or a value with its unit in quotes",
                f'{name} = {{ low = "10 cm", high = "30 cm" }}')
            return None
    (low, unit, whole_low), (high, unit_high, whole_high) = ends["low"], ends["high"]
    if unit != unit_high:
        bad(where, f"the low and high of {name} have different units ({unit or 'none'} and "
            f"{unit_high or 'none'})", "give both in the same unit")
        return None
    if not low < high:
        bad(where, f"the low of {name} is not below its high")
        return None
    log = table.get("log", False)
    if not isinstance(log, bool):
        bad(where, "log is true or false", f"{name} = {{ low = 0.1, high = 10, log = true }}")
        return None
    if log and low <= 0:
        bad(where, f"a log scale needs a low above 0 ({name})")
        return None
    step = None
    whole = whole_low and whole_high
    if "step" in table:
        q = _quantity(table["step"])
        if q is None or q[0] <= 0 or (q[1] and q[1] != unit):
            bad(where, f"the step of {name} is a positive number in the range's unit")
            return None
        if log:
            bad(where, f"{name} has a step and a log scale: give one of them")
            return None
        step = q[0]
        whole = whole and q[2]
    return Param(name, "int" if whole else "float", low, high, step if step else None, log,
                 unit)


def _settings(search: Search, table: dict, data, pos, bad):
    def at(key):
        return pos.key(key, "search")

    text = table.get("objective")
    if text is None:
        bad(pos.key(None, "search"), "[search] has no objective",
            'objective = "coverage - contacts / 100"')
    elif not isinstance(text, str):
        bad(at("objective"), "the objective is an expression in quotes",
            'objective = "coverage - contacts / 100"')
    else:
        try:
            search.objective = parse(text)
        except ObjectiveError as exc:
            line, col = at("objective")
            bad((line, col + exc.column), str(exc), exc.help)
    direction = table.get("direction", "maximize")
    names = {"maximize": "maximize", "maximise": "maximize", "minimize": "minimize",
             "minimise": "minimize"}
    if direction not in names:
        bad(at("direction"), "the direction is \"maximize\" or \"minimize\"")
    else:
        search.direction = names[direction]
    how = table.get("aggregate", "mean")
    m = re.fullmatch(r"\s*quantile\s+([0-9.]+)\s*", how) if isinstance(how, str) else None
    if how in ("mean", "median"):
        search.aggregate = (how,)
    elif m and 0 <= float(m.group(1)) <= 1:
        search.aggregate = ("quantile", float(m.group(1)))
    else:
        bad(at("aggregate"), "the aggregate over the seeds is \"mean\", \"median\" or "
            "\"quantile Q\" with Q from 0 to 1", 'aggregate = "quantile 0.25"')
    _budget(search, table, data, at, bad)
    for key, low, high in (("sampler_seed", 0, 2 ** 32 - 1), ("parallel", 1, 1024),
                           ("min_seeds", 1, 1000)):
        if key in table:
            v = table[key]
            if isinstance(v, bool) or not isinstance(v, int) or not low <= v <= high:
                bad(at(key), f"{key} is a whole number from {low} to {high}")
            else:
                setattr(search, key, v)
    for key, choices in (("sampler", ("tpe", "random")), ("pruning", ("median", "none"))):
        if key in table:
            if table[key] not in choices:
                bad(at(key), f"the {key} is " + " or ".join(f'"{c}"' for c in choices))
            else:
                setattr(search, key, table[key])
    if "baseline" in table:
        if not isinstance(table["baseline"], bool):
            bad(at("baseline"), "baseline is true or false")
        else:
            search.baseline = table["baseline"]
    if "test_seeds" in table:
        v = table["test_seeds"]
        ok = (isinstance(v, int) and not isinstance(v, bool) and 1 <= v <= 100_000) or (
            isinstance(v, list) and v and all(isinstance(s, int) and not isinstance(s, bool)
                                              and 0 <= s < 2 ** 32 for s in v)
            and len(set(v)) == len(v))
        if not ok:
            bad(at("test_seeds"), "test_seeds is a number of seeds or a list of distinct seeds",
                "test_seeds = 20 (the 20 seeds after the design seeds)")
        else:
            search.test_seeds = v


def _budget(search: Search, table: dict, data, at, bad):
    from ..experiment.spec import parse_duration
    if "budget" not in table:
        return
    v = table["budget"]
    if isinstance(v, int) and not isinstance(v, bool):
        seeds = data.get("seeds", 1)
        n = seeds if isinstance(seeds, int) else len(seeds) if isinstance(seeds, list) else 1
        if not 1 <= v <= MAX_BUDGET:
            bad(at("budget"), f"the budget is a number of runs from 1 to {MAX_BUDGET}, or a "
                "time in quotes")
        elif isinstance(n, int) and v < n:
            bad(at("budget"), f"a budget of {v} runs does not cover one candidate on the "
                f"{n} design seeds", f"budget = {20 * n}")
        else:
            search.budget_runs = v
        return
    ms = parse_duration(v)
    if ms is None or ms < 1000:
        bad(at("budget"), "the budget is a number of runs, or a wall-clock time in quotes of "
            "at least 1 s", 'budget = 200 or budget = "30 min"')
        return
    search.budget_runs, search.budget_s = None, ms / 1000


def distributions(search: Search) -> dict:
    """Optuna's distributions of the ranges."""
    from optuna.distributions import (CategoricalDistribution, FloatDistribution,
                                      IntDistribution)
    out = {}
    for p in search.params:
        if p.kind == "choice":
            out[p.name] = CategoricalDistribution(p.choices)
        elif p.kind == "int":
            out[p.name] = IntDistribution(int(p.low), int(p.high), step=int(p.step or 1),
                                          log=p.log)
        else:
            out[p.name] = FloatDistribution(p.low, p.high, step=p.step, log=p.log)
    return out
