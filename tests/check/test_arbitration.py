"""W009 against brute force, and the timing it knows.

The property test generates pairs of rules of one priority that fire at
the same times as far as their events go (`every 1 s`, or a sensor event),
with guards over two variables (whose values at the start of a poll are
exactly an interval: a rule of lower priority draws them with `random`)
and two readings, and maybe an assignment in the first rule. A scenario is
a choice of the variables' and readings' values at the start of a poll:
the first rule fires if its condition holds, its assignment runs, then the
second rule's condition is evaluated. Each reading is tried at the values
where a comparison can change (each number compared with, +-1, and the
ends), which covers every case. W009 must be given whenever some scenario
fires both, and, when the first rule assigns nothing, only then."""
from __future__ import annotations

import itertools
import re

from hypothesis import given, settings
from hypothesis import strategies as st

from epuckc.base.source import SourceFile
from epuckc.check.checker import check
from epuckc.diagnostics import Collector
from epuckc.syntax.parser import parse

OPS = ("<", "<=", ">", ">=", "==", "!=")
COMPARE = {"<": lambda a, b: a < b, "<=": lambda a, b: a <= b, ">": lambda a, b: a > b,
           ">=": lambda a, b: a >= b, "==": lambda a, b: a == b, "!=": lambda a, b: a != b}


def _codes(text: str) -> list:
    source = SourceFile("t.epk", text)
    diags = Collector(source)
    check(parse(source, diags), diags)
    assert not diags.has_errors, [d.message for d in diags.items]
    return [d for d in diags.items if d.code == "W009"]


@st.composite
def formulas(draw, depth=0):
    if depth >= 2 or draw(st.integers(0, 2)) == 0:
        name = draw(st.sampled_from(["v", "w", "ir0", "ir1"]))
        value = draw(st.integers(-2, 6)) if name in ("v", "w") else \
            draw(st.sampled_from([0, 1, 100, 101, 4094, 4095]))
        return ("atom", name, draw(st.sampled_from(OPS)), value)
    kind = draw(st.sampled_from(["and", "or", "not"]))
    if kind == "not":
        return ("not", draw(formulas(depth + 1)))
    return (kind, draw(formulas(depth + 1)), draw(formulas(depth + 1)))


def text_of(f) -> str:
    if f[0] == "atom":
        return f"{f[1]} {f[2]} {f[3]}"
    if f[0] == "not":
        return f"not ({text_of(f[1])})"
    return f"({text_of(f[1])}) {f[0]} ({text_of(f[2])})"


def holds(f, env) -> bool:
    if f[0] == "atom":
        return COMPARE[f[2]](env[f[1]], f[3])
    if f[0] == "not":
        return not holds(f[1], env)
    if f[0] == "and":
        return holds(f[1], env) and holds(f[2], env)
    return holds(f[1], env) or holds(f[2], env)


def numbers(f, name) -> set:
    if f is None:
        return set()
    if f[0] == "atom":
        return {f[3]} if f[1] == name else set()
    return set().union(*(numbers(p, name) for p in f[1:]))


sensor_events = st.lists(st.tuples(st.sampled_from(["ir0", "ir1"]), st.sampled_from(["<", ">"]),
                                   st.sampled_from([0, 100, 101, 4095])),
                         min_size=1, max_size=2, unique_by=lambda c: c[0])


@settings(max_examples=250, deadline=None)
@given(st.one_of(st.none(), formulas()), st.one_of(st.none(), formulas()),
       st.one_of(st.none(), sensor_events), st.one_of(st.none(), sensor_events),
       st.integers(-2, 3), st.integers(-2, 3),
       st.one_of(st.none(), st.tuples(st.sampled_from(["v", "w"]), st.sampled_from(["=", "+="]),
                                      st.integers(-3, 3))))
