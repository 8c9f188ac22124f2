"""Semantic checks: names, arguments, kinds, ranges, rules that cannot fire.

The checker finds every problem it can in one run and resolves what is
right into a CheckedProgram: each call with its arguments converted to the
integers the runtime uses (steps, steps/s, degrees, ms). Code generation
starts from that and never re-derives a value.
"""
from __future__ import annotations

import math
import os
import re
from functools import lru_cache
from pathlib import Path
from typing import Optional

from . import ast, check_arbitration, check_modes
from .diagnostics import Collector, Fix, Note
from .records import field, record
from .resources import runtime_dir
from .source import Span
from .stdlib import (ACTION_ALIASES, CHOICE, EVENT_ALIASES, EXTERN_TYPES, MOTION_ACTIONS,
                     SENSOR_NAMES, STANDARD_ACTIONS, STANDARD_EVENTS, THRESHOLD_MAX, Param)
from .units import (ANGLE, ARTICLE, DISTANCE, DURATION, INT, INT16_MAX, INT16_MIN, INT32_MAX,
                    KIND_UNITS, SPEED, UNITS, Geometry, Quantity, curve_wheels,
                    describe_kind, quantity, round_nearest)

# A duration written without a unit is in ms; below this many it was very
# likely meant in seconds (`timer(2)`), and W008 says so.
BARE_DURATION_WARNING = 100
PRIORITY_MAX = 255         # `priority N`: 0 (the default) .. 255
_SENSOR_INDEX = {name: index for index, name in enumerate(SENSOR_NAMES)}    # ir0 -> 0


# ---- the checked program ------------------------------------------------------

@record
class ResolvedCall:
    """A call whose arguments are checked and converted.

    kind: "standard" | "extern" | "named" | "cancel" | "enter" (name: the mode)
    values: parameter name -> integer in runtime units (for an enumerated
    parameter, the C text of its value: `SET_LED_BODY`); for start_curve
    also `outer_steps` and `inner_speed`.
    shown: parameter name -> the argument as the user wrote it.
    """
    kind: str
    name: str
    values: dict
    shown: dict
    node: object


@record
class ResolvedEvent:
    kind: str               # "standard" | "extern"
    name: str
    values: dict            # timer: time (ms); extern: its params
    conditions: tuple = ()  # sensor, ambient: (index, op, threshold), sorted by index
    node: object = None


@record
class ResolvedRule:
    name: Optional[str]
    event: ResolvedEvent
    repeat: bool
    body: list              # steps, each a list of ResolvedCall
    node: ast.Rule
    priority: int = 0
    mode: Optional[str] = None      # the mode whose block holds it


@record
class ExternInfo:
    kind: str               # "action" | "event"
    name: str
    params: tuple           # Param
    file: str
    node: ast.ExternDef


@record
class CheckedProgram:
    file: str
    geometry: Geometry
    actions: dict = field(default_factory=dict)   # name -> list of steps
    action_nodes: dict = field(default_factory=dict)
    externs: dict = field(default_factory=dict)   # name -> ExternInfo
    rules: list = field(default_factory=list)     # ResolvedRule
    robot_given: bool = False
    modes: list = field(default_factory=list)     # mode names, in declared order
    initial_mode: Optional[str] = None


def did_you_mean(ident: ast.Ident, candidates) -> Optional[Fix]:
    """The closest of `candidates` to a misspelt name, as a fix that
    replaces the name (its help reads "did you mean `start_straight`?")."""
    import difflib          # only for a misspelt name: `check` starts faster without it
    close = difflib.get_close_matches(ident.name, sorted(candidates), n=1, cutoff=0.6)
    return Fix(ident.span, close[0], f"did you mean `{close[0]}`?") if close else None


def _code(text: str) -> str:
    return f"`{text}`"


def _shown(value) -> str:
    if isinstance(value, ast.Number):
        return value.text + (f" {value.unit}" if value.unit else "")
    return ("-" if value.negative else "") + value.name.name


