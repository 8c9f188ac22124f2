"""Statements nested to an exact depth (epuckc/syntax/limits.py), built from
layers: each layer wraps what is inside it (`{}`) in one construct of the
grammar, an expression in an expression (`abs({})`, `a[{}]`, `{} + 1`,
`~{}`, `{} << 1`, `{} & 0xFF`, `{} + sum(a[1:3])`), a condition in a
condition (`not ({})`), an action in an action (`if v > 0 {{ {} }}`), or
one kind in another (`{} > 3`, `if {} {{ v = 1 }}`, `v = {}`, `a = [{},
0, 1]`, `fill(a, {})`). What is inside a layer is put in parentheses where
the grammar's precedence needs them (`({} + 1) * 2`, `({} | 1) << 2`). A
layer's cost in levels is measured once, on the tree the parser builds:
depth is the tree's shape, so costs add up; parentheses around the
innermost leaf make a depth exact. Used by tests/syntax/test_limits.py,
tests/syntax/test_depth_property.py and the fuzz generators
(tests/support/language.py)."""
from __future__ import annotations

from functools import lru_cache

from epuckc.base.source import SourceFile
from epuckc.diagnostics import Collector
from epuckc.syntax.limits import measure
from epuckc.syntax.lexer import iter_statements, iter_tokens
from epuckc.syntax.parser import parse_statement

# what a program needs around the statements: `v`, an int array `a` of 3
HEAD = "var v = 0\nvar a = [0, 1, 2]\non immediate do v = 1, a[1] = 2\n"

# how tightly a construct binds, loosest first: what a layer makes, and
# what its slot `{}` takes without parentheses
# (the bitwise operators bind as in Python: `|` loosest, then `^`, `&`, the
# shifts, all looser than `+`, tighter than a comparison)
_ORDER = {"any": -1, "or": 0, "and": 1, "not": 2, "cmp": 3, "bor": 4, "bxor": 5, "band": 6,
          "shift": 7, "sum": 8, "product": 9, "unary": 10, "atom": 11}

# (kind outside, kind inside): [(template, what it makes, what its slot takes)]
LAYERS = {
    ("expr", "expr"): [
        ("abs({})", "atom", "any"), ("clamp({}, -5, 5)", "atom", "any"),
        ("min({}, 7)", "atom", "any"), ("max(-7, {})", "atom", "any"), ("({})", "atom", "any"),
        ("a[{}]", "atom", "any"), ("sqrt({})", "atom", "any"),
        ("{} + 1", "sum", "sum"), ("{} - v", "sum", "sum"), ("1 - {}", "sum", "product"),
        ("random(0, 3) + {}", "sum", "product"), ("{} * 2", "product", "product"),
        ("{} / 3", "product", "product"), ("{} % 7", "product", "product"),
        ("-({})", "unary", "any"), ("- {}", "unary", "unary"),
        ("~{}", "unary", "unary"), ("~({})", "unary", "any"),
        ("{} << 1", "shift", "shift"), ("{} >> 2", "shift", "shift"),
        ("v << {}", "shift", "sum"), ("0x7F >> {}", "shift", "sum"),
        ("{} & 0xFF", "band", "band"), ("0b1011 & {}", "band", "shift"),
        ("{} ^ v", "bxor", "bxor"), ("{} | 0x10", "bor", "bor"), ("v | {}", "bor", "bxor"),
        ("{} + sum(a[1:3])", "sum", "sum"), ("max(a[:2]) - {}", "sum", "product")],
    ("cond", "cond"): [
        ("not ({})", "not", "any"), ("not {}", "not", "not"), ("({}) and v > 1", "and", "any"),
        ("{} and v > 1", "and", "and"), ("v < 9 or {}", "or", "and"), ("({})", "atom", "any")],
    ("cond", "expr"): [("{} > 3", "cmp", "bor"), ("-2 <= {}", "cmp", "bor"),
                       ("{} != v", "cmp", "bor")],
    ("action", "action"): [
        ("if v > 0 {{ {} }}", "any", "any"), ("if v > 0 {{ v = 1 }} else {{ {} }}", "any", "any"),
        ("if v > 0 {{ v = 1, {} }}", "any", "any"),
        ("if v > 0 {{ v = 1 }} else if v > 1 {{ {} }} else {{ v = 2 }}", "any", "any")],
    ("action", "cond"): [("if {} {{ v = 1 }}", "any", "any"),
                         ("if v > 5 {{ v = 2 }} else if {} {{ v = 1 }}", "any", "any")],
    ("action", "expr"): [("v = {}", "any", "any"), ("v += {}", "any", "any"),
                         ("a[{}] = 1", "any", "any"), ("a[0] = {}", "any", "any"),
                         ("a[2] -= {}", "any", "any"),
                         ("a = [{}, 0, 1]", "any", "any"), ("a = [0, 1, {}]", "any", "any"),
                         ("fill(a, {})", "any", "any"),
                         ("set_speed(({}) * 1 steps/s, 0 steps/s)", "any", "any")],
}
# statements around an innermost kind: (template, kind inside)
STATEMENTS = [
    ("every 10 ms do {}", "action"),
    ("every 20 ms do stop_motor, {}", "action"),
    ("on sensor(ir0 > 300) repeat do {}", "action"),
    ("when {} do led_toggle(body)", "cond"),
    ("every 30 ms if {} do v = 1", "cond"),
    ("action act = {}\nevery 40 ms do act", "action"),
]
LEAF = "v"
_CLOSE = {"expr": [], "cond": [LAYERS[("cond", "expr")][0]],
          "action": [LAYERS[("action", "expr")][0]]}
