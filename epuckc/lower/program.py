"""Lowering: a CheckedProgram becomes the paper's model (parameter structs,
generated action functions, sequences, actions and the events that trigger
them) in the runtime's static registration form that templates/program.c.j2
lays out: const tables of actions and events registered at once with
register_program, the rules' sensor conditions compiled into one function
the runtime calls once per poll, and only the state that changes in RAM.

Every C name and initialiser is decided here; the template only prints.
A rule file needs no entry of the runtime's dynamic arrays (MAX_ACTIONS,
MAX_EVENTS): its rules are tables. Only the user's C registers more.

Generated names never collide with each other, C, the runtime or the
user's C: every name epuckc makes up (tables, state, the conditions
function and its locals, structs, functions) starts with PREFIX (`epk_`),
which the checker forbids to extern names (the only user names that reach C
as they are). Derived names put their kind after it (`epk_p2_a_go` is the
second parameter struct of action `go`, `epk_p1_r3` the first of rule 3's
own action list).

Externs: their parameter structs (`param_NAME`) and prototypes go in a
header of their own, `<program>_externs.h`, which both the generated
program and the user's C files include; the user's C is compiled as its own
translation unit and linked.
"""
from __future__ import annotations

import re
from dataclasses import dataclass
from pathlib import PurePath
from typing import Optional

from ..check.program import CheckedProgram, ResolvedCall, calls_within
from ..check.splice import splice
from ..stdlib.table import STANDARD_ACTIONS, STANDARD_EVENTS
from ..stdlib.units import round_nearest
from .exprs import (CONST_PREFIX, ODOMETRY, c_expr, c_int, changes_with_time, indexed_arrays,
                    proximity_read,
                    readings_of, var_name, variables_of)
from . import statements
from .model import (CAction, CCondition, CConditionWord, CEvent, CEventFunction, CExtern,
                    CExternStruct, CFunction, CProgram, CSequence, CStruct, CVariable)

# Every C name that epuckc makes up starts with this; see the module doc.
PREFIX = "epk_"

# C types of extern parameters, by declared type.
EXTERN_C_TYPES = {"int": "int", "distance": "int", "speed": "int", "angle": "int",
                  "duration": "long"}


def rule_action_key(index: int, rule) -> tuple:
    """Rules whose whole body is one named action share its registration."""
    body = rule.body
    if len(body) == 1 and len(body[0]) == 1 and body[0][0].kind == "named":
        return ("named", body[0][0].name)
    return ("rule", index)


def externs_header_name(program_name: str) -> str:
    """The header that declares a program's externs, for the user's C:
    `#include "<program>_externs.h"`."""
    return f"{program_name}_externs.h"


# ---- C text helpers ------------------------------------------------------------

def c_string(text: str) -> str:
    """A C string literal of `text`: printable ASCII only, so the bytes do
    not depend on the compiler's source character set; `?` is escaped so
    that no trigraph (`??=`) forms."""
    if text.isascii() and text.isprintable() and not any(c in text for c in '"\\?'):
        return f'"{text}"'
    out = []
    for ch in text:
        if ch in '"\\?':
            out.append("\\" + ch)
        elif 32 <= ord(ch) < 127:
            out.append(ch)
        else:
            out.extend(f"\\{b:03o}" for b in ch.encode("utf-8"))
    return '"' + "".join(out) + '"'


def c_comment(text: str) -> str:
    """Text safe inside /* */ on one line: printable ASCII (other
    characters as `\\uXXXX`), no comment delimiters, no trigraphs; one
    line, so no backslash-newline can splice it."""
    text = " ".join(text.split())
    if not (text.isascii() and text.isprintable()):
        text = "".join(ch if 32 <= ord(ch) < 127 else
                       f"\\u{ord(ch):04X}" if ord(ch) <= 0xFFFF else f"\\U{ord(ch):08X}"
                       for ch in text)
    while "*/" in text or "/*" in text or "??" in text:
        text = text.replace("*/", "* /").replace("/*", "/ *").replace("??", "? ?")
    return text


