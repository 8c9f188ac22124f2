"""Variables: their declarations, the intervals of their values (from every
assignment of the program, iterated to a fixed point and widened where
they keep growing), and assignments."""
from __future__ import annotations

from typing import Optional

from ..diagnostics import Collector, Note
from ..stdlib.table import STANDARD_READINGS
from ..stdlib.units import INT16_MAX, INT16_MIN
from ..syntax import ast
from .exprs import _kind_word
from .messages import _code, did_you_mean
from .program import BOOL, Expr, ResolvedCall, VarInfo

# passes of the variables' intervals before the growing ones are widened
RANGE_PASSES = 4
# rules that run at most once are joined once each, up to this many assignments
ONCE_MAX = 16
# passes that give back what widening took where the assignments bound it
NARROW_PASSES = 2


class Variables:
    """The checker's variables and assignments (a part of Checker; the
    expressions they hold are exprs.py's)."""

    def _declare_var(self, stmt: ast.VarDef, claim):
        name = stmt.name.name
        if name in STANDARD_READINGS:
            self.diags.error("E015", stmt.name.span,
                             f"{_code(name)} is already the name of a reading of the robot",
                             help=f"choose another name, e.g. `my_{name}`")
            return
        if not claim("const", stmt.name, "variable"):
            return
        value = self._literal(stmt.value, allow_vars=False)
        if value is None:
            return
        self.vars[name] = VarInfo(name, value.kind, value.value, value.value, value.value,
                                  len(self.vars), stmt)

    def _var_ranges(self):
        """Each variable's interval: its initial value joined with what
        every assignment of the program can give it."""
        if not self.vars:
            return
        assigns, once = [], []          # (the rules that run at most once: `once`)
        for stmt in self.program.statements:
            bodies = []
            if isinstance(stmt, ast.Rule):
                bodies.append(stmt.body)
            elif isinstance(stmt, ast.ActionDef):
                bodies.append(stmt.body)
            for body in bodies:
                found = [c for step in body.steps for c in step.calls
                         if isinstance(c, ast.Assign) and c.target.name in self.vars]
                runs_once = isinstance(stmt, ast.Rule) and not stmt.repeat \
                    and stmt.mode is None and stmt.trigger != "every"
                (once if runs_once else assigns).extend(found)
        if len(once) > ONCE_MAX:
            assigns, once = assigns + once, []
        if not assigns and not once:
            return
        saved = self.diags
        self.diags = Collector(saved.source)
        try:
            self._join_assigned(assigns)
            # each of `once` runs at most once, in any order among the others
            for _ in once:
                if not self._join_assigned(once, widen=False):
                    break
                self._join_assigned(assigns)
            self._narrow_ranges(assigns + once)
        finally:
            self.diags = saved

    def _narrow_ranges(self, assigns):
        """Gives back what widening took where the assignments bound it
        (`n = min(n + 1, 1000)`): every value a variable takes is its initial
        value or one an assignment gives from values within the intervals,
        so each interval may be met with the hull of those."""
        for _ in range(NARROW_PASSES):
            hulls = {name: (info.init, info.init) for name, info in self.vars.items()}
            for call in assigns:
                info = self.vars[call.target.name]
                value = self._assigned(call, info)
                if value is None or value.kind == BOOL:
                    return              # not every value is known: keep the intervals
                lo, hi = hulls[info.name]
                hulls[info.name] = (min(lo, value.lo), max(hi, value.hi))
            changed = False
            for name, (lo, hi) in hulls.items():
                info = self.vars[name]
                met = (max(info.lo, lo), min(info.hi, hi))
                if met != (info.lo, info.hi):
                    info.lo, info.hi = met
                    changed = True
            if not changed:
                return

    def _join_assigned(self, assigns, widen: bool = True) -> bool:
        """Joins what `assigns` can give into their variables' intervals,
        repeated to a fixed point (widened where they keep growing); with
        widen False, once. Whether an interval grew."""
        grew = False
        attempt = 0
        while True:                     # each widening takes a bound to an end: it stops
            changed = False
            for call in assigns:
                info = self.vars[call.target.name]
                value = self._assigned(call, info)
                if value is None or value.kind == BOOL:
                    continue
                lo, hi = min(info.lo, value.lo), max(info.hi, value.hi)
                if (lo, hi) != (info.lo, info.hi):
                    if widen and attempt >= RANGE_PASSES:       # still growing: widen
                        lo = INT16_MIN if lo < info.lo else lo
                        hi = INT16_MAX if hi > info.hi else hi
                    info.lo, info.hi = lo, hi
                    changed = grew = True
            attempt += 1
            if not changed or not widen:
                break
        return grew

    def _assigned(self, call: ast.Assign, info: VarInfo) -> Optional[Expr]:
        """The value an assignment gives its variable (`x += e` is x + e)."""
        value = self._expr(call.value)
        if value is None:
            return None
        if call.op == "=":
            return self._adapt(value, info.kind)
        current = Expr("var", info.kind, info.lo, info.hi, name=info.name, node=call.target)
        return self._binary("+" if call.op == "+=" else "-", current, value, call)

    def _assign(self, call: ast.Assign) -> Optional[ResolvedCall]:
        name = call.target.name
        info = self.vars.get(name)
        if info is None:
            if name in self.consts or name in STANDARD_READINGS:
                what = "constant" if name in self.consts else "reading of the robot"
                self.diags.error("E051", call.target.span,
                                 f"{_code(name)} is a {what}: it cannot be given a value",
                                 help=f"declare a variable instead: `var {name} = ...`"
                                 if name in self.consts else
                                 f"store it in a variable: `var my_{name} = 0` and "
                                 f"`my_{name} = {name}`")
            else:
                self.diags.error("E051", call.target.span, f"unknown variable {_code(name)}",
                                 help=did_you_mean(call.target, self.vars) or
                                 f"declare it first: `var {name} = 0`")
            return None
        self.vars_used.add(name)
        value = self._assigned(call, info)
        if value is None:
            return None
        self._overflow(value)
        if value.kind != info.kind:
            self._kind_clash(call, info.kind, value.kind,
                             f"variable {_code(name)} is {_kind_word(info.kind)} (from its "
                             f"initial value)", notes=[Note(f"{_code(name)} is declared here",
                                                            info.node.span)])
            return None
        return ResolvedCall("assign", name, {"value": value}, {"value": self._text(call.value)},
                            call, dynamic=True)

