"""Random rule programs with hostile names, and what must hold for each one
the checker accepts: its C (program, externs header, and an extern C file
written for it) compiles with gcc and 16-bit avr-gcc under
`-std=c99 -Wall -Wextra -Werror -pedantic`, and runs on the host harness
clean under ASan and UBSan.

Used by tests/emit/test_property.py (a modest number of examples) and by
bench/fuzz_campaign.py (a long campaign)."""
from __future__ import annotations

import os
import subprocess
from dataclasses import dataclass, field
from pathlib import Path

from hypothesis import strategies as st

from epuckc.base.resources import (LIBRARY_SIMULATION, RUNTIME_CORE, RUNTIME_DEVICES,
                                   RUNTIME_SIMULATED)

REPO = Path(__file__).resolve().parents[2]
RUNTIME = REPO / "runtime_c"
STRICT = ["-std=c99", "-Wall", "-Wextra", "-Werror", "-pedantic"]
SANITIZE = ["-g", "-O1", "-fsanitize=address,undefined", "-fno-sanitize-recover=all"]

# Names C, the runtime, the C library or the generated C already use, and
# look-alikes of the names epuckc generates.
HOSTILE = """int NULL static __LINE__ __func__ __STDC__ _x _Bad printf exit abs size_t offsetof
    SENSOR_OFF main param epk_param do_r1 p1_r1 when_r1 seq_r1 steps_r1 step1_r1 rule_x a1 e1
    a2 e2 epk_a1 epk_e1 epk_p1_r1 register_action register_event mainloop timer sensor
    immediate sequence run_sequence action event param_x e_init_port rt_millis stub_pose
    time speed steps count memory status errno bool true FILE stdin assert signal while
    straight_steps curve_steps param_straight_steps EPUCK_MAX_SPEED MAX_ACTIONS y q
    action_table event_table event_state event_memory event_program event_conditions ir c
    ir0 epk_ir epk_c epk_program register_program rt_program rt_event RT_REPEAT""".split()
FILE_STEMS = ["prog", "x??=", "a*b", "c\\d", "\u00e9t\u00e9", "int", "epuckrt", "utility",
              "main", "q'uote", "sp ace"]
EXTERN_TYPES = ["int", "distance", "speed", "angle", "duration"]
# Each kind's usual values, then values at or beyond the limits.
VALUES = {"int": (["0", "1", "-5", "7"], ["32767", "-32768", "40000"]),
          "distance": (["1 cm", "-20 mm", "0 mm", "100 steps", "25 cm"],
                       ["4 m", "0.01 mm", "1000 m", "-4.2 m"]),
          "speed": (["100", "-300 steps/s", "50 mm/s", "500"], ["1000", "0", "2000", "-1000"]),
          "angle": (["90 deg", "-45 deg", "0 deg", "180"], ["720", "40000 deg", "-32768"]),
          "duration": (["10 ms", "1 s", "0.5 s", "3"], ["0 ms", "3000000000 ms", "2147483647"])}


def names(one_in: int = 4):
    """Plain names, and one in `one_in` hostile. Externs and their
    parameters get fewer (most hostile ones are refused, rightly), the names
    of rules and named actions, which never reach C as they are, more."""
    return st.integers(1, one_in).flatmap(
        lambda k: st.sampled_from(HOSTILE) if k == 1
        else st.from_regex(r"[a-z][a-z0-9_]{0,6}", fullmatch=True))


def value(kind: str):
    usual, extreme = VALUES[kind]
    return st.integers(0, 7).flatmap(
        lambda k: st.sampled_from(extreme) if k == 0 else st.sampled_from(usual))


@dataclass
class Extern:
    kind: str
    name: str
    params: list        # (name, type)


@dataclass
class Program:
    stem: str
    text: str
    externs: list = field(default_factory=list)


