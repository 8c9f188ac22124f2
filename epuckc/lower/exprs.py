"""Expressions as C: each checked Expr becomes one C expression over the
program's variables (`epk_v_NAME`) and the runtime's readings and
saturating operations (runtime_c/rt_lang.c), so that the values are the
same on every target and no operation is undefined."""
from __future__ import annotations

from ..check.program import Expr
from ..stdlib.table import STANDARD_READINGS

VAR_PREFIX = "epk_v_"

_CALLS = {"+": "rt_add", "-": "rt_sub", "*": "rt_mul", "/": "rt_div", "%": "rt_mod",
          "neg": "rt_neg", "abs": "rt_abs", "min": "rt_min", "max": "rt_max",
          "clamp": "rt_clamp", "random": "rt_random"}
_C_OPS = {"<": "<", "<=": "<=", ">": ">", ">=": ">=", "==": "==", "!=": "!=",
          "and": "&&", "or": "||"}


def var_name(name: str) -> str:
    return VAR_PREFIX + name


def c_int(value: int) -> str:
    """An int literal that is an int on a 16-bit target too."""
    return "RT_INT_MIN" if value == -32768 else str(value)


def c_expr(e: Expr, top: bool = True, readings: dict = None) -> str:
    """The C text of `e`; `top`: no parentheses around a comparison;
    `readings`: C names that hold readings already read (name -> C)."""
    op = e.op
    if op == "num":
        return c_int(e.value)
    if op == "var":
        return var_name(e.name)
    if op == "read":
        if readings and e.name in readings:
            return readings[e.name]
        return STANDARD_READINGS[e.name].c
    if op == "not":
        return f"!{c_expr(e.args[0], False, readings)}"
    if op in _C_OPS:
        text = (f"{c_expr(e.args[0], False, readings)} {_C_OPS[op]} "
                f"{c_expr(e.args[1], False, readings)}")
        return text if top else f"({text})"
    return f"{_CALLS[op]}({', '.join(c_expr(a, True, readings) for a in e.args)})"


ODOMETRY = frozenset({"x", "y", "heading"})


def variables_of(e: Expr) -> set:
    """The names of the variables an expression's C reads (after folding:
    a variable inside a comparison that the checker decided is not read)."""
    found, todo = set(), [e]
    while todo:
        x = todo.pop()
        if x.op == "var":
            found.add(x.name)
        todo.extend(x.args)
    return found


def readings_of(e: Expr) -> set:
    """The names of the readings an expression reads."""
    found = {e.name} if e.op == "read" else set()
    for a in e.args:
        found |= readings_of(a)
    return found


def proximity_read(e: Expr) -> set:
    """The proximity sensors (0..7) an expression reads."""
    found = set()
    if e.op == "read" and e.name.startswith("ir") and e.name[2:].isdigit():
        found.add(int(e.name[2:]))
    for a in e.args:
        found |= proximity_read(a)
    return found