def test_w009_iff_a_poll_fires_both(guard_a, guard_b, sensor_a, sensor_b, v_lo, w_lo, assign):
    bounds = {"v": (v_lo, v_lo + 2), "w": (w_lo, w_lo + 1)}

    def head(sensor, guard):
        event = "every 1 s" if sensor is None else \
            "on sensor(" + ", ".join(f"{n} {op} {t}" for n, op, t in sensor) + ") repeat"
        return event + " priority 1" + (f" if {text_of(guard)}" if guard is not None else "")

    assigned = f"{assign[0]} {assign[1]} {assign[2]}, " if assign else ""
    program = "\n".join([
        f"var v = {v_lo}", f"var w = {w_lo}",
        "on immediate do start_sensor",
        f"every 1 ms do v = random({v_lo}, {v_lo + 2}), w = random({w_lo}, {w_lo + 1})",
        f"{head(sensor_a, guard_a)} do {assigned}start_straight(100, 1 cm)",
        f"{head(sensor_b, guard_b)} do start_straight(-100, 1 cm)",
        "on stop_motor do exit_main"]) + "\n"
    warned = [d for d in _codes(program) if d.span.line in (5, 6)]

    def condition(sensor, guard, env):
        ok = guard is None or holds(guard, env)
        if sensor is not None:
            ok = ok and any(COMPARE[op](env[n], t) for n, op, t in sensor)
        return ok

    def points(name):
        found = {0, 4095}
        for f in (guard_a, guard_b):
            found |= numbers(f, name)
        for s in (sensor_a, sensor_b):
            found |= {t for n, _, t in s or () if n == name}
        return sorted({p + d for p in found for d in (-1, 0, 1) if 0 <= p + d <= 4095})

    both = False
    for v, w, ir0, ir1 in itertools.product(range(bounds["v"][0], bounds["v"][1] + 1),
                                            range(bounds["w"][0], bounds["w"][1] + 1),
                                            points("ir0"), points("ir1")):
        env = {"v": v, "w": w, "ir0": ir0, "ir1": ir1}
        if not condition(sensor_a, guard_a, env):
            continue
        if assign:
            name, op, k = assign
            env[name] = k if op == "=" else env[name] + k
        if condition(sensor_b, guard_b, env):
            both = True
            break
    if both:
        assert warned, program
    elif assign is None:
        assert not warned, (program, [d.message for d in warned])


def _w009(text: str) -> list:
    return [d.message for d in _codes(text)]


MOVE = "start_straight(100, 1 cm)"


def test_on_enter_and_every_of_one_mode_do_not_meet():
    """`every` and `after` are armed at the entry, when `on enter` (and a
    one-shot `immediate` of the mode) fires; they fire a period later."""
    for event in ("every 8 s", "after 1 ms"):
        for first in ("on enter", "on immediate"):
            assert _w009(f"initial mode m {{\n{first} do {MOVE}\n{event} do {MOVE}\n}}\n") == []
    # outside the mode, its own timer meets an entry at any time
    assert _w009(f"initial mode m {{\non enter do {MOVE}\n}}\nevery 8 s do {MOVE}\n")
    # `immediate repeat` fires at every poll
    assert _w009(f"initial mode m {{\non immediate repeat do {MOVE}\nevery 8 s do {MOVE}\n}}\n")


def test_modes_that_cannot_be_current_together():
    assert _w009(f"initial mode a {{\nevery 1 s do {MOVE}\n}}\n"
                 f"mode b {{\nevery 1 s do {MOVE}\n}}\n") == []


def test_enter_and_stop_motor_meet_when_a_motion_can_end_at_the_entry():
    inside = f"initial mode m {{\non enter do {MOVE}\non stop_motor repeat do {MOVE}\n}}\n"
    assert _w009(inside) == []
    # a motion of a rule outside modes goes on across the entry
    assert _w009(inside + f"on immediate do {MOVE}\n")
    # a stop just before an entry, in the same poll: the event comes at the entry
    assert _w009(inside.replace("initial mode m", "mode m")
                 + "initial mode n {\non enter do start_straight(100, 1 m)\n"
                   "after 1 s do stop_motor, enter m\n}\n")
    # ... but not when exit_main follows the stop
    assert _w009(inside.replace("initial mode m", "mode m")
                 + "initial mode n {\non enter do start_straight(100, 1 m)\n"
                   "after 1 s do enter m\n}\non remote(1) priority 5 do stop_motor, exit_main\n") == []