@st.composite
def programs(draw) -> Program:
    lines = []
    if draw(st.booleans()):
        settings = draw(st.lists(st.sampled_from([
            "wheel_diameter: 41 mm", "wheel_diameter: 0.001 mm", "wheel_circumference: 1500 mm",
            "axle: 53 mm", "axle: 0.5 mm", "axle: 90 m", "steps_per_rev: 1000",
            "steps_per_rev: 999999", "steps_per_rev: 99999999999", "max_speed: 800 steps/s",
            "max_speed: 100 mm/s"]), max_size=3, unique_by=lambda s: s.split(":")[0]))
        lines.append("robot { " + ", ".join(settings) + " }")
    externs = []
    for kind in ("action", "event"):
        for _ in range(draw(st.integers(0, 2))):
            params = draw(st.lists(st.tuples(names(8), st.sampled_from(EXTERN_TYPES)),
                                   max_size=3, unique_by=lambda p: p[0]))
            ext = Extern(kind, draw(names(6)), params)
            externs.append(ext)
            decl = ", ".join(f"{n}: {t}" for n, t in params)
            lines.append(f'extern {kind} {ext.name}({decl}) from "ext.c"')
    actions = [e for e in externs if e.kind == "action"]
    events = [e for e in externs if e.kind == "event"]
    # issue 9: modes (their names reach C only as epk_mode_NAME), priorities,
    # the LEDs, the speaker and the other devices' events
    modes = draw(st.lists(names(2), max_size=2, unique=True))

    def call():
        options = [
            lambda: f"start_straight({draw(value('speed'))}, "
                    f"{draw(value('distance'))})",
            lambda: f"start_curve({draw(st.sampled_from(['0 mm', '30 mm', '1 m']))}, "
                    f"{draw(value('angle'))}, "
                    f"{draw(value('speed'))})",
            lambda: draw(st.sampled_from(["stop_motor", "set_timer", "reset_timer",
                                          "start_sensor", "stop_sensor", "exit_main"])),
            lambda: f"{draw(st.sampled_from(['led_on', 'led_off', 'led_toggle']))}("
                    f"{draw(st.sampled_from(['led0', 'led7', 'all', 'body', 'front']))})",
            lambda: f"play_sound({draw(st.sampled_from(['haa', 'spaah', 'wouaaaaaaaah']))})"]
        if modes:
            options.append(lambda: f"enter {draw(st.sampled_from(modes))}")
        if actions:
            def extern_call():
                ext = draw(st.sampled_from(actions))
                args = ", ".join(draw(value(t)) for _, t in ext.params)
                return f"{ext.name}({args})" if ext.params else ext.name
            options.append(extern_call)
        return draw(st.sampled_from(options))()

    def body():
        steps = draw(st.lists(st.lists(st.just(None), min_size=1, max_size=3), min_size=1,
                              max_size=4))
        return " then ".join(", ".join(call() for _ in step) for step in steps)

    named = draw(st.lists(names(2), max_size=2, unique=True))
    for name in named:
        lines.append(f"action {name} = {body()}")
    rule_names = draw(st.lists(names(2), max_size=2, unique=True))
    n_rules = max(draw(st.integers(1, 4)), len(rule_names))
    in_mode: dict = {mode: [] for mode in modes}
    for i in range(n_rules):
        head = f"rule {rule_names[i]}: " if i < len(rule_names) else ""
        mode = draw(st.sampled_from([None, *modes]))
        event_options = ["immediate", "stop_motor", "timer(100 ms)", "sensor(ir0 > 300, ir3 < 20)",
                         "clap(3000)", "tap(600)", "tilt(800)", "selector(15)", "remote(5)",
                         "remote(standby)", "ambient(ir0 < 200)"]
        if mode is not None:
            event_options.append("enter")
        if events:
            ext = draw(st.sampled_from(events))
            args = ", ".join(draw(value(t)) for _, t in ext.params)
            event_options.append(f"{ext.name}({args})" if ext.params else ext.name)
        event = draw(st.sampled_from(event_options))
        repeat = " repeat" if draw(st.booleans()) and event != "immediate" else ""
        repeat += draw(st.sampled_from(["", "", " priority 1", " priority 255"]))
        parts = [body()]
        if named and draw(st.booleans()):
            parts = [draw(st.sampled_from(named))]
        if rule_names and draw(st.booleans()):
            parts.append(f"cancel {draw(st.sampled_from(rule_names))}")
        rule = f"{head}on {event}{repeat} do {', '.join(parts)}"
        if mode is None:
            lines.append(rule)
        else:
            in_mode[mode].append(rule)
    for k, mode in enumerate(modes):
        lines.append(("initial " if k == 0 else "") + f"mode {mode} {{")
        lines += [f"  {rule}" for rule in in_mode[mode]]
        lines.append("}")
    lines.append("on timer(1500 ms) do exit_main")
    lines.insert(0, "on immediate do set_timer, start_sensor")
    stem = draw(st.sampled_from(FILE_STEMS))
    return Program(stem, "\n".join(lines) + "\n", externs)


def extern_c(program, header: str) -> str:
    """C for the program's externs, as a user would write it (no local
    name can clash with an extern: theirs cannot start with epk_)."""
    out = [f'#include "{header}"', "", "static volatile long epk_sink;", ""]
    for info in program.externs.values():
        if info.kind == "action":
            out.append(f"void {info.name}(void *epk_p)\n{{")
        else:
            out.append(f"void {info.name}(void *epk_p, void *epk_s)\n{{")
        if info.params:
            out.append(f"    const param_{info.name} *epk_q = (const param_{info.name} *)epk_p;")
            out += [f"    epk_sink += epk_q->{p.name};" for p in info.params]
        else:
            out.append("    (void)epk_p;")
        if info.kind == "event":
            out.append("    if (++((event_status *)epk_s)->memory > 3)\n"
                       "        ((event_status *)epk_s)->occurred = 1;")
        out.append("}\n")
    return "\n".join(out)


