"""Lowering: a CheckedProgram becomes the registrations of the paper's model
(parameter structs, generated action functions, sequences, register_action /
register_event calls) that templates/program.c.j2 lays out.

Every C name and initialiser is decided here; the template only prints.
The same rules decide how many registrations the runtime's arrays must hold,
so the checker asks count_registrations() rather than guessing.

Generated names never collide with each other, C keywords or the runtime:
user names only ever appear after a prefix that the runtime does not use
(`a_`, `rule_`, `mode_`), and derived names put their kind first
(`p2_a_go` is the second parameter struct of action `go`, `p1_r3` the first
of rule 3's own action list).
"""
from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import PurePath
from typing import Optional

from .checker import CheckedProgram, ResolvedCall
from .stdlib import STANDARD_ACTIONS, STANDARD_EVENTS
from .units import INT16_MAX, INT16_MIN, round_nearest

# C types of extern parameters, by declared type.
EXTERN_C_TYPES = {"int": "int", "distance": "int", "speed": "int", "angle": "int",
                  "duration": "long"}


def rule_action_key(index: int, rule) -> tuple:
    """Rules whose whole body is one named action share its registration."""
    body = rule.body
    if len(body) == 1 and len(body[0]) == 1 and body[0][0].kind == "named":
        return ("named", body[0][0].name)
    return ("rule", index)


def count_registrations(program: CheckedProgram) -> tuple[int, int]:
    """(actions, events) that the program registers with the runtime."""
    actions = {rule_action_key(i, r) for i, r in enumerate(program.rules)}
    return len(actions), len(program.rules)


# ---- the C-shaped program ------------------------------------------------------

@dataclass
class CStruct:
    """A static parameter struct: `static TYPE NAME = INIT; /* COMMENT */`."""
    ctype: str
    name: str
    init: str
    comment: str


@dataclass
class CFunction:
    """A generated action: runs `statements` in order."""
    name: str
    comment: str
    statements: list


@dataclass
class CSequence:
    steps_name: str
    name: str
    entries: list          # "{function, &param}" initialisers
    comment: str


@dataclass
class CRegistration:
    comment: str
    action_var: str
    new_action: Optional[tuple]    # (function, param expression) when registered here
    action_label: str
    event_var: str
    event_function: str
    event_param: str
    event_label: str
    repeat: bool
    rule_id_var: Optional[str]     # file-scope id for `cancel RULE`
    extensions: list = field(default_factory=list)   # set_event_priority(...); and the like


@dataclass
class CExternStruct:
    name: str
    fields: list           # (ctype, field name)


@dataclass
class CProgram:
    source_name: str
    version: str
    extern_structs: list = field(default_factory=list)
    includes: list = field(default_factory=list)
    structs: list = field(default_factory=list)
    functions: list = field(default_factory=list)
    sequences: list = field(default_factory=list)
    rule_id_vars: list = field(default_factory=list)
    action_vars: list = field(default_factory=list)
    event_vars: list = field(default_factory=list)
    registrations: list = field(default_factory=list)
    actions_needed: int = 0
    events_needed: int = 0
    geometry: Optional[str] = None   # set_robot_geometry arguments, for a robot block
    modes: list = field(default_factory=list)       # (id, C string of its name)
    initial_mode: Optional[tuple] = None            # (id, name)


# ---- C text helpers ------------------------------------------------------------

def c_string(text: str) -> str:
    """A C string literal of `text`: ASCII only, so the bytes do not depend
    on the compiler's source character set."""
    out = []
    for ch in text:
        if ch in '"\\':
            out.append("\\" + ch)
        elif 32 <= ord(ch) < 127:
            out.append(ch)
        else:
            out.extend(f"\\{b:03o}" for b in ch.encode("utf-8"))
    return '"' + "".join(out) + '"'


def c_comment(text: str) -> str:
    """Text safe inside /* */: one line, no comment terminator."""
    return " ".join(text.split()).replace("*/", "* /")


def _shorten(text: str, limit: int = 100) -> str:
    text = " ".join(text.split())
    return text if len(text) <= limit else text[: limit - 3] + "..."


# ---- lowering ------------------------------------------------------------------

