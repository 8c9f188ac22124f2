"""Experiment files: TOML, read with the standard library (tomllib), every
problem reported as `file:line:col: error: what is wrong` with the line, a
caret and how to fix it (a misspelt key, table or metric: the name meant),
all of them at once in the file's order, a constant or a variable no program
declares among them. tomllib gives no positions for the values it
reads, so the line of a key is found by scanning the text (`_Positions`).

    program = "brait.epk"          # or a list: one more axis of the grid
    world = "arena.world"
    duration = "20 s"
    seeds = 6                      # seeds 1..6, or a list of seeds
    metrics = ["contacts", "distance", "coverage"]
    traces = false                 # true: DIR/traces/RUN.jsonl for each run
    timeout = "5 min"              # the watchdog: wall clock per run
    [params]                       # a grid over the programs' constants
    GAIN = [1, 3]

and the axes of axes.py (a list of worlds, the robot count `robots`, the
`[placement]` of its copies, `series` over time at a `period`).
docs/experiments.md is the reference.
"""
from __future__ import annotations

import re
from dataclasses import dataclass, field
from pathlib import Path
from typing import Optional

KEYS = ("program", "world", "duration", "seeds", "metrics", "params", "traces", "timeout",
        "series", "period", "placement")
SIMPLE_METRICS = ("contacts", "distance", "coverage", "still", "exit", "pose")
DEFAULT_METRICS = ["contacts", "distance", "coverage"]
MAX_SEEDS = 1_000_000
MAX_DURATION_MS = 1_000_000_000
_UNITS_MS = {"ms": 1, "s": 1000, "min": 60_000}
_NAME = re.compile(r"[A-Za-z_][A-Za-z0-9_]*\Z")


class ExperimentError(Exception):
    """A problem in an experiment file; str() is the whole diagnostic.
    `status`: 2 for the experiment or world file, 1 for a program's errors."""

    def __init__(self, message: str, status: int = 2):
        super().__init__(message)
        self.status = status


@dataclass
class Experiment:
    path: Path
    programs: list                      # Paths; more than one: an axis of the grid
    world: Path
    duration_ms: int
    seeds: list
    metrics: list
    params: dict = field(default_factory=dict)     # NAME -> [value text, ...]
    traces: bool = False
    timeout_s: float = 300.0
    lines: dict = field(default_factory=dict)      # key -> (line, col), for later errors
    shown: str = ""                                # the file's name as the user gave it
    worlds: list = field(default_factory=list)     # Paths; more than one: an axis of the grid
    series: list = field(default_factory=list)     # metrics over time (axes.py)
    period_ms: int = 1000                          # ... sampled every period
    placement: object = None                       # swarm.Placement of the robots' copies
    extra: dict = field(default_factory=dict)      # key -> what an extension's reader gave

    def where(self, key: str) -> tuple:
        return self.lines.get(key, (1, 1))


class _Positions:
    """Where each key of the file is: (table, key) -> (line, column of the
    value), by scanning the text as TOML writes it (one key a line)."""

    def __init__(self, text: str):
        self.lines = text.splitlines()
        self.at = {}
        table = ""
        for n, raw in enumerate(self.lines, 1):
            line = raw.split("#", 1)[0]
            m = re.match(r"\s*\[\s*([A-Za-z0-9_.\"-]+)\s*\]", line)
            if m:
                table = m.group(1).strip('"')
                self.at.setdefault((table, None), (n, raw.index("[") + 1))
                continue
            m = re.match(r"\s*(\"?[A-Za-z0-9_-]+\"?)\s*=\s*", line)
            if m:
                self.at.setdefault((table, m.group(1).strip('"')), (n, m.end() + 1))

    def error(self, shown: str, where: tuple, message: str, help: str = "") -> ExperimentError:
        line, col = where
        text = self.lines[line - 1].rstrip() if 0 < line <= len(self.lines) else ""
        out = f"{shown}:{line}:{col}: error: {message}\n {line} | {text}\n"
        out += " " * (len(str(line)) + 1) + " | " + " " * (col - 1) + "^"
        return ExperimentError(out + (f"\nhelp: {help}" if help else ""))

    def key(self, key: str, table: str = "") -> tuple:
        """Where a key's value is written; a table's `[name]` for a key that
        is a table (`[param]`); the file's start when neither is found."""
        return self.at.get((table, key)) or (self.at.get((key, None)) if not table else None) \
            or (1, 1)

    def item(self, key: str, value, table: str = "", nth: int = 0) -> tuple:
        """Where an element of a key's list is written (the nth one equal
        to it; the key's value when it cannot be found)."""
        line, col = self.key(key, table)
        raw = self.lines[line - 1] if 0 < line <= len(self.lines) else ""
        texts = ([("true" if value else "false")] if isinstance(value, bool)
                 else [f'"{value}"', f"'{value}'", str(value)])
        for text in texts:
            at = [m.start() for m in re.finditer(re.escape(text), raw)
                  if m.start() >= col - 1 and (text[0] in "\"'"
                                                or not (raw[m.end():m.end() + 1].isalnum()
                                                        or raw[m.start() - 1:m.start()]
                                                        .isalnum()))]
            if len(at) > nth:
                return line, at[nth] + 1
        return line, col