def const_ref(param: str) -> str:
    """A parameter for a const table entry (rt_action, rt_event)."""
    return "NULL" if param == "NULL" else f"&{param}"


def void_ref(param: str) -> str:
    """A parameter passed where the paper's API takes `void *` (a call, a
    sequence step): the const struct's address, cast; actions only read it."""
    return "NULL" if param == "NULL" else f"(void *)&{param}"


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
    def __init__(self, program: CheckedProgram, source_text: str, version: str,
                 program_name: str):
        self.program = program
        self.source_lines = source_text.split("\n")
        self.source_name = PurePath(program.file).name
        self.out = CProgram(c_comment(self.source_name), version)
        self.program_name = program_name
        self.params: dict = {}           # id(ResolvedCall) -> param expression
        self.owner_counts: dict = {}     # owner -> structs made so far
        self.flat: dict = {}             # named action -> flattened steps
        self.rule_ids: dict = {}         # rule name -> C name of its event id
        self.sensors: set = set()        # the IRs the compiled conditions read
        # a `when` condition (without a guard) is compiled with the sensors'
        self.always = any(r.event.name == "when" and r.guard is None and r.event.kind == "standard"
                          for r in program.rules)
        self.when_reads: set = set()     # the proximity readings the `when` conditions read
        # a compiled `when` condition can change while only time passes
        self.conditions_vary = any(r.event.name == "when" and r.guard is None
                                   and r.event.kind == "standard"
                                   and changes_with_time(r.event.values["condition"])
                                   for r in program.rules)
        self.odometry = False            # an expression reads x, y or heading
        self.variables_in_c: set = set()   # the variables the C reads or assigns
        self.const_arrays_in_c: set = set()   # the constant arrays the C indexes
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
            name = self.rule_ids[call.name]
            # a rule of a mode is disarmed until its mode is entered again
            function = "disarm_event" if self.rule_modes.get(call.name) else "cancel_event"
            return _Primitive(None, "", f"{function}({name});", text)
        if call.kind == "enter":         # one param_enter_mode struct per mode entered
            key = ("enter", call.name)
            if key not in self.params:
                name = f"{PREFIX}mode_{call.name}"
                self.out.structs.append(CStruct("param_enter_mode", name,
                                                f"{{{self.mode_ids[call.name]}}}",
                                                c_comment(f"mode {call.name}")))
                self.params[key] = name
            param = self.params[key]
            return _Primitive("action_enter_mode", param,
                              f"action_enter_mode({void_ref(param)});", text)
        if call.kind == "assign":
            return _Primitive(None, "", statements.assignment(self, call), text)
        if call.kind == "if":
            return _Primitive(None, "", statements.if_statement(self, call, owner), text)
        if call.dynamic:
            return _Primitive(None, "", statements.dynamic_call(self, call), text)
        function = STANDARD_ACTIONS[call.name].runtime if call.kind == "standard" else call.name
        if not call.values:       # stop_motor, exit_main, an extern without parameters...
            return _Primitive(function, "NULL", f"{function}(NULL);", text)
        key = id(call)
        if key not in self.params:
            n = self.owner_counts.get(owner, 0) + 1
            self.owner_counts[owner] = n
            name = f"{PREFIX}p{n}_{owner}"
            ctype, init, comment = self.param_struct(call)
            self.out.structs.append(CStruct(ctype, name, init,
                                            c_comment(f"{self.where(call.node)}: {text}"
                                                      + (f" ({comment})" if comment else ""))))
            self.params[key] = name
        param = self.params[key]
        return _Primitive(function, param, f"{function}({void_ref(param)});", text)

    def param_struct(self, call: ResolvedCall) -> tuple[str, str, str]:
        v = call.values
        if call.kind == "standard" and call.name == "start_straight":
            return (STANDARD_ACTIONS[call.name].runtime_param,
                    f"{{{v['speed']}, {v['distance']}}}",
                    f"{v['speed']} steps/s for {v['distance']} steps")
        if call.kind == "standard" and call.name == "start_curve":
            outer, inner = v["speed"], v["inner_speed"]
            # a positive angle turns left: the right wheel is the outer one
            left, right = (inner, outer) if v["degrees"] >= 0 else (outer, inner)
            return (STANDARD_ACTIONS[call.name].runtime_param,
                    f"{{{left}, {right}, {v['outer_steps']}}}",
                    f"left wheel {left} steps/s, right {right} steps/s, "
                    f"{v['outer_steps']} steps of the outer wheel")
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
        """Steps of primitives, with named actions spliced in (splice.py);
        a named action's own parameter structs belong to `a_NAME`."""
        return splice(steps, lambda call, context: self.primitive(call, context or owner),
                      lambda name: (self.program.actions[name], f"a_{name}"), self.flat)

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

    def body_action(self, steps: list, owner: str, where: str, comment: str) -> tuple[str, str]:
        """(function, param) to register for a whole body. `comment` (the
        whole body) is printed once; a step's function says only its step,
        so the C stays linear in the size of the rule file."""
        if len(steps) == 1:
            return self.step_action(steps[0], f"{PREFIX}do_{owner}", comment)
        entries, labels = [], []
        for k, prims in enumerate(steps, 1):
            text = ", ".join(p.text for p in prims)
            fn, param = self.step_action(prims, f"{PREFIX}step{k}_{owner}",
                                         f"{where}: step {k} of {len(steps)}: {text}")
            entries.append(f"{{{fn}, {void_ref(param)}}}")
            labels.append(c_string(_shorten(text)))
        self.out.sequences.append(CSequence(f"{PREFIX}steps_{owner}", f"{PREFIX}seq_{owner}",
                                            entries, c_comment(comment),
                                            f"{PREFIX}step_names_{owner}", labels))
        return "run_sequence", f"{PREFIX}seq_{owner}"

    # -- events --

    def event(self, rule, index: int) -> tuple:
        """(function, param name or "NULL", memory?, condition): a sensor
        event is a compiled condition (function "NULL", its C expression)."""
        ev = rule.event
        owner = f"r{index}"
        when = f"{PREFIX}when_{owner}"
        comment = c_comment(f"{self.where(rule.node)}: {self.text_of(rule.node.event)}")
        if ev.kind == "extern":
            info = self.program.externs[ev.name]
            if not info.params:
                return ev.name, "NULL", True, None
            self.out.structs.append(CStruct(f"param_{ev.name}", when,
                                            self.extern_init(info.params, ev.values), comment))
            return ev.name, when, True, None
        spec = STANDARD_EVENTS[ev.name]
        if ev.name == "when" and rule.guard is None:
            # a compiled condition, read at every poll (RT_CONDITIONS_ALWAYS);
            # its proximity readings are read once, at the function's top
            condition = ev.values["condition"]
            used = proximity_read(condition)
            self.when_reads |= used
            return "NULL", "NULL", False, ("when", self.expr(condition, readings={
                f"ir{n}": f"{PREFIX}r{n}" for n in used}))
        if ev.name == "when":
            self.out.event_functions.append(CEventFunction(
                when, comment, [f"rt_when(epk_status, {self.expr(ev.values['condition'])});"]))
            return when, "NULL", True, None
        if spec.runtime_param is None:      # immediate, stop_motor, enter
            return spec.runtime, "NULL", spec.memory, None
        if spec.fields:
            self.out.structs.append(CStruct(spec.runtime_param, when,
                                            "{" + ", ".join(f.format(**ev.values)
                                                            for f in spec.fields) + "}",
                                            comment))
            return spec.runtime, when, spec.memory, None
        if ev.name == "ambient":            # a function event: not the proximity sensors
            self.sensor_struct(ev, spec, when, comment)
            return spec.runtime, when, spec.memory, None
        if ev.name == "timer":
            self.out.structs.append(CStruct(spec.runtime_param, when,
                                            f"{{{ev.values['time']}L}}", comment))
            return spec.runtime, when, spec.memory, None
        if rule.guard is not None:      # its function, which the guard wraps
            self.sensor_struct(ev, spec, when, comment)
            return "event_sensor", when, True, None
        terms = [f"{PREFIX}ir{sensor} {op} {value}" for sensor, op, value in ev.conditions]
        self.sensors |= {sensor for sensor, _, _ in ev.conditions}
        return "NULL", "NULL", False, ("sensor", " || ".join(terms))

    def sensor_struct(self, ev, spec, name: str, comment: str):
        """The param_event_sensor of an event function on the sensors'
        conditions: a threshold per sensor (or SENSOR_OFF), the `<` ones' bits."""
        thresholds = ["SENSOR_OFF"] * 8
        below = 0
        for sensor, op, value in ev.conditions:
            thresholds[sensor] = str(value)
            if op == "<":
                below |= 1 << sensor
        self.out.structs.append(CStruct(spec.runtime_param, name,
                                        f"{{{{{', '.join(thresholds)}}}, 0x{below:02x}}}",
                                        comment))

    # -- the whole program --

    def externs(self):
        out = self.out
        if not self.program.externs:
            return
        out.externs_header = externs_header_name(self.program_name)
        out.header_guard = "EPK_" + re.sub(r"[^A-Za-z0-9]", "_", self.program_name).upper() \
            + "_EXTERNS_H"
        for info in self.program.externs.values():
            if info.params:     # ISO C has no empty structs; such externs get NULL
                out.extern_structs.append(CExternStruct(
                    f"param_{info.name}", [(EXTERN_C_TYPES[p.kind], p.name) for p in info.params]))
            params = ", ".join(f"{p.name}: {p.kind}" for p in info.params)
            out.externs.append(CExtern(info.kind, info.name, c_comment(
                f"{self.where(info.node)}: extern {info.kind} {info.name}({params})"),
                f"param_{info.name} *" if info.params else "NULL"))

    def lower(self) -> CProgram:
        out = self.out
        self.externs()
        cancelled = self.cancelled_rules()
        # The events are numbered by priority, highest first, in file order
        # within a priority: the order in which mainloop polls them, so that
        # its walk takes the table as it is, sixteen events at a time.
        rules = self.program.rules
        order = sorted(range(len(rules)), key=lambda i: -(rules[i].priority or 0))
        for event_id, i in enumerate(order):
            rule = rules[i]
            if rule.name is not None and rule.name in cancelled:
                self.rule_ids[rule.name] = f"{PREFIX}rule_{rule.name}"
                out.rule_ids.append((f"{PREFIX}rule_{rule.name}", event_id))
        out.rule_ids.sort(key=lambda pair: pair[1])
        registered: dict = {}          # rule_action_key -> action id
        conditions: dict = {}          # word -> [CCondition]
        for index, rule in ((i + 1, rules[i]) for i in order):
            key = rule_action_key(index, rule)
            body_text = self.text_of(rule.node.body)
            if key not in registered:
                if key[0] == "named":
                    name = key[1]
                    steps = self.named_steps(name)
                    node = self.program.action_nodes[name]
                    where = f"{self.where(node)}: action {name} = {self.text_of(node.body)}"
                    function, param = self.body_action(steps, f"a_{name}", self.where(node), where)
                else:
                    where = f"{self.where(rule.node)}: {body_text}"
                    function, param = self.body_action(self.flatten(rule.body, f"r{index}"),
                                                       f"r{index}", self.where(rule.node), where)
                registered[key] = len(out.actions)
                if function == "run_sequence":      # the trace names its steps
                    out.sequences[-1].action_id = registered[key]
                out.actions.append(CAction(function, const_ref(param),
                                           c_comment(f"{registered[key]}: {_shorten(where)}"),
                                           c_string(_shorten(body_text))))
            function, param, memory, condition = self.event(rule, index)
            if rule.guard is not None:      # the entry keeps its event's parameter,
                # which the runtime reads for RT_WAKE_AS_TIMER (the function reads its own)
                function = self.guarded(rule, index, function, param)
            event_id = len(out.events)
            if condition is not None:
                what, text = condition
                if what == "sensor" and self.always:
                    text = f"{PREFIX}on && ({text})"    # sensor conditions hold while they are on
                term = f"if ({text}) {PREFIX}c[{event_id // 16}] |= 0x{1 << (event_id % 16):04x}u;"
                conditions.setdefault(event_id // 16, []).append(
                    CCondition(term, c_comment(f"event {event_id}: {self.where(rule.node)}")))
            slot = "RT_NO_MEMORY"
            if memory:
                slot = str(out.memory_slots)
                out.memory_slots += 1
            head = f"rule {rule.name}: " if rule.name else ""
            out.events.append(CEvent(
                function, const_ref(param), registered[key], event_flags(rule),
                slot, c_comment(f"{event_id}: {self.where(rule.node)}: {self.text_of(rule.node)}"
                                + (f" (mode {rule.mode})" if rule.mode is not None else "")),
                c_string(_shorten(f"{self.where(rule.node)} {head}"
                                  f"{'on ' if rule.node.trigger == 'on' else ''}"
                                  f"{self.text_of(rule.node.event)}"
                                  + (" repeat" if rule.node.repeat else "")
                                  + (f" priority {rule.priority}" if rule.priority else ""))),
                priority=rule.priority or 0,
                mode=self.mode_ids[rule.mode] if rule.mode is not None else 0))
        out.conditions = [CConditionWord(w, terms) for w, terms in sorted(conditions.items())]
        out.sensors = f"0x{sum(1 << n for n in self.sensors):02x}" + (
            " | RT_CONDITIONS_ALWAYS" if self.always else "") + (
            " | RT_CONDITIONS_ON_CHANGE" if self.always and not self.conditions_vary else "")
        out.conditions_comment = [
            "/* The rules' sensor conditions, from this poll's proximity readings",
            " * epk_ir[0..7]: bit k % 16 of epk_c[k / 16] is event k's.  The runtime",
            " * calls it at most once per poll, while the sensors are on. */"] \
            if not self.always else [
            "/* The rules' conditions: bit k % 16 of epk_c[k / 16] is event k's.  The",
            " * runtime calls it once per poll; epk_ir[0..7] are this poll's",
            " * proximity readings, or NULL while the sensors are off, when the",
            " * sensor conditions are false (the `when` conditions hold anyway). */"]
        readings = []
        if self.when_reads:     # read once, with one call
            mask = sum(1 << n for n in self.when_reads)
            readings = [f"const int *{PREFIX}prox = rt_proximity(0x{mask:02x}u);"] + [
                f"const int {PREFIX}r{n} = {PREFIX}prox[{n}];" for n in sorted(self.when_reads)]
        if self.always and not self.sensors:     # `when` conditions only
            out.condition_locals = [f"(void){PREFIX}ir;"] + readings
        elif self.always:   # called with epk_ir NULL while the sensors are off
            out.condition_locals = [f"const int {PREFIX}on = {PREFIX}ir != NULL;"] + [
                f"const int {PREFIX}ir{n} = {PREFIX}on ? {PREFIX}ir[{n}] : 0;"
                for n in sorted(self.sensors)] + readings
        else:
            out.condition_locals = [f"const int {PREFIX}ir{n} = {PREFIX}ir[{n}];"
                                    for n in sorted(self.sensors)]
        self.variables()        # last: they are declared where the C uses them
        out.modes = [(i, c_string(name)) for name, i in self.mode_ids.items()]
        if self.program.initial_mode is not None:
            out.initial_mode = (self.mode_ids[self.program.initial_mode], self.program.initial_mode)
        out.odometry = self.odometry
        if self.program.robot_given:
            geo = self.program.geometry
            out.geometry = (f"{round_nearest(geo.wheel_circumference_mm * 1000)}L, "
                            f"{round_nearest(geo.axle_mm * 1000)}L, {geo.steps_per_rev}L")
        return out

    def expr(self, e, **options) -> str:
        """The C of an expression; notes whether the program reads the odometry."""
        self.odometry = self.odometry or bool(readings_of(e) & ODOMETRY)
        self.variables_in_c |= variables_of(e)
        consts = self.program.const_arrays
        self.const_arrays_in_c |= indexed_arrays(e) & set(consts)
        return c_expr(e, consts=consts, **options)

    def guarded(self, rule, index: int, function: str, param: str) -> str:
        """An event function that runs the rule's event, then its guard."""
        name = f"{PREFIX}if_r{index}"
        self.out.event_functions.append(CEventFunction(
            name, c_comment(f"{self.where(rule.node)}: {self.text_of(rule.node.event)} if "
                            f"{self.text_of(rule.node.guard)}"),
            [f"{function}({'NULL' if param == 'NULL' else void_ref(param)}, epk_status);",
             f"if (rt_occurred(epk_status)) rt_guard(epk_status, {self.expr(rule.guard)});"]))
        return name

    def variables(self):
        """Every variable, for the trace's names; declared in the C only
        where the C reads or assigns it (once everything else is lowered),
        so that -Werror never meets a variable defined but not used."""
        for info in self.program.variables.values():
            comment = c_comment(f"{self.where(info.node)}: var {info.name}: {info.lo}..{info.hi}")
            if info.size:       # an array: one declaration, a trace name per element
                variable = CVariable(f"{var_name(info.name)}[{info.size}]",
                                     "{" + ", ".join(map(c_int, info.inits)) + "}", comment,
                                     c_string(f"{info.name}[0]"))
                self.out.variables += [CVariable(variable.name, "", "", c_string(label))
                                       for label, _ in info.traced()]
            else:
                variable = CVariable(var_name(info.name), c_int(info.init), comment,
                                     c_string(info.name))
                self.out.variables.append(variable)
            if info.name in self.variables_in_c:
                self.out.declared_variables.append(variable)
        for name in sorted(self.const_arrays_in_c):
            values = self.program.const_arrays[name]
            self.out.structs.append(CStruct("int", f"{CONST_PREFIX}{name}[{len(values)}]",
                                            "{" + ", ".join(map(c_int, values)) + "}",
                                            c_comment(f"const {name}")))

    def cancelled_rules(self) -> set:
        """The rules that some `cancel` names, found in one pass."""
        names = set()
        for steps in [r.body for r in self.program.rules] + list(self.program.actions.values()):
            names.update(c.name for step in steps for c in calls_within(step)
                         if c.kind == "cancel")
        return names