class Outcome:
    REJECTED = "rejected by the checker"
    BUILT = "accepted, built and ran clean"
    COMPILED = "accepted, compiled with gcc and avr-gcc"


def runtime_objects(folder: Path, cc: str) -> list:
    """The host runtime, compiled once with the sanitizers."""
    objects = []
    # (the devices too: the language generator's programs send messages)
    for src in (*RUNTIME_CORE, *RUNTIME_SIMULATED, *RUNTIME_DEVICES, "platform/platform_host.c",
                "host/scenario.c", *LIBRARY_SIMULATION):
        obj = folder / (Path(src).stem + ".o")
        if not obj.exists():
            subprocess.run([cc, *STRICT, *SANITIZE, f"-I{RUNTIME}", f"-I{RUNTIME / 'epuck_api'}",
                            f"-I{RUNTIME / 'host'}", f"-I{RUNTIME / 'epuck_api_unsimulated'}",
                            "-c", str(RUNTIME / src), "-o", str(obj)], check=True)
        objects.append(obj)
    return objects


def check_one(program: Program, work: Path, cc: str, avr: str, runtime: list,
              run: bool = True) -> str:
    """Check a program; if accepted, build it both ways and run it (with
    `run` False: compile it with gcc, without linking or running). Raises
    AssertionError with the evidence when an accepted program fails."""
    from epuckc.diagnostics import Report
    from epuckc.cli.driver import _program_name
    from epuckc.emit.program import emit_program
    from epuckc.check.frontend import check_file

    work.mkdir(parents=True, exist_ok=True)
    rules = work / f"{program.stem}.epk"
    rules.write_text(program.text, encoding="utf-8")
    (work / "ext.c").write_text("/* placeholder: written once the program is accepted */\n")
    result = check_file(rules, Report(), shown_name=rules.name)
    if result.checked is None:
        return Outcome.REJECTED
    name = _program_name(rules)
    generated = emit_program(result.checked, result.source.text, name)
    prog_c = work / f"{name}.c"
    prog_c.write_text(generated.c_text)
    sources = [prog_c]
    if generated.header_name:
        (work / generated.header_name).write_text(generated.header_text)
        (work / "ext.c").write_text(extern_c(result.checked, generated.header_name))
        sources.append(work / "ext.c")
    context = f"\n--- {rules.name} ---\n{program.text}"

    def compile_with(command, what):
        res = subprocess.run(command, capture_output=True, text=True, cwd=work)
        assert res.returncode == 0, f"{what} failed:\n{res.stderr}{context}"

    includes = [f"-I{work}", f"-I{RUNTIME}"]
    compile_with([avr, "-mmcu=atmega128", *STRICT, "-Os", *includes, "-c", *map(str, sources)],
                 "avr-gcc (16-bit int)")
    if not run:
        compile_with([cc, *STRICT, *includes, "-c", *map(str, sources)], "gcc")
        return Outcome.COMPILED
    exe = work / "prog"
    compile_with([cc, *STRICT, *SANITIZE, *includes, *map(str, sources), *map(str, runtime),
                  "-o", str(exe), "-lm"], "gcc with ASan/UBSan")
    env = {k: v for k, v in os.environ.items() if not k.startswith("EPUCK_")}
    env.update({"EPUCK_QUIET": "1", "EPUCK_TIME_LIMIT_MS": "3000"})
    run = subprocess.run([str(exe)], capture_output=True, text=True, env=env, timeout=120)
    assert run.returncode in (0, 3), f"exit status {run.returncode}:\n{run.stderr}{context}"
    assert "runtime error" not in run.stderr and "Sanitizer" not in run.stderr, \
        run.stderr + context
    return Outcome.BUILT


def build_outcomes(tmp_path_factory, strategy, examples: int, folder: str,
                   fuzz_seed=None) -> list:
    """check_one over `examples` programs of a Hypothesis strategy (with a
    seed, reproducibly): the outcome of each. Needs cc and avr-gcc."""
    import itertools
    from conftest import require_tool
    from hypothesis import HealthCheck, given, seed, settings
    cc, avr = require_tool("cc"), require_tool("avr-gcc")
    runtime = runtime_objects(tmp_path_factory.mktemp("runtime"), cc)
    counter = itertools.count()
    outcomes = []

    @settings(max_examples=examples, deadline=None, database=None,
              suppress_health_check=list(HealthCheck))
    @given(strategy)
    def prop(program):
        work = tmp_path_factory.getbasetemp() / folder / str(next(counter))
        outcomes.append(check_one(program, work, cc, avr, runtime))

    (seed(fuzz_seed)(prop) if fuzz_seed is not None else prop)()
    return outcomes
