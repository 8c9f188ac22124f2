"""Calls: binding arguments to parameters (by position or name), converting
them, and resolving a call to a standard action, an extern, a named action,
`enter` or `cancel`."""
from __future__ import annotations

from typing import Optional

from ..base.source import Span
from ..diagnostics import Fix, Note
from ..stdlib.table import ACTION_ALIASES, CHOICE, STANDARD_ACTIONS
from ..stdlib.units import ANGLE, DISTANCE, curve_wheels, round_nearest
from ..syntax import aseba, ast
from . import arrays, devices, modes
from .messages import _code, _count, _shown, _signature_help, did_you_mean
from .program import Expr, ResolvedCall


class Calls:
    """The checker's calls of actions (a part of Checker)."""

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
        spec = STANDARD_ACTIONS.get(call_name.name) if what == "action" else None
        misuse = spec.misuse if spec is not None and not params else ""
        help_text = (f"write `{call_name.name}` alone: {misuse}" if misuse
                     else _signature_help(call_name.name, params))
        for arg in args:
            if isinstance(arg, ast.ConditionArg):
                self.diags.error("E024", arg.span,
                                 f"a condition such as `{arg.sensor.name} {arg.op} ...` "
                                 f"can only be given to `sensor` or `ambient`",
                                 help=help_text)
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
                             f"but {given} {'is' if given == 1 else 'are'} given",
                             help=help_text)
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

    def _convert(self, bound: dict, params, dynamic: bool = False,
                 what: str = "") -> Optional[tuple[dict, dict]]:
        """Check and convert each bound argument to its runtime integer; an
        argument computed while the program runs to its Expr, where `dynamic`
        (else an error that says what must be fixed: `what`)."""
        values, shown, ok = {}, {}, True
        for p in params:
            arg = bound[p.name]
            value = arg.value
            if value.__class__ is not ast.Number and p.kind != CHOICE and (
                    self._is_dynamic(value) or (dynamic and value.__class__ is ast.ConstRef
                                                and value.name.name not in self.consts)):
                if not dynamic:
                    self.diags.error("E052", arg.value.span,
                                     f"{_code(p.name)} must be a fixed value, but "
                                     f"`{self._text(arg.value)}` changes as the program runs",
                                     help=what or "write a number (with its unit) or a "
                                                  "constant")
                    ok = False
                    continue
                e = self._dynamic_arg(arg.value, p, "")
                if e is None:
                    ok = False
                    continue
                values[p.name], shown[p.name] = e, self._text(arg.value)
                continue
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

    def _call(self, call) -> Optional[ResolvedCall]:
        if isinstance(call, ast.Assign):
            return self._assign(call)
        if isinstance(call, ast.IfAction):
            return self._if_call(call)          # (branches.py)
        if isinstance(call, ast.EnterCall):
            return modes.enter_call(self, call)
        if isinstance(call, ast.CancelCall):
            name = call.rule.name
            if name not in self.rule_names:
                self.diags.error("E012", call.rule.span, f"unknown rule {_code(name)}",
                                 help=did_you_mean(call.rule, self.rule_names) or
                                 f"name the rule to cancel: `rule {name}: on ...`")
                return None
            return ResolvedCall("cancel", name, {}, {}, call)
        name = call.name.name
        if name == "fill" and name not in self.actions and name not in self.externs:
            return arrays.fill_call(self, call)         # `fill(a, v)`: a = [v, v, ...]
        canonical = ACTION_ALIASES.get(name, name)
        if canonical in STANDARD_ACTIONS:
            self.called.add(canonical)
            return self._standard_action(canonical, call)
        if name in self.externs and self.externs[name].kind == "action":
            info = self.externs[name]
            self.used_actions.add(name)
            bound = self._bind(call.name, call.args, info.params, "action")
            converted = self._convert(
                bound, info.params, what="an extern action's arguments are fixed when the "
                "program is compiled; pass a value that changes through a variable of your C "
                "file") if bound is not None else None
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
        if name == "sort":           # Aseba's `call math.sort(a)`
            aseba.sort_diagnostic(self.diags, call.name.span)
            return None
        candidates = set(STANDARD_ACTIONS) | set(self.actions) | {
            n for n, e in self.externs.items() if e.kind == "action"}
        self.diags.error("E011", call.name.span, f"unknown action {_code(name)}",
                         help=did_you_mean(call.name, candidates) or
                         f"define it with `action {name} = ...` or declare it with "
                         f"`extern action {name}(...) from \"{name}.c\"`")
        return None

    def _standard_action(self, name: str, call: ast.Call) -> Optional[ResolvedCall]:
        spec = STANDARD_ACTIONS[name]
        if not devices.require(self, spec.device, name, call.name.span):
            return None
        params = spec.params
        bound = self._bind(call.name, call.args, params, "action")
        if bound is None:
            return None
        converted = self._convert(bound, params, dynamic=spec.dynamic is not None,
                                  what=f"`{name}` takes fixed values: write a number with "
                                       f"its unit, or a constant")
        if converted is None:
            return None
        values, shown = converted
        if any(isinstance(v, Expr) for v in values.values()):
            # computed while the program runs: converted by the runtime, with
            # the fixed arguments in the same natural units
            for p in params:
                if not isinstance(values[p.name], Expr) and p.kind != CHOICE:   # (a choice: its C)
                    fixed = self._literal(bound[p.name].value)
                    if fixed is None:
                        return None
                    values[p.name] = self._adapt(fixed, p.kind)
            if name == "start_curve" and values["radius"].constant \
                    and values["radius"].value < 0:
                self.diags.error("E036", bound["radius"].value.span,
                                 f"`radius` cannot be negative (`{shown['radius']}`)",
                                 help="a positive `degrees` turns left, a negative one right")
                return None
            for p in params:
                if p.kind != CHOICE:
                    self._interval_warning(values[p.name], p, bound[p.name].value, name)
            return ResolvedCall("standard", name, values, shown, call, dynamic=True)
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
        elif name == "start_straight" and values["speed"] < 0 and values["distance"] < 0:
            self._backward_twice(bound["distance"].value, shown)
        return ResolvedCall("standard", name, values, shown, call)

    def _interval_warning(self, e, p, node, name: str):
        """W030: an expression whose interval can leave the whole numbers
        `p.lo`..`p.hi` its parameter carries (`send`'s byte)."""
        if p.lo is None or not isinstance(e, Expr) or (p.lo <= e.lo and e.hi <= p.hi):
            return
        if e.constant:
            self.diags.error(p.range_code, node.span,
                             f"`{name}` carries {p.lo}..{p.hi}, but `{self._text(node)}` is "
                             f"{e.value}", help=f"give a value in {p.lo}..{p.hi}")
            return
        text = self._text(node)
        self.diags.warning("W030", node.span,
                           f"`{text}` can be {e.lo}..{e.hi}, but `{name}` carries only "
                           f"{p.lo}..{p.hi}: a value outside is sent modulo {p.hi + 1}",
                           help=Fix(node.span, f"clamp({text}, {p.lo}, {p.hi})",
                                    f"clamp it: `clamp(..., {p.lo}, {p.hi})`"))

    def _backward_twice(self, distance, shown: dict):
        """W012: `start_straight(-300, -10 cm)` drives forward."""
        written = shown["distance"]
        help_text = "one minus is enough to back up"
        fix = (Fix(distance.span, written[1:].lstrip(), f"{help_text}: write "
                                                         f"`{written[1:].lstrip()}`")
               if written.startswith("-") else None)
        self.diags.warning("W012", distance.span,
                           f"a negative speed (`{shown['speed']}`) and a negative distance "
                           f"(`{written}`) drive forward: the two signs cancel",
                           help=fix or f"{help_text}: make the distance positive")
