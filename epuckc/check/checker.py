"""Semantic checks: names, arguments, kinds, ranges, rules that cannot fire.

The checker finds every problem it can in one run and resolves what is
right into a CheckedProgram: each call with its arguments converted to the
integers the runtime uses (steps, steps/s, degrees, ms). Code generation
starts from that and never re-derives a value.
"""
from __future__ import annotations

import bisect
import operator
from pathlib import Path
from typing import Optional

from ..diagnostics import ERROR, Collector
from ..syntax import ast
from . import modes, races
from .branches import Branches
from .calls import Calls
from .exprs import Exprs
from .variables import Variables
from .ranges import Ranges
from .externs import Externs
from .names import Names
from .overflow import Overflow
from .program import CheckedProgram
from .robot import RobotSettings
from .rules import Rules
from .state import Declarations, Facts, Memories, Step
from .values import Values

_START = operator.itemgetter(0, 1)     # a Span's (line, column)


class Checker(Names, Externs, RobotSettings, Values, Exprs, Variables, Ranges, Calls, Rules,
              Overflow, Branches):
    """The checker's state and its order of work; each concern's methods live in
    the mixin of its module (names.py, externs.py, robot.py, values.py,
    exprs.py, variables.py, ranges.py, calls.py, rules.py, overflow.py,
    branches.py), the whole-program analyses in modes.py and
    arbitration.py."""

    # the rules as runs (owner, resolved rules), each the same while its owner
    # is: what W009 keeps by run (the language server's, ide/recheck.py)
    rule_groups = None

    def __init__(self, program: ast.Program, diags: Collector,
                 base_dir: Optional[Path] = None, target: str = "host", world: bool = True):
        self.program = program
        self.target = target             # what it is built for: the devices it has
        self.world = world               # False: run without a world (devices.py, W070)
        self.diags = diags               # the sink, the same object throughout (Collector.capture)
        self.base_dir = base_dir
        # the state, by owner and lifetime (state.py); the tables, facts and
        # memories read as attributes (self.vars, self.called, ...) are theirs
        self.decls = Declarations()
        self.facts = Facts()
        self.memories = Memories()
        # per check, of resolving the named actions (names.py, modes.py)
        self._cycle_calls: set = set()   # ids of calls that close a cycle of named actions
        self._resolved_actions: dict = {}
        self._flat_actions: dict = {}    # named action -> flattened steps (modes.flat_steps)

    def apart(self, decls: Optional[Declarations] = None) -> "_Apart":
        """`with checker.apart() as step:` a step (a rule, the named actions)
        checked with its own diagnostics, facts and memories, given back
        in `step` (state.Step) when it ends, the checker's own as they
        were; `decls`: the declarations it reads instead of the checker's
        (a copy whose tables note what it looked up, ide/watch.py)."""
        return _Apart(self, decls)

    # -- asked by the language server's hover, apart from the check --

    def evaluated(self, node):
        """The Expr (unit and interval) of expression `node`, checked apart:
        what it says and finds is not the check's."""
        with self.apart():
            return self._expr(node)

    def converted(self, value, param):
        """(the quantity, the runtime integer) a number or constant is where
        `param` wants it (None, or an integer None, where it is not
        valid), checked apart."""
        with self.apart():
            q = self._value(value, param.kind, param.name)
            return None if q is None else (q, self._to_runtime(q, param, value))

    # -- entry point --

    def check(self) -> CheckedProgram:
        robot_given = self._declarations()
        self._var_ranges()
        out = CheckedProgram(self.program.file, self.geo, robot_given=robot_given)
        out.externs = self.externs
        out.variables = self.vars
        out.const_arrays = {name: tuple(e.value for e in values)
                            for name, (_, values) in self.const_arrays.items()}
        self._resolve_actions(out)
        out.modes, out.initial_mode = list(self.modes), self.initial_mode
        self._rules(out)
        # Warnings that conclude from an absence ("no action runs set_timer",
        # "never used") are drawn only from a complete program: a statement
        # or call dropped by an error may be the very one that was missing,
        # and a warning caused by an error is noise (a cascade).
        complete = not self._has_errors()
        self._never_fire(out, complete)
        if complete:
            self._unused()
        out.devices = frozenset(self.devices_used)
        self._modes_program(out, complete)
        self._races(out)
        self._no_warnings_beside_errors()
        return out

    def _has_errors(self) -> bool:
        return self.diags.has_errors

    def _races(self, out: CheckedProgram):
        """W009 (races.py), by the runs of rules (rule_groups) when kept."""
        races.check_program(self, out, self.rule_groups)

    def _modes_program(self, out: CheckedProgram, complete: bool):
        """modes.check_program (the language server gives it its rules in
        modes and the modes they enter, kept by blocks of rules)."""
        modes.check_program(self, out, complete)

    def _declarations(self) -> bool:
        """Every declaration and the robot block (the language server
        replays them while the statements that declare are the same);
        whether the program describes the robot."""
        self._declare()
        robot_blocks = self.program.of_type(ast.RobotBlock)
        self._robot(robot_blocks)
        return bool(robot_blocks)

    def _rules(self, out: CheckedProgram):
        """Resolve every rule, in the file's order (the language server
        replays unchanged ones, ide/recheck.py)."""
        for rule in self.program.of_type(ast.Rule):
            resolved = self._rule(rule)
            if resolved is not None:
                out.rules.append(resolved)

    def _no_warnings_beside_errors(self):
        """One root mistake gives one error: a warning about a statement
        that has an error (its own place or a note's is in it) is dropped,
        as W009 about a rule whose call is wrong would be; the error is
        what to fix, and the warning may be gone once it is fixed."""
        items = self.diags.items
        errors = [d.span for d in items if d.severity == ERROR]
        if not errors or len(errors) == len(items):
            return
        # (sorted: the language server numbers statements' lines by their ids)
        statements = sorted((s.span for s in self.program.statements
                             if getattr(s, "span", None)), key=_START)
        starts = list(map(_START, statements))

        def holder(span):
            i = bisect.bisect_right(starts, (span.line, span.column)) - 1
            if i >= 0 and (span.end_line, span.end_column) <= (statements[i].end_line,
                                                                statements[i].end_column):
                return i
            return None

        broken = {holder(span) for span in errors} - {None}
        if not broken:
            return

        def beside(d):
            return holder(d.span) in broken or any(
                n.span is not None and holder(n.span) in broken for n in d.notes)

        items[:] = [d for d in items if d.severity == ERROR or not beside(d)]   # in place: callers hold the list

    # Resolving the named actions and each rule are the steps that the
    # language server's incremental checker (epuckc/ide/incremental.py) reuses
    # from one keystroke to the next.

    def _resolve_actions(self, out: CheckedProgram):
        self._resolve_named_actions()
        for name, node in self.actions.items():
            out.actions[name] = self._named_action(name)
            out.action_nodes[name] = node


    # -- declarations --


    # -- the robot block --


    # -- values --


    # -- arguments --


    # -- actions --


    # -- events --


    # -- whole-program warnings --


