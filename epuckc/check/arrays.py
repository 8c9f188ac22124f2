"""Arrays: constants and variables of several values (`const W = [8, 4, 2]`,
`var counts = [0, 0, 0, 0]`), the readings of several sensors (`ir`,
`ambient`, `mic`, `acc`, `ground`), their elements (`a[i]`, `a[i] = e`), the
functions of whole arrays (`sum`, `min`, `max`, `argmin`, `argmax`, `dot`)
and the constant slices they read (`sum(ir[0:3])`: the elements 0..2).

An array is never a value of its own: every use is turned into ordinary
expressions over its elements here, so that kinds, intervals, folding,
overflow warnings and lowering need nothing new. An element with a fixed
index is the element itself (`ir[3]` is `ir3`, `W[2]` is its number); an
element with an index computed while the program runs is an "index" Expr
over that index, whose interval is the hull of the array's elements; `sum`
and `dot` are balanced trees of `+` over the elements (`dot(W, ir)` with a
constant W is the weighted sum GCtronic's C writes, without its zero
terms); `min` and `max` trees of `min` and `max`. An index outside the
array is an error where it is fixed [E061], a warning where its interval
can leave the array [W022]; at run time such an index is clamped to the
nearest element (`rt_index`), never out of bounds.

The checker (a `Checker`) is passed in; this module keeps no state of its
own but the checker's `const_arrays`.
"""
from __future__ import annotations

from typing import Optional

from ..stdlib import arith
from ..stdlib.table import READING_ARRAYS, STANDARD_READINGS
from ..stdlib.units import INT
from ..syntax import ast
from . import devices
from .messages import _code, _kind_word
from .program import Expr, VarInfo

MAX_SIZE = 256          # elements of one array


class ArrayRef:
    """What an array name stands for: its size, kind and each element as
    an Expr (a number, a reading, or a variable's element)."""
    def __init__(self, name: str, kind: str, elements: list, c_base: str, lo: int, hi: int,
                 constant: bool):
        self.name, self.kind, self.elements = name, kind, elements
        self.size = len(elements)
        self.c_base = c_base            # "var", "const" or the reading's runtime call
        self.lo, self.hi = lo, hi
        self.constant = constant


def is_array(ck, name: str) -> bool:
    info = ck.vars.get(name)
    return name in ck.const_arrays or name in READING_ARRAYS or (info is not None and info.size)


def declare_const(ck, stmt: ast.ConstDef) -> None:
    """A constant array: its elements checked now (numbers or constants of
    one kind)."""
    values = _literals(ck, stmt.value, stmt.name.name)
    if values is not None:
        ck.const_arrays[stmt.name.name] = (stmt, values)


def declare_var(ck, stmt: ast.VarDef) -> Optional[VarInfo]:
    values = _literals(ck, stmt.value, stmt.name.name, allow_vars=False)
    if values is None:
        return None
    kind = values[0].kind
    inits = tuple(v.value for v in values)
    return VarInfo(stmt.name.name, kind, inits[0], min(inits), max(inits), ck._trace_ids, stmt,
                   size=len(inits), inits=inits)


def _literals(ck, lit: ast.ArrayLit, name: str, allow_vars: bool = True) -> Optional[list]:
    if not lit.items:
        ck.diags.error("E061", lit.span, f"array {_code(name)} has no elements",
                       help="give it its elements: `[0, 0, 0]`")
        return None
    if len(lit.items) > MAX_SIZE:
        ck.diags.error("E061", lit.span, f"array {_code(name)} has {len(lit.items)} elements: "
                       f"at most {MAX_SIZE}", help="use a smaller array")
        return None
    values = [ck._literal(item, allow_vars=allow_vars) for item in lit.items]
    if any(v is None for v in values):
        return None
    return ck._one_kind(values, lit, f"the elements of {_code(name)} are of one kind:")


def _ref(ck, ident: ast.Ident) -> Optional[ArrayRef]:
    name = ident.name
    if name in ck.const_arrays:
        ck.const_used.add(name)
        values = ck.const_arrays[name][1]
        elements = [Expr("num", v.kind, v.value, v.value, value=v.value, node=ident, bare=v.bare)
                    for v in values]
        return ArrayRef(name, values[0].kind, elements, "const",
                        min(v.value for v in values), max(v.value for v in values), True)
    if name in READING_ARRAYS:
        names, call = READING_ARRAYS[name]
        readings = [STANDARD_READINGS[n] for n in names]
        # a device's readings (`ground`): E070 where the target lacks it
        devices.require(ck, readings[0].device, name, ident.span)
        elements = [Expr("read", r.kind, r.lo, r.hi, name=r.name, node=ident) for r in readings]
        return ArrayRef(name, readings[0].kind, elements, call,
                        min(r.lo for r in readings), max(r.hi for r in readings), False)
    info = ck.vars.get(name)
    if info is not None and info.size:
        ck.vars_used.add(name)
        elements = [Expr("var", info.kind, info.lo, info.hi, name=f"{name}[{k}]", node=ident)
                    for k in range(info.size)]
        return ArrayRef(name, info.kind, elements, "var", info.lo, info.hi, False)
    return None


