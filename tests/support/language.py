"""Random programs of the whole language (rare branches are taken on the
largest draw, since Hypothesis leans towards the smallest): variables of every kind and
constants (the 16-bit edges included), expressions of every operator and
function over numbers, constants, variables and readings, `when` rules,
guards, `every`/`after`, `wait` in sequences, `set_speed`, `random`,
odometry, modes with their own rules and variables, priorities, and now
and then an expression nested or chained right at or beyond the depth
limit (syntax/limits.py).

Most programs are well-kinded so that most are accepted and go on to the
C compilers; some mix kinds or break the rules on purpose, so that the
checker's errors are exercised too. Used by tests/emit/test_property.py,
tests/ide/test_everywhere.py and bench/fuzz_campaign.py."""
from __future__ import annotations

from hypothesis import strategies as st

from epuckc.syntax.limits import MAX_DEPTH

from .hostile import Program

INT_NUMBERS = ["0", "1", "-1", "2", "3", "7", "100", "300", "4095", "32767", "-32768", "-32767"]
UNIT_NUMBERS = {"speed": ["0 steps/s", "300 steps/s", "-200 steps/s", "50 mm/s", "1000 steps/s"],
                "distance": ["0 mm", "10 cm", "-50 mm", "2 m", "100 steps"],
                "angle": ["0 deg", "90 deg", "-45 deg", "360 deg"]}
READINGS = {"int": ["ir0", "ir3", "ir7", "ambient2", "mic0", "acc_x", "acc_z", "selector"],
            "distance": ["x", "y"], "angle": ["heading"], "speed": []}
KINDS = ["int", "int", "int", "speed", "distance", "angle"]
COMPARE = ["<", "<=", ">", ">=", "==", "!="]


