"""W020 against brute force: random expressions over variables with small
intervals (far from 0 or not), each variable used once; every choice of
the variables' values is evaluated as the runtime does (each operation
exact while it fits 32 bits, saturated there), and an operation whose
exact result leaves 32 bits is an overflow, and so is the whole expression
where the value it stores leaves -32768..32767. The checker must warn on the expression iff some choice
overflows, and each warning must be at an operation that overflows for
some choice."""
from __future__ import annotations

import itertools

from hypothesis import assume, given, settings
from hypothesis import strategies as st

from epuckc.base.source import SourceFile
from epuckc.check.checker import check
from epuckc.diagnostics import Collector
from epuckc.stdlib import arith
from epuckc.syntax.parser import parse

VARS = ("a", "b", "c")
LO, HI = arith.INT16_MIN, arith.INT16_MAX


def _diags(text: str) -> list:
    source = SourceFile("t.epk", text)
    diags = Collector(source)
    check(parse(source, diags), diags)
    return diags.items


@st.composite
def trees(draw, free=None, depth=0):
    """("num", v) | ("var", name) | (op, children...); `free`: the
    variables not used yet (shared along one tree)."""
    if free is None:
        free = list(VARS)
    leaf = depth >= 3 or draw(st.integers(0, 3)) == 0
    if leaf:
        if free and draw(st.booleans()):
            return ("var", free.pop(draw(st.integers(0, len(free) - 1))))
        return ("num", draw(st.sampled_from([0, 1, 2, 3, -1, -7, 100, 4095, 20000, 32767,
                                             -32767, 16384, -200])))
    op = draw(st.sampled_from(["+", "-", "*", "*", "/", "neg", "abs", "min", "max",
                               "clamp"]))
    if op in ("neg", "abs"):
        return (op, draw(trees(free, depth + 1)))
    if op == "clamp":
        return (op, draw(trees(free, depth + 1)), draw(trees(free, depth + 1)),
                draw(trees(free, depth + 1)))
    if op == "/":       # a divisor that is a leaf, not 0: its corners are values it takes
        left = draw(trees(free, depth + 1))
        if free and draw(st.booleans()):
            right = ("var", free.pop(0))
        else:
            right = ("num", draw(st.sampled_from([1, 2, 3, -1, -2, 7, 100])))
        return (op, left, right)
    return (op, draw(trees(free, depth + 1)), draw(trees(free, depth + 1)))


def text_of(t, spans: list, col: int) -> str:
    """The source text of `t` starting at column `col` (1-based); appends
    (start, end, node) of each operation to `spans` (end exclusive)."""
    kind = t[0]
    if kind == "num":
        return f"({t[1]})" if t[1] < 0 else str(t[1])
    if kind == "var":
        return t[1]
    if kind in ("neg", "abs", "min", "max", "clamp"):
        head = "-(" if kind == "neg" else f"{kind}("
        parts, at = [], col + len(head)
        for child in t[1:]:
            part = text_of(child, spans, at)
            parts.append(part)
            at += len(part) + 2
        text = head + ", ".join(parts) + ")"
        spans.append((col, col + len(text), t))
        return text
    left = text_of(t[1], spans, col + 1)
    right_col = col + len(left) + len(kind) + 5     # `(left) op (`
    right = text_of(t[2], spans, right_col)
    inner = f"({left}) {kind} ({right})"
    spans.append((col, col + len(inner), t))
    return inner


def evaluate(t, env, overflowed: set) -> int:
    """The runtime's value; the operations whose exact result left the
    range are added to `overflowed` (by id)."""
    kind = t[0]
    if kind == "num":
        return t[1]
    if kind == "var":
        return env[t[1]]
    args = [evaluate(c, env, overflowed) for c in t[1:]]
    if kind in ("+", "-", "*"):
        exact = {"+": args[0] + args[1], "-": args[0] - args[1],
                 "*": args[0] * args[1]}[kind]
    elif kind == "/":
        exact = 0 if args[1] == 0 else int(args[0] / args[1]) if abs(args[0]) < 2 ** 50 else 0
        if args[1] != 0:
            q = abs(args[0]) // abs(args[1])
            exact = q if (args[0] < 0) == (args[1] < 0) else -q
    elif kind == "neg":
        exact = -args[0]
    elif kind == "abs":
        exact = abs(args[0])
    elif kind == "min":
        exact = min(args)
    elif kind == "max":
        exact = max(args)
    else:
        exact = arith.clamp(*args)
    if not arith.fits32(exact, exact):
        overflowed.add(id(t))
    return arith.sat32(exact)