CLOSE_COND, CLOSE_ACTION = _CLOSE["cond"][0], _CLOSE["action"][0]


def kinds_inside(kind: str) -> list:
    return [inner for (outer, inner) in LAYERS if outer == kind]


def _fits(made: str, slot: str) -> bool:
    return slot == "any" or _ORDER[made] >= _ORDER[slot]


def text_of(statement: str, layers: list, pad: int = 1) -> str:
    """The statement with `layers` (outermost first, each a (template, makes,
    takes)) and the leaf `v` inside `pad` parentheses (at least one, so
    that a minus before it is an operator); the layers end at an
    expression."""
    inner, made = "(" * pad + LEAF + ")" * pad, "atom"
    for template, makes, takes in reversed(layers):
        if not _fits(made, takes):
            inner = f"({inner})"
        inner, made = template.format(inner), makes
    return statement.format(inner)


def depth_of(text: str) -> int:
    """The depth of the deepest statement of `text`, parsed by the Python
    front end's LALR parser without its depth gate (nothing may fail to
    parse)."""
    source = SourceFile("nest.epk", text)
    diags = Collector(source)
    chunks = list(iter_statements(iter_tokens(source, diags)))
    depths = []
    for k, chunk in enumerate(chunks):
        following = chunks[k + 1][0] if k + 1 < len(chunks) else None
        statement = parse_statement(chunk, following, source, diags)
        if statement is not None:
            depths.append(measure(statement, None)[0])
    assert not diags.items, [d.message for d in diags.items]
    return max(depths)


_AROUND = {"expr": "every 10 ms do v = {}", "cond": "when {} do stop_motor",
           "action": "every 10 ms do {}"}


@lru_cache(maxsize=None)
def cost(layer: tuple, outer: str, inner: str) -> int:
    """The levels `layer` (from `outer` to `inner`) adds, its slot's
    parentheses (which the leaf's own never need) left out."""
    around = _AROUND[outer]
    return (depth_of(text_of(around, [layer] + _CLOSE[inner], 3) + "\n")
            - depth_of(text_of(around, _CLOSE[outer], 3) + "\n"))


def plan(r, statement: tuple, target: int) -> list:
    """Layers (outermost first) that nest `statement` ((template, kind
    inside)) to close below `target` levels: drawn from `r` (any object
    with integers(lo, hi) and choice(options), tests/support/language.py's
    Choices), changing kind now and then; `exactly` pads the rest."""
    template, kind = statement
    layers, made = [], "any"
    depth = depth_of(HEAD + text_of(template, _CLOSE[kind], 3) + "\n") - 2
    while True:
        inner = kind
        if r.integers(0, 5) == 0 and len(kinds_inside(kind)) > 1:
            inner = r.choice([k for k in kinds_inside(kind) if k != kind])
        layer = r.choice(LAYERS[(kind, inner)])
        step = cost(layer, kind, inner) + (0 if not layers or _fits(layer[1], layers[-1][2])
                                           else 1)
        if depth + step > target - 4:
            break
        layers.append(layer)
        kind, depth = inner, depth + step
    return layers + _CLOSE[kind]


def exactly(statement: str, layers: list, target: int) -> str:
    """`statement` with `layers` at exactly `target` levels (its leaf padded)."""
    base = depth_of(HEAD + text_of(statement, layers, 1) + "\n")
    assert base <= target, (base, target)
    pad = 1 + target - base
    text = text_of(statement, layers, pad)
    # (a layer's other operand can be deeper than a leaf in few parentheses,
    # `max(a[:2]) - (v)`: then the first parentheses add no level)
    while depth_of(HEAD + text + "\n") < target:
        pad += 1
        text = text_of(statement, layers, pad)
    assert depth_of(HEAD + text + "\n") == target
    return text


def nested(r, target: int, statement_index=None) -> str:
    """A statement (with what it needs after HEAD) exactly `target` levels
    deep, its layers drawn from `r`."""
    index = r.integers(0, len(STATEMENTS) - 1) if statement_index is None else statement_index
    statement = STATEMENTS[index]
    return exactly(statement[0], plan(r, statement, target), target)


def layer(template: str) -> tuple:
    """The layer of LAYERS whose template is `template`."""
    return next(t for group in LAYERS.values() for t in group if t[0] == template)


def repeated(statement: str, around: list, template: str, after: list, target: int) -> str:
    """`statement` nesting one layer (`template`) again and again inside the
    layers `around` (outermost first), with the layers `after` inside the
    last one (to end at an expression), at exactly `target` levels."""
    one = layer(template)

    def depth(n):
        return depth_of(HEAD + text_of(statement, around + [one] * n + after) + "\n")
    step = max(1, depth(2) - depth(1))
    n = max(0, (target - depth(0)) // step - 1)
    while depth(n + 1) <= target:
        n += 1
    return exactly(statement, around + [one] * n + after, target)
