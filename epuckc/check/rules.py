"""Events and rules: each rule's event and its conditions, priorities, and the
warning for rules that can never fire."""
from __future__ import annotations

from typing import Optional

from ..diagnostics import Note
from ..stdlib.table import (EVENT_ALIASES, MOTION_ACTIONS, SENSOR_NAMES, STANDARD_EVENTS,
                            THRESHOLD_MAX)
from ..stdlib.units import INT
from ..syntax import ast
from . import devices, modes, splice
from .messages import _code, _shown, _then, did_you_mean
from .program import CheckedProgram, ResolvedEvent, ResolvedRule

PRIORITY_MAX = 255         # `priority N`: 0 (the default) .. 255
_SENSOR_INDEX = {name: index for index, name in enumerate(SENSOR_NAMES)}    # ir0 -> 0


class Rules:
    """The checker's events and rules (a part of Checker)."""

    def _rule(self, rule: ast.Rule) -> Optional[ResolvedRule]:
        splice.check_depth(self, rule)      # (its named actions spliced in: E056)
        if rule.trigger == "on":
            event = self._event(rule.event)
        else:
            event = self._head_event(rule)
        guard = self._condition(rule.guard) if rule.guard is not None else None
        body = self._guarded_body(rule.body, guard)
        priority = self._priority(rule.priority)
        modes.check_rule(self, rule, event)
        if event is None or priority is None or (rule.guard is not None and guard is None):
            return None
        # `every` stays armed: it fires at each period
        repeat = rule.repeat or rule.trigger == "every"
        return ResolvedRule(rule.name.name if rule.name else None, event, repeat, body, rule,
                            priority, rule.mode.name if rule.mode else None, guard)

    def _head_event(self, rule: ast.Rule) -> Optional[ResolvedEvent]:
        """`when COND`, `every D`, `after D`."""
        call = rule.event
        arg = call.args[0].value
        if rule.trigger != "when" and rule.repeat:
            keyword = call.name.name
            self.diags.error("E055", rule.span if rule.span.line == rule.span.end_line
                             else call.span,
                             f"`{keyword}` takes no `repeat`",
                             help="`every` fires at each period by itself" if keyword == "every"
                             else "`after` fires once; for a period write `every`")
            return None
        if rule.trigger == "when":
            start = len(self.diags.items)
            condition = self._condition(arg)
            if condition is None:
                return None
            # a comparison inside that is always true or false has said so
            if condition.constant and not any(d.code == "W016" for d in self.diags.items[start:]):
                self.diags.warning("W016", arg.span,
                                   f"this condition is always "
                                   f"{'true' if condition.value else 'false'}",
                                   help="a `when` rule fires when its condition becomes true: "
                                        "it needs a variable or a reading")
            return ResolvedEvent("standard", "when", {"condition": condition}, node=call)
        spec = STANDARD_EVENTS[rule.trigger]
        bound = {spec.params[0].name: call.args[0]}
        converted = self._convert(bound, spec.params,
                                  what=f"the period of `{rule.trigger}` is fixed: for a "
                                       f"changing one, use a variable and a `when` rule")
        if converted is None:
            return None
        return ResolvedEvent("standard", rule.trigger, converted[0], node=call)

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

    def _event(self, call: ast.Call) -> Optional[ResolvedEvent]:
        name = call.name.name
        canonical = EVENT_ALIASES.get(name, name)
        spec = STANDARD_EVENTS.get(canonical)
        if spec is not None and spec.params is None:
            return self._sensor(call, canonical)
        if spec is not None:
            if not devices.require(self, spec.device, canonical, call.name.span):
                return None
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

    def _may_never_fire(self, out: CheckedProgram, events: set):
        """The rules _never_fire looks at: at least those that may_never_fire
        whose event is one of `events` (the language server keeps them by
        blocks of rules, and by event)."""
        return out.rules

    def _never_fire(self, out: CheckedProgram, complete: bool):
        needs = {"timer": ("set_timer", "W001", "no action runs `set_timer`",
                           "add `set_timer` to an action, e.g. `on immediate do set_timer`"),
                 "sensor": ("start_sensor", "W002", "no action runs `start_sensor`",
                            "add `start_sensor` to an action, e.g. `on immediate do start_sensor`")}
        no_motion = complete and not (self.called & MOTION_ACTIONS) \
            and not any(e.kind == "action" for e in self.externs.values())
        # (the events of the rules that can be warned about)
        events = {"immediate"} | ({"stop_motor"} if no_motion else set()) | {
            event for event, (action, *_) in needs.items() if action not in self.called and complete}
        for rule in self._may_never_fire(out, events):
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


def may_never_fire(rule) -> bool:
    """Whether _never_fire can say something of a resolved rule."""
    event = rule.event
    return event.kind == "standard" and (
        event.name in ("timer", "sensor", "stop_motor")
        or (event.name == "immediate" and bool(rule.repeat)))