def parse_duration(value) -> Optional[int]:
    """"20 s", "500ms", "2 min" -> ms, or None."""
    if not isinstance(value, str):
        return None
    m = re.fullmatch(r"\s*([0-9]+(?:\.[0-9]+)?)\s*(ms|s|min)\s*", value)
    if m is None:
        return None
    ms = float(m.group(1)) * _UNITS_MS[m.group(2)]
    return int(ms) if ms == int(ms) else None


def read_experiment(path: Path, shown: Optional[str] = None,
                    extensions: Optional[dict] = None) -> Experiment:
    """`extensions`: more top-level keys (a table such as `tune`'s
    [search]), each KEY -> read(data, pos, fail) whose value is
    `Experiment.extra[KEY]`; its errors join the file's others."""
    try:
        import tomllib
    except ModuleNotFoundError:         # Python before 3.11: the same parser, as tomli
        import tomli as tomllib
    from . import axes
    shown = shown or str(path)
    try:
        text = Path(path).read_text(encoding="utf-8")
    except FileNotFoundError:
        raise ExperimentError(f"the experiment file {shown} does not exist") from None
    except (OSError, UnicodeDecodeError) as exc:
        raise ExperimentError(f"cannot read the experiment file {shown}: "
                              f"{getattr(exc, 'strerror', None) or exc}") from None
    pos = _Positions(text)
    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        message = str(exc)
        m = re.search(r"\(at line (\d+), column (\d+)\)", message)
        end = re.search(r"\(at end of document\)", message)
        where = (int(m.group(1)), int(m.group(2))) if m else (len(pos.lines) + 1, 1)
        if m or end:
            message = message[:(m or end).start()].strip()
        if where[0] > len(pos.lines):
            where = (max(len(pos.lines), 1), len(pos.lines[-1]) + 1 if pos.lines else 1)
        raise pos.error(shown, where, f"this is not TOML: {message[0].lower() + message[1:]}",
                        "see docs/experiments.md for the file's form") from None
    errors = []

    def fail(where, message, help=""):
        errors.append((where, str(pos.error(shown, where, message, help))))

    base = Path(path).parent
    extensions = extensions or {}
    keys = KEYS + tuple(extensions)
    for key in data:
        if key not in keys:
            what = "table" if isinstance(data[key], dict) else "key"
            fail(pos.key(key), f"unknown {what} `{key}`",
                 _did_you_mean(key, keys) or f"an experiment file has {', '.join(keys)}")
    programs = _programs(data, pos, base, fail)
    world = None
    worlds = []
    if "world" not in data:
        fail((1, 1), "the experiment names no world", 'add a line: world = "arena.world"')
    elif isinstance(data["world"], list):
        worlds = axes.worlds(data, pos, base, fail)
        world = worlds[0] if worlds else None
    elif not isinstance(data["world"], str):
        fail(pos.key("world"), "the world is a file name in quotes", 'world = "arena.world"')
    else:
        world = base / data["world"]
        worlds = [world]
        if not world.is_file():
            fail(pos.key("world"), f"the world file {data['world']} does not exist",
                 "the path is relative to the experiment file's folder")
    duration = None
    if "duration" not in data:
        fail((1, 1), "the experiment gives no duration", 'add a line: duration = "20 s"')
    else:
        duration = parse_duration(data["duration"])
        if duration is None or not 1 <= duration <= MAX_DURATION_MS:
            fail(pos.key("duration"), "the duration is a time in quotes with its unit, from "
                 "1 ms to 1000000 s", 'duration = "20 s" (or "500 ms", "2 min")')
    seeds = _seeds(data, pos, fail)
    metrics = _metrics(data, pos, fail)
    params = _params(data, pos, fail)
    if isinstance(data.get("params"), dict) and axes.ROBOTS in data["params"]:
        value = data["params"][axes.ROBOTS]
        params[axes.ROBOTS] = axes.robot_counts(value if isinstance(value, list) else [value],
                                                pos, fail)
    series, period_ms = axes.series(data, pos, fail, duration, parse_duration)
    placement = axes.placement(data, pos, fail)
    extra = {key: read(data, pos, fail) for key, read in extensions.items()}
    if not errors or programs or worlds:        # what the programs define, with the rest
        _defined(params, metrics, programs, worlds, pos, fail)
    traces = data.get("traces", False)
    if not isinstance(traces, bool):
        fail(pos.key("traces"), "traces is true or false", "traces = true")
    timeout_ms = 300_000
    if "timeout" in data:
        timeout_ms = parse_duration(data["timeout"])
        if timeout_ms is None or timeout_ms < 1:
            fail(pos.key("timeout"), "the timeout is a time in quotes with its unit",
                 'timeout = "5 min"')
            timeout_ms = 300_000
    if errors:
        count = f"{len(errors)} error{'s' if len(errors) > 1 else ''}"
        # all at once, in the file's order
        errors.sort(key=lambda e: e[0])
        raise ExperimentError("\n\n".join(text for _, text in errors) + f"\n\n{count} in {shown}")
    lines = {key: pos.key(key) for key in keys}
    lines.update({f"params.{k}": pos.key(k, "params") for k in params})
    return Experiment(Path(path), programs, world, duration, seeds, metrics, params,
                      traces, timeout_ms / 1000, lines, shown, worlds, series, period_ms,
                      placement, extra)