@st.composite
def language_programs(draw) -> Program:
    variables: dict = {}        # name -> kind
    constants: dict = {}
    lines = []
    for i in range(draw(st.integers(0, 3))):
        kind = draw(st.sampled_from(KINDS))
        value = draw(st.sampled_from(INT_NUMBERS if kind == "int" else UNIT_NUMBERS[kind]))
        constants[f"K{i}"] = kind
        lines.append(f"const K{i} = {value}")
    for i in range(draw(st.integers(1, 5))):
        kind = draw(st.sampled_from(KINDS))
        value = draw(st.sampled_from(INT_NUMBERS if kind == "int" else UNIT_NUMBERS[kind]))
        variables[f"v{i}"] = kind
        lines.append(f"var v{i} = {value}")

    def leaf(kind):
        options = [lambda: draw(st.sampled_from(INT_NUMBERS if kind == "int"
                                                else UNIT_NUMBERS[kind]))]
        names = [n for n, k in variables.items() if k == kind]
        names += [n for n, k in constants.items() if k == kind]
        names += READINGS[kind]
        if names:
            options += [lambda: draw(st.sampled_from(names))] * 3
            options.append(lambda: "-" + draw(st.sampled_from(names)))
        return draw(st.sampled_from(options))()

    def number(kind, depth):
        if depth <= 0 or draw(st.integers(0, 3)) == 0:
            return leaf(kind)
        form = draw(st.integers(0, 9))
        if form <= 3:
            op = draw(st.sampled_from(["+", "-"]))
            return f"{number(kind, depth - 1)} {op} {number(kind, depth - 1)}"
        if form == 4:
            return f"({number('int', depth - 1)}) * ({number(kind, depth - 1)})"
        if form == 5:
            op = draw(st.sampled_from(["/", "%"]))
            return f"({number(kind, depth - 1)}) {op} ({number('int', depth - 1)})"
        if form == 6:
            f = draw(st.sampled_from(["min", "max"]))
            return f"{f}({number(kind, depth - 1)}, {number(kind, depth - 1)})"
        if form == 7:
            return (f"clamp({number(kind, depth - 1)}, {number(kind, depth - 1)}, "
                    f"{number(kind, depth - 1)})")
        if form == 8:
            f = draw(st.sampled_from(["abs", "-"]))
            return f"{f}({number(kind, depth - 1)})"
        lo, hi = sorted(draw(st.lists(st.integers(-32768, 32767), min_size=2, max_size=2)))
        if kind == "int":
            return f"random({lo}, {hi})"
        return f"random({lo}, {hi}) * ({number(kind, depth - 1)})"

    def condition(depth):
        form = draw(st.integers(0, 5))
        if depth <= 0 or form <= 2:
            kind = draw(st.sampled_from(KINDS))
            left = number(kind, depth - 1)
            right = left if draw(st.integers(0, 9)) == 9 else number(kind, depth - 1)
            return f"{left} {draw(st.sampled_from(COMPARE))} {right}"
        if form == 3:
            return f"not ({condition(depth - 1)})"
        return f"({condition(depth - 1)}) {draw(st.sampled_from(['and', 'or']))} " \
               f"({condition(depth - 1)})"

    def deep(kind):
        """An expression at or just beyond the depth limit."""
        n = MAX_DEPTH + draw(st.sampled_from([-1, 0, 1]))
        shape = draw(st.integers(0, 2))
        if shape == 0:
            return "abs(" * n + leaf(kind) + ")" * n
        if shape == 1:
            return "(" * n + leaf(kind) + ")" * n
        return leaf(kind) + "".join(f" + {leaf(kind)}" for _ in range(n))

    def expression(kind):
        if draw(st.integers(0, 79)) == 79:
            return deep(kind)
        return number(kind, draw(st.integers(0, 4)))

    def action():
        form = draw(st.integers(0, 9))
        if form <= 3 and variables:
            name = draw(st.sampled_from(sorted(variables)))
            kind = variables[name] if draw(st.integers(0, 19)) < 19 else draw(st.sampled_from(KINDS))
            return f"{name} {draw(st.sampled_from(['=', '=', '+=', '-=']))} {expression(kind)}"
        if form <= 5:
            return f"set_speed({expression('speed')}, {expression('speed')})"
        if form == 6:
            return f"start_straight({draw(st.sampled_from(UNIT_NUMBERS['speed']))}, " \
                   f"{draw(st.sampled_from(['5 cm', '-2 cm', '1 m']))})"
        return draw(st.sampled_from(["stop_motor", "led_toggle(body)", "led_on(led3)",
                                     "start_sensor", "set_timer", "play_sound(haa)"]))

    def body(allow_wait=True):
        steps = []
        for _ in range(draw(st.integers(1, 3))):
            calls = [action() for _ in range(draw(st.integers(1, 3)))]
            if allow_wait and draw(st.integers(0, 3)) == 3:
                calls.append(f"wait({draw(st.sampled_from(['10 ms', '100 ms', '1 s']))})")
            steps.append(", ".join(calls))
        return " then ".join(steps)

    modes = [f"m{i}" for i in range(draw(st.integers(0, 2)))]

    def rule(in_mode):
        form = draw(st.integers(0, 6))
        tail = draw(st.sampled_from(["", "", " priority 1", " priority 2"]))
        guard = f" if {condition(draw(st.integers(0, 2)))}" if draw(st.integers(0, 3)) == 3 \
            else ""
        if form <= 1:
            head = f"when {condition(draw(st.integers(0, 3)))}"
            guard = ""
        elif form == 2:
            head = f"every {draw(st.sampled_from(['10 ms', '50 ms', '200 ms', '1 s']))}"
        elif form == 3:
            head = f"after {draw(st.sampled_from(['10 ms', '300 ms', '1 s']))}"
        else:
            events = ["immediate", "stop_motor", "timer(100 ms)", "sensor(ir0 > 300)",
                      "ambient(ir2 < 200)"] + (["enter"] if in_mode else [])
            event = draw(st.sampled_from(events))
            repeat = " repeat" if event != "immediate" and draw(st.booleans()) else ""
            head = f"on {event}{repeat}"
        actions = body()
        if modes and draw(st.integers(0, 4)) == 4:
            actions += f", enter {draw(st.sampled_from(modes))}"
        return f"{head}{tail}{guard} do {actions}"

    for _ in range(draw(st.integers(1, 5))):
        lines.append(rule(False))
    for k, mode in enumerate(modes):
        lines.append(("initial " if k == 0 else "") + f"mode {mode} {{")
        if draw(st.integers(0, 9)) == 9:
            lines.append(f"    var local{k} = 0")        # not allowed: E001, never a crash
        for _ in range(draw(st.integers(1, 3))):
            lines.append("    " + rule(True))
        lines.append("}")
    lines.insert(0, "on immediate do start_sensor, set_timer")
    lines.append("after 1500 ms priority 3 do exit_main")
    return Program("lang", "\n".join(lines) + "\n")
