"""The C of the statements that compute values while the program runs: an
assignment (of a variable, or of an array's element), a standard action
whose arguments are computed (`set_speed(left: ..., right: ...)`), and an
`if` with its branches.
A statement that reads three proximity sensors or more reads them with one
call (`rt_proximity`: the values of this poll) rather than one `rt_ir`
each. `lw` is the lowerer (program.py), whose `expr` prints expressions."""
from __future__ import annotations

from ..stdlib.table import STANDARD_ACTIONS
from .exprs import proximity_read, var_name, variables_of

PREFIX = "epk_"


def proximity(e) -> tuple:
    """(readings, C before the statement, C after it): ({}, "", "") for
    fewer than three sensors."""
    sensors = sorted(proximity_read(e))
    if len(sensors) < 3:
        return {}, "", ""
    mask = sum(1 << n for n in sensors)
    return ({f"ir{n}": f"{PREFIX}p[{n}]" for n in sensors},
            f"{{ const int *{PREFIX}p = rt_proximity(0x{mask:02x}u); ", " }")


class _Together:
    """Several expressions as one, for what they read."""
    op, name = "args", None

    def __init__(self, args):
        self.args = args


def assignment(lw, call) -> str:
    info = lw.program.variables[call.name]
    lw.variables_in_c.add(call.name)
    value = call.values["value"]
    index = call.values.get("index")
    if value.op in ("elements", "fill"):
        return _whole_array(lw, call.name, info, value)
    if index is None:
        readings, head, tail = proximity(value)
        return (f"{head}rt_assign(&{var_name(call.name)}, {info.index}, "
                f"{lw.expr(value, readings=readings)});{tail}")
    if index.constant:      # one element: its own trace id
        k = index.value
        return (f"rt_assign(&{var_name(call.name)}[{k}], {info.index + k}, "
                f"{lw.expr(value, index_name=str(k))});")
    # the index once, as the element it names (clamped into the array)
    k = lw.expr(index)
    if not (0 <= index.lo and index.hi < info.size):
        k = f"rt_index({k}, {info.size})"
    trace_id = f"{info.index} + {PREFIX}k" if info.index else f"{PREFIX}k"
    return (f"{{ const int {PREFIX}k = {k}; rt_assign(&{var_name(call.name)}[{PREFIX}k], "
            f"{trace_id}, {lw.expr(value, index_name=f'{PREFIX}k')}); }}")


def _whole_array(lw, name: str, info, value) -> str:
    """`a = [e0, e1, ...]`: the values computed first (in order), then
    stored, each element with its trace id, so that an element read on
    the right is the one before the assignment (`a = [a[1], a[0]]` swaps);
    `fill(a, v)`: v once, into every element."""
    target = var_name(name)
    readings, head, tail = proximity(value)
    values = [lw.expr(e, readings=readings) for e in value.args]
    if value.op == "fill":          # the table's runtime call, its struct's fields
        function, ctype, fields = STANDARD_ACTIONS["fill"].dynamic
        init = ", ".join(f.format(array=target, id=info.index, count=value.value,
                                  value=values[0]) for f in fields)
        return f"{head}{{ {ctype} {PREFIX}arg = {{{init}}}; {function}(&{PREFIX}arg); }}{tail}"
    reads_itself = name in variables_of(value)
    if not reads_itself:
        return head + " ".join(f"rt_assign(&{target}[{k}], {info.index + k}, {v});"
                               for k, v in enumerate(values)) + tail
    temps = " ".join(f"const int {PREFIX}e{k} = {v};" for k, v in enumerate(values))
    stores = " ".join(f"rt_assign(&{target}[{k}], {info.index + k}, {PREFIX}e{k});"
                      for k in range(len(values)))
    return f"{head}{{ {temps} {stores} }}{tail}"


def dynamic_call(lw, call) -> str:
    function, ctype, fields = STANDARD_ACTIONS[call.name].dynamic
    exprs = tuple(v for v in call.values.values() if not isinstance(v, str))
    readings, head, tail = proximity(_Together(exprs))
    values = {name: v if isinstance(v, str) else lw.expr(v, readings=readings)  # a choice: its C
              for name, v in call.values.items()}
    init = ", ".join(f.format(**values) for f in fields)
    return f"{head}{{ {ctype} {PREFIX}arg = {{{init}}}; {function}(&{PREFIX}arg); }}{tail}"


def if_statement(lw, call, owner: str) -> str:
    """An `if` as the C `if (...) { ... } else if ...` of its branches,
    each branch's primitives in order (its named actions spliced in: a
    branch is one step). Its lines after the first are indented for
    the function body the template prints it in."""
    lines = []
    for k, (condition, calls) in enumerate(call.values["branches"]):
        head = "if" if k == 0 else "} else if"
        lines.append(f"{head} ({lw.expr(condition)}) {{")
        lines += _branch_lines(lw, calls, owner)
    if call.values["otherwise"] is not None:
        lines.append("} else {")
        lines += _branch_lines(lw, call.values["otherwise"], owner)
    lines.append("}")
    return "\n    ".join(lines)


def _branch_lines(lw, calls: list, owner: str) -> list:
    """The C lines of a branch's calls, one indent in."""
    prims = []
    for call in calls:
        if call.kind == "named":
            prims += [p for step in lw.named_steps(call.name) for p in step]
        else:
            prims.append(lw.primitive(call, owner))
    return ["    " + line for p in prims for line in p.statement.split("\n    ")]
