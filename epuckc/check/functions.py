"""Calls of functions in expressions: the plain ones (`abs`, `min`,
`max`, `clamp`, `random`), the math of stdlib/imath.py (`atan2`, `hypot`,
`sqrt`, `sin`, `cos`: the kinds they take and give, their intervals), and
those of whole arrays, which arrays.py turns into expressions. `self` is
the checker."""
from __future__ import annotations

from typing import Optional

from ..stdlib import arith, imath
from ..stdlib.table import AGGREGATES, CHOICE_READINGS, FUNCTIONS
from ..stdlib.units import ANGLE, INT
from ..syntax import aseba, ast
from . import arrays, readings
from .messages import _code, _kind_word, did_you_mean
from .program import Expr

# what the math functions take and give: (kind of the arguments, or None:
# any one kind; kind of the result, or None: the arguments')
_MATH_KINDS = {"atan2": (None, ANGLE), "hypot": (None, None), "sqrt": (INT, INT),
               "sin": (ANGLE, INT), "cos": (ANGLE, INT)}


def call(self, node: ast.FuncCall) -> Optional[Expr]:
    name = node.name.name
    if name in CHOICE_READINGS:                 # `seen(red)`: check/readings.py
        return readings.choice_reading(self, node)
    if name in AGGREGATES or (name in ("min", "max") and len(node.args or ()) == 1):
        return arrays.aggregate(self, node)
    if name == "sort":               # Aseba's: E096 says what to write
        aseba.sort_diagnostic(self.diags, node.name.span)
        return None
    if name not in FUNCTIONS:
        self.diags.error("E054", node.name.span, f"unknown function {_code(name)}",
                         help=did_you_mean(node.name, FUNCTIONS) or
                         "the functions are " + ", ".join(map(_code, FUNCTIONS)))
        return None
    params, _ = FUNCTIONS[name]
    args = node.args or ()
    if len(args) != len(params) or any(not isinstance(a, ast.PositionalArg) for a in args):
        self.diags.error("E016" if len(args) > len(params) else "E017", node.span,
                         f"{_code(name)} takes {len(params)} argument"
                         f"{'s' if len(params) > 1 else ''}: "
                         f"`{name}({', '.join(params)})`",
                         help=f"write `{name}({', '.join(params)})`")
        return None
    values = []
    for a in args:          # a loop: a comprehension would cost a frame per level
        value = self._expr(a.value)
        if value is None:
            return None
        values.append(value)
    if not all(self._is_number(v, _code(name)) for v in values):
        return None
    if len(values) > 1:
        values = self._one_kind(values, node, f"the arguments of {_code(name)} differ:")
        if values is None:
            return None
    kind = values[0].kind
    bare = all(v.bare for v in values)
    if name == "random":
        values = [self._store(v) for v in values]
        lo, hi = values[0].lo, values[1].hi
        if values[0].constant and values[1].constant and lo > hi:
            self.diags.error("E042", node.span,
                             f"`random({self._text(args[0].value)}, "
                             f"{self._text(args[1].value)})`: the lower bound is above "
                             f"the upper one", help="write the smaller bound first")
            return None
        return Expr("random", kind, min(lo, hi), max(lo, hi), tuple(values), node=node)
    if name in _MATH_KINDS:
        return _math(self, name, values, node)
    lo, hi = arith.interval(name, *[(v.lo, v.hi) for v in values])
    return self._fold(Expr(name, kind, lo, hi, tuple(values), node=node, bare=bare))

def _math(self, name: str, values: list, node) -> Optional[Expr]:
    """atan2, hypot, sqrt, sin, cos: their arguments' kind, their
    result's kind and interval (stdlib/imath.py, as rt_math.c computes)."""
    takes, gives = _MATH_KINDS[name]
    if takes is not None:
        values = [self._adapt(v, takes) for v in values]
        wrong = next((v for v in values if v.kind != takes), None)
        if wrong is not None:
            self.diags.error("E048", wrong.node.span,
                             f"{_code(name)} takes {_kind_word(takes)}, but "
                             f"`{self._text(wrong.node)}` is {_kind_word(wrong.kind)}",
                             help=f"`{name}(...)` of {_kind_word(takes)}"
                                  + (": write the angle in deg, e.g. `sin(30 deg)`"
                                     if takes == ANGLE else ""))
            return None
    kind = gives or values[0].kind
    lo, hi = imath.interval(name, *[(v.lo, v.hi) for v in values])
    return self._fold(Expr(name, kind, lo, hi, tuple(values), node=node,
                           bare=gives is None and all(v.bare for v in values)))

