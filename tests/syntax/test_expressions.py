"""The syntax of the language's expressions and new statements: precedence,
the minus of a number, two-character operators, rule heads, and the two
front ends (Python and C) agreeing on them."""
import pytest

from epuckc.base.source import SourceFile
from epuckc.check.messages import _shown
from epuckc.diagnostics import Collector
from epuckc.syntax import accel, ast, parser


def parse(text, front=parser.parse_python):
    source = SourceFile("t.epk", text)
    diags = Collector(source)
    program = front(source, diags)
    return program, diags.items


def condition(text):
    program, errors = parse(f"when {text} do stop_motor")
    assert not errors, errors
    return program.statements[0].event.args[0].value


def shape(node) -> str:
    """The tree with every operation in parentheses."""
    if isinstance(node, ast.BinOp):
        return f"({shape(node.left)} {node.op} {shape(node.right)})"
    if isinstance(node, ast.UnaryOp):
        return f"({node.op} {shape(node.operand)})"
    if isinstance(node, ast.Paren):
        return shape(node.expr)
    if isinstance(node, ast.FuncCall):
        return f"{node.name.name}({', '.join(shape(a.value) for a in node.args)})"
    return _shown(node)


@pytest.mark.parametrize("text, tree", [
    ("a + b * c > 3", "((a + (b * c)) > 3)"),
    ("a - b - c == 0", "(((a - b) - c) == 0)"),
    ("a / b % c < 1", "(((a / b) % c) < 1)"),
    ("not a > 1 and b < 2 or c != 3", "(((not (a > 1)) and (b < 2)) or (c != 3))"),
    ("a > 1 or b > 2 and c > 3", "((a > 1) or ((b > 2) and (c > 3)))"),
    ("-a * -3 cm >= -(b + 1)", "((-a * -3 cm) >= (- (b + 1)))"),
    ("clamp(x - 1, -5 mm, max(y, 2)) <= 10 steps/s", "(clamp((x - 1), -5 mm, max(y, 2)) <= 10 steps/s)"),
    ("heading >= 90 deg", "(heading >= 90 deg)"),
])
def test_precedence_and_associativity(text, tree):
    assert shape(condition(text)) == tree


def test_a_minus_before_a_number_or_a_name_is_the_values():
    """`-5 cm` is the Number -5 cm and `-x` a negated ConstRef, as a value
    always was, so that the checker reads fixed arguments as before."""
    program, _ = parse("on immediate do start_straight(-x, -5 cm)")
    speed, distance = (a.value for a in program.statements[0].body.steps[0].calls[0].args)
    assert isinstance(speed, ast.ConstRef) and speed.negative
    assert isinstance(distance, ast.Number) and distance.text == "-5" and distance.unit == "cm"


def test_statements_of_the_language():
    program, errors = parse("""\
var n = 0
rule r: when n >= 3 repeat priority 2 if ir0 < 10 do n = 0
every 20 ms do n += 1, x -= 2
after 1 s do n = n * 2 then wait(1 s) then exit_main
on stop_motor repeat if n != 1 do stop_motor
""")
    assert not errors
    var, rule, every, after, guarded = program.statements
    assert isinstance(var, ast.VarDef)
    assert (rule.trigger, rule.name.name, rule.repeat, shape(rule.guard)) == \
        ("when", "r", True, "(ir0 < 10)")
    assert [c.op for c in every.body.steps[0].calls] == ["+=", "-="]
    assert (after.trigger, after.event.name.name) == ("after", "after")
    assert guarded.trigger == "on" and shape(guarded.guard) == "(n != 1)"


def test_a_bang_alone_is_an_unexpected_character():
    _, errors = parse("when a ! b do stop_motor")
    assert [d.code for d in errors][:1] == ["E002"]
    _, errors = parse("when a != b do stop_motor")
    assert not [d for d in errors if d.code == "E002"]


@pytest.mark.skipif(accel.front() is None, reason="the C front end is not built")
@pytest.mark.parametrize("text", [
    "var n = 0\nrule r: when n >= 3 and not (ir1 <= 2) do n += 1, n -= 2\n",
    "every 20 ms do set_speed(left: 300 - (ir0 + ir1) * 1 steps/s / 3, right: 300 % 7)\n",
    "after 2 s priority 1 if x == 3 mm do led_on(body)\non immediate do n = -(-3)\n",
    "on immediate do a = random(1, 6) then wait(1 s)\nrule q: every 1 s do exit_main\n",
])
def test_the_c_front_end_reads_the_language_as_python_does(text):
    c_program = parser.parse_c(parser._c_driver(), SourceFile("t.epk", text),
                               Collector(SourceFile("t.epk", text)))
    py_program, errors = parse(text)
    assert not errors and c_program == py_program