def test_every_pair_is_named_and_none_is_only_counted():
    """Ten pairs one by one, then one more warning that lists every other
    pair: together, every pair of the seven racing rules once."""
    import re
    rules = "\n".join(f"rule r{i}: every 1 s do start_straight({100 + i}, 1 cm)"
                      for i in range(7))
    found = _w009(rules + "\n")
    assert len(found) == 11
    pairs = [tuple(re.findall(r"rule `(r\d)`", m)[:2]) for m in found[:10]]
    summary = found[10]
    assert summary.startswith("11 more pairs")
    for group in summary.split(": ", 1)[1].split("; "):
        first, partners = group.split(" with ")
        pairs += [(re.findall(r"r\d", first)[0], p) for p in re.findall(r"r\d", partners)]
    assert sorted(pairs) == sorted((f"r{i}", f"r{j}") for i in range(7) for j in range(i + 1, 7))


def test_a_rule_is_named_by_its_name_or_its_head_and_line():
    [message] = _w009(f"rule a: on immediate do {MOVE}\non immediate if x > 0 do {MOVE}\n")
    assert message.startswith("rule `a` and `on immediate if x > 0` (line 2)")


def test_a_variable_counts_where_no_action_changes_it_between_the_two_conditions():
    pair = (f"every 1 s priority 1 if v == 0 do {MOVE}\n"
            f"every 1 s priority 1 if v == 1 do {MOVE}\n")
    flip = "every 1 s priority {} do v = 1 - v\n"
    # run before both (a higher priority) or after both (a lower one): no race
    assert _w009("var v = 0\n" + flip.format(2) + pair) == []
    assert _w009("var v = 0\n" + pair + flip.format(0)) == []
    # between them, in the walk: a race, though the rule that flips commands nothing
    assert _w009("var v = 0\n" + pair.replace("\n", "\n" + flip.format(1), 1))
    # a `when` condition without a guard is evaluated with the others, early
    early = (f"when v == 0 priority 1 do {MOVE}\n"
             f"every 1 s priority 1 if v == 1 do {MOVE}\n")
    assert _w009("var v = 0\n" + early + flip.format(0)) == []


def test_the_pair_loop_decides_as_can_fire_together():
    """_racing_pairs, W009's fast loop over every pair, gives what
    can_fire_together gives pair by pair (on the examples and the cases)."""
    from pathlib import Path

    from epuckc.check import arbitration
    from epuckc.check.checker import Checker
    root = Path(__file__).resolve().parents[2]
    files = sorted((root / "examples").glob("*.epk")) + sorted(
        (root / "tests" / "check" / "cases").glob("W0*.epk"))
    compared = 0
    for path in files:
        source = SourceFile(path.name, path.read_text(encoding="utf-8"))
        diags = Collector(source)
        checker = Checker(parse(source, diags), diags)
        out = checker.check()
        rules = out.rules
        if len(rules) < 2:
            continue
        facts = arbitration._Rules(checker, rules, rules)
        by_priority: dict = {}
        for r in rules:
            by_priority.setdefault(r.priority, []).append(r)
        for group in by_priority.values():
            fast = arbitration._racing_pairs(group, facts)
            slow = [(a, b) for i, a in enumerate(group) for b in group[i + 1:]
                    if arbitration.can_fire_together(a, b, facts)]
            assert [(id(a), id(b)) for a, b in fast] == [(id(a), id(b)) for a, b in slow], path
            # and by kinds of rules, as for a big group
            blocks = arbitration._racing_blocks(
                group, arbitration.rule_facts(group, facts), facts, {})
            assert _expanded(blocks) == {frozenset((id(a), id(b))) for a, b in slow}, path
            compared += len(group) * (len(group) - 1) // 2
    assert compared > 100


def _expanded(blocks) -> set:
    pairs = set()
    for _, _, xs, ys in blocks:
        for x in xs:
            for y in ys:
                if x is not y:
                    pairs.add(frozenset((id(x), id(y))))
    return pairs


