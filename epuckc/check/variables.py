"""Variables: their declarations and assignments (the intervals of their
values are ranges.py's)."""
from __future__ import annotations

from typing import Optional

from ..diagnostics import Note
from ..stdlib.table import STANDARD_READINGS
from ..syntax import ast
from . import arrays, convert
from .exprs import _kind_word
from .messages import _code, did_you_mean
from .program import Expr, ResolvedCall, VarInfo


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
        if isinstance(stmt.value, ast.ArrayLit):
            info = arrays.declare_var(self, stmt)
            if info is not None:
                self.vars[name] = info
                self._trace_ids += info.size
            return
        value = self._literal(stmt.value, allow_vars=False)
        if value is None:
            return
        self.vars[name] = VarInfo(name, value.kind, value.value, value.value, value.value,
                                  self._trace_ids, stmt)
        self._trace_ids += 1

    def _assigned(self, call: ast.Assign, info: VarInfo) -> Optional[Expr]:
        """The value an assignment gives its variable (`x += e` is x + e;
        `a[i] += e` is the element + e: "cur"), as it is stored: saturated to
        16 bits."""
        if call.value.__class__ is ast.ArrayLit:
            return self._assigned_array(call, info)
        if convert.is_fraction(call.value):     # `a = 0.8`: E038 in the variable's unit
            self._whole(call.value, call.value.value, info.kind)
            return None
        value = self._expr(call.value)
        if value is None:
            return None
        if call.op == "=":
            return self._store(self._adapt(value, info.kind))
        current = Expr("cur" if call.index is not None else "var", info.kind, info.lo, info.hi,
                       name=info.name, node=call.target)
        total = self._binary("+" if call.op == "+=" else "-", current, value, call)
        return None if total is None else self._store(total)

    def _assigned_array(self, call: ast.Assign, info: VarInfo) -> Optional[Expr]:
        """`a = [e0, e1, ...]` (and `fill(a, v)`, whose ArrayLit has one
        item for every element): each element's value as it is stored, all
        computed before any is stored (`a = [a[1], a[0]]` swaps), gathered
        in an "elements" Expr whose interval is their hull (an array's
        interval is its elements')."""
        items = call.value.items
        if not info.size:
            arrays.not_an_array(self, call.target, "it holds one value; give it one value")
            return None
        if len(items) != info.size:
            self.diags.error("E061", call.value.span,
                             f"{_code(info.name)} has {info.size} elements, and this gives "
                             f"{len(items)}", help=f"give every element its value (or all "
                             f"one value: `fill({info.name}, 0)`)",
                             notes=[Note(f"{_code(info.name)} is declared here",
                                         info.node.span)])
            return None
        fill = len(items) > 1 and all(item is items[0] for item in items)
        elements = [self._expr(item) for item in (items[:1] if fill else items)]
        if None in elements:
            return None
        stored = []
        for e in elements:
            if not self._is_number(e, "an element"):
                return None
            e = self._adapt(e, info.kind)
            if e.kind != info.kind:
                self._kind_clash(ast.PositionalArg(e.node, e.node.span), info.kind, e.kind,
                                 f"the elements of {_code(info.name)} are "
                                 f"{_kind_word(info.kind)} (from its initial value)",
                                 notes=[Note(f"{_code(info.name)} is declared here",
                                             info.node.span)])
                return None
            stored.append(self._store(e))
        # `fill`: its one value (computed once), for as many elements
        return Expr("fill" if fill else "elements", info.kind, min(e.lo for e in stored),
                    max(e.hi for e in stored), tuple(stored), value=len(items),
                    node=call.value)

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
        index = None
        if call.value.__class__ is ast.ArrayLit:
            pass                                # the whole array (`_assigned_array`)
        elif call.index is not None or info.size:
            ref = arrays._ref(self, call.target) if info.size else None
            if ref is None:
                arrays.not_an_array(self, call.target, "it holds one value")
                return None
            if call.index is None:
                arrays.bare_use(self, call.target, call.target)
                return None
            index = arrays.index_value(self, ref, call.index, call)
            if index is None:
                return None
        self.vars_used.add(name)
        self.vars_assigned.add(name)
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
        values = {"value": value} if index is None else {"value": value, "index": index}
        return ResolvedCall("assign", name, values, {"value": self._text(call.value)},
                            call, dynamic=True)