def _forward(record: str, name: str) -> property:
    get = operator.attrgetter(f"{record}.{name}")

    def put(self, value):
        setattr(getattr(self, record), name, value)
    return property(get, put, doc=f"{record}.{name}")


# the records' fields, read and set as the checker's attributes by the
# modules of each concern (`self.vars`, `self._const_memo`)
for _record, _cls, _private in (("decls", Declarations, {"trace_ids"}),
                                ("facts", Facts, ()),
                                ("memories", Memories, {"const_memo", "const_reported",
                                                        "const_diagnostics"})):
    for _name in _cls.__match_args__:
        setattr(Checker, f"_{_name}" if _name in _private else _name, _forward(_record, _name))


class _Apart:
    __slots__ = ("checker", "decls", "step", "_saved", "_said")

    def __init__(self, checker: Checker, decls):
        self.checker, self.decls = checker, decls

    def __enter__(self) -> Step:
        c = self.checker
        self._saved = (c.facts, c.memories, c.decls)
        c.facts, c.memories = Facts(), Memories()
        if self.decls is not None:
            c.decls = self.decls
        self._said = c.diags.capture()
        self.step = Step(self._said.__enter__())
        return self.step

    def __exit__(self, *exc):
        c = self.checker
        self._said.__exit__(*exc)
        self.step.facts = c.facts.items()
        c.facts, c.memories, c.decls = self._saved
        return False


def check(program: ast.Program, diags: Collector, **options) -> CheckedProgram:
    return Checker(program, diags, **options).check()