def not_an_array(ck, ident: ast.Ident, what: str) -> None:
    ck.diags.error("E062", ident.span, f"{_code(ident.name)} is not an array: {what}",
                   help="index an array (`ir[i]`, or one declared `var a = [0, 0]`), or use "
                        f"`{ident.name}` without brackets")


def bare_use(ck, ident: ast.Ident, node) -> None:
    """E058: an array's name where one value is wanted."""
    ref = _ref(ck, ident)
    ck.diags.error("E062", node.span,
                   f"{_code(ident.name)} is an array of {ref.size}, not one value",
                   help=f"take one element (`{ident.name}[0]`..`{ident.name}[{ref.size - 1}]`), "
                        f"or all of them: `sum({ident.name})`, `max({ident.name})`, ...")


def index_value(ck, ref: ArrayRef, index_node, where) -> Optional[Expr]:
    """The checked index of `ref`: a plain number; E057 where it is fixed
    and outside, W018 where its interval can leave the array."""
    i = ck._expr(index_node)
    if i is None or not ck._is_number(i, "an index"):
        return None
    if i.kind != INT:
        ck.diags.error("E048", index_node.span,
                       f"an index is a plain number, but `{ck._text(index_node)}` is "
                       f"{_kind(i.kind)}", help="index with a count: 0, 1, 2, ...")
        return None
    last = ref.size - 1
    if i.constant:
        if not 0 <= i.value <= last:
            ck.diags.error("E061", index_node.span,
                           f"index {i.value} is outside {_code(ref.name)}, which has {ref.size} "
                           f"element{'s' if ref.size > 1 else ''} (0..{last})",
                           help=f"index it with 0..{last}")
            return None
        return i
    if i.lo < 0 or i.hi > last:
        text = ck._text(index_node)
        counted = text if isinstance(index_node, (ast.ConstRef, ast.Paren, ast.FuncCall,
                                                  ast.Index)) else f"({text})"
        ck.diags.warning("W022", index_node.span,
                         f"`{ck._text(index_node)}` can be {i.lo}..{i.hi}, outside "
                         f"{_code(ref.name)} (0..{last}): at run time an index outside is "
                         f"taken as the nearest end, 0 or {last}",
                         help=f"bound it: `clamp({ck._text(index_node)}, 0, {last})`, or "
                              f"`{counted} % {ref.size}` for a count")
    ck._overflow(i)
    return i


def _not_an_array_or_unknown(ck, name: ast.Ident):
    """What is wrong with `name[...]` when `name` is no array: a name of one
    value, or no name at all [E013]."""
    if name.name in ck.vars or name.name in ck.consts or name.name in STANDARD_READINGS:
        not_an_array(ck, name, "it holds one value")
    else:
        ck._name(ast.ConstRef(name, False, name.span))   # reports E013


def element(ck, node: ast.Index) -> Optional[Expr]:
    """`a[i]` in an expression."""
    ref = _ref(ck, node.name)
    if ref is None:
        _not_an_array_or_unknown(ck, node.name)
        return None
    i = index_value(ck, ref, node.index, node)
    if i is None:
        return None
    if i.constant:
        e = ref.elements[i.value]
        return Expr(e.op, e.kind, e.lo, e.hi, e.args, e.value, e.name, node, e.bare)
    return Expr("index", ref.kind, ref.lo, ref.hi, (i,), name=ref.name, value=ref.size,
                node=node)


