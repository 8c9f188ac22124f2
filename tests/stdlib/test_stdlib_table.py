"""The table of standard actions and events is the one source: the language
reference prints it, the runtime declares every function it names, and the
codes it cites exist."""
import re

from epuckc.base.resources import RUNTIME_CORE
from epuckc.stdlib import table as stdlib
from epuckc.diagnostics.codes import CODES
from tests.conftest import REPO


def test_language_reference_prints_the_table():
    doc = (REPO / "docs" / "language.md").read_text()
    start = doc.index("### 3.1 Actions")
    end = doc.index("<!-- end of generated tables -->")
    assert doc[start:end] == stdlib.reference_markdown(), \
        "docs/language.md section 3 is stale: paste `python3 -m epuckc.stdlib.table` over it"


def test_every_runtime_name_is_declared_by_the_runtime():
    header = (REPO / "runtime_c" / "epuckrt.h").read_text()
    declared = set(re.findall(r"\b(\w+)\s*\(void \*(?:param|status)", header)) | \
        set(re.findall(r"\}\s*(\w+)\s*;", header)) | \
        set(re.findall(r"typedef \w+ (\w+);", header))
    for spec in (*stdlib.ACTIONS, *stdlib.EVENTS):
        assert spec.runtime in declared, f"{spec.name}: {spec.runtime} is not in epuckrt.h"
        if isinstance(spec, stdlib.EventSpec) and spec.runtime_param:
            assert spec.runtime_param in declared, spec.runtime_param


def test_every_cited_code_exists_and_every_entry_is_documented():
    for spec in (*stdlib.ACTIONS, *stdlib.EVENTS):
        assert spec.doc and not spec.doc.endswith(".")
        for p in spec.params or ():
            assert p.doc and p.range, f"{spec.name}.{p.name} needs a doc and a range"
            for code in re.findall(r"\[([EW]\d{3})\]", p.range):
                assert code in CODES, code
    for code in re.findall(r"\[([EW]\d{3})\]", stdlib.SENSOR_CONDITION_DOC):
        assert code in CODES


def test_aliases_follow_the_table():
    assert set(stdlib.ACTION_ALIASES.values()) == set(stdlib.STANDARD_ACTIONS)
    assert stdlib.MOTION_ACTIONS == {"start_straight", "start_curve"}
    assert stdlib.STANDARD_EVENTS["sensor"].signature.startswith("sensor(irN")
    assert stdlib.STANDARD_ACTIONS["start_curve"].signature == \
        "start_curve(radius: distance, degrees: angle, speed: speed)"


def test_parameter_structs_and_choices_are_the_runtime_s():
    """Every struct the table names is a typedef of epuckrt.h with as many
    fields as the table initialises, and every choice's C text is a
    number or a macro the header defines."""
    header = (REPO / "runtime_c" / "epuckrt.h").read_text()
    structs = {name: body for body, name in
               re.findall(r"typedef struct \{([^}]*)\}\s*(\w+);", header)}
    macros = set(re.findall(r"#define (\w+) ", header))
    for spec in (*stdlib.ACTIONS, *stdlib.EVENTS):
        if spec.fields:
            assert spec.runtime_param in structs, spec.name
            fields = re.findall(r"\b(?:int|long) \w+;", structs[spec.runtime_param])
            assert len(fields) == len(spec.fields), spec.name
            for field in spec.fields:
                names = set(re.findall(r"\{(\w+)\}", field))
                assert names <= {p.name for p in spec.params}, spec.name
                if not names:
                    assert field in macros, field
    for choices in stdlib.CHOICES:
        for choice in choices.values:
            assert choice.c.isdigit() or choice.c in macros, choice
        assert len(set(choices.names())) == len(choices.values)


def test_every_motor_command_is_arbitrated_by_the_runtime():
    """The actions the arbitration check counts as motor commands are the
    ones the runtime refuses when a rule of higher priority owns the motors:
    the function each compiles to (start_straight -> straight_steps ->
    action_straight_steps) asks motors_refused, under the name the rule file
    used, and nothing else does."""
    source = "".join((REPO / "runtime_c" / name).read_text() for name in RUNTIME_CORE)

    def body(function: str) -> str:
        alias = re.search(rf"^void {function}\(void \*param\) \{{ (\w+)\(param\); \}}$",
                          source, re.M)
        if alias:
            return body(alias.group(1))
        found = re.search(rf"^void {function}\(void \*param\)\n\{{\n(.*?)^\}}$", source,
                          re.M | re.S)
        assert found, function
        return found.group(1)

    for name in stdlib.MOTOR_ACTIONS:
        runtime = stdlib.STANDARD_ACTIONS[name].runtime
        assert f'motors_refused("{name}")' in body(runtime), (name, runtime)
    assert set(re.findall(r'motors_refused\("(\w+)"\)', source)) == set(stdlib.MOTOR_ACTIONS)


def test_every_reading_calls_a_function_the_runtime_declares():
    """A reading, a reading's array and each of their choices become calls
    of runtime functions: each is declared in epuckrt.h with as many
    arguments as the call gives (a new reading without its runtime
    function would be accepted by the checker and fail to build)."""
    header = (REPO / "runtime_c" / "epuckrt.h").read_text()
    arity = {name: 0 if args.strip() in ("", "void") else args.count(",") + 1
             for name, args in re.findall(r"^\w[\w ]*?\b(rt_\w+)\(([^)]*)\);", header, re.M)}
    calls = [r.c for r in stdlib.STANDARD_READINGS.values()]
    calls += [f"{function}(0)" for _, function in stdlib.READING_ARRAYS.values()]
    for call in calls:
        name, args = re.fullmatch(r"(rt_\w+)\((.*)\)", call).groups()
        assert name in arity, f"{call}: {name} is not declared in epuckrt.h"
        assert arity[name] == (len(args.split(",")) if args else 0), call