class Checker:
    def __init__(self, program: ast.Program, diags: Collector,
                 base_dir: Optional[Path] = None):
        self.program = program
        self.diags = diags
        self.base_dir = base_dir
        self.geo = Geometry()
        self.consts: dict = {}           # name -> ConstDef
        self.const_used: set = set()
        self.actions: dict = {}          # name -> ActionDef
        self.externs: dict = {}          # name -> ExternInfo
        self.broken_externs: dict = {}   # name -> kind, of externs with bad declarations
        self.extern_c_names: dict = {}   # name -> first ExternDef: one C namespace
        self.rule_names: dict = {}       # name -> Rule
        self.used_actions: set = set()
        self.called: set = set()         # standard actions called anywhere
        self._cycle_calls: set = set()   # ids of calls that close a cycle of named actions
        self._const_memo: dict = {}      # constant -> (Number, negated, problem)
        self._const_reported: set = set()
        self._const_diagnostics: set = set()
        self._resolved_actions: dict = {}
        self._flat_actions: dict = {}    # named action -> flattened steps (check_modes.flat_steps)
        self.modes: dict = {}            # name -> ModeDef
        self.initial_mode: Optional[str] = None

    # -- entry point --

    def check(self) -> CheckedProgram:
        self._declare()
        robot_blocks = self.program.of_type(ast.RobotBlock)
        self._robot(robot_blocks)
        out = CheckedProgram(self.program.file, self.geo, robot_given=bool(robot_blocks))
        out.externs = self.externs
        self._resolve_actions(out)
        out.modes, out.initial_mode = list(self.modes), self.initial_mode
        for rule in self.program.of_type(ast.Rule):
            resolved = self._rule(rule)
            if resolved is not None:
                out.rules.append(resolved)
        # Warnings that conclude from an absence ("no action runs set_timer",
        # "never used") are drawn only from a complete program: a statement
        # or call dropped by an error may be the very one that was missing,
        # and a warning caused by an error is noise (a cascade).
        complete = not self.diags.has_errors
        self._never_fire(out, complete)
        if complete:
            self._unused()
        check_modes.check_program(self, out, complete)
        check_arbitration.check_program(self, out)
        return out

    # Resolving the named actions and each rule are the steps that the
    # language server's incremental checker (epuckc/incremental.py) reuses
    # from one keystroke to the next.

    def _resolve_actions(self, out: CheckedProgram):
        self._resolve_named_actions()
        for name, node in self.actions.items():
            out.actions[name] = self._named_action(name)
            out.action_nodes[name] = node

    def _rule(self, rule: ast.Rule) -> Optional[ResolvedRule]:
        event = self._event(rule.event)
        body = self._body(rule.body)
        priority = self._priority(rule.priority)
        check_modes.check_rule(self, rule, event)
        if event is None or priority is None:
            return None
        return ResolvedRule(rule.name.name if rule.name else None, event, rule.repeat, body, rule,
                            priority, rule.mode.name if rule.mode else None)

    # -- declarations --

    def _declare(self):
        seen: dict = {}     # (namespace, name) -> first node

        def claim(namespace: str, ident: ast.Ident, what: str) -> bool:
            key = (namespace, ident.name)
            if key in seen:
                first = seen[key]
                self.diags.error("E015", ident.span,
                                 f"{what} {_code(ident.name)} is defined twice",
                                 help="rename one of them",
                                 notes=[Note("first defined here", first.span)])
                return False
            seen[key] = ident
            return True

        for stmt in self.program.statements:
            if isinstance(stmt, ast.Rule):          # the most of them, first
                if stmt.name is not None and claim("rule", stmt.name, "rule"):
                    self.rule_names[stmt.name.name] = stmt
            elif isinstance(stmt, ast.ConstDef):
                if claim("const", stmt.name, "constant"):
                    self.consts[stmt.name.name] = stmt
            elif isinstance(stmt, ast.ActionDef):
                if self._clashes_with_standard(stmt.name, "action"):
                    continue
                if claim("action", stmt.name, "action"):
                    self.actions[stmt.name.name] = stmt
            elif isinstance(stmt, ast.ExternDef):
                self._extern(stmt, claim)
        check_modes.declare(self, claim)

    def _clashes_with_standard(self, ident: ast.Ident, namespace: str) -> bool:
        standard = STANDARD_ACTIONS if namespace == "action" else STANDARD_EVENTS
        aliases = ACTION_ALIASES if namespace == "action" else EVENT_ALIASES
        if ident.name in standard or ident.name in aliases:
            self.diags.error("E015", ident.span,
                             f"{_code(ident.name)} is already the name of a standard {namespace}",
                             help=f"choose another name, e.g. `my_{ident.name}`")
            return True
        return False

    def _extern(self, stmt: ast.ExternDef, claim):
        # only for externs: a program without them is checked without it
        from .cnames import extern_name_problem, parameter_name_problem
        if self._clashes_with_standard(stmt.name, stmt.kind):
            return
        # an extern is a C function of exactly this name, its parameters the
        # fields of a struct, both declared after utility.h (cnames.py)
        problem = extern_name_problem(stmt.name.name, bool(stmt.params))
        if problem is not None:
            self.diags.error("E027", stmt.name.span,
                             f"an extern {stmt.kind} cannot be named {_code(stmt.name.name)}: "
                             f"{problem}",
                             help=f"rename it in both files, e.g. `my_{stmt.name.name}`")
            self.broken_externs[stmt.name.name] = stmt.kind
            return
        first = self.extern_c_names.get(stmt.name.name)
        if first is not None and first.kind != stmt.kind:
            self.diags.error("E015", stmt.name.span,
                             f"{_code(stmt.name.name)} is already an extern {first.kind}: "
                             "both would be the C function of that name",
                             help="rename one of them in both files",
                             notes=[Note("first declared here", first.name.span)])
            return
        self.extern_c_names.setdefault(stmt.name.name, stmt)
        params, ok = [], True
        names: dict = {}
        for p in stmt.params:
            problem = parameter_name_problem(p.name.name)
            if problem is not None:
                self.diags.error("E027", p.name.span,
                                 f"a parameter cannot be named {_code(p.name.name)}: {problem}",
                                 help=f"rename it in the declaration and in your C, "
                                      f"e.g. `{p.name.name.strip('_') or 'value'}_value`")
                ok = False
            if p.type.name not in EXTERN_TYPES:
                self.diags.error("E026", p.type.span, f"unknown type {_code(p.type.name)}",
                                 help=did_you_mean(p.type, EXTERN_TYPES)
                                 or "the types are " + ", ".join(map(_code, EXTERN_TYPES)))
                ok = False
            if p.name.name in names:
                self.diags.error("E015", p.name.span,
                                 f"parameter {_code(p.name.name)} is declared twice",
                                 notes=[Note("first declared here", names[p.name.name].span)])
                ok = False
            names[p.name.name] = p.name
            params.append(Param(p.name.name, p.type.name))
        unterminated = any(d.code == "E003" and d.span == stmt.file_span for d in self.diags.items)
        if self.base_dir is not None and not unterminated:
            self._extern_file(stmt)
        if claim(stmt.kind, stmt.name, f"{stmt.kind}"):
            if ok:
                self.externs[stmt.name.name] = ExternInfo(stmt.kind, stmt.name.name,
                                                          tuple(params), stmt.file, stmt)
            else:       # reported above; its uses are not errors of their own
                self.broken_externs[stmt.name.name] = stmt.kind

    def _extern_file(self, stmt: ast.ExternDef):
        looked = self.base_dir / stmt.file
        try:
            os.stat(looked)
            problem = None if looked.is_file() else "is not a file"
        except FileNotFoundError:
            problem = "does not exist"
        except OSError as exc:      # a name longer than NAME_MAX, a loop of links, ...
            problem = f"cannot be used: {exc.strerror or exc}"
        except ValueError:          # a NUL byte
            problem = "cannot be used: it contains a NUL character"
        if problem is not None:
            self.diags.error("E040", stmt.file_span,
                             f"the C file {_code(_clip(stmt.file, 60))} {problem}",
                             help=f"epuckc looked for `{_clip(str(looked), 100)}`: the path is "
                                  "relative to the folder of the rule file")

    # -- the robot block --

    def _robot(self, blocks: list):
        for extra in blocks[1:]:
            self.diags.error("E022", extra.span, "the robot is described twice",
                             help="merge the two `robot { ... }` blocks into one",
                             notes=[Note("first described here", blocks[0].span)])
        if not blocks:
            return
        kinds = {"wheel_diameter": DISTANCE, "wheel_circumference": DISTANCE,
                 "axle": DISTANCE, "steps_per_rev": INT, "max_speed": SPEED}
        given: dict = {}
        for setting in blocks[0].settings:
            name = setting.name.name
            if name not in kinds:
                settings = "the settings are " + ", ".join(map(_code, kinds))
                guess = did_you_mean(setting.name, kinds)
                self.diags.error("E022", setting.name.span, f"unknown robot setting {_code(name)}",
                                 help=guess.then(settings) if guess else settings)
                continue
            if name in given:
                self.diags.error("E018", setting.name.span, f"{_code(name)} is given twice",
                                 notes=[Note("first given here", given[name][0].span)])
                continue
            q = self._value(setting.value, kinds[name], name)
            if q is None:
                continue
            if kinds[name] == DISTANCE and q.in_steps:
                self.diags.error("E019", setting.value.span,
                                 f"{_code(name)} cannot be given in steps: it defines what a step is",
                                 help="give it in mm")
                continue
            if q.value <= 0:
                self.diags.error("E037", setting.value.span, f"{_code(name)} must be positive",
                                 help=Fix(setting.value.span, _ROBOT_EXAMPLE[name],
                                          f"for the e-puck, write `{name}: {_ROBOT_EXAMPLE[name]}`"))
                continue
            if kinds[name] == INT and not self._whole(setting.value, q.value):
                continue
            if not self._robot_range(name, setting, q):
                continue
            given[name] = (setting, q)
        if "wheel_diameter" in given and "wheel_circumference" in given:
            self.diags.error("E037", given["wheel_circumference"][0].span,
                             "give the wheel's diameter or its circumference, not both",
                             notes=[Note("the diameter is given here", given["wheel_diameter"][0].span)])
            return
        geo = Geometry()
        circumference = geo.wheel_circumference_mm
        if "wheel_diameter" in given:
            circumference = math.pi * given["wheel_diameter"][1].value
        if "wheel_circumference" in given:
            circumference = given["wheel_circumference"][1].value
        steps_per_rev = int(given["steps_per_rev"][1].value) if "steps_per_rev" in given else geo.steps_per_rev
        axle = given["axle"][1].value if "axle" in given else geo.axle_mm
        max_speed = geo.max_speed
        if "max_speed" in given:
            # mm/s converts with the new geometry, so build it first.
            partial = Geometry(circumference, axle, steps_per_rev)
            max_speed = given["max_speed"][1].steps(partial)
            if max_speed > 1000:
                self.diags.error("E030", given["max_speed"][0].value.span,
                                 f"`max_speed` of {max_speed:.0f} steps/s is above the 1000 steps/s "
                                 "that the e-puck library allows", help="use at most 1000 steps/s")
                max_speed = 1000.0
        self.geo = Geometry(circumference, axle, steps_per_rev, max_speed)

    def _robot_range(self, name: str, setting, q: Quantity) -> bool:
        """The runtime takes the wheel and the axle in micrometres and the
        steps per turn as 32-bit longs (set_robot_geometry), up to its limits
        EPUCK_MAX_GEOMETRY_UM and EPUCK_MAX_STEPS_PER_REV (epuckrt.h), within
        which its conversions cannot overflow: each setting must fit, which
        also keeps every derived quantity finite."""
        max_um, max_steps = runtime_geometry_limits()
        if name in ("wheel_diameter", "wheel_circumference", "axle"):
            factor = math.pi if name == "wheel_diameter" else 1
            um = q.value * 1000 * factor
            if 1 <= round_nearest(um) <= max_um:
                return True
            low = 0.001 / factor
            high = math.floor(max_um / 1000 / factor)
            what = {"wheel_diameter": "the wheel's circumference", "axle": "the axle",
                    "wheel_circumference": "the wheel's circumference"}[name]
            self.diags.error("E037", setting.value.span,
                             f"`{name}` of `{_clip(_shown(setting.value))}` is out of range: "
                             f"give {low:.4g} mm to {high} mm",
                             help=f"the runtime keeps {what} in micrometres, at most "
                                  f"{max_um // 1000000} m; for the e-puck, write "
                                  f"`{name}: {_ROBOT_EXAMPLE[name]}`")
            return False
        if name == "steps_per_rev" and q.value > max_steps:
            self.diags.error("E037", setting.value.span,
                             f"`steps_per_rev` of `{_clip(_shown(setting.value))}` is out of range: "
                             f"give 1 to {max_steps}",
                             help=f"the runtime takes at most {max_steps} steps per turn; for the "
                                  "e-puck, write `steps_per_rev: 1000`")
            return False
        return True

    # -- values --

    def _plain(self, value, kind: str, lo: Optional[int] = None,
               hi: Optional[int] = None) -> Optional[int]:
        """The runtime integer of `value` where `kind` is wanted (lo..hi:
        the range of a whole number), when `value` is the common case: a
        number (or a constant that is one), without a unit or with one of
        the kind, that converts with nothing to say. None sends it the
        general way (`_value`, then `_to_runtime` or the caller's own range
        check), which reports what is wrong; this is that way without the
        Quantity, with the same float operations, so both give the same
        integer (tests/frontend/test_plain_numbers.py)."""
        negative = False
        if value.__class__ is ast.ConstRef:
            name = value.name.name
            if name not in self.consts:
                return None
            number_node, negated, problem = self._const_chain(name)
            if problem is not None:
                return None
            value, negative = number_node, negated != value.negative
        if value.__class__ is not ast.Number:
            return None
        number = value.value
        if not abs(number) < 1e12:
            return None
        unit = value.unit
        in_steps = False
        if unit is None:
            if kind == SPEED:
                in_steps = True
            elif kind == DURATION and 0 < number < BARE_DURATION_WARNING:
                return None                 # W008
        else:
            found = UNITS.get(unit)
            if found is None or found[0] != kind:
                return None
            factor = found[1]
            if factor is None:
                in_steps = True
            else:
                number = number * factor
        if negative:                        # as _const_value negates the Quantity
            number = -number
        if kind == INT:
            if number != int(number):
                return None
            v = int(number)
            if INT16_MIN <= v <= INT16_MAX and (lo is None or lo <= v <= hi):
                return v
            return None
        if kind == DISTANCE:
            v = round_nearest(number if in_steps else number / self.geo.step_mm)
            return v if INT16_MIN <= v <= INT16_MAX else None
        if kind == SPEED:
            v = round_nearest(number if in_steps else number / self.geo.step_mm)
            return v if abs(v) <= self.geo.max_speed else None
        if kind == ANGLE:
            v = round_nearest(number)
            return v if INT16_MIN <= v <= INT16_MAX else None
        if kind == DURATION:
            v = round_nearest(number)
            return v if 0 < v <= INT32_MAX else None
        return None                         # CHOICE: names, the general way

    def _value(self, value, kind: str, param: str) -> Optional[Quantity]:
        """The quantity a value denotes where `kind` is wanted, or None after
        reporting why it cannot be one."""
        if isinstance(value, ast.ConstRef):
            return self._const_value(value, kind, param)
        if not abs(value.value) < 1e12:     # also inf, from a 400-digit number
            self.diags.error("E034", value.span,
                             f"`{_shown(value)}` is far too large for {_code(param)}",
                             help="the runtime stores values in 16-bit ints and 32-bit longs")
            return None
        if value.unit is not None:
            if value.unit not in UNITS:
                all_units = sorted(UNITS)
                hint = did_you_mean(ast.Ident(value.unit, value.unit_span),
                                    KIND_UNITS.get(kind, all_units)) or (
                    f"`{param}` is {ARTICLE[kind]}: write it in "
                    + _either(KIND_UNITS[kind]) if kind != INT
                    else f"`{param}` takes a plain number, without a unit")
                self.diags.error("E020", value.unit_span, f"unknown unit {_code(value.unit)}",
                                 help=hint)
                return None
            unit_kind = UNITS[value.unit][0]
            if unit_kind != kind:
                self.diags.error("E019", value.span,
                                 f"{_code(param)} expects {describe_kind(kind)}, "
                                 f"but `{_shown(value)}` is {describe_kind(unit_kind).split(' (')[0]}",
                                 help=self._kind_help(kind, param))
                return None
        if kind == DURATION and value.unit is None and 0 < value.value < BARE_DURATION_WARNING:
            n = value.text.lstrip("-")
            self.diags.warning("W008", value.span,
                               f"`{n}` without a unit is {n} ms: did you mean {n} s?",
                               help=Fix(Span(value.span.end_line, value.span.end_column,
                                             value.span.end_line, value.span.end_column),
                                        " s", f"write `{n} s`, or `{n} ms` if milliseconds are meant"))
        return quantity(value.value, value.unit, kind)

    @staticmethod
    def _kind_help(kind: str, param: str) -> str:
        if kind == INT:
            return f"write `{param}` as a plain number, without a unit"
        return f"write it with a unit of {describe_kind(kind).split(' (')[0]}, e.g. `{_example(kind)}`"

    def _const_chain(self, name: str):
        """Follow constant `name` through the constants it is defined by, to
        the number at the end: (Number or None, negated, problem), where
        problem is None, ("unknown", ConstRef) or ("cycle", ConstRef).

        A loop, not recursion, so a chain of thousands of constants is
        fine; memoised, so each constant is followed once per file."""
        memo = self._const_memo
        if name in memo:
            return memo[name]
        value = self.consts[name].value
        if isinstance(value, ast.Number):       # most constants: the loop's first step
            self.const_used.add(name)
            memo[name] = (value, False, None)
            return memo[name]
        path = []                   # (name, the ConstRef that led on from it)
        negated = False
        current = name
        on_path: dict = {}
        result = None
        while True:
            if current in memo:
                number, neg, problem = memo[current]
                result = (number, negated != neg, problem)
                break
            const = self.consts[current]
            self.const_used.add(current)
            value = const.value
            if isinstance(value, ast.Number):
                result = (value, negated, None)
                path.append((current, None))
                break
            on_path[current] = len(path)
            path.append((current, value))
            negated = negated != value.negative
            following = value.name.name
            if following not in self.consts:
                result = (None, negated, ("unknown", value))
                break
            if following in on_path:
                result = (None, negated, ("cycle", value))
                break
            current = following
        # Fill the memo from the end of the path back: each constant's own
        # sign is the total sign up to it, undone.
        number, total, problem = result
        sign_before = False
        signs = []
        for _, ref in path:
            signs.append(sign_before)
            if ref is not None:
                sign_before = sign_before != ref.negative
        for (const_name, _), before in zip(path, signs):
            if const_name not in memo:
                memo[const_name] = (number, total != before, problem)
        return memo[name] if name in memo else result

    def _const_value(self, ref: ast.ConstRef, kind: str, param: str) -> Optional[Quantity]:
        name = ref.name.name
        if name not in self.consts:
            self.diags.error("E013", ref.name.span, f"unknown constant {_code(name)}",
                             help=did_you_mean(ref.name, self.consts) or
                             f"define it first: `const {name} = VALUE`")
            return None
        number, negated, problem = self._const_chain(name)
        if problem is not None:
            what, at = problem
            if what == "unknown":
                missing = at.name.name
                diag_args = ("E013", at.name.span, f"unknown constant {_code(missing)}")
                help = (did_you_mean(at.name, self.consts)
                        or f"define it first: `const {missing} = VALUE`")
            else:
                diag_args = ("E023", at.span,
                             f"constant {_code(at.name.name)} is defined in terms of itself")
                help = "give one of the constants a number"
            if diag_args not in self._const_reported:
                self._const_reported.add(diag_args)
                self.diags.error(*diag_args, help=help)
            return None
        # Check the number where it is used: a constant's kind is that of
        # its unit, or whatever its use wants when it has none.
        inner = Collector(self.diags.source)
        saved, self.diags = self.diags, inner
        try:
            q = self._value(number, kind, param)
        finally:
            self.diags = saved
        if q is None:
            first = inner.items[0] if inner.items else None
            if first is not None and first.code == "E019":
                const = self.consts[name]
                self.diags.error("E019", ref.span,
                                 f"{_code(param)} expects {describe_kind(kind)}, but constant "
                                 f"{_code(name)} is `{_shown(const.value)}`",
                                 help=self._kind_help(kind, param),
                                 notes=[Note(f"{_code(name)} is defined here", const.span)])
                return None
        seen = self._const_diagnostics
        for d in inner.items:       # each problem of a definition, said once
            if d not in seen:
                seen.add(d)
                self.diags.items.append(d)
        if q is None:
            return None
        if negated != ref.negative:
            q = Quantity(q.kind, -q.value, q.in_steps)
        return q

    def _whole(self, node, value: float) -> bool:
        if value != int(value):
            whole = round_nearest(value)
            self.diags.error("E038", node.span, f"`{_shown(node)}` is not a whole number",
                             help=Fix(node.span, f"{whole} {node.unit}" if node.unit else str(whole),
                                      f"write {whole}") if isinstance(node, ast.Number)
                             else f"write {whole}")
            return False
        return True

    # -- arguments --

    def _bind(self, call_name: ast.Ident, args, params, what: str) -> Optional[dict]:
        """Match arguments to parameters: positional in the paper's order,
        then named. Returns parameter name -> argument node, or None."""
        if not args:
            if not params:
                return {}
        elif len(args) == len(params):
            # The common case first: each parameter given once, the
            # positional arguments before the named ones. Anything else
            # takes the general way below, which says what is wrong.
            bound = {}
            named = False
            for p, arg in zip(params, args):
                cls = arg.__class__
                if cls is ast.PositionalArg and not named:
                    bound[p.name] = arg
                elif cls is ast.NamedArg:
                    named = True
                    bound[arg.name.name] = arg
                else:
                    break
            else:
                if len(bound) == len(params) and (
                        not named or all(p.name in bound for p in params)):
                    return bound
        args = args or ()
        bound: dict = {}
        ok = True
        seen_named = False
        positional = 0
        by_name = {p.name: p for p in params}
        extra = []                  # positional arguments beyond the parameters
        for arg in args:
            if isinstance(arg, ast.ConditionArg):
                self.diags.error("E024", arg.span,
                                 f"a condition such as `{arg.sensor.name} {arg.op} ...` "
                                 f"can only be given to `sensor` or `ambient`",
                                 help=_signature_help(call_name.name, params))
                ok = False
                continue
            if isinstance(arg, ast.NamedArg):
                seen_named = True
                pname = arg.name.name
                if pname not in by_name:
                    names = [p.name for p in params]
                    self.diags.error("E014", arg.name.span,
                                     f"{what} {_code(call_name.name)} has no parameter {_code(pname)}",
                                     help=did_you_mean(arg.name, names) or (
                                         "its parameters are " + ", ".join(map(_code, names))
                                         if names else "it takes no arguments"))
                    ok = False
                    continue
                if pname in bound:
                    self.diags.error("E018", arg.span, f"{_code(pname)} is given twice",
                                     notes=[Note("first given here", bound[pname].span)])
                    ok = False
                    continue
                bound[pname] = arg
                continue
            if seen_named:
                self.diags.error("E021", arg.span, "a positional argument cannot follow a named one",
                                 help="give the positional arguments first, or name this one too")
                ok = False
                continue
            if positional >= len(params):
                extra.append(arg)
                positional += 1
                continue
            bound[params[positional].name] = arg
            positional += 1
        if extra:
            given = sum(not isinstance(a, ast.NamedArg) for a in args)
            self.diags.error("E016", Span.of(extra[0], extra[-1]),
                             f"{what} {_code(call_name.name)} takes {_count(len(params))}, "
                             f"but {given} are given",
                             help=_signature_help(call_name.name, params))
            ok = False
        missing = [p.name for p in params if p.name not in bound]
        if missing and ok:
            span = call_name.span if not args else Span.of(call_name, args[-1])
            self.diags.error("E017", span,
                             f"{what} {_code(call_name.name)} is missing "
                             f"{' and '.join(map(_code, missing))}",
                             help=_signature_help(call_name.name, params))
            ok = False
        return bound if ok else None

    def _convert(self, bound: dict, params) -> Optional[tuple[dict, dict]]:
        """Check and convert each bound argument to its runtime integer."""
        values, shown, ok = {}, {}, True
        for p in params:
            arg = bound[p.name]
            v = self._plain(arg.value, p.kind, p.lo, p.hi)
            if v is not None:
                values[p.name], shown[p.name] = v, _shown(arg.value)
                continue
            if p.kind == CHOICE:
                choice = self._choice(arg.value, p)
                if choice is None:
                    ok = False
                    continue
                values[p.name], shown[p.name] = choice, _shown(arg.value)
                continue
            q = self._value(arg.value, p.kind, p.name)
            if q is None:
                ok = False
                continue
            shown[p.name] = _shown(arg.value)
            v = self._to_runtime(q, p, arg.value)
            if v is None:
                ok = False
                continue
            values[p.name] = v
        return (values, shown) if ok else None

    def _to_runtime(self, q: Quantity, p: Param, node) -> Optional[int]:
        geo = self.geo
        if p.kind == INT:
            if not self._whole(node, q.value):
                return None
            v = self._fits16(int(q.value), node, p.name, "")
            if v is not None and p.lo is not None and not p.lo <= v <= p.hi:
                self.diags.error(p.range_code, node.span,
                                 f"{_code(p.name)} `{_shown(node)}` is outside {p.lo}..{p.hi}",
                                 help=f"{_code(p.name)} is {p.doc}: {p.range.split(' [')[0]}")
                return None
            return v
        if p.kind == DISTANCE:
            return self._fits16(round_nearest(q.steps(geo)), node, p.name, " steps")
        if p.kind == SPEED:
            steps = round_nearest(q.steps(geo))
            if abs(steps) > geo.max_speed:
                self.diags.error("E030", node.span,
                                 f"{_code(p.name)} of `{_shown(node)}` is {abs(steps)} steps/s, above "
                                 f"the robot's maximum of {geo.max_speed:.0f} steps/s",
                                 help=f"use a speed of at most {geo.max_speed:.0f} steps/s "
                                      f"({geo.max_speed * geo.step_mm:.0f} mm/s)")
                return None
            return steps
        if p.kind == ANGLE:
            return self._fits16(round_nearest(q.value), node, p.name, " deg")
        if p.kind == DURATION:
            ms = round_nearest(q.value)
            if ms <= 0:
                self.diags.error("E033", node.span,
                                 f"{_code(p.name)} must be a positive duration, not `{_shown(node)}`",
                                 help="durations count from when the timer was set; use at least 1 ms")
                return None
            if ms > INT32_MAX:
                self.diags.error("E034", node.span, f"`{_shown(node)}` is too long a duration",
                                 help=f"the runtime counts milliseconds in a 32-bit long (at most {INT32_MAX} ms)")
                return None
            return ms
        raise AssertionError(p.kind)

    def _fits16(self, v: int, node, param: str, unit: str) -> Optional[int]:
        if INT16_MIN <= v <= INT16_MAX:
            return v
        self.diags.error("E034", node.span,
                         f"{_code(param)} of `{_shown(node)}` is {v}{unit}, which does not fit "
                         f"the robot's 16-bit int ({INT16_MIN}..{INT16_MAX})",
                         help="split the motion into several shorter ones with `then`"
                         if param == "distance" else None)
        return None

    def _choice(self, value, p: Param) -> Optional[str]:
        """The C text of a value of an enumerated parameter (`led3`, `haa`,
        `mute`, or a number its Choices accept)."""
        choices = p.choices
        if isinstance(value, ast.ConstRef) and not value.negative:
            choice = choices.get(value.name.name)
            if choice is not None:
                return choice.c
            if value.name.name not in self.consts or choices.numbers is None:
                names = choices.names()
                self.diags.error("E041", value.name.span,
                                 f"unknown {choices.what} {_code(value.name.name)}",
                                 help=_then(did_you_mean(value.name, names),
                                            f"{_code(p.name)} is one of {choices.describe()}"))
                return None
        if choices.numbers is None:
            self.diags.error("E041", value.span,
                             f"{_code(p.name)} names {_article(choices.what)} {choices.what}, "
                             "not a number",
                             help=f"write one of {choices.describe()}")
            return None
        q = self._value(value, INT, p.name)
        if q is None or not self._whole(value, q.value):
            return None
        lo, hi = choices.numbers
        if not lo <= q.value <= hi:
            self.diags.error("E042", value.span,
                             f"{_code(p.name)} `{_shown(value)}` is outside {lo}..{hi}",
                             help=f"the numbered {choices.what}s are {lo}..{hi}; the others have "
                                  f"names: {', '.join(map(_code, choices.names()))}")
            return None
        return str(int(q.value))

    def _priority(self, value) -> Optional[int]:
        """A rule's priority: a whole number 0..PRIORITY_MAX, 0 without one."""
        if value is None:
            return 0
        priority = self._plain(value, INT, 0, PRIORITY_MAX)
        if priority is not None:
            return priority
        q = self._value(value, INT, "priority")
        if q is None or not self._whole(value, q.value):
            return None
        if not 0 <= q.value <= PRIORITY_MAX:
            self.diags.error("E042", value.span,
                             f"priority `{_shown(value)}` is outside 0..{PRIORITY_MAX}",
                             help="rules without a priority have 0; a higher number wins the motors")
            return None
        return int(q.value)

    # -- actions --

    def _named_calls(self, name: str) -> list:
        """The calls of named actions in action `name`'s body."""
        return [call for step in self.actions[name].body.steps for call in step.calls
                if isinstance(call, ast.Call) and not call.args
                and call.name.name in self.actions and call.name.name not in self.externs]

    def _resolve_named_actions(self):
        """Resolve every named action, the actions it runs first. A
        depth-first walk with a stack of its own rather than recursion, so a
        chain of thousands of actions is fine; a call back into an action
        still being walked closes a cycle (E023 when its body is resolved)."""
        state: dict = {}            # name -> "open" while walked, "done" after
        order = []
        for root in self.actions:
            if root in state:
                continue
            state[root] = "open"
            stack = [(root, iter(self._named_calls(root)))]
            while stack:
                name, calls = stack[-1]
                for call in calls:
                    callee = call.name.name
                    if callee not in state:
                        state[callee] = "open"
                        stack.append((callee, iter(self._named_calls(callee))))
                        break
                    if state[callee] == "open":
                        self._cycle_calls.add(id(call))
                else:
                    stack.pop()
                    state[name] = "done"
                    order.append(name)
        for name in order:
            self._resolved_actions[name] = self._body(self.actions[name].body)

    def _named_action(self, name: str) -> list:
        return self._resolved_actions.get(name, [])

    def _body(self, body: ast.ActionBody) -> list:
        steps = []
        for step in body.steps:
            calls = []
            for call in step.calls:
                resolved = self._call(call)
                if resolved is not None:
                    calls.append(resolved)
            steps.append(calls)
        return steps

    def _call(self, call) -> Optional[ResolvedCall]:
        if isinstance(call, ast.EnterCall):
            return check_modes.enter_call(self, call)
        if isinstance(call, ast.CancelCall):
            name = call.rule.name
            if name not in self.rule_names:
                self.diags.error("E012", call.rule.span, f"unknown rule {_code(name)}",
                                 help=did_you_mean(call.rule, self.rule_names) or
                                 f"name the rule to cancel: `rule {name}: on ...`")
                return None
            return ResolvedCall("cancel", name, {}, {}, call)
        name = call.name.name
        canonical = ACTION_ALIASES.get(name, name)
        if canonical in STANDARD_ACTIONS:
            self.called.add(canonical)
            return self._standard_action(canonical, call)
        if name in self.externs and self.externs[name].kind == "action":
            info = self.externs[name]
            self.used_actions.add(name)
            bound = self._bind(call.name, call.args, info.params, "action")
            converted = self._convert(bound, info.params) if bound is not None else None
            if converted is None:
                return None
            return ResolvedCall("extern", name, converted[0], converted[1], call)
        if name in self.actions:
            self.used_actions.add(name)
            if call.args:
                self.diags.error("E016", call.span, f"action {_code(name)} takes no arguments",
                                 help=Fix(call.span, name, f"write `{name}` alone; named actions "
                                                           "have no parameters"),
                                 notes=[Note(f"{_code(name)} is defined here", self.actions[name].span)])
                return None
            if id(call) in self._cycle_calls:
                self.diags.error("E023", call.name.span,
                                 f"action {_code(name)} is defined in terms of itself",
                                 help="an action cannot run itself; use a `repeat` rule to do something again")
                return None
            return ResolvedCall("named", name, {}, {}, call)
        if self.broken_externs.get(name) == "action":
            return None               # its declaration is already reported
        if name in self.externs:      # an extern event used as an action
            self.diags.error("E011", call.name.span,
                             f"{_code(name)} is an event, not an action",
                             notes=[Note("declared here", self.externs[name].node.span)])
            return None
        candidates = set(STANDARD_ACTIONS) | set(self.actions) | {
            n for n, e in self.externs.items() if e.kind == "action"}
        self.diags.error("E011", call.name.span, f"unknown action {_code(name)}",
                         help=did_you_mean(call.name, candidates) or
                         f"define it with `action {name} = ...` or declare it with "
                         f"`extern action {name}(...) from \"{name}.c\"`")
        return None

    def _standard_action(self, name: str, call: ast.Call) -> Optional[ResolvedCall]:
        params = STANDARD_ACTIONS[name].params
        bound = self._bind(call.name, call.args, params, "action")
        if bound is None:
            return None
        converted = self._convert(bound, params)
        if converted is None:
            return None
        values, shown = converted
        geo = self.geo
        if name == "start_curve":
            radius = self._value(bound["radius"].value, DISTANCE, "radius").mm(geo)
            if radius < 0:
                self.diags.error("E036", bound["radius"].value.span,
                                 f"`radius` cannot be negative (`{shown['radius']}`)",
                                 help="a positive `degrees` turns left, a negative one right")
                return None
            degrees = self._value(bound["degrees"].value, ANGLE, "degrees").value
            outer, inner = curve_wheels(radius, degrees, values["speed"], geo)
            outer_steps = self._fits16(round_nearest(outer), bound["degrees"].value,
                                       "degrees", " steps of the outer wheel")
            if outer_steps is None:
                return None
            inner_speed = round_nearest(inner)
            if abs(inner_speed) > geo.max_speed:
                self.diags.error("E035", call.span,
                                 f"this curve drives the inner wheel at {abs(inner_speed)} steps/s, "
                                 f"above the robot's maximum of {geo.max_speed:.0f}",
                                 help="lower `speed`")
                return None
            values["radius"] = self._fits16(round_nearest(radius), bound["radius"].value,
                                            "radius", " mm")
            if values["radius"] is None:
                return None
            values["outer_steps"] = outer_steps
            values["inner_speed"] = inner_speed
        return ResolvedCall("standard", name, values, shown, call)

    # -- events --

    def _event(self, call: ast.Call) -> Optional[ResolvedEvent]:
        name = call.name.name
        canonical = EVENT_ALIASES.get(name, name)
        spec = STANDARD_EVENTS.get(canonical)
        if spec is not None and spec.params is None:
            return self._sensor(call, canonical)
        if spec is not None:
            params = spec.params
            bound = self._bind(call.name, call.args, params, "event")
            converted = self._convert(bound, params) if bound is not None else None
            if converted is None:
                return None
            return ResolvedEvent("standard", canonical, converted[0], node=call)
        info = self.externs.get(name)
        if info is not None and info.kind == "event":
            bound = self._bind(call.name, call.args, info.params, "event")
            converted = self._convert(bound, info.params) if bound is not None else None
            if converted is None:
                return None
            return ResolvedEvent("extern", name, converted[0], node=call)
        if self.broken_externs.get(name) == "event":
            return None
        if info is not None or name in self.actions:
            self.diags.error("E010", call.name.span, f"{_code(name)} is an action, not an event",
                             help="a rule reads `on EVENT do ACTION`")
            return None
        candidates = set(STANDARD_EVENTS) | {n for n, e in self.externs.items() if e.kind == "event"}
        self.diags.error("E010", call.name.span, f"unknown event {_code(name)}",
                         help=did_you_mean(call.name, candidates) or
                         f"the standard events are {', '.join(map(_code, STANDARD_EVENTS))}; "
                         f"declare others with `extern event {name}(...) from \"{name}.c\"`")
        return None

    def _sensor(self, call: ast.Call, event: str = "sensor") -> Optional[ResolvedEvent]:
        """`sensor` and `ambient`: conditions on the eight IR sensors."""
        if not call.args:
            self.diags.error("E017", call.span, f"`{event}` needs at least one condition",
                             help=f"write e.g. `{event}(ir0 > 300, ir7 > 300)`")
            return None
        conditions, seen, ok = [], {}, True
        for arg in call.args:
            if not isinstance(arg, ast.ConditionArg):
                self.diags.error("E024", arg.span, f"`{event}` takes conditions such as `ir0 > 300`",
                                 help="compare a sensor ir0..ir7 with a threshold using `>` or `<`")
                ok = False
                continue
            sensor = arg.sensor.name
            index = _SENSOR_INDEX.get(sensor)
            if index is None:
                self.diags.error("E031", arg.sensor.span, f"unknown sensor {_code(sensor)}",
                                 help=_then(did_you_mean(arg.sensor, SENSOR_NAMES),
                                            "the e-puck's proximity sensors are ir0..ir7"))
                ok = False
                continue
            if index in seen:
                self.diags.error("E025", arg.span, f"{_code(sensor)} is listed twice",
                                 help="each sensor has one threshold; keep one condition",
                                 notes=[Note("first listed here", seen[index].span)])
                ok = False
                continue
            seen[index] = arg
            threshold = self._plain(arg.value, INT, 0, THRESHOLD_MAX)
            if threshold is not None:
                conditions.append((index, arg.op, threshold))
                continue
            q = self._value(arg.value, INT, "threshold")
            if q is None or not self._whole(arg.value, q.value):
                ok = False
                continue
            if not 0 <= q.value <= THRESHOLD_MAX:
                self.diags.error("E032", arg.value.span,
                                 f"threshold `{_shown(arg.value)}` is outside 0..{THRESHOLD_MAX}",
                                 help="proximity readings are 12-bit: 0 (nothing near) to 4095 (touching)"
                                 if event == "sensor" else
                                 "ambient light readings are 12-bit: 0 to 4095")
                ok = False
                continue
            conditions.append((index, arg.op, int(q.value)))
        if not ok:
            return None
        return ResolvedEvent("standard", event, {}, tuple(sorted(conditions)), node=call)

    # -- whole-program warnings --

    def _never_fire(self, out: CheckedProgram, complete: bool):
        needs = {"timer": ("set_timer", "W001", "no action runs `set_timer`",
                           "add `set_timer` to an action, e.g. `on immediate do set_timer`"),
                 "sensor": ("start_sensor", "W002", "no action runs `start_sensor`",
                            "add `start_sensor` to an action, e.g. `on immediate do start_sensor`")}
        no_motion = complete and not (self.called & MOTION_ACTIONS) \
            and not any(e.kind == "action" for e in self.externs.values())
        for rule in out.rules:
            event, node = rule.event, rule.node
            if event.kind != "standard":
                continue
            if event.name in needs:
                action, code, why, fix = needs[event.name]
                if action not in self.called and complete:
                    self.diags.warning(code, node.event.span, f"this rule can never fire: {why}",
                                       help=fix)
            elif event.name == "stop_motor":
                if no_motion:
                    self.diags.warning("W003", node.event.span,
                                       "this rule can never fire: no action starts a motion",
                                       help="`stop_motor` fires when a `start_straight` or "
                                            "`start_curve` motion ends")
            elif event.name == "immediate" and rule.repeat:
                self.diags.warning("W004", node.span,
                                   "`immediate repeat` runs its action at every poll, about 1000 times a second",
                                   help="remove `repeat` to run it once at start, or use `timer(...) repeat`")

    def _unused(self):
        for name, node in self.actions.items():
            if name not in self.used_actions:
                self.diags.warning("W005", node.name.span, f"action {_code(name)} is never used",
                                   help=f"use it in a rule (`on immediate do {name}`) or remove it")
        for name, info in self.externs.items():
            if info.kind == "action" and name not in self.used_actions:
                self.diags.warning("W005", info.node.name.span,
                                   f"extern action {_code(name)} is never used",
                                   help=f"use it in a rule or remove the declaration")
        for name, node in self.consts.items():
            if name not in self.const_used:
                self.diags.warning("W007", node.name.span, f"constant {_code(name)} is never used",
                                   help="use it or remove it")
        if not any(isinstance(s, ast.Rule) for s in self.program.statements):
            self.diags.warning("W006", Span(1, 1, 1, 1), "this program has no rules: it does nothing",
                               help="add a rule, e.g. `on immediate do start_straight(200, 10 cm)`")


