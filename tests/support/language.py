"""Random programs of the whole language (rare branches are taken on the
largest draw, since Hypothesis leans towards the smallest): variables of every kind and
constants (the 16-bit edges included), expressions of every operator and
function over numbers, constants, variables and readings, `when` rules,
guards, `every`/`after`, `wait` in sequences, `set_speed`, `random`,
odometry, modes with their own rules and variables, priorities, arrays
(constant and variable ones, the readings' arrays, elements with fixed and
computed indices, `sum`/`min`/`max`/`argmin`/`argmax`/`dot`), the math
functions (`atan2`, `hypot`, `sqrt`, `sin`, `cos`), `if` / `else if` /
`else` actions (nested, now and then with a `then` inside a branch, which
is E080), the bitwise operators with hexadecimal and binary numbers (shifts
by any count, of any value), constant slices where whole arrays are read,
whole arrays assigned (`a = [...]`, `fill`), and now and then an
expression, or `if`s, nested or chained right at or beyond the depth limit
(syntax/limits.py): sums, calls, parentheses, array indexes
(`W0[W0[...]]`), `~`s, shifts, chains of `&`, `|` and `^`, a slice's
bounds; long `else if` chains (up to 300
branches), arrays of the largest size, many rules; and IR messages
(`send`, `on message`, the `message` readings), always with
`messages=True` (the world runs under the sanitizers,
tests/sim/test_world_sanitizers.py).

Most programs are well-kinded so that most are accepted and go on to the
C compilers; some mix kinds or break the rules on purpose, so that the
checker's errors are exercised too. Used by tests/emit/test_property.py,
tests/ide/test_everywhere.py and bench/fuzz_campaign.py."""
from __future__ import annotations

from hypothesis import strategies as st

from epuckc.check.arrays import MAX_SIZE as ARRAY_MAX
from epuckc.syntax.limits import MAX_DEPTH

from .hostile import Program

INT_NUMBERS = ["0", "1", "-1", "2", "3", "7", "100", "300", "4095", "32767", "-32768", "-32767",
               "0x1F", "0xFF00", "0xFFFF", "0b101", "0x7FFF"]
UNIT_NUMBERS = {"speed": ["0 steps/s", "300 steps/s", "-200 steps/s", "50 mm/s", "1000 steps/s"],
                "distance": ["0 mm", "10 cm", "-50 mm", "2 m", "100 steps"],
                "angle": ["0 deg", "90 deg", "-45 deg", "360 deg"]}
READINGS = {"int": ["ir0", "ir3", "ir7", "ambient2", "mic0", "acc_x", "acc_z", "selector",
                    "message"],
            "distance": ["x", "y"], "angle": ["heading"], "speed": []}
KINDS = ["int", "int", "int", "speed", "distance", "angle"]
COMPARE = ["<", "<=", ">", ">=", "==", "!="]


class Choices:
    """What a generator asks of its source of choices; `RandomChoices` and
    Hypothesis (`language_programs`) each give them."""
    def integers(self, lo: int, hi: int) -> int: ...
    def choice(self, options): ...
    def boolean(self) -> bool: ...


class RandomChoices(Choices):
    """Choices from random.Random: what a long campaign uses, at a
    fraction of Hypothesis's cost per example (bench/fuzz_campaign.py)."""
    def __init__(self, rng):
        self.rng = rng

    def integers(self, lo, hi):
        return self.rng.randint(lo, hi)

    def choice(self, options):
        return self.rng.choice(list(options))

    def boolean(self):
        return self.rng.random() < 0.5


class _Drawn(Choices):
    def __init__(self, draw):
        self.draw = draw

    def integers(self, lo, hi):
        return self.draw(st.integers(lo, hi))

    def choice(self, options):
        return self.draw(st.sampled_from(list(options)))

    def boolean(self):
        return self.draw(st.booleans())


@st.composite
def language_programs(draw) -> Program:
    """The Hypothesis strategy of language programs."""
    return language_program(_Drawn(draw))