def _programs(data, pos, base, fail) -> list:
    value = data.get("program", [])
    items = value if isinstance(value, list) else [value]
    out = []
    for item in items:
        if not isinstance(item, str):
            fail(pos.key("program"), "a program is a file name in quotes (.epk or .c)",
                 'program = "brait.epk" or program = ["a.epk", "b.epk"]')
            continue
        path = base / item
        if Path(item).suffix not in (".epk", ".c"):
            fail(pos.item("program", item), f"{item} is not a program (.epk or .c)")
        elif not path.is_file():
            fail(pos.item("program", item), f"the program {item} does not exist",
                 "the path is relative to the experiment file's folder")
        elif path in out:
            fail(pos.item("program", item), f"{item} is named twice")
        else:
            out.append(path)
    return out


def _seeds(data, pos, fail) -> list:
    value = data.get("seeds", 1)
    if isinstance(value, int) and not isinstance(value, bool):
        if 1 <= value <= MAX_SEEDS:
            return list(range(1, value + 1))
        fail(pos.key("seeds"), f"seeds = N runs the seeds 1..N: N is from 1 to {MAX_SEEDS}")
        return []
    if isinstance(value, list) and value:
        seeds = []
        for s in value:
            if isinstance(s, bool) or not isinstance(s, int) or not 0 <= s < 2 ** 32:
                fail(pos.item("seeds", s), f"{s!r} is not a seed: a whole number "
                     "from 0 to 4294967295")
            elif s in seeds:
                fail(pos.item("seeds", s, nth=seeds.count(s)), f"the seed {s} is given twice")
            else:
                seeds.append(s)
        return seeds
    fail(pos.key("seeds"), "seeds is a number of seeds or a list of seeds",
         "seeds = 10 (the seeds 1..10) or seeds = [3, 7, 11]")
    return []