@lru_cache(maxsize=1)
def runtime_geometry_limits() -> tuple[int, int]:
    """EPUCK_MAX_GEOMETRY_UM and EPUCK_MAX_STEPS_PER_REV of the runtime
    header, so that the checker and the runtime cannot disagree."""
    header = (runtime_dir() / "epuckrt.h").read_text(encoding="utf-8")
    found = dict(re.findall(r"#define\s+(EPUCK_MAX_GEOMETRY_UM|EPUCK_MAX_STEPS_PER_REV)\s+(\d+)",
                            header))
    return int(found["EPUCK_MAX_GEOMETRY_UM"]), int(found["EPUCK_MAX_STEPS_PER_REV"])


_ROBOT_EXAMPLE = {"wheel_diameter": "41 mm", "wheel_circumference": "128.8 mm",
                  "axle": "53 mm", "steps_per_rev": "1000", "max_speed": "1000 steps/s"}


def _clip(text: str, limit: int = 24) -> str:
    return text if len(text) <= limit else text[:limit] + "..."


def _article(word: str) -> str:
    return "an" if word[:1] in "aeiouAEIOU" or word == "LED" else "a"


def _then(fix: Optional[Fix], more: str):
    """A fix followed by more help, or the help alone."""
    return fix.then(more) if fix is not None else more


def _either(names) -> str:
    names = [_code(n) for n in names]
    return names[0] if len(names) == 1 else ", ".join(names[:-1]) + " or " + names[-1]


def _count(n: int) -> str:
    return {0: "no arguments", 1: "1 argument"}.get(n, f"{n} arguments")


def _signature_help(name: str, params) -> str:
    if not params:
        return f"write `{name}` with no arguments"
    return f"write `{name}({', '.join(f'{p.name}: {_example_of(p)}' for p in params)})`"


def _example_of(p: Param) -> str:
    return p.choices.values[0].name if p.choices is not None else _example(p.kind)


def _example(kind: str) -> str:
    return {DISTANCE: "10 cm", SPEED: "300 steps/s", ANGLE: "90 deg",
            DURATION: "2 s", INT: "3"}[kind]


def check(program: ast.Program, diags: Collector, **options) -> CheckedProgram:
    return Checker(program, diags, **options).check()
