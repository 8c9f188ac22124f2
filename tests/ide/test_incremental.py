"""The language server's incremental checking (epuckc/ide/incremental.py) must
report exactly what `epuckc check` reports, edit after edit, and splitting
resumed at a statement start must cut as the whole file's split does."""
from __future__ import annotations

import random
from pathlib import Path

from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from epuckc.diagnostics import Collector, Report
from epuckc.check.frontend import check_file
from epuckc.ide.incremental import Analyzer
from epuckc.ide.statements import VLINE, line_starts, split_statements
from epuckc.syntax.lexer import MAX_LEXICAL_ERRORS, iter_statements, iter_tokens
from epuckc.base.source import SourceFile

REPO = Path(__file__).resolve().parents[2]
PROGRAMS = [p.read_text(encoding="utf-8") for p in sorted((REPO / "examples").glob("*.epk"))] + [
    p.read_text(encoding="utf-8", errors="replace")
    for p in sorted((REPO / "tests" / "check" / "cases").glob("*.epk"))]

# pieces that make statements start, merge, break and come back
FRAGMENTS = ["on ", "rule r", "rule r: ", ": ", "do ", "then ", ", ", "(", ")", "cancel r",
             "start_straight(300, 2 m)", "stop_motor", "const K = 5 cm\n", "action a = ",
             "timer(2 s)", "sensor(", "ir0 > 300", "\n", "\r\n", "\r", "#", " # é on\n",
             '"x.c"', "extern action e() from ", "extern ", "action", "é", "@", "5on", "online",
             "robot { axle: 53 mm }", "=", "-", "1.5", "steps/s", "repeat ", "K", "a", "\t", '"',
             "\\", "x", "99999 m", "event_timer(time: 1 s)", "start_sensor", "set_timer"]


def full_check(text: str) -> list:
    report = Report()
    check_file(Path("/nonexistent/prog.epk"), report, shown_name="prog.epk", text=text)
    return report.sorted()


def lexer_starts(text: str) -> list:
    """Offsets (in `text`, as an editor has it) of the lexer's statements."""
    source = SourceFile("x", text)
    starts = line_starts(text)
    return [starts[chunk[0].line - 1] + chunk[0].column - 1
            for chunk in iter_statements(iter_tokens(source, Collector(source)))]


def splitter_starts(text: str) -> list:
    starts, _ = split_statements(text)
    return starts[1:]


def edit(rng: random.Random, text: str) -> str:
    start = rng.randint(0, len(text))
    end = min(len(text), start + rng.choice([0, 0, 1, 3, 10, 40]))
    new = "".join(rng.choice(FRAGMENTS) for _ in range(rng.choice([0, 1, 1, 2, 4])))
    return text[:start] + new + text[end:]


def test_edit_after_edit_equals_a_full_check():
    rng = random.Random(2026)
    for program in PROGRAMS:
        analyzer = Analyzer("prog.epk")
        text = program
        for _ in range(25):
            analysis = analyzer.analyse(text)
            assert analysis.diagnostics == full_check(text), text
            if sum(d.code == "E002" for d in analysis.diagnostics) < MAX_LEXICAL_ERRORS:
                assert splitter_starts(text) == lexer_starts(text)[1:]
            text = edit(rng, text)