def aggregate(ck, node: ast.FuncCall) -> Optional[Expr]:
    """sum(a), min(a), max(a), argmin(a), argmax(a), dot(a, b)."""
    name = node.name.name
    args = node.args or ()
    want = 2 if name == "dot" else 1
    refs = []
    for arg in args:
        value = arg.value if isinstance(arg, ast.PositionalArg) else None
        if isinstance(value, ast.Slice):
            refs.append(sliced(ck, value))
            continue
        if not isinstance(value, ast.ConstRef) or value.negative:
            refs.append(None)
            continue
        refs.append(_ref(ck, value.name))
    if _REPORTED in refs:
        return None
    if len(args) != want or None in refs:
        shown = "a, b" if want == 2 else "a"
        ck.diags.error("E017" if len(args) < want else "E016", node.span,
                       f"{_code(name)} takes {want} array{'s' if want > 1 else ''}: "
                       f"`{name}({shown})`",
                       help=f"name {'two arrays' if want > 1 else 'an array'}: e.g. "
                            f"`{name}({'W, ir' if want > 1 else 'ir'})`")
        return None
    if name == "dot":
        a, b = refs
        if a.size != b.size:
            ck.diags.error("E063", node.span,
                           f"`dot` of arrays of different sizes: {_code(a.name)} has {a.size}, "
                           f"{_code(b.name)} {b.size}", help="give both arrays as many elements")
            return None
        terms = []          # (sign, product): a negative weight is subtracted
        for x, y in zip(a.elements, b.elements):
            if y.constant and not x.constant:
                x, y = y, x
            if x.constant and x.value == 0:             # a zero weight adds nothing
                continue
            sign = "+"
            if x.constant and x.value < 0 and x.value != -32768 and terms:
                sign, x = "-", Expr("num", x.kind, -x.value, -x.value, value=-x.value,
                                    node=x.node, bare=x.bare)
            p = ck._binary("*", _at(x, node), _at(y, node), node)
            if p is None:
                return None
            terms.append((sign, p))
        if not terms:
            return Expr("num", INT, 0, 0, value=0, node=node, bare=True)
        return _tree(ck, "+", [p for _, p in terms], node, [sign for sign, _ in terms])
    (a,) = refs
    elements = [_at(e, node) for e in a.elements]
    if name == "sum":
        return _tree(ck, "+", elements, node)
    if name in ("min", "max"):
        return _tree(ck, name, elements, node)
    # argmin, argmax: the runtime compares the elements (the first of equals)
    values = tuple(elements)
    if all(v.constant for v in values):
        pick = min if name == "argmin" else max
        best = pick(range(len(values)), key=lambda k: (values[k].value, -k if pick is max else k))
        return Expr("num", INT, best, best, value=best, node=node, bare=True)
    return Expr(name, INT, 0, len(values) - 1, values, node=node, bare=True)


_REPORTED = object()     # (a slice whose problem was said)


def sliced(ck, node: ast.Slice):
    """`a[lo:hi]` where a whole array is read: the array of the elements
    lo..hi-1 (lo 0 and hi the size where left out), its bounds fixed
    numbers [E061]; _REPORTED after saying what is wrong."""
    ref = _ref(ck, node.name)
    if ref is None:
        _not_an_array_or_unknown(ck, node.name)
        return _REPORTED
    bounds = []
    for bound, default in ((node.lo, 0), (node.hi, ref.size)):
        if bound is None:
            bounds.append(default)
            continue
        b = ck._expr(bound)
        if b is None:
            return _REPORTED
        if not b.constant or b.kind != INT:
            ck.diags.error("E061", bound.span,
                           f"the bounds of a slice are fixed plain numbers, but "
                           f"`{ck._text(bound)}` is "
                           + ("computed while the program runs" if not b.constant
                              else _kind(b.kind)),
                           help=f"write numbers or constants (`{node.name.name}[1:3]`); for "
                                f"one element chosen while the program runs, index it: "
                                f"`{node.name.name}[i]`")
            return _REPORTED
        bounds.append(b.value)
    lo, hi = bounds
    if not 0 <= lo < hi <= ref.size:
        ck.diags.error("E061", node.span,
                       f"`{ck._text(node)}` is outside {_code(ref.name)} or empty: "
                       f"{_code(ref.name)} has {ref.size} element{'s' if ref.size > 1 else ''}, "
                       f"and `{ref.name}[lo:hi]` takes elements lo..hi-1",
                       help=f"take 0 <= lo < hi <= {ref.size}: `{ref.name}[0:{ref.size}]` is "
                            f"all of it")
        return _REPORTED
    elements = ref.elements[lo:hi]
    return ArrayRef(f"{ref.name}[{lo}:{hi}]", ref.kind, elements, ref.c_base,
                    min(e.lo for e in elements), max(e.hi for e in elements), ref.constant)


def bare_slice(ck, node: ast.Slice) -> None:
    """E062: a slice where one value is wanted."""
    ref = sliced(ck, node)
    if ref is _REPORTED:
        return
    ck.diags.error("E062", node.span,
                   f"`{ck._text(node)}` is {ref.size} elements, not one value",
                   help=f"read them as a whole: `sum({ck._text(node)})`, "
                        f"`max({ck._text(node)})`, `dot({ck._text(node)}, ...)`, ...")


# ---- fill(a, v): every element of a variable array one value -----------------------

