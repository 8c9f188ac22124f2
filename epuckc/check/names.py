"""Names and scopes: declarations (constants, actions, externs, rules, modes),
clashes with the standard names, named actions resolved once, unused names."""
from __future__ import annotations

from ..base.source import Span
from ..diagnostics import Fix, Note
from ..stdlib.table import ACTION_ALIASES, EVENT_ALIASES, STANDARD_ACTIONS, STANDARD_EVENTS
from ..syntax import ast
from . import arrays, modes, splice
from .messages import _code


class Names:
    """The checker's declarations and named actions (a part of Checker)."""

    def _declare(self):
        seen: dict = {}     # (namespace, name) -> first node
        array_consts = []

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
                if not claim("const", stmt.name, "constant"):
                    continue
                if isinstance(stmt.value, ast.ArrayLit):
                    array_consts.append(stmt)
                else:
                    self.consts[stmt.name.name] = stmt
            elif isinstance(stmt, ast.ActionDef):
                if self._clashes_with_standard(stmt.name, "action"):
                    continue
                if claim("action", stmt.name, "action"):
                    self.actions[stmt.name.name] = stmt
            elif isinstance(stmt, ast.ExternDef):
                self._extern(stmt, claim)
        for stmt in array_consts:                   # after the constants they may name
            arrays.declare_const(self, stmt)
        for stmt in self.program.statements:
            if isinstance(stmt, ast.VarDef):
                self._declare_var(stmt, claim)
        modes.declare(self, claim)

    def _clashes_with_standard(self, ident: ast.Ident, namespace: str) -> bool:
        standard = STANDARD_ACTIONS if namespace == "action" else STANDARD_EVENTS
        aliases = ACTION_ALIASES if namespace == "action" else EVENT_ALIASES
        if ident.name in standard or ident.name in aliases:
            self.diags.error("E015", ident.span,
                             f"{_code(ident.name)} is already the name of a standard {namespace}",
                             help=f"choose another name, e.g. `my_{ident.name}`")
            return True
        return False

    def _named_calls(self, name: str) -> list:
        """The calls of named actions in action `name`'s body (inside its
        `if`s too)."""
        return splice.named_calls(self, self.actions[name].body)

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
        splice.action_depths(self, order)
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
        for name, info in self.vars.items():
            if name not in self.vars_used:
                self.diags.warning("W015", info.node.name.span,
                                   f"variable {_code(name)} is never used",
                                   help="use it in an expression or an assignment, or remove it")
            elif name not in self.vars_assigned:
                keyword = info.node.span
                self.diags.warning(
                    "W017", info.node.name.span,
                    f"variable {_code(name)} is never assigned: it is always "
                    f"{self._text(info.node.value)}",
                    help=Fix(Span(keyword.line, keyword.column, keyword.line, keyword.column + 3),
                             "const", f"make it a constant: `const {name} = "
                                      f"{self._text(info.node.value)}`, or assign it in a rule"))
        if not any(isinstance(s, ast.Rule) for s in self.program.statements):
            self.diags.warning("W006", Span(1, 1, 1, 1), "this program has no rules: it does nothing",
                               help="add a rule, e.g. `on immediate do start_straight(200, 10 cm)`")
