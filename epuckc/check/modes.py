"""Checks of modes: `[initial] mode NAME { rules }`, `enter NAME`, `on enter`.

Called by the checker (checker.py) at its stages: `declare` with the other
declarations, `enter_call` for each `enter` action, `check_rule` for each
rule, `check_program` once everything is resolved. The semantics that make
these checks necessary are in docs/language.md section 2.7.
"""
from __future__ import annotations

from typing import Optional

from ..diagnostics import Note
from ..syntax import ast
from .messages import _code, did_you_mean
from .program import ResolvedCall, branches_of
from .splice import splice



def declare(checker, claim) -> None:
    """Collect the modes (unique names, E015) and the initial one: the mode
    marked `initial` [at most one, E046], else the first declared."""
    first_initial = None
    for stmt in checker.program.of_type(ast.ModeDef):
        if claim("mode", stmt.name, "mode"):
            checker.modes[stmt.name.name] = stmt
        if stmt.initial:
            if first_initial is not None:
                checker.diags.error("E046", stmt.span,
                                    f"mode {_code(stmt.name.name)} is marked `initial`, but so is "
                                    f"mode {_code(first_initial.name.name)}",
                                    help="the program starts in one mode: keep one `initial`",
                                    notes=[Note("the first initial mode", first_initial.span)])
            else:
                first_initial = stmt
    if first_initial is not None:
        checker.initial_mode = first_initial.name.name
    elif checker.modes:
        checker.initial_mode = next(iter(checker.modes))


def enter_call(checker, call: ast.EnterCall):
    """`enter NAME`: NAME must be a mode [E043]."""
    name = call.mode.name
    if name not in checker.modes:
        if checker.modes:
            help_text = did_you_mean(call.mode, checker.modes) or (
                "the modes are " + ", ".join(map(_code, checker.modes)))
        else:
            help_text = f"declare it: `mode {name} {{ on enter do ... }}`"
        checker.diags.error("E043", call.mode.span, f"unknown mode {_code(name)}", help=help_text)
        return None
    return ResolvedCall("enter", name, {}, {}, call)


def check_rule(checker, rule: ast.Rule, event) -> None:
    """`on enter` only inside a mode [E044]."""
    if event is not None and event.kind == "standard" and event.name == "enter" \
            and rule.mode is None:
        checker.diags.error("E044", rule.event.span,
                            "`on enter` is only for rules inside a mode",
                            help="put the rule in a `mode NAME { ... }` block, or use "
                                 "`on immediate` to run something at start")


def flat_steps(checker, steps) -> list:
    """A body's steps with its named actions spliced in, as lowering does
    (splice.py), memoised per named action on the checker."""
    resolved = checker._resolved_actions
    return splice(steps, lambda call, _: call, lambda name: (resolved.get(name, []), None),
                  checker._flat_actions)


def may_run(checker, calls) -> list:
    """Every call that a step's `calls` may run: each of them and, for an
    `if`, every call of every branch (any branch may run), the named
    actions of the branches spliced in (flat_steps); in order."""
    out, todo = [], list(reversed(calls))
    while todo:
        call = todo.pop()
        out.append(call)
        if call.kind == "if":
            inner = [c for branch in branches_of(call)
                     for step in flat_steps(checker, [branch]) for c in step]
            todo.extend(reversed(inner))
    return out


def _steps_after_enter(checker, steps) -> Optional[object]:
    """The first `enter` call of a body that a later step follows, or None
    (an `enter` inside an `if` may not run: not this one's)."""
    for step in flat_steps(checker, steps)[:-1]:
        for call in step:
            if call.kind == "enter":
                return call
    return None


def entered_by(checker, bodies) -> set:
    """The modes that the bodies' `enter` calls may enter."""
    entered = set()
    for body in bodies:
        for step in body:
            for call in may_run(checker, step):
                if call.kind == "enter":
                    entered.add(call.name)
    return entered


def check_program(checker, out, complete: bool = True, in_modes=None, entered=None) -> None:
    """Whole-program checks: modes never entered [W010] (a conclusion from an
    absence: only when the program is `complete`, free of errors); `cancel`
    of a rule of another mode [E045]; steps of a mode's sequence after its
    `enter` [W011]. `in_modes`: the rules of out.rules that have a mode,
    `entered`: a callable giving the modes the rules enter (the language
    server keeps both by blocks of rules); by default found here."""
    diags = checker.diags
    rule_mode = {}                      # rule name -> its mode (None: outside modes)
    for name, node in checker.rule_names.items():
        rule_mode[name] = node.mode.name if node.mode else None
    if checker.modes:
        by_rules = entered_by(checker, [r.body for r in out.rules]) if entered is None \
            else entered()
        entered = by_rules | entered_by(checker, checker._resolved_actions.values())
    for name, node in checker.modes.items():
        if complete and name != checker.initial_mode and name not in entered:
            diags.warning("W010", node.name.span, f"mode {_code(name)} is never entered",
                          help=f"its rules can never fire: add `enter {name}` to an action, or "
                               f"mark it `initial mode {name} {{` to start in it")
    for rule in out.rules if in_modes is None else in_modes:
        if rule.mode is None:
            continue
        for call in (c for step in flat_steps(checker, rule.body)
                     for c in may_run(checker, step)):
            if call.kind == "cancel" and rule_mode.get(call.name) not in (None, rule.mode):
                other = rule_mode[call.name]
                diags.error("E045", call.node.span,
                            f"rule {_code(call.name)} belongs to mode {_code(other)}, but this "
                            f"rule of mode {_code(rule.mode)} cancels it",
                            help=f"while mode {_code(rule.mode)} is current, {_code(call.name)} "
                                 f"is not armed anyway, and entering {_code(other)} re-arms it; "
                                 f"cancel it from a rule of mode {_code(other)}",
                            notes=[Note(f"{_code(call.name)} is defined here",
                                        checker.rule_names[call.name].span)])
        enter = _steps_after_enter(checker, rule.body)
        if enter is not None:
            diags.warning("W011", enter.node.span,
                          f"the steps after `enter {enter.name}` never run",
                          help=f"entering a mode abandons the sequence that a rule of mode "
                               f"{_code(rule.mode)} started; make `enter` the last step")