_FILLS: dict = {}       # id(call) -> (call, size, its Assign): the same Assign each time


def fill_assign(variables: dict, call) -> Optional[ast.Assign]:
    """`fill(a, v)` as the assignment `a = [v, v, ...]` (one item per
    element, the same node: variables.py computes it once), for the
    checker and for the intervals (dependencies.py), which see the same
    node each time; None when the call is not of that shape (the checker
    says why: `fill_call`)."""
    args = call.args or ()
    if len(args) != 2 or not all(isinstance(a, ast.PositionalArg) for a in args):
        return None
    target = args[0].value
    if not isinstance(target, ast.ConstRef) or target.negative:
        return None
    info = variables.get(target.name.name)
    if info is None or not info.size:
        return None
    hit = _FILLS.get(id(call))
    if hit is not None and hit[0] is call and hit[1] == info.size:
        return hit[2]
    if len(_FILLS) > 4096:
        _FILLS.clear()
    value = args[1].value
    assign = ast.Assign(target.name, "=", ast.ArrayLit((value,) * info.size, call.span),
                        call.span, None)
    _FILLS[id(call)] = (call, info.size, assign)
    return assign


def fill_call(ck, call):
    """The checked `fill(a, v)`, or None after saying what is wrong."""
    assign = fill_assign(ck.vars, call)
    if assign is not None:
        return ck._assign(assign)
    args = call.args or ()
    if len(args) != 2 or not all(isinstance(a, ast.PositionalArg) for a in args):
        ck.diags.error("E017" if len(args) < 2 else "E016", call.span,
                       "`fill` takes a variable array and its elements' value: `fill(a, 0)`",
                       help="name the array first, then the value every element gets")
        return None
    target = args[0].value
    if isinstance(target, ast.ConstRef) and not target.negative:
        name = target.name.name
        if name in ck.const_arrays or name in READING_ARRAYS:
            ck.diags.error("E051", target.span,
                           f"{_code(name)} is {'a constant' if name in ck.const_arrays else 'a reading of the robot'}: "
                           "`fill` gives a variable array its values",
                           help=f"declare a variable array: `var my_{name} = [0, 0, 0]`")
        elif name in ck.vars or name in ck.consts or name in STANDARD_READINGS:
            ck.diags.error("E062", target.span,
                           f"`fill` fills a variable array, but {_code(name)} holds one value",
                           help=f"give it its value with `=`: `{name} = {ck._text(args[1].value)}`"
                           if name in ck.vars else "name a variable array: `fill(a, 0)`")
        else:
            ck.diags.error("E051", target.span, f"unknown variable {_code(name)}",
                           help=f"declare it first: `var {name} = [0, 0, 0]`")
        return None
    ck.diags.error("E062", target.span,
                   f"`fill` fills a variable array, but `{ck._text(target)}` is not one",
                   help="name the array: `fill(a, 0)`")
    return None


def _at(e: Expr, node) -> Expr:
    """An element, placed at the call for messages."""
    return Expr(e.op, e.kind, e.lo, e.hi, e.args, e.value, e.name, node, e.bare)


CHAIN = 32         # up to this many items, a chain `a + b + c` as C writes it


def _tree(ck, op: str, items: list, node, signs=None) -> Optional[Expr]:
    """`op` over items: a chain from the left as one writes it (`signs`:
    "+" or "-" for each item after the first), or for many items a
    balanced tree, of depth log2(n) rather than n."""
    if len(items) <= CHAIN:
        acc = items[0]
        for k, item in enumerate(items[1:], 1):
            if op == "+":
                acc = ck._binary(signs[k] if signs else "+", acc, item, node)
            else:
                acc = _minmax(ck, op, acc, item, node)
            if acc is None:
                return None
        return acc
    if signs and "-" in signs:          # many terms: subtract none
        items = [item if sign == "+" else ck._unary("neg", item, node)
                 for sign, item in zip(signs, items)]
    while len(items) > 1:
        paired = []
        for k in range(0, len(items) - 1, 2):
            if op == "+":
                joined = ck._binary("+", items[k], items[k + 1], node)
            else:
                joined = _minmax(ck, op, items[k], items[k + 1], node)
            if joined is None:
                return None
            paired.append(joined)
        if len(items) % 2:
            paired.append(items[-1])
        items = paired
    return items[0]


def _minmax(ck, op: str, a: Expr, b: Expr, node) -> Expr:
    lo, hi = arith.interval(op, (a.lo, a.hi), (b.lo, b.hi))
    return ck._fold(Expr(op, a.kind, lo, hi, (a, b), node=node, bare=a.bare and b.bare))


def _kind(kind: str) -> str:
    return _kind_word(kind)
