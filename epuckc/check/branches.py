"""`if C { A } else if D { B } else { E }` as an action: its conditions,
its branches, what it tells the variables inside each branch, and the
warnings about branches that never run.

An `if` runs in the poll of the step that holds it, like any other call
of the step, with the values the calls before it gave (docs/language.md,
section 2.8). A branch is one step: its calls run together, in order, in
that same poll. `then` inside a branch [E080] would make the steps of
the rule's sequence (each run once the motion of the one before has
ended, docs/runtime.md; fixed when compiling) depend on a condition; so
would a named action of several steps [E080]. A motion started in a
branch is a motion like any other: it goes on after the step, and the
rule holds the motors as it would without the `if`.

The whole-program analyses read an `if` as "any branch may run": every
call of every branch may happen (modes.may_run), which is sound for what
they conclude from calls that may happen (W009, W010, E045, the variables'
intervals) and leaves out of what they conclude from calls that must
happen (W011's `enter`, arbitration's `set_timer` first) the calls of a
branch.
"""
from __future__ import annotations

from dataclasses import replace
from typing import Optional

from ..base.source import Span
from ..base.views import Overlaid
from ..diagnostics import Note
from ..syntax import ast
from . import conditions
from .messages import _code
from .modes import flat_steps
from .program import ResolvedCall, with_interval


