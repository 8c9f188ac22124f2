"""The case model: a rule file `NAME.epk` is a case; its inputs are found by
name beside it (`NAME.scn`, `NAME.world`, `NAME.toml`), its expected
outputs too (`NAME.trace`, `NAME.diag`, `NAME.c`). A folder's
`epuckc-test.toml` gives defaults to every case in it and below it (the
nearest one wins); `NAME.toml` overrides them key by key. Discovery and
every option are checked before anything runs: a problem is a `UsageError`
with `file:line:col`."""
from __future__ import annotations

import re
from dataclasses import dataclass, field
from pathlib import Path
from typing import Optional

FOLDER_FILE = "epuckc-test.toml"
DEFAULT_TIME_LIMIT_MS = 60_000
MAX_TIME_LIMIT_MS = 1_000_000_000
KEYS = {
    "time_limit": "the virtual time limit with its unit, e.g. \"10s\" or \"500ms\"",
    "seed": "the seed of `random`, 0 to 4294967295",
    "scenario": "a scenario file, relative to this file's folder",
    "world": "a world file, relative to this file's folder",
    "trace": "true or false: compare the readable trace with NAME.trace",
    "diag": "true or false: compare the diagnostics with NAME.diag",
    "c": "true or false: also compare the generated C with NAME.c",
    "expect": "a list of property checks such as \"exit within 5 s\"",
    "tolerance": "a table: pose_mm, heading_deg, time_ms",
    "constants": "a table of the program's constants and their values, as `-D NAME=VALUE` "
                 "gives them: NAME = \"400 steps/s\" or NAME = 3",
    "target": "where the case runs: \"host\" (the simulated e-puck; the only one so far)",
    "recorded": "a robot's trace recorded by `epuckc monitor --trace` (JSON lines), relative "
                "to this file's folder: the case's run, instead of a simulation",
}
TOLERANCE_KEYS = ("pose_mm", "heading_deg", "time_ms")


class UsageError(Exception):
    """A bad path or a bad options file: `epuckc test` exits 2. A message
    about a place in a file starts with `file:line:col: error:`."""

    @property
    def located(self) -> bool:
        return bool(re.match(r"[^:\n]+:\d+:\d+: error: ", str(self)))


@dataclass
class Tolerance:
    pose_mm: float = 0.0
    heading_deg: float = 0.0
    time_ms: float = 0.0

    def any(self) -> bool:
        return bool(self.pose_mm or self.heading_deg or self.time_ms)


@dataclass
class Case:
    path: Path                      # the rule file
    shown: str                      # its name as reported (relative to where the run started)
    scenario: Optional[Path] = None
    world: Optional[Path] = None
    time_limit_ms: int = DEFAULT_TIME_LIMIT_MS
    seed: int = 1
    compare_trace: Optional[bool] = None     # default: true unless there are property checks
    compare_diag: Optional[bool] = None      # default: as compare_trace
    compare_c: bool = False
    expect: list = field(default_factory=list)      # props.Property
    tolerance: Tolerance = field(default_factory=Tolerance)
    constants: dict = field(default_factory=dict)   # NAME -> VALUE text (`-D`)
    recorded: Optional[Path] = None     # a robot's recorded trace: the run, not simulated

    @property
    def name(self) -> str:
        return self.path.stem

    @property
    def folder(self) -> Path:
        return self.path.parent

    def expected(self, suffix: str) -> Path:
        return self.path.with_suffix(suffix)


def _toml():
    try:
        import tomllib
    except ImportError:         # Python < 3.11
        try:
            import tomli as tomllib
        except ImportError:
            raise UsageError("reading NAME.toml needs Python 3.11 or the tomli package "
                             "(pip install tomli)") from None
    return tomllib


def _where(text: str, needle: str) -> tuple:
    """The line and column of a key (`needle =`) or of a string value
    (`"needle"`) in the text, for messages about what TOML parsed well."""
    patterns = [r"(?m)^[ \t]*(" + re.escape(needle) + r")[ \t]*=",
                r"[\"'](" + re.escape(needle) + r")[\"']",
                r"\b(" + re.escape(needle) + r")\b"]
    for pattern in patterns:
        m = re.search(pattern, text)
        if m:
            start = m.start(1) - (1 if pattern is patterns[1] else 0)
            line = text.count("\n", 0, start) + 1
            return line, start - (text.rfind("\n", 0, start) + 1) + 1
    return 1, 1


