"""Lowering: a CheckedProgram becomes the registrations of the paper's
model (parameter structs, actions, events) that the C templates lay out.

The same rules decide what the runtime's arrays must hold, so the checker
asks count_registrations() rather than guessing.
"""
from __future__ import annotations


def rule_action_key(index: int, rule) -> tuple:
    """Rules whose whole body is one named action share its registration."""
    body = rule.body
    if len(body) == 1 and len(body[0]) == 1 and body[0][0].kind == "named":
        return ("named", body[0][0].name)
    return ("rule", index)


def count_registrations(program) -> tuple[int, int]:
    """(actions, events) that the program registers with the runtime."""
    actions = {rule_action_key(i, r) for i, r in enumerate(program.rules)}
    return len(actions), len(program.rules)
