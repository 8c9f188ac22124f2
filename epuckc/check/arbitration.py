"""Whole-program arbitration check [W009]: two rules of the same priority
that can fire in the same poll and both command the motors.

Within a poll the runtime runs the actions of the events that occurred
highest priority first, then in file order (docs/runtime.md). Between two
rules of one priority nothing arbitrates: both run, and the motor command
of the later one replaces the earlier one's, silently. That is the bug
priorities exist to prevent, so the checker names both rules and the one
that wins.

"Can fire in the same poll" is decided from the events alone, and errs on
the side of warning; two rules are known not to, when:
- they belong to two different modes (one mode is current at a time, and
  after `enter` no mode's rule fires in the rest of that poll);
- one is a one-shot `immediate` outside any mode (it fires at the first
  poll only) and the other waits for a `stop_motor` or a `timer`, which
  cannot occur at the first poll (nothing ran before it);
- both are `timer` rules outside modes whose firings (one-shot: at T;
  repeat: at every multiple of T, of one and the same timer) never meet;
- in one mode, its `on enter` rule (first poll after the entry) and a
  `stop_motor` rule: entering stops the motion of the mode left without a
  `stop_motor` event, so one could only come from a motion of a rule outside
  the mode ending at that very poll -- a deliberate blind spot, since the
  pattern `on enter do ... start_straight` + `on stop_motor repeat` is
  the usual way to write a behaviour;
- in one mode, an `on enter` rule whose first step runs `set_timer` and a
  later `timer` rule: polled after the timer restarted in the same poll,
  the timer rule cannot fire there.
A rule "commands the motors" when its action, through the named actions it
uses, calls `start_straight`, `start_curve` or `stop_motor`; extern
actions are not looked into.
"""
from __future__ import annotations

from ..diagnostics import Note
from ..stdlib.table import MOTION_ACTIONS, MOTOR_ACTIONS
from ..syntax import ast
from .messages import _shown
from .modes import flat_steps

# Beyond this many reports the rest are summed up in one: a file of
# thousands of racing rules needs one fix, not thousands of warnings.
MAX_REPORTS = 5


def _code(text: str) -> str:
    return f"`{text}`"


def _commands_motors(checker, steps, named: dict) -> bool:
    """Whether `steps` call a motor action, themselves or through the named
    actions they use; `named` memoises the answer of each named action
    (from its steps spliced as lowering splices them)."""
    for step in steps:
        for call in step:
            kind = call.kind
            if kind == "standard":
                if call.name in MOTOR_ACTIONS:
                    return True
            elif kind == "named":
                found = named.get(call.name)
                if found is None:
                    found = named[call.name] = any(
                        c.kind == "standard" and c.name in MOTOR_ACTIONS
                        for spliced in flat_steps(checker, [[call]]) for c in spliced)
                if found:
                    return True
    return False


def _periods_meet(va: dict, every_a: bool, vb: dict, every_b: bool) -> bool:
    """Whether an `every`/`after` rule and another, armed at the same poll,
    can fire at the same time."""
    ta, tb = va.get("period", va.get("delay")), vb.get("period", vb.get("delay"))
    if every_a and every_b:
        return True                     # at the least common multiple
    if not every_a and not every_b:
        return ta == tb
    period, once = (ta, tb) if every_a else (tb, ta)
    return once % period == 0


def _timer_meets(a, b) -> bool:
    """Whether timer rules a, b (outside modes) can fire at the same time."""
    ta, tb = a.event.values["time"], b.event.values["time"]
    if a.repeat and b.repeat:
        return True                     # at the least common multiple
    if not a.repeat and not b.repeat:
        return ta == tb
    every, once = (ta, tb) if a.repeat else (tb, ta)
    return once % every == 0


def _at_first_poll_only(rule) -> bool:
    """A one-shot `immediate` rule outside modes."""
    return rule.event.name == "immediate" and not rule.repeat and rule.mode is None