def language_program(r: Choices, messages: bool = False) -> Program:
    variables: dict = {}        # name -> kind
    constants: dict = {}
    lines = []
    for i in range(r.integers(0, 3)):
        kind = r.choice(KINDS)
        value = r.choice(INT_NUMBERS if kind == "int" else UNIT_NUMBERS[kind])
        constants[f"K{i}"] = kind
        lines.append(f"const K{i} = {value}")
    for i in range(r.integers(1, 5)):
        kind = r.choice(KINDS)
        value = r.choice(INT_NUMBERS if kind == "int" else UNIT_NUMBERS[kind])
        variables[f"v{i}"] = kind
        lines.append(f"var v{i} = {value}")
    arrays: dict = {"ir": 8, "ambient": 8, "mic": 3, "acc": 3}     # name -> size (int ones)
    var_arrays: list = []
    for i in range(r.integers(0, 2)):
        size = r.choice([1, 3, 8] * 10 + [ARRAY_MAX])
        arrays[f"W{i}"] = size
        lines.append(f"const W{i} = [{', '.join(r.choice(INT_NUMBERS) for _ in range(size))}]")
    for i in range(r.integers(0, 2)):
        size = r.choice([1, 3, 8])
        arrays[f"a{i}"] = size
        var_arrays.append(f"a{i}")
        lines.append(f"var a{i} = [{', '.join(r.choice(INT_NUMBERS) for _ in range(size))}]")

    def array_form(depth):
        """An int from arrays: an element, or a function of a whole array."""
        name = r.choice(sorted(arrays))
        form = r.integers(0, 3)
        if form == 0:
            index = r.choice([str(r.integers(0, arrays[name] - 1)), number("int", depth - 1)])
            return f"{name}[{index}]"
        if form == 1:
            return f"{r.choice(['sum', 'min', 'max', 'argmin', 'argmax'])}({name})"
        if form == 2 and arrays[name] > 1:      # a constant slice, its ends now and then left out
            lo = r.integers(0, arrays[name] - 1)
            hi = r.integers(lo + 1, arrays[name])
            shown = f"{'' if lo == 0 and r.boolean() else lo}:" \
                    f"{'' if hi == arrays[name] and r.boolean() else hi}"
            f = r.choice(["sum", "min", "max", "argmin", "argmax", "dot"])
            if f == "dot":
                other = r.choice([n for n in sorted(arrays) if arrays[n] >= hi - lo])
                return f"dot({name}[{shown}], {other}[0:{hi - lo}])"
            return f"{f}({name}[{shown}])"
        same = [n for n in sorted(arrays) if arrays[n] == arrays[name]]
        return f"dot({name}, {r.choice(same)})"

    def math_form(kind, depth):
        if kind == "angle":
            other = r.choice(["int", "distance"])
            return f"atan2({number(other, depth - 1)}, {number(other, depth - 1)})"
        if kind != "int":
            return f"hypot({number(kind, depth - 1)}, {number(kind, depth - 1)})"
        f = r.choice(["sqrt", "sin", "cos"])
        return f"{f}({number('int' if f == 'sqrt' else 'angle', depth - 1)})"

    def leaf(kind):
        options = [lambda: r.choice(INT_NUMBERS if kind == "int"
                                                else UNIT_NUMBERS[kind])]
        names = [n for n, k in variables.items() if k == kind]
        names += [n for n, k in constants.items() if k == kind]
        names += READINGS[kind]
        if names:
            options += [lambda: r.choice(names)] * 3
            options.append(lambda: "-" + r.choice(names))
        return r.choice(options)()

    def bits(depth):
        """An int from the bitwise operators (on any ints: the checker
        saturates operands beyond 16 bits, and shifts by any count)."""
        form = r.integers(0, 3)
        if form == 0:
            return f"~({number('int', depth - 1)})"
        if form == 1:
            count = r.choice(["1", "4", "15", "16", "-3", "0b11", number("int", depth - 1)])
            return f"({number('int', depth - 1)}) {r.choice(['<<', '>>'])} ({count})"
        op = r.choice(["&", "|", "^"])
        return f"({number('int', depth - 1)}) {op} ({number('int', depth - 1)})"

    def number(kind, depth):
        if depth <= 0 or r.integers(0, 3) == 0:
            return leaf(kind)
        form = r.integers(0, 12)
        if form == 12:
            return bits(depth) if kind == "int" else f"({bits(depth)}) * ({leaf(kind)})"
        if form == 10:
            return array_form(depth) if kind == "int" else f"({array_form(depth)}) * " \
                f"({number(kind, depth - 1)})"
        if form == 11:
            return math_form(kind, depth)
        if form <= 3:
            op = r.choice(["+", "-"])
            return f"{number(kind, depth - 1)} {op} {number(kind, depth - 1)}"
        if form == 4:
            return f"({number('int', depth - 1)}) * ({number(kind, depth - 1)})"
        if form == 5:
            op = r.choice(["/", "%"])
            return f"({number(kind, depth - 1)}) {op} ({number('int', depth - 1)})"
        if form == 6:
            f = r.choice(["min", "max"])
            return f"{f}({number(kind, depth - 1)}, {number(kind, depth - 1)})"
        if form == 7:
            return (f"clamp({number(kind, depth - 1)}, {number(kind, depth - 1)}, "
                    f"{number(kind, depth - 1)})")
        if form == 8:
            f = r.choice(["abs", "-"])
            return f"{f}({number(kind, depth - 1)})"
        lo, hi = sorted((r.integers(-32768, 32767), r.integers(-32768, 32767)))
        if kind == "int":
            return f"random({lo}, {hi})"
        return f"random({lo}, {hi}) * ({number(kind, depth - 1)})"

    def condition(depth):
        form = r.integers(0, 5)
        if depth <= 0 or form <= 2:
            kind = r.choice(KINDS)
            left = number(kind, depth - 1)
            right = left if r.integers(0, 9) == 9 else number(kind, depth - 1)
            return f"{left} {r.choice(COMPARE)} {right}"
        if form == 3:
            return f"not ({condition(depth - 1)})"
        return f"({condition(depth - 1)}) {r.choice(['and', 'or'])} " \
               f"({condition(depth - 1)})"

    def deep(kind):
        """An expression at or just beyond the depth limit (the figures of
        docs/language.md 2.9: n nested calls about 2n levels, n nested
        indexes, `~`s, shifts or a slice's parentheses about n), or far
        beyond it."""
        # (a rule and its action take some 10 levels around an expression)
        n = MAX_DEPTH + r.choice([-30, -16, -12, -8, 4 * MAX_DEPTH])
        shape = r.integers(0, 7)
        if shape == 0:
            return "abs(" * (n // 2) + leaf(kind) + ")" * (n // 2)
        if shape == 1:
            return "(" * n + leaf(kind) + ")" * n
        if kind == "int" and shape == 2:
            name = r.choice(sorted(arrays))
            return f"{name}[" * n + "0" + "]" * n
        if kind == "int" and shape == 3:           # `~~~x`
            return "~" * n + f"({leaf(kind)})"
        if kind == "int" and shape == 4:           # `x << (x << (...))`, `x >> 1 >> 1 ...`
            if r.boolean():
                return f"{leaf(kind)} << (" * n + leaf(kind) + ")" * n
            return leaf(kind) + f" {r.choice(['>>', '<<'])} 1" * n
        if kind == "int" and shape == 5:           # `a & b | c ^ ...`
            return leaf(kind) + "".join(f" {r.choice(['&', '|', '^'])} {leaf(kind)}"
                                        for _ in range(n))
        if kind == "int" and shape == 6:           # a slice's bound, nested (fixed: a number)
            name = r.choice([a for a in sorted(arrays) if arrays[a] > 1] or ["ir"])
            return f"sum({name}[" + "(" * n + "0" + ")" * n + ":1])"
        return leaf(kind) + "".join(f" + {leaf(kind)}" for _ in range(n))

    def expression(kind):
        if r.integers(0, 159) == 159:
            return deep(kind)
        return number(kind, r.integers(0, 4))

    def if_action(depth):
        parts = [f"if {condition(r.integers(0, 2))} {{ {branch(depth)} }}"]
        if depth == 0 and r.integers(0, 39) == 39:
            return long_chain()
        for _ in range(r.integers(0, 2)):
            parts.append(f"else if {condition(r.integers(0, 2))} {{ {branch(depth)} }}")
        if r.boolean():
            parts.append(f"else {{ {branch(depth)} }}")
        return " ".join(parts)

    def long_chain():
        """An `if` of 20 to 300 `else if`s (of plain comparisons and
        actions, so that most are accepted and built)."""
        ints = sorted(n for n, k in variables.items() if k == "int")
        names = ints + READINGS["int"]
        parts = []
        for k in range(r.integers(20, 300)):
            act = f"{r.choice(ints)} = {k}" if ints and r.boolean() else \
                r.choice(["led_toggle(body)", "stop_motor", f"led_on(led{k % 8})"])
            parts.append(f"if {r.choice(names)} {r.choice(COMPARE)} {k * 13 - 900} {{ {act} }}")
        return " else ".join(parts) + (" else { stop_motor }" if r.boolean() else "")

    def branch(depth):
        calls = [action(depth + 1) for _ in range(r.integers(1, 2))]
        if len(calls) > 1 and r.integers(0, 29) == 29:
            return " then ".join(calls)         # E080, on purpose
        return ", ".join(calls)

    def deep_ifs():
        """`if`s nested at or just beyond the depth limit."""
        n = MAX_DEPTH // 4 + r.choice([-3, -2, -1, 0])
        name = r.choice(sorted(variables)) if variables else "ir0"
        return f"if {name} > 0 {{ " * n + "led_toggle(body)" + " }" * n

    def action(depth=0):
        if depth < 3 and r.integers(0, 5) == 5:
            return if_action(depth)
        if depth == 0 and r.integers(0, 199) == 199:
            return deep_ifs()
        form = r.integers(0, 9)
        if form == 0 and var_arrays and r.integers(0, 3) == 3:     # the whole array
            name = r.choice(var_arrays)
            if r.boolean():
                return f"fill({name}, {expression('int')})"
            size = arrays[name] + (r.choice([-1, 1]) if r.integers(0, 19) == 19 else 0)
            return f"{name} = [{', '.join(expression('int') for _ in range(max(size, 1)))}]"
        if form == 0 and var_arrays:
            name = r.choice(var_arrays)
            index = r.choice([str(r.integers(0, arrays[name] - 1)), expression("int")])
            return f"{name}[{index}] {r.choice(['=', '+=', '-='])} {expression('int')}"
        if form <= 3 and variables:
            name = r.choice(sorted(variables))
            kind = variables[name] if r.integers(0, 19) < 19 else r.choice(KINDS)
            return f"{name} {r.choice(['=', '=', '+=', '-='])} {expression(kind)}"
        if form <= 5:
            return f"set_speed({expression('speed')}, {expression('speed')})"
        if form == 6:
            return f"start_straight({r.choice(UNIT_NUMBERS['speed'])}, " \
                   f"{r.choice(['5 cm', '-2 cm', '1 m'])})"
        if form == 7 and (messages or r.integers(0, 9) == 9):
            return f"send({expression('int')})"
        return r.choice(["stop_motor", "led_toggle(body)", "led_on(led3)",
                                     "start_sensor", "set_timer", "play_sound(haa)"])

    def body(allow_wait=True):
        steps = []
        for _ in range(r.integers(1, 3)):
            calls = [action() for _ in range(r.integers(1, 3))]
            if allow_wait and r.integers(0, 3) == 3:
                calls.append(f"wait({r.choice(['10 ms', '100 ms', '1 s'])})")
            steps.append(", ".join(calls))
        return " then ".join(steps)

    modes = [f"m{i}" for i in range(r.integers(0, 2))]

    def rule(in_mode):
        form = r.integers(0, 6)
        tail = r.choice(["", "", " priority 1", " priority 2"])
        guard = f" if {condition(r.integers(0, 2))}" if r.integers(0, 3) == 3 \
            else ""
        if form <= 1:
            head = f"when {condition(r.integers(0, 3))}"
            guard = ""
        elif form == 2:
            head = f"every {r.choice(['10 ms', '50 ms', '200 ms', '1 s'])}"
        elif form == 3:
            head = f"after {r.choice(['10 ms', '300 ms', '1 s'])}"
        else:
            events = ["immediate", "stop_motor", "timer(100 ms)", "sensor(ir0 > 300)",
                      "ambient(ir2 < 200)"] + (["enter"] if in_mode else []) + \
                (["message"] * 3 if messages else ["message"])
            event = r.choice(events)
            repeat = " repeat" if event != "immediate" and r.boolean() else ""
            head = f"on {event}{repeat}"
        actions = body()
        if modes and r.integers(0, 4) == 4:
            actions += f", enter {r.choice(modes)}"
        return f"{head}{tail}{guard} do {actions}"

    for _ in range(r.integers(1, 5) if r.integers(0, 49) < 49 else r.integers(50, 200)):
        lines.append(rule(False))
    if messages:
        lines.append(f"every {r.choice(['50 ms', '100 ms', '300 ms'])} do send({expression('int')})")
        lines.append(f"on message repeat do {action()}")
    for k, mode in enumerate(modes):
        lines.append(("initial " if k == 0 else "") + f"mode {mode} {{")
        if r.integers(0, 9) == 9:
            lines.append(f"    var local{k} = 0")        # not allowed: E001, never a crash
        for _ in range(r.integers(1, 3)):
            lines.append("    " + rule(True))
        lines.append("}")
    lines.insert(0, "on immediate do start_sensor, set_timer")
    lines.append("after 1500 ms priority 3 do exit_main")
    return Program("lang", "\n".join(lines) + "\n")
