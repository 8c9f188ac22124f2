"""Values and units: numbers with units, constants and their chains, kinds,
the conversion to runtime integers and the 16-bit range."""
from __future__ import annotations

from typing import Optional

from ..base.source import Span
from ..diagnostics import Fix, Note
from ..stdlib.table import Param
from ..stdlib.units import (ANGLE, ARTICLE, DISTANCE, DURATION, INT, INT16_MAX, INT16_MIN,
                            INT32_MAX, KIND_UNITS, SPEED, UNITS, Quantity, describe_kind, quantity,
                            round_nearest)
from ..syntax import ast
from . import convert
from .messages import _article, _code, _either, _example, _shown, _then, did_you_mean

# A duration written without a unit is in ms; below this many it was very
# likely meant in seconds (`timer(2)`), and W008 says so.
BARE_DURATION_WARNING = 100


class Values:
    """The checker's values, units and ranges (a part of Checker)."""

    def _plain(self, value, kind: str, lo: Optional[int] = None,
               hi: Optional[int] = None) -> Optional[int]:
        """The runtime integer of `value` where `kind` is wanted (lo..hi:
        the range of a whole number), when `value` is the common case: a
        number (or a constant that is one), without a unit or with one of
        the kind, that converts with nothing to say. None sends it the
        general way (`_value`, then `_to_runtime` or the caller's own range
        check), which reports what is wrong; this is that way without the
        Quantity, with the same float operations, so both give the same
        integer (tests/check/test_plain_numbers.py)."""
        negative = False
        if value.__class__ is ast.ConstRef:
            name = value.name.name
            if name not in self.consts:
                return None
            number_node, negated, problem = self._const_chain(name)
            if problem is not None:
                return None
            value, negative = number_node, negated != value.negative
        if value.__class__ is not ast.Number:
            return None
        number = value.value
        if not abs(number) < 1e12:
            return None
        unit = value.unit
        in_steps = False
        if unit is None:
            if kind == SPEED:
                in_steps = True
            elif kind == DURATION and 0 < number < BARE_DURATION_WARNING:
                return None                 # W008
        else:
            found = UNITS.get(unit)
            if found is None or found[0] != kind:
                return None
            factor = found[1]
            if factor is None:
                in_steps = True
            else:
                number = number * factor
        if negative:                        # as _const_value negates the Quantity
            number = -number
        if kind == INT:
            if number != int(number):
                return None
            v = int(number)
            if INT16_MIN <= v <= INT16_MAX and (lo is None or lo <= v <= hi):
                return v
            return None
        if kind == DISTANCE:
            v = round_nearest(number if in_steps else number / self.geo.step_mm)
            return v if INT16_MIN <= v <= INT16_MAX else None
        if kind == SPEED:
            v = round_nearest(number if in_steps else number / self.geo.step_mm)
            return v if abs(v) <= self.geo.max_speed else None
        if kind == ANGLE:
            v = round_nearest(number)
            return v if INT16_MIN <= v <= INT16_MAX else None
        if kind == DURATION:
            v = round_nearest(number)
            return v if 0 < v <= INT32_MAX else None
        return None                         # CHOICE: names, the general way

    def _value(self, value, kind: str, param: str) -> Optional[Quantity]:
        """The quantity a value denotes where `kind` is wanted, or None after
        reporting why it cannot be one."""
        if isinstance(value, ast.ConstRef):
            return self._const_value(value, kind, param)
        if not abs(value.value) < 1e12:     # also inf, from a 400-digit number
            self.diags.error("E034", value.span,
                             f"`{_shown(value)}` is far too large for {_code(param)}",
                             help="the runtime stores values in 16-bit ints and 32-bit longs")
            return None
        if value.unit is not None:
            if value.unit not in UNITS:
                all_units = sorted(UNITS)
                hint = did_you_mean(ast.Ident(value.unit, value.unit_span),
                                    KIND_UNITS.get(kind, all_units)) or (
                    f"`{param}` is {ARTICLE[kind]}: write it in "
                    + _either(KIND_UNITS[kind]) if kind != INT
                    else f"`{param}` takes a plain number, without a unit")
                self.diags.error("E020", value.unit_span, f"unknown unit {_code(value.unit)}",
                                 help=hint)
                return None
            unit_kind = UNITS[value.unit][0]
            if unit_kind != kind:
                self.diags.error("E019", value.span,
                                 f"{_code(param)} expects {describe_kind(kind)}, "
                                 f"but `{_shown(value)}` is {describe_kind(unit_kind).split(' (')[0]}",
                                 help=self._kind_help(kind, param))
                return None
        if kind == DURATION and value.unit is None and 0 < value.value < BARE_DURATION_WARNING:
            n = value.text.lstrip("-")
            self.diags.warning("W008", value.span,
                               f"`{n}` without a unit is {n} ms: did you mean {n} s?",
                               help=Fix(Span(value.span.end_line, value.span.end_column,
                                             value.span.end_line, value.span.end_column),
                                        " s", f"write `{n} s`, or `{n} ms` if milliseconds are meant"))
        return quantity(value.value, value.unit, kind)

    @staticmethod
    def _kind_help(kind: str, param: str) -> str:
        if kind == INT:
            return f"write `{param}` as a plain number, without a unit"
        return f"write it with a unit of {describe_kind(kind).split(' (')[0]}, e.g. `{_example(kind)}`"

    def _const_chain(self, name: str):
        """Follow constant `name` through the constants it is defined by, to
        the number at the end: (Number or None, negated, problem), where
        problem is None, ("unknown", ConstRef) or ("cycle", ConstRef).

        A loop, not recursion, so a chain of thousands of constants is
        fine; memoised, so each constant is followed once per file."""
        memo = self._const_memo
        if name in memo:
            return memo[name]
        value = self.consts[name].value
        if isinstance(value, ast.Number):       # most constants: the loop's first step
            self.const_used.add(name)
            memo[name] = (value, False, None)
            return memo[name]
        path = []                   # (name, the ConstRef that led on from it)
        negated = False
        current = name
        on_path: dict = {}
        result = None
        while True:
            if current in memo:
                number, neg, problem = memo[current]
                result = (number, negated != neg, problem)
                break
            const = self.consts[current]
            self.const_used.add(current)
            value = const.value
            if isinstance(value, ast.Number):
                result = (value, negated, None)
                path.append((current, None))
                break
            on_path[current] = len(path)
            path.append((current, value))
            negated = negated != value.negative
            following = value.name.name
            if following not in self.consts:
                result = (None, negated, ("unknown", value))
                break
            if following in on_path:
                result = (None, negated, ("cycle", value))
                break
            current = following
        # Fill the memo from the end of the path back: each constant's own
        # sign is the total sign up to it, undone.
        number, total, problem = result
        sign_before = False
        signs = []
        for _, ref in path:
            signs.append(sign_before)
            if ref is not None:
                sign_before = sign_before != ref.negative
        for (const_name, _), before in zip(path, signs):
            if const_name not in memo:
                memo[const_name] = (number, total != before, problem)
        return memo[name] if name in memo else result

    def _const_value(self, ref: ast.ConstRef, kind: str, param: str) -> Optional[Quantity]:
        name = ref.name.name
        if name not in self.consts:
            self.diags.error("E013", ref.name.span, f"unknown constant {_code(name)}",
                             help=did_you_mean(ref.name, self.consts) or
                             f"define it first: `const {name} = VALUE`")
            return None
        number, negated, problem = self._const_chain(name)
        if problem is not None:
            what, at = problem
            if what == "unknown":
                missing = at.name.name
                diag_args = ("E013", at.name.span, f"unknown constant {_code(missing)}")
                help = (did_you_mean(at.name, self.consts)
                        or f"define it first: `const {missing} = VALUE`")
            else:
                diag_args = ("E023", at.span,
                             f"constant {_code(at.name.name)} is defined in terms of itself")
                help = "give one of the constants a number"
            if diag_args not in self._const_reported:
                self._const_reported.add(diag_args)
                self.diags.error(*diag_args, help=help)
            return None
        # Check the number where it is used: a constant's kind is that of
        # its unit, or whatever its use wants when it has none.
        with self.diags.capture() as inner:
            q = self._value(number, kind, param)
        if q is None:
            first = inner[0] if inner else None
            if first is not None and first.code == "E019":
                const = self.consts[name]
                self.diags.error("E019", ref.span,
                                 f"{_code(param)} expects {describe_kind(kind)}, but constant "
                                 f"{_code(name)} is `{_shown(const.value)}`",
                                 help=self._kind_help(kind, param),
                                 notes=[Note(f"{_code(name)} is defined here", const.span)])
                return None
        seen = self._const_diagnostics
        for d in inner:       # each problem of a definition, said once
            if d not in seen:
                seen.add(d)
                self.diags.items.append(d)
        if q is None:
            return None
        if negated != ref.negative:
            q = Quantity(q.kind, -q.value, q.in_steps)
        return q

    def _whole(self, node, value: float, kind: Optional[str] = None) -> bool:
        """E038 unless `value` is whole; `kind`: what a bare number is
        taken as where it stands, whose unit the help names (convert.py)."""
        if value != int(value):
            whole = round_nearest(value)
            said = convert.fraction(value, kind) if getattr(node, "unit", None) is None else None
            if said is not None:
                help = said
            elif isinstance(node, ast.Number):
                help = Fix(node.span, f"{whole} {node.unit}" if node.unit else str(whole),
                           f"write {whole}")
            else:
                help = f"write {whole}"
            self.diags.error("E038", node.span, f"`{_shown(node)}` is not a whole number",
                             help=help)
            return False
        return True

    def _to_runtime(self, q: Quantity, p: Param, node) -> Optional[int]:
        geo = self.geo
        if p.kind == INT:
            if not self._whole(node, q.value):
                return None
            v = self._fits16(int(q.value), node, p.name, "")
            if v is not None and p.lo is not None and not p.lo <= v <= p.hi:
                self.diags.error(p.range_code, node.span,
                                 f"{_code(p.name)} `{_shown(node)}` is outside {p.lo}..{p.hi}",
                                 help=f"{_code(p.name)} is {p.doc}: {p.range.split(' [')[0]}")
                return None
            return v
        if p.kind == DISTANCE:
            return self._fits16(round_nearest(q.steps(geo)), node, p.name, " steps")
        if p.kind == SPEED:
            steps = round_nearest(q.steps(geo))
            if abs(steps) > geo.max_speed:
                self.diags.error("E030", node.span,
                                 f"{_code(p.name)} of `{_shown(node)}` is {abs(steps)} steps/s, above "
                                 f"the robot's maximum of {geo.max_speed:.0f} steps/s",
                                 help=f"use a speed of at most {geo.max_speed:.0f} steps/s "
                                      f"({geo.max_speed * geo.step_mm:.0f} mm/s)")
                return None
            return steps
        if p.kind == ANGLE:
            return self._fits16(round_nearest(q.value), node, p.name, " deg")
        if p.kind == DURATION:
            ms = round_nearest(q.value)
            if ms <= 0:
                self.diags.error("E033", node.span,
                                 f"{_code(p.name)} must be a positive duration, not `{_shown(node)}`",
                                 help="durations count from when the timer was set; use at least 1 ms")
                return None
            if ms > INT32_MAX:
                self.diags.error("E034", node.span, f"`{_shown(node)}` is too long a duration",
                                 help=f"the runtime counts milliseconds in a 32-bit long (at most {INT32_MAX} ms)")
                return None
            return ms
        raise AssertionError(p.kind)

    def _fits16(self, v: int, node, param: str, unit: str) -> Optional[int]:
        if INT16_MIN <= v <= INT16_MAX:
            return v
        self.diags.error("E034", node.span,
                         f"{_code(param)} of `{_shown(node)}` is {v}{unit}, which does not fit "
                         f"the robot's 16-bit int ({INT16_MIN}..{INT16_MAX})",
                         help="split the motion into several shorter ones with `then`"
                         if param == "distance" else None)
        return None

    def _choice(self, value, p: Param) -> Optional[str]:
        """The C text of a value of an enumerated parameter (`led3`, `haa`,
        `mute`, or a number its Choices accept)."""
        choices = p.choices
        if isinstance(value, ast.ConstRef) and not value.negative:
            choice = choices.get(value.name.name)
            if choice is not None:
                return choice.c
            if value.name.name not in self.consts or choices.numbers is None:
                names = choices.names()
                self.diags.error("E041", value.name.span,
                                 f"unknown {choices.what} {_code(value.name.name)}",
                                 help=_then(did_you_mean(value.name, names),
                                            f"{_code(p.name)} is one of {choices.describe()}"))
                return None
        if choices.numbers is None:
            self.diags.error("E041", value.span,
                             f"{_code(p.name)} names {_article(choices.what)} {choices.what}, "
                             "not a number",
                             help=f"write one of {choices.describe()}")
            return None
        q = self._value(value, INT, p.name)
        if q is None or not self._whole(value, q.value):
            return None
        lo, hi = choices.numbers
        if not lo <= q.value <= hi:
            self.diags.error("E042", value.span,
                             f"{_code(p.name)} `{_shown(value)}` is outside {lo}..{hi}",
                             help=f"the numbered {choices.what}s are {lo}..{hi}; the others have "
                                  f"names: {', '.join(map(_code, choices.names()))}")
            return None
        return str(int(q.value))