@dataclass
class _Primitive:
    """One call that the runtime can run as an action: a function and its
    parameter expression, or a statement (cancel) that needs a wrapper."""
    function: Optional[str]
    param: str
    statement: str
    text: str


class _Lowerer:
    def __init__(self, program: CheckedProgram, source_text: str, version: str):
        self.program = program
        self.source_lines = source_text.split("\n")
        self.source_name = PurePath(program.file).name
        self.out = CProgram(self.source_name, version)
        self.params: dict = {}           # id(ResolvedCall) -> param expression
        self.owner_counts: dict = {}     # owner -> structs made so far
        self.flat: dict = {}             # named action -> flattened steps
        self.rule_ids: dict = {}         # rule name -> file-scope id variable
        self.mode_ids = {name: i for i, name in enumerate(program.modes, 1)}
        self.rule_modes = {r.name: r.mode for r in program.rules if r.name is not None}

    def text_of(self, node) -> str:
        """The source text of a node, from its span, on one line and without
        comments (rule bodies hold no strings, so `#` always starts one)."""
        span = node.span
        lines = self.source_lines[span.line - 1: span.end_line]
        if not lines:
            return ""
        if len(lines) == 1:
            lines = [lines[0][span.column - 1: span.end_column - 1]]
        else:
            lines[0] = lines[0][span.column - 1:]
            lines[-1] = lines[-1][: span.end_column - 1]
        return " ".join(" ".join(line.split("#", 1)[0].split()) for line in lines).strip()

    def where(self, node) -> str:
        return f"{self.source_name}:{node.span.line}"

    # -- calls and steps --

    def primitive(self, call: ResolvedCall, owner: str) -> _Primitive:
        text = self.text_of(call.node)
        if call.kind == "cancel":
            var = self.rule_ids[call.name]
            # a rule of a mode is disarmed until its mode is entered again
            function = "disarm_event" if self.rule_modes.get(call.name) else "cancel_event"
            return _Primitive(None, "", f"{function}({var});", text)
        if call.kind == "enter":         # one param_enter_mode struct per mode entered
            key = ("enter", call.name)
            if key not in self.params:
                name = f"mode_{call.name}"
                self.out.structs.append(CStruct("param_enter_mode", name,
                                                f"{{{self.mode_ids[call.name]}}}",
                                                c_comment(f"mode {call.name}")))
                self.params[key] = f"&{name}"
            param = self.params[key]
            return _Primitive("action_enter_mode", param, f"action_enter_mode({param});", text)
        function = STANDARD_ACTIONS[call.name].runtime if call.kind == "standard" else call.name
        if not call.values:       # stop_motor, exit_main, an extern without parameters...
            return _Primitive(function, "NULL", f"{function}(NULL);", text)
        key = id(call)
        if key not in self.params:
            n = self.owner_counts.get(owner, 0) + 1
            self.owner_counts[owner] = n
            name = f"p{n}_{owner}"
            ctype, init, comment = self.param_struct(call)
            self.out.structs.append(CStruct(ctype, name, init,
                                            c_comment(f"{self.where(call.node)}: {text}"
                                                      + (f" ({comment})" if comment else ""))))
            self.params[key] = f"&{name}"
        param = self.params[key]
        return _Primitive(function, param, f"{function}({param});", text)

    def param_struct(self, call: ResolvedCall) -> tuple[str, str, str]:
        v = call.values
        if call.name == "start_straight":
            # `distance` (mm) is only read when `steps` is 0; with a large
            # wheel it may not fit a 16-bit int, and then 0 says "see steps".
            mm = v["distance_mm"] if INT16_MIN <= v["distance_mm"] <= INT16_MAX else 0
            return ("param_start_straight",
                    f"{{{v['speed']}, {mm}, {v['distance']}}}",
                    f"{v['speed']} steps/s, {v['distance']} steps")
        if call.name == "start_curve":
            return ("param_start_curve",
                    f"{{{v['radius']}, {v['degrees']}, {v['speed']}, {v['outer_steps']}, {v['inner_speed']}}}",
                    f"outer wheel {v['speed']} steps/s for {v['outer_steps']} steps, "
                    f"inner {v['inner_speed']} steps/s")
        if call.kind == "standard":
            spec = STANDARD_ACTIONS[call.name]
            return (spec.runtime_param, "{" + ", ".join(f.format(**v) for f in spec.fields) + "}",
                    "")
        info = self.program.externs[call.name]
        return (f"param_{call.name}", self.extern_init(info.params, v), "")

    @staticmethod
    def extern_init(params, values: dict) -> str:
        items = [f"{values[p.name]}L" if EXTERN_C_TYPES[p.kind] == "long" else str(values[p.name])
                 for p in params]
        return "{" + ", ".join(items) + "}"

    def flatten(self, steps: list, owner: str) -> list:
        """Steps of primitives. A named action used alone as a step splices
        in its own steps; inside a comma list its first step runs in its
        place and its later steps follow the list.

        Named actions inside are flattened on a stack of our own rather
        than by recursion (a chain of thousands of named actions is deeper
        than Python's stack), in the same order recursion would take."""
        stack = [(self._flatten_steps(steps, owner), None)]
        result = None
        while True:
            walk, name = stack[-1]
            try:
                needed = walk.send(result)
            except StopIteration as done:
                stack.pop()
                if name is not None:
                    self.flat[name] = done.value
                if not stack:
                    return done.value
                result = done.value
                continue
            stack.append((self._flatten_steps(self.program.actions[needed], f"a_{needed}"),
                          needed))
            result = None

    def _flatten_steps(self, steps: list, owner: str):
        """flatten's body: yields the name of a named action it needs that
        is not flattened yet, and is sent its steps."""
        out = []
        for step in steps:
            current: list = []
            later: list = []
            for call in step:
                if call.kind == "named":
                    inner = self.flat.get(call.name)
                    if inner is None:
                        inner = yield call.name
                    if inner:
                        current.extend(inner[0])
                        later.extend(inner[1:])
                else:
                    current.append(self.primitive(call, owner))
            out.append(current)
            out.extend(later)
        return out

    def named_steps(self, name: str) -> list:
        if name not in self.flat:
            self.flat[name] = self.flatten(self.program.actions[name], f"a_{name}")
        return self.flat[name]

    def step_action(self, prims: list, fname: str, comment: str) -> tuple[str, str]:
        """(function, param) running a step's primitives."""
        if len(prims) == 1 and prims[0].function is not None:
            return prims[0].function, prims[0].param
        self.out.functions.append(CFunction(fname, c_comment(comment),
                                            [p.statement for p in prims] or [";"]))
        return fname, "NULL"

    def body_action(self, steps: list, owner: str, comment: str) -> tuple[str, str]:
        """(function, param) to register for a whole body."""
        if len(steps) == 1:
            return self.step_action(steps[0], f"do_{owner}", comment)
        entries = []
        for k, prims in enumerate(steps, 1):
            text = ", ".join(p.text for p in prims)
            fn, param = self.step_action(prims, f"step{k}_{owner}", f"{comment} - step {k}: {text}")
            entries.append(f"{{{fn}, {param}}}")
        self.out.sequences.append(CSequence(f"steps_{owner}", f"seq_{owner}", entries,
                                            c_comment(comment)))
        return "run_sequence", f"&seq_{owner}"

    # -- events --

    def event(self, rule, index: int) -> tuple[str, str]:
        ev = rule.event
        owner = f"r{index}"
        comment = c_comment(f"{self.where(rule.node)}: {self.text_of(rule.node.event)}")
        if ev.kind == "extern":
            info = self.program.externs[ev.name]
            if not info.params:
                return ev.name, "NULL"
            self.out.structs.append(CStruct(f"param_{ev.name}", f"when_{owner}",
                                            self.extern_init(info.params, ev.values), comment))
            return ev.name, f"&when_{owner}"
        spec = STANDARD_EVENTS[ev.name]
        if spec.runtime_param is None:      # immediate, stop_motor, enter
            return spec.runtime, "NULL"
        if spec.fields:
            self.out.structs.append(CStruct(spec.runtime_param, f"when_{owner}",
                                            "{" + ", ".join(f.format(**ev.values)
                                                            for f in spec.fields) + "}",
                                            comment))
            return spec.runtime, f"&when_{owner}"
        if ev.name == "timer":
            self.out.structs.append(CStruct(spec.runtime_param, f"when_{owner}",
                                            f"{{{ev.values['time']}L}}", comment))
            return spec.runtime, f"&when_{owner}"
        thresholds = ["SENSOR_OFF"] * 8
        below = 0
        for sensor, op, value in ev.conditions:
            thresholds[sensor] = str(value)
            if op == "<":
                below |= 1 << sensor
        self.out.structs.append(CStruct(spec.runtime_param, f"when_{owner}",
                                        f"{{{{{', '.join(thresholds)}}}, 0x{below:02x}}}", comment))
        return spec.runtime, f"&when_{owner}"

    # -- the whole program --

    def lower(self) -> CProgram:
        out = self.out
        for info in self.program.externs.values():
            if info.params:     # ISO C has no empty structs; such externs get NULL
                out.extern_structs.append(CExternStruct(
                    f"param_{info.name}", [(EXTERN_C_TYPES[p.kind], p.name) for p in info.params]))
            if info.file not in out.includes:
                out.includes.append(info.file)
        for rule in self.program.rules:
            if rule.name is not None and self.uses_cancel(rule.name):
                self.rule_ids[rule.name] = f"rule_{rule.name}"
                out.rule_id_vars.append(f"rule_{rule.name}")
        registered: dict = {}          # rule_action_key -> action variable
        for index, rule in enumerate(self.program.rules, 1):
            key = rule_action_key(index, rule)
            body_text = self.text_of(rule.node.body)
            if key in registered:
                action_var, new_action = registered[key], None
            else:
                action_var = f"a{len(registered) + 1}"
                out.action_vars.append(action_var)
                if key[0] == "named":
                    name = key[1]
                    steps = self.named_steps(name)
                    node = self.program.action_nodes[name]
                    new_action = self.body_action(
                        steps, f"a_{name}", f"{self.where(node)}: action {name} = {self.text_of(node.body)}")
                else:
                    steps = self.flatten(rule.body, f"r{index}")
                    new_action = self.body_action(
                        steps, f"r{index}", f"{self.where(rule.node)}: {body_text}")
                registered[key] = action_var
            event_function, event_param = self.event(rule, index)
            event_var = f"e{index}"
            out.event_vars.append(event_var)
            head = f"rule {rule.name}: " if rule.name else ""
            extensions = []
            if rule.priority:
                extensions.append(f"set_event_priority({event_var}, {rule.priority});")
            if rule.mode is not None:
                extensions.append(f"set_event_mode({event_var}, {self.mode_ids[rule.mode]});"
                                  f"  /* mode {rule.mode} */")
            out.registrations.append(CRegistration(
                comment=c_comment(f"{self.where(rule.node)}: {self.text_of(rule.node)}"),
                action_var=action_var, new_action=new_action,
                action_label=c_string(_shorten(body_text)),
                event_var=event_var, event_function=event_function, event_param=event_param,
                event_label=c_string(_shorten(f"{self.where(rule.node)} {head}on "
                                              f"{self.text_of(rule.node.event)}"
                                              + (" repeat" if rule.repeat else "")
                                              + (f" priority {rule.priority}" if rule.priority
                                                 else ""))),
                repeat=rule.repeat, rule_id_var=self.rule_ids.get(rule.name),
                extensions=extensions))
        out.modes = [(i, c_string(name)) for name, i in self.mode_ids.items()]
        if self.program.initial_mode is not None:
            out.initial_mode = (self.mode_ids[self.program.initial_mode], self.program.initial_mode)
        out.actions_needed, out.events_needed = count_registrations(self.program)
        if self.program.robot_given:
            geo = self.program.geometry
            out.geometry = (f"{round_nearest(geo.wheel_circumference_mm * 1000)}L, "
                            f"{round_nearest(geo.axle_mm * 1000)}L, {geo.steps_per_rev}L")
        return out

    def uses_cancel(self, rule_name: str) -> bool:
        def in_steps(steps):
            return any(c.kind == "cancel" and c.name == rule_name for step in steps for c in step)
        return any(in_steps(r.body) for r in self.program.rules) or \
            any(in_steps(s) for s in self.program.actions.values())


def lower(program: CheckedProgram, source_text: str, version: str) -> CProgram:
    return _Lowerer(program, source_text, version).lower()
