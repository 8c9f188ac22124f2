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


def c_expr(e: Expr, top: bool = True) -> str:
    """The C text of `e`; `top`: no parentheses around a comparison."""
    op = e.op
    if op == "num":
        return c_int(e.value)
    if op == "var":
        return var_name(e.name)
    if op == "read":
        return STANDARD_READINGS[e.name].c
    if op == "not":
        return f"!{c_expr(e.args[0], False)}"
    if op in _C_OPS:
        text = f"{c_expr(e.args[0], False)} {_C_OPS[op]} {c_expr(e.args[1], False)}"
        return text if top else f"({text})"
    return f"{_CALLS[op]}({', '.join(c_expr(a) for a in e.args)})"