def can_fire_together(a, b) -> bool:
    ma, mb = a.mode, b.mode
    if ma is not None and mb is not None and ma != mb:
        return False
    ea, eb = a.event, b.event
    if ea.kind != "standard" or eb.kind != "standard":
        return True
    na, nb = ea.name, eb.name
    # (stop_motor and timer events cannot occur at the first poll, nor
    # can `every` and `after`, which count from it, nor a sensor event: the
    # sensors are off at start, and read from the poll after start_sensor)
    later = ("stop_motor", "timer", "every", "after", "sensor")
    if (nb in later and _at_first_poll_only(a)) or (na in later and _at_first_poll_only(b)):
        return False
    if na == "timer" and nb == "timer" and ma is None and mb is None:
        return _timer_meets(a, b)
    own = ("every", "after")
    if na in own and nb in own and ma is None and mb is None:
        # both timers start at the first poll: they meet as one timer's would
        return _periods_meet(ea.values, na == "every", eb.values, nb == "every")
    if ma is not None and ma == mb:
        for first, second in ((a, b), (b, a)):
            if first.event.name != "enter":
                continue
            if second.event.name == "stop_motor":
                return False
            if second.event.name == "timer" and second is b and _sets_timer_first(first):
                return False
    return True


def _sets_timer_first(rule) -> bool:
    """The rule's first step runs `set_timer` itself."""
    return any(c.kind == "standard" and c.name == "set_timer" for c in rule.body[0]) \
        if rule.body else False


def describe(rule) -> str:
    """rule `avoid`, or the rule `on sensor(ir0 > 300)`: words that do not
    depend on the layout (the note gives the position)."""
    if rule.name is not None:
        return f"rule {_code(rule.name)}"
    head = "on " if rule.node.trigger == "on" else ""
    return f"the rule {_code(head + event_text(rule.event.node))}"


def event_text(call) -> str:
    """An event as written, in the formatter's layout."""
    if call.name.name in ("when", "every", "after"):     # a rule head: `when COND`
        return f"{call.name.name} {_shown(call.args[0].value)}"
    if call.args is None:
        return call.name.name
    args = []
    for arg in call.args:
        if isinstance(arg, ast.NamedArg):
            args.append(f"{arg.name.name}: {_shown(arg.value)}")
        elif isinstance(arg, ast.ConditionArg):
            args.append(f"{arg.sensor.name} {arg.op} {_shown(arg.value)}")
        else:
            args.append(_shown(arg.value))
    return f"{call.name.name}({', '.join(args)})"


def _events_that_never_occur(checker) -> set:
    """The standard events of the rules W001..W003 report: they race with
    nothing."""
    never = set()
    if "start_sensor" not in checker.called:
        never.add("sensor")
    if "set_timer" not in checker.called:
        never.add("timer")
    if not (checker.called & MOTION_ACTIONS) and not any(
            e.kind == "action" for e in checker.externs.values()):
        never.add("stop_motor")
    return never


def check_program(checker, out) -> None:
    named: dict = {}
    never = _events_that_never_occur(checker)
    motor_rules = [r for r in out.rules
                   if _commands_motors(checker, r.body, named)
                   and not (r.event.kind == "standard" and r.event.name in never)]
    reported = 0
    more = 0
    for i, loser in enumerate(motor_rules):
        for j in range(i + 1, len(motor_rules)):    # (no slice: a copy per rule)
            winner = motor_rules[j]
            if winner.priority != loser.priority or not can_fire_together(loser, winner):
                continue
            if reported == MAX_REPORTS:
                more += 1
                break
            reported += 1
            checker.diags.warning(
                "W009", loser.node.event.span,
                f"{describe(loser)} and {describe(winner)} can fire in the same poll, both "
                f"command the motors and have the same priority ({loser.priority}): "
                f"{describe(winner)} runs later and wins",
                help=f"give the rule that should win a higher priority "
                     f"(`on ... priority {loser.priority + 1} do ...`)",
                notes=[_note(winner)])
            break
    if more:
        checker.diags.warning(
            "W009", motor_rules[-1].node.event.span,
            f"{more} more rule{'s' if more > 1 else ''} race for the motors with a later rule of "
            "the same priority (not listed one by one)",
            help="give the rules that should win higher priorities")


def _note(rule):
    return Note(f"{describe(rule)} is here", rule.node.span)