class Branches:
    """The checker's `if` actions (a part of Checker)."""

    def _if_call(self, call: ast.IfAction) -> Optional[ResolvedCall]:
        """An `if`: each condition checked (W016 where it is decided when
        compiling, W080 for the branches that follow an always-true one),
        each branch's calls resolved with the intervals its condition (and
        the failed ones before it) leave the variables."""
        ok = True
        branches = []
        failed = conditions.TRUE_BOXES      # where the conditions before all failed
        decided_true = None                 # the first condition that always holds
        for branch in call.branches:
            start = len(self.diags.items)
            # (checked where the conditions before it failed, as the C
            # compiler reads it: `if v - 1000 != -v {} else if v > -v`)
            condition = self._condition_where(branch.condition, failed)
            if condition is None:
                ok = False
                calls = self._branch(branch.body, None)
                continue
            last = branch is call.branches[-1] and call.otherwise is None
            # (always true before other branches: W080 says it, with them)
            if condition.constant and decided_true is None and (
                    not condition.value or last) and not any(
                    d.code == "W016" for d in self.diags.items[start:]):
                self.diags.warning(
                    "W016", branch.condition.span,
                    f"this condition is always {'true' if condition.value else 'false'}",
                    help="its branch runs every time: write its actions without the `if`"
                    if condition.value else "its branch never runs: remove it, or compare "
                    "a variable or a reading")
            # (one meet per branch: a chain of n branches is linear in n)
            here = conditions.conjoined(failed, conditions.formula(condition))
            failed = conditions.conjoined(failed, conditions.formula(condition, False))
            calls = self._branch(branch.body, here if decided_true is None else None)
            if calls is None:
                ok = False
            branches.append((condition, calls))
            if condition.constant and condition.value and decided_true is None:
                decided_true = branch
        otherwise = None
        if call.otherwise is not None:
            otherwise = self._branch(call.otherwise, failed if decided_true is None else None)
            if otherwise is None:
                ok = False
        if decided_true is not None:
            self._dead_branches(call, decided_true)
        if not ok:
            return None
        return ResolvedCall("if", "if", {"branches": tuple(branches), "otherwise": otherwise},
                            {}, call, dynamic=True)

    def _dead_branches(self, call: ast.IfAction, decided: ast.IfBranch):
        """W080: the branches after a condition that always holds."""
        later = list(call.branches[call.branches.index(decided) + 1:])
        bodies = [b.span for b in later] + ([call.otherwise.span] if call.otherwise else [])
        if not bodies:
            return
        first = bodies[0]
        kinds = ([f"{len(later)} `else if`" if len(later) > 1 else "`else if`"] if later
                 else []) + (["`else`"] if call.otherwise else [])
        many = len(bodies) > 1
        self.diags.warning(
            "W080", Span(first.line, first.column, bodies[-1].end_line, bodies[-1].end_column),
            f"the {' and '.join(kinds)} branch{'es' if many else ''} never "
            f"run{'' if many else 's'}: `{self._text(decided.condition)}` is always true",
            help="remove the branches that never run, or make the condition one that can "
                 "be false",
            notes=[Note("the condition that always holds", decided.condition.span)])

    def _branch(self, body: ast.ActionBody, holds) -> Optional[list]:
        """A branch's calls (one step [E080]), checked with the intervals the
        conjunction `holds` (conditions.conjoined's boxes) leaves the
        variables (None: none narrowed)."""
        if len(body.steps) > 1:
            first_then = body.steps[1]
            self.diags.error(
                "E080", first_then.span,
                "`then` cannot go inside an `if` branch: a branch is one step, whose "
                "actions run together in one poll",
                help="put the sequence in a named action run by a rule, or make the `if` "
                     "its own step: `if C { A } then B` runs B after the `if` whatever it chose")
            for step in body.steps[1:]:
                for c in step.calls:
                    self._call(c)       # still checked: their own mistakes are reported
        bounds = {}
        if holds is not None:
            # (only the variables compared: the language server's memo of a
            # rule then depends on those alone, ide/incremental.py)
            base = {}
            for n in sorted(set().union(*(bounds for bounds, _ in holds))):
                info = self.vars.get(n)
                if info is not None:
                    base[n] = (info.lo, info.hi)
            # (a branch that cannot run is still checked, with the whole intervals)
            bounds = conditions.narrowed_where(holds, base) or {}
        calls = self._calls_narrowed(body.steps[0].calls, bounds)
        ok = len(body.steps) == 1
        for resolved in calls:
            if resolved.kind == "named" and len(flat_steps(self, [[resolved]])) > 1:
                node = self.actions[resolved.name]
                self.diags.error(
                    "E080", resolved.node.span,
                    f"action {_code(resolved.name)} has several steps (`then`): it cannot run "
                    f"inside an `if` branch, which is one step",
                    help="run it from a rule of its own (`when COND do "
                         f"{resolved.name}`), or split it so that the branch runs its first "
                         "step only",
                    notes=[Note(f"{_code(resolved.name)} is defined here", node.span)])
                ok = False
        return calls if ok else None

    def _condition_where(self, node, holds: tuple):
        """A condition checked with the variables it compares narrowed to
        what `holds` (boxes, conditions.py) leaves them; unnarrowed where
        it cannot hold (a branch that never runs is still checked)."""
        base = {}
        for n in sorted(set().union(*(bounds for bounds, _ in holds))):
            info = self.vars.get(n)
            if info is not None:
                base[n] = (info.lo, info.hi)
        bounds = conditions.narrowed_where(holds, base) if base else None
        if not bounds:
            return self._condition(node)
        table = self.vars
        self.vars = Overlaid(table, {n: with_interval(table[n], b) for n, b in bounds.items()})
        try:
            with self.diags.capture() as said:
                condition = self._condition(node)
        finally:
            self.vars = table
        where = Note("where the conditions before it in this `if` are false: "
                     + ", ".join(f"`{n}` is {lo}" + (f"..{hi}" if hi != lo else "")
                                 for n, (lo, hi) in bounds.items()))
        self.diags.items.extend(replace(d, notes=d.notes + (where,)) if d.code == "W016" else d
                                for d in said)
        return condition

    _whole_ranges = None    # name -> its VarInfo before any branch narrowed it, meanwhile

    def _calls_narrowed(self, calls, bounds: dict) -> list:
        """`calls` resolved in order, the variables in `bounds` given those
        intervals until a call may assign them (an assignment to one, a
        named action, or an `if` whose branches may): from the next call
        on, such a variable has its whole interval again (the one over
        every assignment, not the one an enclosing branch narrowed). The
        narrowed variables are VarInfo of their own in a view of the
        table (base/views.Overlaid); the table's are never changed."""
        if not bounds:
            return [r for r in map(self._call, calls) if r is not None]
        outermost = self._whole_ranges is None
        if outermost:
            self._whole_ranges = {}
        whole = self._whole_ranges
        table = self.vars
        over = {}
        for name, interval in bounds.items():
            info = table[name]
            whole.setdefault(name, info)        # (narrowed for the first time here)
            over[name] = with_interval(info, interval)
        out = []
        self.vars = Overlaid(table, over)
        try:
            for call in calls:
                resolved = self._call(call)
                if resolved is not None:
                    out.append(resolved)
                for inner in ast.calls_within((call,)):
                    if isinstance(inner, ast.Assign) and inner.target.name in whole:
                        over[inner.target.name] = whole[inner.target.name]
                    elif isinstance(inner, ast.Call) and inner.name.name in self.actions:
                        over.update(whole)
        finally:
            self.vars = table
            if outermost:
                self._whole_ranges = None
        return out