def read_options(path: Path, shown: str) -> tuple:
    """The options of one file: (dict, text). Raises UsageError with
    file:line:col."""
    try:
        text = path.read_text(encoding="utf-8")
    except (OSError, UnicodeDecodeError) as exc:
        raise UsageError(f"{shown}: cannot read it: {getattr(exc, 'strerror', None) or exc}") \
            from None
    tomllib = _toml()
    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        message = str(exc)
        m = re.search(r"\(at line (\d+), column (\d+)\)", message)
        where = f"{m.group(1)}:{m.group(2)}" if m else "1:1"
        message = re.sub(r"\s*\(at line \d+, column \d+\)", "", message)
        if m is None and "end of document" in message:
            where = f"{text.count(chr(10)) + 1}:1"
        raise UsageError(f"{shown}:{where}: error: not valid TOML: {message}") from None
    for key in data:
        if key not in KEYS:
            line, col = _where(text, key)
            known = ", ".join(KEYS)
            raise UsageError(f"{shown}:{line}:{col}: error: unknown option `{key}`; "
                             f"the options are {known}")
    return data, text


def _bad(shown: str, text: str, key: str, what: str) -> UsageError:
    line, col = _where(text, key)
    return UsageError(f"{shown}:{line}:{col}: error: `{key}` must be {what}")


_UNIT_MS = {"ms": 1, "s": 1000, "min": 60_000}


def parse_duration(text: str) -> Optional[int]:
    """`10s`, `500 ms`, `1.5s`, `2min` in whole ms, or None."""
    m = re.fullmatch(r"\s*([0-9]+(?:\.[0-9]+)?)\s*(ms|s|min)\s*", text)
    if not m:
        return None
    from decimal import Decimal
    ms = Decimal(m.group(1)) * _UNIT_MS[m.group(2)]
    if ms != ms.to_integral_value():
        return None
    return int(ms)


def _apply(case: Case, data: dict, text: str, shown: str, folder: Path):
    """Options of one file onto the case (later files override)."""
    from .props import PropertyError, parse_property
    for key, value in data.items():
        if key == "time_limit":
            ms = parse_duration(value) if isinstance(value, str) else None
            if ms is None or not 1 <= ms <= MAX_TIME_LIMIT_MS:
                raise _bad(shown, text, key, KEYS[key] + f" (1 ms to {MAX_TIME_LIMIT_MS // 1000} s)")
            case.time_limit_ms = ms
        elif key == "seed":
            if isinstance(value, bool) or not isinstance(value, int) or not 0 <= value <= 0xFFFFFFFF:
                raise _bad(shown, text, key, KEYS[key])
            case.seed = value
        elif key in ("scenario", "world", "recorded"):
            if not isinstance(value, str) or not value:
                raise _bad(shown, text, key, KEYS[key])
            target = folder / value
            if not target.is_file():
                line, col = _where(text, value)
                what = "recorded trace" if key == "recorded" else f"{key} file"
                raise UsageError(f"{shown}:{line}:{col}: error: the {what} {value} does "
                                 f"not exist (paths are relative to {shown}'s folder)")
            setattr(case, key, target)
            if key != "recorded":
                setattr(case, "world" if key == "scenario" else "scenario", None)
        elif key in ("trace", "diag", "c"):
            if not isinstance(value, bool):
                raise _bad(shown, text, key, KEYS[key])
            setattr(case, {"trace": "compare_trace", "diag": "compare_diag",
                           "c": "compare_c"}[key], value)
        elif key == "expect":
            if not isinstance(value, list) or not all(isinstance(v, str) for v in value):
                raise _bad(shown, text, key, KEYS[key])
            checks = []
            for item in value:
                try:
                    checks.append(parse_property(item))
                except PropertyError as exc:
                    line, col = _where(text, item)
                    raise UsageError(f"{shown}:{line}:{col}: error: {exc}") from None
            case.expect = checks
        elif key == "constants":
            from ..check.defines import DefineError, check_value, format_value
            if not isinstance(value, dict):
                raise _bad(shown, text, key, KEYS[key])
            from ..check.defines import constants_of
            constants = dict(case.constants)
            try:
                known = constants_of(case.path.read_text(encoding="utf-8"), case.path.name)
            except (OSError, UnicodeDecodeError):
                known = None        # the run reports the file itself
            for name, given in value.items():
                line, col = _where(text, name)
                try:
                    shown_value = format_value(given)
                    check_value(name, shown_value)
                except (DefineError, TypeError, ValueError) as exc:
                    raise UsageError(f"{shown}:{line}:{col}: error: {exc}") from None
                if known is not None and name not in known:
                    raise UsageError(f"{shown}:{line}:{col}: error: {case.path.name} has no "
                                     f"constant {name} (its constants: "
                                     f"{', '.join(known) or 'none'})")
                constants[name] = shown_value
            case.constants = constants
        elif key == "target":
            if value != "host":
                line, col = _where(text, str(value)) if isinstance(value, str) else _where(text, key)
                raise UsageError(f"{shown}:{line}:{col}: error: cases run on the host harness "
                                 f"(the simulated e-puck, alone or in a world): write target = "
                                 f"\"host\"; the robots' builds are `epuckc build`'s")
        elif key == "tolerance":
            if not isinstance(value, dict):
                raise _bad(shown, text, key, KEYS[key])
            tolerance = Tolerance()
            for name, amount in value.items():
                if name not in TOLERANCE_KEYS:
                    line, col = _where(text, name)
                    raise UsageError(f"{shown}:{line}:{col}: error: unknown tolerance `{name}`; "
                                     f"the tolerances are {', '.join(TOLERANCE_KEYS)}")
                if isinstance(amount, bool) or not isinstance(amount, (int, float)) or amount < 0:
                    raise _bad(shown, text, name, "a number, 0 or more")
                setattr(tolerance, name, float(amount))
            case.tolerance = tolerance


