"""The checker's fast path for plain numbers (Checker._plain) gives what its
general path gives (`_value`, then `_to_runtime`): the same integer when
that has nothing to say, and None, so that the general path reports,
whenever it would report anything."""
from __future__ import annotations

import math

from hypothesis import given, settings
from hypothesis import strategies as st

from epuckc.syntax import ast
from epuckc.check.checker import Checker
from epuckc.diagnostics import Collector
from epuckc.base.source import SourceFile, Span
from epuckc.stdlib.table import Param
from epuckc.stdlib.units import KINDS, UNITS, Geometry

SPAN = Span(1, 1, 1, 2)

numbers = st.one_of(
    st.integers(-70000, 70000).map(float),
    st.floats(-1e13, 1e13, allow_nan=False),
    st.sampled_from([0.0, -0.0, 0.5, -0.5, 1.5, 99.0, 99.5, 100.0, 999.5, 1000.5, 32767.0,
                     32767.5, 32768.0, -32768.0, -32768.5, 2.0**31 - 1, 2.0**31, 1e12,
                     -1e12, math.inf]))
units = st.sampled_from([None, None, None, *UNITS, "km", "kg", "Steps"])
geometries = st.builds(Geometry,
                       st.floats(1.0, 2000.0), st.floats(1.0, 500.0),
                       st.integers(1, 100000), st.floats(1.0, 1000.0))
ranges = st.one_of(st.just((None, None)),
                   st.tuples(st.integers(-40000, 300), st.integers(0, 40000)))


def general(checker: Checker, number: ast.Number, param: Param):
    """The general path's integer, and whether it said anything."""
    with checker.diags.capture() as said:
        q = checker._value(number, param.kind, param.name)
        v = checker._to_runtime(q, param, number) if q is not None else None
    return v, bool(said)


@settings(max_examples=2000, deadline=None)
@given(numbers, units, st.sampled_from(KINDS), ranges, geometries)
def test_plain_numbers_convert_as_the_general_path_does(value, unit, kind, bounds, geo):
    checker = Checker(ast.Program("t.epk"), Collector(SourceFile("t.epk", "")))
    checker.geo = geo
    lo, hi = bounds if kind == "int" else (None, None)
    number = ast.Number(value, repr(value), unit, SPAN if unit else None, SPAN)
    param = Param("p", kind, lo=lo, hi=hi)
    expected, said = general(checker, number, param)
    fast = checker._plain(number, kind, lo, hi)
    assert fast == (None if said else expected)
    if fast is not None:
        assert type(fast) is int and type(expected) is int


@settings(max_examples=1000, deadline=None)
@given(numbers, units, st.sampled_from(KINDS), ranges, st.lists(st.booleans(), max_size=3),
       st.booleans())
def test_constants_convert_as_the_general_path_does(value, unit, kind, bounds, chain, negative):
    """`-c` where `const c = -b`, `const b = a`, `const a = NUMBER`: the
    signs along the chain and at the use, as _const_value applies them."""
    checker = Checker(ast.Program("t.epk"), Collector(SourceFile("t.epk", "")))
    lo, hi = bounds if kind == "int" else (None, None)
    number = ast.Number(value, repr(value), unit, SPAN if unit else None, SPAN)
    names = [f"c{i}" for i in range(len(chain) + 1)]
    checker.consts[names[0]] = ast.ConstDef(ast.Ident(names[0], SPAN), number, SPAN)
    for name, before, negated in zip(names[1:], names, chain):
        ref = ast.ConstRef(ast.Ident(before, SPAN), negated, SPAN)
        checker.consts[name] = ast.ConstDef(ast.Ident(name, SPAN), ref, SPAN)
    use = ast.ConstRef(ast.Ident(names[-1], SPAN), negative, SPAN)
    param = Param("p", kind, lo=lo, hi=hi)
    fast = checker._plain(use, kind, lo, hi)
    checker._const_memo.clear()
    expected, said = general(checker, use, param)
    assert fast == (None if said else expected)


def test_the_fast_path_is_taken_for_the_common_cases():
    checker = Checker(ast.Program("t.epk"), Collector(SourceFile("t.epk", "")))

    def plain(value, unit, kind, lo=None, hi=None):
        return checker._plain(ast.Number(value, str(value), unit, SPAN, SPAN), kind, lo, hi)

    assert plain(300.0, None, "speed") == 300
    assert plain(10.0, "cm", "distance") == 776        # 100 mm, 0.1288 mm a step
    assert plain(2.0, "s", "duration") == 2000
    assert plain(90.0, "deg", "angle") == 90
    assert plain(300.0, None, "int", 0, 4095) == 300
    # everything the general path has something to say about
    assert plain(50.0, None, "duration") is None        # W008: ms meant as s?
    assert plain(2.0, "cm", "speed") is None            # E019
    assert plain(4096.0, None, "int", 0, 4095) is None  # out of range
    assert plain(1.5, None, "int") is None              # E038
    c, minus_c = (ast.ConstRef(ast.Ident("c", SPAN), negative, SPAN) for negative in (False, True))
    assert checker._plain(c, "int") is None                         # E013
    checker.consts["c"] = ast.ConstDef(ast.Ident("c", SPAN), ast.Number(5.0, "5", "cm", SPAN, SPAN),
                                       SPAN)
    assert checker._plain(c, "distance") == 388
    assert checker._plain(minus_c, "distance") == -388