intervals = st.tuples(st.sampled_from([-32768, -32700, -20000, -5000, -3, 0, 5, 200, 4000,
                                       16000, 30000, 32764]),
                      st.integers(0, 3))


@settings(max_examples=300, deadline=None)
@given(trees(), st.tuples(intervals, intervals, intervals))
def test_w020_iff_some_values_overflow(tree, ranges):
    bounds = {v: (lo, min(lo + width, HI)) for v, (lo, width) in zip(VARS, ranges)}
    spans: list = []
    prefix = "every 1 s do r = "
    expr = text_of(tree, spans, len(prefix) + 1)
    lines = ["var r = 0"]
    lines += [f"var {v} = {lo}" for v, (lo, hi) in bounds.items()]
    lines += [f"on immediate do {v} = {hi}" for v, (lo, hi) in bounds.items()]
    lines.append(prefix + expr)
    line_no = len(lines)
    found = _diags("\n".join(lines) + "\n")
    assume(not any(d.severity == "error" for d in found))     # `/ a` where a is always 0
    warned = [d for d in found if d.code == "W020" and d.span.line == line_no]

    overflowed: set = set()
    for values in itertools.product(*(range(lo, hi + 1) for lo, hi in bounds.values())):
        stored = evaluate(tree, dict(zip(bounds, values)), overflowed)
        if not LO <= stored <= HI:      # saturated where `r` stores it
            overflowed.add(id(tree))

    assert bool(warned) == bool(overflowed), (expr, bounds, [d.message for d in warned])
    by_span = {(start, end): t for start, end, t in spans}
    for d in warned:
        node = by_span.get((d.span.column, d.span.end_column))
        assert node is not None, (expr, d.span, d.message)
        assert id(node) in overflowed, (expr, bounds, d.message)
    # one warning per root cause: never one above another
    for d in warned:
        for e in warned:
            if d is not e:
                assert not (d.span.column <= e.span.column and e.span.end_column <= d.span.end_column)


def test_the_issue_s_programs():
    """`area = 300 * 200` and GCtronic's weighted sum warn where they are
    stored; what is proven inside does not, and a sum that leaves 16 bits
    inside the expression but is divided before it is stored does not."""
    found = _diags("var area = 0\nevery 1 s do area = 300 * 200\n")
    assert [d.code for d in found] == ["W020"] and "60000" in found[0].message
    found = _diags("var t = 0\nevery 10 ms do t = 8 * ir0 + 4 * ir1 - 4 * ir6 - 16 * ir7\n")
    assert {d.code for d in found} == {"W020"}
    assert _diags("var t = 0\nevery 10 ms do t = ir0 / 2 + ir1 / 4 - ir6 / 4 - ir7\n") == []
    assert _diags("var t = 0\nevery 10 ms do t = (16 * ir7 + 16 * ir0) / 4\n") == []
    # a guard bounds the first step; a bound where it is given keeps it inside
    assert _diags("var n = 0\non sensor(ir0 > 9) repeat if n < 3 do n += 1\n"
                  "on immediate do start_sensor\n") == []
    assert _diags("var n = 0\nevery 1 s do n = min(n + 1, 1000)\n") == []
    # a one-shot rule adds once
    assert _diags("var n = 0\nvar r = 0\non immediate do n += 1\nevery 1 s do r = n * 30000\n") \
        == []
    assert _diags("var n = 0\nvar r = 0\non stop_motor repeat do n += 1, start_straight(1, 1 mm)\n"
                  "every 1 s do r = n * 30000\n")


def test_a_guard_narrows_only_until_the_variable_changes():
    found = _diags("var n = 0\nevery 1 s if n < 3 do n += 1, n = n * 20000\n")
    assert [d.code for d in found] == ["W020"] and "n * 20000" in found[0].message