def test_the_runtime_agrees_on_a_mode_s_own_timers(tmp_path):
    """Run against the runtime: a mode entered again and again, its `on
    enter`, one-shot `immediate`, `every` and `after` rules. The pairs W009
    leaves out never fire in one poll; the one it reports does (`on enter`
    and `on immediate`, both at each entry)."""
    from tests.support.programs import events, run_program
    program = tmp_path / "timers.epk"
    program.write_text(
        "initial mode m {\n"
        "    on enter do start_straight(100, 1 mm)\n"
        "    every 3 ms do start_straight(100, 2 mm)\n"
        "    after 2 ms do start_straight(100, 3 mm)\n"
        "    on immediate do start_straight(100, 4 mm)\n"
        "    after 7 ms priority 1 do enter m\n"
        "}\n"
        "after 60 ms priority 9 do exit_main\n")
    warned = _codes(program.read_text())
    reported = {tuple(sorted(re.findall(r"\(line (\d)\)", d.message)[:2])) for d in warned}
    assert reported == {("2", "5")}
    records, _ = run_program(program, tmp_path)
    fired: dict = {}
    for r in events(records, "timers.epk:"):
        line = r["name"].split(":")[1].split()[0]
        fired.setdefault(line, set()).add(r["t_ms"])
    assert len(fired["6"]) >= 5                      # entered again and again
    for a, b in itertools.combinations(["2", "3", "4", "5"], 2):
        together = fired[a] & fired[b]
        assert bool(together) == ((a, b) in reported), (a, b, together)


def test_a_when_rule_beside_an_event_rule_of_the_same_facts_is_compared_without_a_crash():
    """Found by bench/fuzz_campaign.py: the help compared the two rules'
    events as if both were `when` rules (TypeError: an internal error)."""
    text = """\
const K1 = -45 deg
when -heading <= heading do v1 += abs(x) + -50 mm + v1 + (-ir7) * (v1), start_straight(50 mm/s, 1 m) then v1 = -x
    on stop_motor if heading + heading < K1 - K1 do start_straight(300 steps/s, -2 cm), set_speed(-200 steps/s - 300 steps/s, abs(random(-25956, 9051) * (1000 steps/s - 0 steps/s))), start_sensor then start_straight(300 steps/s, 1 m), v2 = v2, set_speed(50 mm/s, ((abs(ir7)) * (0 steps/s + -200 steps/s)) / (random(24159, 30910) - acc_z))
"""
    source = SourceFile("t.epk", text)
    diags = Collector(source)
    check(parse(source, diags), diags)      # v1, v2 are not declared: errors, no crash
    assert "E051" in {d.code for d in diags.items}


def test_a_big_group_by_timing_only_misses_no_race():
    """Past PAIR_BUDGET kinds of rules, a group is compared by timing
    alone: every pair that can fire together is still reported (the
    conditions are not looked at, and the help says so)."""
    from epuckc.check import arbitration
    from epuckc.check.checker import Checker
    lines = ["on immediate do start_sensor"]
    lines += [f"on sensor(ir{i % 8} > {100 + i}) repeat do start_curve(0 mm, 90 deg, 300)"
              for i in range(90)]
    lines += [f"when ir{i % 8} > {200 + i} and ir{(i + 1) % 8} < {300 + i} do stop_motor"
              for i in range(10)]
    source = SourceFile("big.epk", "\n".join(lines) + "\n")
    diags = Collector(source)
    checker = Checker(parse(source, diags), diags)
    rules = checker.check().rules
    group = [r for r in rules if r.event.name != "immediate"]
    facts = arbitration._Rules(checker, group, rules)
    blocks = arbitration._racing_blocks(group, arbitration.rule_facts(group, facts), facts, {})
    assert facts.by_timing_only
    exact = {frozenset((id(a), id(b))) for i, a in enumerate(group) for b in group[i + 1:]
             if arbitration.can_fire_together(a, b, facts)}
    assert exact and exact <= _expanded(blocks)
    w009 = [d for d in diags.items if d.code == "W009"]
    assert w009 and all("timing only" in d.help for d in w009)