def _folder_file(folder: Path, stop: Optional[Path] = None) -> Optional[Path]:
    """The nearest `epuckc-test.toml` in `folder` or a folder above it, up
    to `stop` (when it is one of them) or the top."""
    here = folder.resolve()
    stop = stop.resolve() if stop is not None else None
    while True:
        candidate = here / FOLDER_FILE
        if candidate.is_file():
            return candidate
        if here == stop or here.parent == here:
            return None
        here = here.parent


def _shown(path: Path, base: Path) -> str:
    try:
        return str(path.resolve().relative_to(base.resolve()))
    except ValueError:
        return str(path)


def load_case(path: Path, root: Optional[Path] = None, base: Optional[Path] = None) -> Case:
    """The case of one rule file, with its options read and checked.
    `root`: how far up a folder's defaults are looked for (default: to the
    top); `base`: names are shown relative to it (default: the current
    folder)."""
    base = base if base is not None else Path.cwd()
    case = Case(path, _shown(path, base))
    defaults = _folder_file(path.parent, root)
    sources = [defaults] if defaults else []
    own = path.with_suffix(".toml")
    if own.is_file():
        sources.append(own)
    scenario, world = path.with_suffix(".scn"), path.with_suffix(".world")
    if scenario.is_file() and world.is_file():
        raise UsageError(f"{case.shown}: both {scenario.name} and {world.name} are beside it; "
                         "a case runs with a scenario or in a world, not both: rename one")
    if scenario.is_file():
        case.scenario = scenario
    elif world.is_file():
        case.world = world
    for source in sources:
        data, text = read_options(source, _shown(source, base))
        if source == defaults and ("scenario" in data or "world" in data) and \
                (case.scenario is not None or case.world is not None):
            data = {k: v for k, v in data.items() if k not in ("scenario", "world")}
        _apply(case, data, text, _shown(source, base), source.parent)
    if case.compare_trace is None:      # property checks replace the goldens unless asked for
        case.compare_trace = not case.expect
    if case.compare_diag is None:
        case.compare_diag = case.compare_trace
    if case.compare_c and case.path.with_suffix(".c").resolve() in _extern_files(case.path):
        raise UsageError(f"{case.shown}: `c = true` would compare the generated C with "
                         f"{case.path.with_suffix('.c').name}, which is the program's own extern "
                         "C file: rename one of them")
    return case


def _extern_files(path: Path) -> set:
    try:
        text = path.read_text(encoding="utf-8")
    except (OSError, UnicodeDecodeError):
        return set()
    return {(path.parent / m.group(1)).resolve()
            for m in re.finditer(r'\bfrom\s+"([^"]+)"', text)}


def discover(paths: list, base: Optional[Path] = None) -> list:
    """Every case under the paths (folders recursively, `.epk` files as
    given), in a stable order, each once. Raises UsageError on a path that
    is neither, or on the first bad options file."""
    found, seen = [], set()
    for name in paths:
        path = Path(name)
        if path.is_dir():
            files = sorted(p for p in path.rglob("*.epk")
                           if p.is_file() and not any(part.startswith(".")
                                                      for part in p.relative_to(path).parts))
        elif path.is_file():
            if path.suffix != ".epk":
                raise UsageError(f"{name}: not a rule file (.epk) nor a folder; a case is a "
                                 "rule file with its expected outputs beside it")
            files = [path]
        else:
            raise UsageError(f"{name}: no such file or folder")
        for file in files:
            key = file.resolve()
            if key not in seen:
                seen.add(key)
                found.append(load_case(file, None, base))
    return found