def event_flags(rule) -> str:
    """The rt_event flags of a rule: RT_REPEAT, how it holds the motors it
    commands (docs/runtime.md, "Holding the motors"): a condition while it
    stays true, a guarded `every` until a period whose guard is false; any
    other rule until its action or sequence has ended (no flag); and when
    its event can occur if nothing but time passes (RT_WAKE_*, the table's
    `wake`: "Idle polls in bulk")."""
    flags = ["RT_REPEAT"] if rule.repeat else []
    if rule.event.name in HOLD_WHILE and rule.event.kind != "extern":
        flags.append("RT_HOLD_WHILE")
    elif rule.event.name == "every" and rule.guard is not None:
        flags.append("RT_HOLD_GUARD")
    wake = wake_flag(rule)
    if wake:
        flags.append(wake)
    return " | ".join(flags) or "0"


WAKE_FLAGS = {"change": "RT_WAKE_ON_CHANGE", "deadline": "RT_WAKE_AT_DEADLINE",
              "timer": "RT_WAKE_AS_TIMER"}


def wake_flag(rule) -> Optional[str]:
    """The event's wake flag: none for an extern event (the user's C may
    read anything) nor for a `when` whose condition changes with time (a
    guard is evaluated only when the event occurs: it does not count)."""
    if rule.event.kind == "extern":
        return None
    spec = STANDARD_EVENTS[rule.event.name]
    if rule.event.name == "when" and changes_with_time(rule.event.values["condition"]):
        return None
    return WAKE_FLAGS.get(spec.wake)


# The events that are conditions: their rules hold the motors while they hold.
HOLD_WHILE = {"when", "sensor", "ambient"}


def lower(program: CheckedProgram, source_text: str, version: str,
          program_name: str = "program") -> CProgram:
    return _Lowerer(program, source_text, version, program_name).lower()