def _metrics(data, pos, fail) -> list:
    value = data.get("metrics", DEFAULT_METRICS)
    if not isinstance(value, list) or not all(isinstance(m, str) for m in value):
        fail(pos.key("metrics"), "metrics is a list of names in quotes",
             'metrics = ["contacts", "distance", "coverage"]')
        return []
    out = []
    for m in value:
        kind, _, name = m.partition(":")
        if m in SIMPLE_METRICS or (kind in ("var", "mean") and _NAME.match(name)):
            if m not in out:
                out.append(m)
        elif m in ("messages", "sent", "received"):
            fail(pos.item("metrics", m), f"`{m}`: messages are not a metric of their own",
                 "count them in a variable of the program (`on message do heard += 1`) and "
                 "ask for it: var:heard")
        else:
            fail(pos.item("metrics", m), f"unknown metric `{m}`",
                 _did_you_mean(m, SIMPLE_METRICS) or
                 f"the metrics are {', '.join(SIMPLE_METRICS)}, var:NAME (a variable's final "
                 "value) and mean:NAME (its time average)")
    return out


def _did_you_mean(word: str, names) -> str:
    """`did you mean `seeds`?` for `seed`, or ""."""
    import difflib
    close = difflib.get_close_matches(word, list(names), n=1, cutoff=0.6)
    return f"did you mean `{close[0]}`?" if close else ""


def _names(path: Path) -> tuple:
    """The constants and the traced variables a rule file declares, or
    None when it cannot be read."""
    from ..check.defines import declared_of
    try:
        return declared_of(path.read_text(encoding="utf-8"), str(path))
    except (OSError, UnicodeDecodeError):
        return None


def _defined(params: dict, metrics: list, programs: list, worlds: list, pos, fail) -> None:
    """A parameter no program of the experiment (its own, the world's
    robots') defines, a metric of a variable none declares: said with the
    file's other problems (plan.py finds them too, but only once the rest
    is right)."""
    from .axes import ROBOTS
    wanted = [m for m in metrics if m.partition(":")[0] in ("var", "mean")]
    if not set(params) - {ROBOTS} and not wanted:
        return
    from ..sim.world import WorldError, parse_world
    paths = list(programs)
    for world in worlds:
        if not world.is_file():
            continue
        try:
            paths += [r.program for r in parse_world(world).robots if r.program is not None]
        except WorldError:
            return              # plan.py says what is wrong with the world
    consts, variables = set(), set()
    for path in paths:
        found = _names(path) if path.suffix == ".epk" else (set(), set())
        if found is None:
            return              # and plan.py (the checker) why it cannot be read
        consts |= found[0]
        variables |= found[1]
    for name in params:
        if name != ROBOTS and name not in consts:
            fail(pos.key(name, "params"), f"no program of the experiment has a constant {name}",
                 _did_you_mean(name, sorted(consts)) or "a parameter is a `const` of a program")
    for m in wanted:
        name = m.partition(":")[2]
        if name not in variables:
            fail(pos.item("metrics", m), f"`{m}`: no program of the experiment declares a "
                 f"variable {name}", _did_you_mean(name, sorted(variables))
                 or f"declared: {', '.join(sorted(variables)) or 'none'}")


def _params(data, pos, fail) -> dict:
    from ..check.defines import DefineError, check_value, format_value
    table = data.get("params", {})
    if not isinstance(table, dict):
        fail(pos.key("params"), "params is a table of constants, each with its values",
             "[params]\nGAIN = [1, 3]")
        return {}
    out = {}
    for name, values in table.items():
        where = pos.key(name, "params")
        if not _NAME.match(name) or name in ("program", "world"):
            fail(where, f"`{name}` cannot name a constant of the language")
            continue
        values = values if isinstance(values, list) else [values]
        texts = []
        for v in values:
            try:
                if not isinstance(v, (int, float, str)):
                    raise DefineError(f"{v!r}")
                text = format_value(v)
                check_value(name, text)
            except DefineError:
                fail(pos.item(name, v, "params"), f"{v!r} is not a value of the language",
                     'give numbers, or values with their unit in quotes: ["10 cm", "20 cm"]')
                continue
            if text in texts:
                fail(pos.item(name, v, "params", nth=1), f"{name} takes the value {text} twice")
            texts.append(text)
        if not values:
            fail(where, f"{name} has no values", f"{name} = [1, 2]")
        out[name] = texts
    return out