@settings(max_examples=300, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(st.lists(st.sampled_from(FRAGMENTS), max_size=40), st.integers(0, 100))
def test_splitting_resumed_at_a_statement_start_cuts_as_the_whole_file(pieces, which):
    from epuckc.ide.statements import _boundaries
    text = "".join(pieces)
    source = SourceFile("x", text)
    bad = Collector(source)
    list(iter_tokens(source, bad))
    if len(bad.items) >= MAX_LEXICAL_ERRORS:
        return      # the lexer stops at the 20th bad run: incremental.py checks such files whole
    whole = list(_boundaries(text))
    assert [at for at, _ in whole] == lexer_starts(text)[1:]
    if whole:
        at, _ = whole[which % len(whole)]
        assert list(_boundaries(text, at)) == [b for b in whole if b[0] > at]


@settings(max_examples=150, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(st.sampled_from(PROGRAMS), st.lists(st.tuples(st.integers(0, 10_000), st.integers(0, 40),
                                                     st.lists(st.sampled_from(FRAGMENTS), max_size=3)),
                                           min_size=1, max_size=6))
def test_random_edit_sequences(program, edits):
    analyzer = Analyzer("prog.epk")
    text = program
    analyzer.analyse(text)
    for at, length, pieces in edits:
        at %= len(text) + 1
        text = text[:at] + "".join(pieces) + text[at + length:]
        assert analyzer.analyse(text).diagnostics == full_check(text)


def test_unchanged_statements_are_not_parsed_or_checked_again(monkeypatch):
    import epuckc.ide.incremental as inc
    program = "\n".join(f"rule r{i}: on timer({i + 1} s) repeat do set_timer, start_straight(300, {i} cm)"
                        for i in range(200)) + "\non immediate do set_timer\n"
    analyzer = Analyzer("prog.epk")
    analyzer.analyse(program)
    parsed, checked = [], []
    real_parse, real_rule = inc._parse_chunk, inc.Checker._rule
    monkeypatch.setattr(inc, "_parse_chunk", lambda *a: parsed.append(a[1]) or real_parse(*a))
    monkeypatch.setattr(inc.Checker, "_rule", lambda self, r: checked.append(r) or real_rule(self, r))
    # a new line in the middle moves every later statement one line down
    edited = program.replace("rule r100:", "rule r100:\n  ", 1).replace("300, 100 cm", "300, 1 m")
    analysis = analyzer.analyse(edited)
    assert len(parsed) == 1 and "rule r100:" in parsed[0]
    assert len(checked) == 1
    assert analysis.diagnostics == full_check(edited)
    # positions of the statements below are real lines again
    assert analysis.real(analysis.program.statements[150].span).line == 152


def test_many_bad_characters_fall_back_to_the_whole_file():
    text = "on immediate do stop_motor\n" + "@ on x\n" * (MAX_LEXICAL_ERRORS + 5)
    analysis = Analyzer("prog.epk").analyse(text)
    assert analysis.diagnostics == full_check(text)
    assert all(s.span.line < VLINE for s in analysis.program.statements)


def test_a_changed_constant_rechecks_only_the_rules_that_use_it(monkeypatch):
    import epuckc.ide.incremental as inc
    program = ("const far = 50 cm\n"
               + "\n".join(f"on timer({i + 1} s) do set_timer, start_straight(300, {i + 1} cm)"
                           for i in range(100))
               + "\non immediate do set_timer, start_straight(300, far)\n")
    analyzer = Analyzer("prog.epk")
    analyzer.analyse(program)
    checked = []
    real_rule = inc.Checker._rule
    monkeypatch.setattr(inc.Checker, "_rule", lambda self, r: checked.append(r) or real_rule(self, r))
    edited = program.replace("far = 50 cm", "far = 5000 m")
    analysis = analyzer.analyse(edited)
    assert len(checked) == 1 and checked[0].event.name.name == "immediate"
    assert "E034" in [d.code for d in analysis.diagnostics]
    assert analysis.diagnostics == full_check(edited)


def test_a_long_editing_session_on_a_big_file():
    import sys
    sys.path.insert(0, str(REPO / "bench"))
    from check_bench import generate
    rng = random.Random(7)
    text = generate(150)
    analyzer = Analyzer("prog.epk")
    for step in range(300):
        text = edit(rng, text)
        if step % 3 == 0:       # several edits may come between two analyses
            assert analyzer.analyse(text).diagnostics == full_check(text)


def test_a_bad_character_before_a_statement_gives_the_same_errors():
    """A bad character at the end of a mode's head, just before the next
    statement's first word: the statement's syntax error is reported by
    `epuckc check` and by the language server alike (it lexes each
    statement on its own and cannot see the character before it).
    Found by test_random_edit_sequences."""
    text = ("initial mode home { on enter do stop_motor }\n"
            "mode rest {\\n enter do exit_main }\n")
    analyzer = Analyzer("prog.epk")
    analyzer.analyse("initial mode home { on enter do stop_motor }\n")
    assert analyzer.analyse(text).diagnostics == full_check(text)
    assert [d.code for d in full_check(text)].count("E001") == 1


# pieces that change what variables can hold, who assigns them and who reads them
VARIABLE_FRAGMENTS = ["v0", "v1", " + 1", " - 7", " * 3", " / 2", "max(", "clamp(", ", 5)", "7",
                      "var v9 = 4\n", "var v0 = 2\n", "v1 += 1, ", "v0 = v1, ", " if v0 > 3",
                      "when v1 < 0 do stop_motor\n", "every 10 ms do v0 = v0 + 1\n", "=", "+=",
                      "(", ")", "\n", "abs(", "ir0", "set_speed(v0 * 1 steps/s, 0 steps/s)",
                      # (W009: rules that command the motors, their guards and priorities)
                      "every 100 ms if v0 < 3 do stop_motor\n", " priority 2", ", stop_motor",
                      "set_speed(300 steps/s, 300 steps/s)", " if v1 >= 2", "v0_1", "v0_2"]


def _programs_with_variables() -> list:
    import random as _random
    import sys
    sys.path.insert(0, str(REPO / "bench"))
    from lsp_bench import expression_program
    from tests.support.language import RandomChoices, language_program
    out = [expression_program(40, seed=s) for s in range(3)]
    # (issue 44's second shape: every variable reads others anywhere, one component)
    out += [expression_program(40, seed=s, coupled=True) for s in range(2)]
    out += [language_program(RandomChoices(_random.Random(s))).text for s in range(12)]
    return out


_PROGRAMS_WITH_VARIABLES = _programs_with_variables()


@settings(max_examples=120, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(st.integers(0, len(_PROGRAMS_WITH_VARIABLES) - 1),
       st.lists(st.tuples(st.integers(0, 10_000), st.integers(0, 12),
                          st.lists(st.sampled_from(VARIABLE_FRAGMENTS), max_size=3)),
                min_size=1, max_size=8))
def test_random_edits_of_programs_with_variables_equal_a_full_check(which, edits):
    """Issue 31: the intervals solved again only where an edit reaches
    (check/ranges.py) give every diagnostic a from-scratch check gives."""
    program = _PROGRAMS_WITH_VARIABLES[which]
    analyzer = Analyzer("prog.epk")
    text = program
    analyzer.analyse(text)
    for at, length, pieces in edits:
        at %= len(text) + 1
        text = text[:at] + "".join(pieces) + text[at + length:]
        assert analyzer.analyse(text).diagnostics == full_check(text)


def test_the_programs_with_variables_exercise_w009():
    """The property above compares W009 too: its programs have races."""
    assert sum("W009" in {d.code for d in full_check(p)} for p in _PROGRAMS_WITH_VARIABLES) >= 3


def test_a_big_group_of_racing_rules_edit_after_edit_equals_a_full_check():
    """W009 by kinds of rules (more than EXPAND_RULES motor rules of one
    priority), its pairs kept or computed again, and the intervals, over
    random edits: errors put in and out, numbers, assignments, guards."""
    import sys
    sys.path.insert(0, str(REPO / "bench"))
    from lsp_bench import error_edits, interval_edits
    rng = random.Random(31)
    text = _expression_program(200)
    analyzer = Analyzer("prog.epk")
    assert "W009" in {d.code for d in analyzer.analyse(text).diagnostics}
    for step in range(30):
        kind = step % 3
        if kind == 0:
            start, end, new = error_edits(text, rng, 1)[0]
        elif kind == 1:
            start, end, new = interval_edits(text, rng, 1)[0]
            new = str(rng.randint(0, 9))
        else:
            start = rng.randrange(len(text))
            end, new = start + rng.choice([0, 1, 2]), rng.choice(VARIABLE_FRAGMENTS)
        text = text[:start] + new + text[end:]
        assert analyzer.analyse(text).diagnostics == full_check(text), (step, new)


# ---- issue 31: what an edit reaches, and only that ---------------------------------

def _expression_program(rules: int) -> str:
    import sys
    sys.path.insert(0, str(REPO / "bench"))
    from lsp_bench import expression_program
    return expression_program(rules)


def _counting(monkeypatch, owner, name: str) -> list:
    """Calls of owner.name, counted (each call's first argument after self)."""
    calls, real = [], getattr(owner, name)
    if isinstance(owner, type):
        monkeypatch.setattr(owner, name, lambda self, *a: calls.append(a[:1]) or real(self, *a))
    else:
        monkeypatch.setattr(owner, name, lambda *a: calls.append(a[:1]) or real(*a))
    return calls


def test_w009_pairs_are_computed_again_only_when_what_they_read_changes(monkeypatch):
    """An edit to a rule that commands no motor and writes the same
    variables keeps W009's pairs; an edit to a motor rule's guard computes
    them again; both report what a full check reports."""
    from epuckc.check import races
    text = _expression_program(200)
    analyzer = Analyzer("prog.epk")
    assert "W009" in {d.code for d in analyzer.analyse(text).diagnostics}
    computed = _counting(monkeypatch, races, "_pairs")
    sensor = text.index("on sensor(ir3 > 300)")
    edited = text[:sensor] + "on sensor(ir3 > 310)" + text[sensor + len("on sensor(ir3 > 300)"):]
    analysis = analyzer.analyse(edited)
    assert computed == []
    assert analysis.diagnostics == full_check(edited)
    guard = edited.index(" < ", edited.index("set_speed") - 60)
    number = edited[guard + 3:].split(" ")[0]
    edited = edited[:guard + 3] + str(int(number) + 500) + edited[guard + 3 + len(number):]
    computed.clear()
    analysis = analyzer.analyse(edited)
    assert len(computed) == 1
    assert analysis.diagnostics == full_check(edited)


def test_an_interval_that_moves_rechecks_only_the_rules_that_read_it(monkeypatch):
    import re
    import epuckc.ide.incremental as inc
    text = _expression_program(200)
    analyzer = Analyzer("prog.epk")
    analyzer.analyse(text)
    checked = _counting(monkeypatch, inc.Checker, "_rule")
    tried = 0
    for at in [m.start() + 2 for m in re.finditer(r", 1000\)", text)]:
        before = dict(analyzer._memo.ranges.ranges)
        edited = text[:at] + "9" + text[at + 1:]           # min(v + 1, 9000): the bound moves
        checked.clear()
        analysis = analyzer.analyse(edited)
        rechecked = {analysis.real(rule.span).line for (rule,) in checked}
        moved = {n for n, r in analyzer._memo.ranges.ranges.items() if before.get(n) != r}
        assert analysis.diagnostics == full_check(edited)
        analyzer.analyse(text)          # and back
        if not moved:
            continue
        tried += 1
        line = edited.count("\n", 0, at) + 1
        words = re.compile(r"\b(" + "|".join(sorted(moved)) + r")\b")
        expected = {i + 1 for i, src in enumerate(edited.split("\n"))
                    if src.startswith(("on ", "every ", "when ")) and words.search(src)}
        assert rechecked == expected | {line}, (moved, line)
        assert len(rechecked) < len(analysis.checked.rules) / 4
        if tried == 4:
            break
    assert tried == 4


def test_components_an_edit_does_not_reach_are_not_solved_again(monkeypatch):
    from epuckc.check.ranges import Ranges
    text = _expression_program(200)
    analyzer = Analyzer("prog.epk")
    analyzer.analyse(text)
    solved = _counting(monkeypatch, Ranges, "_solve")
    # a number of a rule that assigns a variable, not in the assignment:
    # parsed again, the same assignment's text, nothing solved
    at = text.index("led_toggle(led1)")
    edited = text[:at] + "led_toggle(led2)" + text[at + len("led_toggle(led1)"):]
    analysis = analyzer.analyse(edited)
    assert solved == []
    assert analysis.diagnostics == full_check(edited)
    # the assignment itself: its component alone (the groups of five
    # variables do not read each other)
    at = edited.index(" - 1, 0)") + 3
    edited = edited[:at] + "3" + edited[at + 1:]
    solved.clear()
    analysis = analyzer.analyse(edited)
    assert len(solved) == 1
    assert analysis.diagnostics == full_check(edited)


def test_the_coupled_programs_variables_are_one_component(monkeypatch):
    """The property above covers issue 44's second shape: in
    lsp_bench.expression_program(coupled=True) the variables the rules
    assign form one strongly connected component, so the fixpoint of
    check/ranges.py solves them all at once (one `_solve` of every
    assigned variable)."""
    import sys
    sys.path.insert(0, str(REPO / "bench"))
    from lsp_bench import expression_program
    from epuckc.check.ranges import Ranges
    solved = _counting(monkeypatch, Ranges, "_solve")
    text = expression_program(40, seed=0, coupled=True)
    full_check(text)
    assigned = {c.target.name for (calls,) in solved for c in calls}
    # (more variables than one of the small groups of five has)
    assert len(solved) == 1 and len(assigned) > 5


def test_blocks_of_unchanged_rules_are_replayed_whole_and_equal_a_full_check(monkeypatch):
    """The rules are replayed a block at a time (recheck._Block): a one-rule
    edit checks again at most the rules of the blocks it touches, and the
    result (every diagnostic, the resolved rules in order, the facts the
    whole-program checks read) is a full check's, edit after edit, for
    edits that put errors in, change intervals, and add or remove rules."""
    import sys
    from epuckc.check.checker import Checker
    from epuckc.ide import recheck
    sys.path.insert(0, str(REPO / "bench"))
    import lsp_bench as lb
    text = _expression_program(300)
    analyzer = Analyzer("prog.epk")
    analyzer.analyse(text)
    assert len(analyzer._memo.blocks) >= 300 // recheck.BLOCK
    replayed = _counting(monkeypatch, recheck.IncrementalChecker, "_rule")
    rng = random.Random(31)
    edits = (lb.error_edits(text, rng, 6) + lb.interval_edits(text, rng, 4)
             + lb.edits(text, rng, 4))     # (each undone by the next)
    line = text.index("\n", len(text) // 2) + 1
    edits.append((line, line, "on timer(3 s) do led_toggle(led1)\n"))   # a rule more
    same_declarations = 0
    for start, end, new in edits:
        replayed.clear()
        env = analyzer._memo.env
        text = text[:start] + new + text[end:]
        analysis = analyzer.analyse(text)
        assert analysis.diagnostics == full_check(text)
        whole = Checker(analysis.program, Collector(analysis.source))
        full = whole.check()
        assert [r.node for r in analysis.checked.rules] == [r.node for r in full.rules]
        assert analysis.checker.facts == whole.facts     # (every field of the record)
        if analyzer._memo.env is env:      # (else each rule looks its names up again)
            same_declarations += 1
            assert len(replayed) <= 3 * recheck.BLOCK
    assert same_declarations >= 5


def test_a_rule_that_reads_a_constant_array_is_checked_again_when_the_array_goes():
    """A rule looks constant arrays up too (check/arrays.py): when the
    array's declaration is broken, the rule's `dot` is checked again
    (hypothesis found the rule replayed with the old array)."""
    text = ("# dot of arrays of different sizes\nconst W = [8, 4, 2, 0]\nvar turn = 0\n"
            "every 10 ms do turn = dot(W, ir) / 16\n")
    analyzer = Analyzer("prog.epk")
    assert "E063" in {d.code for d in analyzer.analyse(text).diagnostics}
    for edited in (text[36:], text, text.replace("[8, 4, 2, 0]", "[8, 4, 2, 0, 1, 1, 1, 1]")):
        assert analyzer.analyse(edited).diagnostics == full_check(edited)


def test_rules_in_modes_are_replayed_and_placing_errors_keep_their_order(monkeypatch):
    """A rule inside a mode is the same object from one analysis to the
    next (ModePlacer keeps what it made of each statement), so an edit
    elsewhere does not check it again; what placing statements reports
    (a definition inside a mode, a mode not closed) comes in the order of
    a whole file's parse, between the statements' own errors."""
    import epuckc.ide.incremental as inc
    rules = "\n".join(f"  on timer({i + 1} s) do set_timer, start_straight(300, {i + 1} cm)"
                      for i in range(40))
    text = f"on immediate do set_timer\nmode roam {{\n{rules}\n}}\non stop_motor do stop\n"
    analyzer = Analyzer("prog.epk")
    analyzer.analyse(text)
    checked = _counting(monkeypatch, inc.Checker, "_rule")
    edited = text.replace("do stop\n", "do stop, set_timer\n")
    analysis = analyzer.analyse(edited)
    assert len(checked) == 1            # (before the full check, which checks them all)
    assert analysis.diagnostics == full_check(edited)
    for edited in (edited.replace("  on timer(3 s)", "  const k = 3\n  on timer(3 s)"),
                   edited.replace("on timer(5 s) do", "on timer(5 s) do do"),
                   edited.replace("}\n", ""), edited):
        assert analyzer.analyse(edited).diagnostics == full_check(edited)


@settings(max_examples=300, deadline=None)
@given(st.text(alphabet="ab\r\n", max_size=30), st.integers(0, 30), st.integers(0, 4),
       st.text(alphabet="ab\r\n", max_size=5))
def test_line_starts_patched_after_an_edit_equal_those_found_again(old, at, cut, new):
    """The split keeps the previous text's line starts where the edit
    cannot move them (statements.patched_line_starts): the same as
    line_starts of the new text, \\r and \\r\\n around the edit too."""
    from epuckc.ide.statements import _common_prefix, _common_suffix, patched_line_starts
    at = min(at, len(old))
    text = old[:at] + new + old[at + cut:]
    p = _common_prefix(old, text)
    s = _common_suffix(old, text, min(len(old), len(text)) - p)
    assert patched_line_starts(line_starts(old), len(old), text, p, s) == line_starts(text)


def test_an_unknown_name_behind_a_constant_read_by_an_assignment_is_reported():
    """The intervals evaluate an assignment before the rules are checked,
    and drop what they say: `epuckc check` then forgot to report the
    unknown name behind the constant at the rule (hypothesis found the
    language server saying it and the full check not)."""
    text = ("var v = 0\nconst K = deg\n"
            "every 10 ms do v = K + 1\non immediate do set_timer\n")
    full = full_check(text)
    assert [(d.code, d.span.line) for d in full if d.code == "E013"] == [("E013", 2)]
    analyzer = Analyzer("prog.epk")
    assert analyzer.analyse(text).diagnostics == full
