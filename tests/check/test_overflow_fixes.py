"""W020's fixes never change what a program computes (issue 41: the fix
of `d = WX[wp] - x` halved the distance). Over random expressions (those
of test_overflow.py) whose stored value can leave 16 bits: the fix is
applied to the text, the program is checked again, and the fixed
expression, parsed back and evaluated as the runtime does, stores the same
value as the original for every choice of its variables' values, with no
W020 left on its line. And the odometry's interval alone, all of 16 bits,
is no reason to warn."""
from __future__ import annotations

import itertools

from hypothesis import HealthCheck, assume, given, settings
from hypothesis import strategies as st

from epuckc.base.source import SourceFile
from epuckc.check.checker import check
from epuckc.diagnostics import Collector
from epuckc.stdlib import arith
from epuckc.syntax import ast
from epuckc.syntax.parser import parse

from tests.check.test_overflow import VARS, intervals, text_of, trees

PREFIX = "every 1 s do r = "


def _check(text: str):
    source = SourceFile("t.epk", text)
    diags = Collector(source)
    program = parse(source, diags)
    check(program, diags)
    return program, diags.items


def _value(node, env) -> int:
    """The runtime's value of an expression's AST: each operation exact,
    saturated at 32 bits (stdlib/arith.py)."""
    cls = node.__class__
    if cls is ast.Paren:
        return _value(node.expr, env)
    if cls is ast.Number:
        return int(node.value)
    if cls is ast.ConstRef:
        v = env[node.name.name]
        return arith.sat32(-v) if node.negative else v
    if cls is ast.UnaryOp:
        return arith.sat32(-_value(node.operand, env))
    if cls is ast.BinOp:
        a, b = _value(node.left, env), _value(node.right, env)
        if node.op == "/":
            exact = 0 if b == 0 else (abs(a) // abs(b)) * (1 if (a < 0) == (b < 0) else -1)
        else:
            exact = {"+": a + b, "-": a - b, "*": a * b}[node.op]
        return arith.sat32(exact)
    args = [_value(a.value, env) for a in node.args]
    name = node.name.name
    if name == "abs":
        return arith.sat32(abs(args[0]))
    if name == "clamp":
        return arith.clamp(*args)
    return {"min": min, "max": max}[name](args)


def _stored(program, env) -> int:
    """What `r = ...` (the last statement) stores: saturated to 16 bits."""
    [step] = program.statements[-1].body.steps
    [assign] = step.calls
    return arith.sat(_value(assign.value, env))


def _apply(text: str, fix) -> str:
    lines = text.split("\n")
    line = lines[fix.span.line - 1]
    lines[fix.span.line - 1] = (line[:fix.span.column - 1] + fix.text
                                + line[fix.span.end_column - 1:])
    return "\n".join(lines)


# Most random expressions stay in 16 bits and have no fix to try: they are
# filtered out (assume), often more than Hypothesis's health check allows at
# the start of a run, though the run goes on to find many that do warn.
@settings(max_examples=200, deadline=None, suppress_health_check=[HealthCheck.filter_too_much])
@given(trees(), st.tuples(intervals, intervals, intervals))
def test_every_fix_keeps_the_value_and_ends_the_warning(tree, ranges):
    bounds = {v: (lo, min(lo + width, arith.INT16_MAX)) for v, (lo, width) in zip(VARS, ranges)}
    expr = text_of(tree, [], len(PREFIX) + 1)
    lines = ["var r = 0"]
    lines += [f"var {v} = {lo}" for v, (lo, hi) in bounds.items()]
    lines += [f"on immediate do {v} = {hi}" for v, (lo, hi) in bounds.items()]
    lines.append(PREFIX + expr)
    line_no = len(lines)
    text = "\n".join(lines) + "\n"
    program, found = _check(text)
    assume(not any(d.severity == "error" for d in found))
    fixes = [d.fixes[0] for d in found if d.code == "W020" and d.span.line == line_no and d.fixes]
    assume(fixes)
    for fix in fixes:
        fixed_text = _apply(text, fix)
        fixed, again = _check(fixed_text)
        assert not [d for d in again if d.severity == "error"], (expr, fix.text)
        assert not [d for d in again if d.code == "W020" and d.span.line == line_no], \
            (expr, fix.text, [d.message for d in again])
        for values in itertools.product(*(range(lo, hi + 1) for lo, hi in bounds.values())):
            env = dict(zip(bounds, values))
            assert _stored(fixed, env) == _stored(program, env), (expr, fix.text, env)


def test_a_counter_s_fix_is_its_saturation_said():
    text = "var n = 0\nevery 1 s do n += 1\n"
    _, [d] = _check(text)
    assert d.code == "W020" and d.fixes[0].text == "n = min(n + 1, 32767)"
    _, again = _check(_apply(text, d.fixes[0]))
    assert again == []


def test_the_odometry_s_full_range_alone_is_no_warning():
    """`x` and `y` are all of 16 bits; a goal's distance from them only
    leaves 16 bits for a robot more than 16 m from its start."""
    goal = "const WX = [100 mm, 500 mm, 800 mm]\nvar wp = 0\nvar d = 0 mm\n" \
           "every 1 s do wp = (wp + 1) % 3\n"
    for value in ("WX[wp] - x", "x - WX[wp]", "y + 500 mm", "x - y", "(x + y) / 2", "x * 2"):
        _, found = _check(goal + f"every 20 ms do d = {value}\n")
        assert not [d for d in found if d.code == "W020"], (value, [d.message for d in found])
    # but beyond what any robot near its start reaches, still
    for value in ("x * 3", "x - y + WX[wp]", "x + 20000 mm"):
        _, found = _check(goal + f"every 20 ms do d = {value}\n")
        assert [d.code for d in found] == ["W020"], value
