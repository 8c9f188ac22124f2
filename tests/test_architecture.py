"""The shape of the code base (docs/architecture.md): each stage is a
subpackage of epuckc, imports point one way, there is no import circle, and
no file grows past the size where it should be split by concern.

Imports are read from the source (module level and inside functions alike:
a lazy import is still a dependency), so the test needs nothing installed.
"""
from __future__ import annotations

import ast
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parents[1]
PACKAGE = REPO / "epuckc"

# Which stages each stage may import (besides itself). The pipeline runs
# syntax -> check -> lower -> emit -> build; ide and sim sit on top of it,
# experiment on sim, link on build and sim, cli on top of everything. docs/architecture.md shows the same table.
ALLOWED = {
    "base": set(),
    "diagnostics": {"base"},
    "stdlib": {"base"},
    "syntax": {"base", "diagnostics"},
    "check": {"base", "diagnostics", "stdlib", "syntax"},
    "lower": {"base", "stdlib", "syntax", "check"},
    "emit": {"base", "check", "lower"},
    "build": {"base"},
    "sim": {"base", "build"},
    "ide": {"base", "diagnostics", "stdlib", "syntax", "check"},
    "testing": {"base", "diagnostics", "check", "emit", "build", "sim"},
    "experiment": {"base", "build", "check", "sim"},
    "tune": {"base", "build", "check", "sim", "experiment"},
    # the robots: flashing what build made, reading what they send (the
    # simulator's records and readable trace)
    "link": {"base", "build", "sim"},
    "studio": {"base", "diagnostics", "stdlib", "syntax", "check", "emit", "build", "sim", "ide",
               "testing", "link"},
    "cli": {"base", "diagnostics", "stdlib", "syntax", "check", "lower", "emit", "build",
            "sim", "ide", "testing", "experiment", "tune", "link", "studio"},
}
TOP_LEVEL = {"__init__", "__main__"}      # the package's own files: version, `python -m epuckc`

MAX_MODULE_LINES = 600
MAX_CLASS_LINES = 400
MAX_C_LINES = 900


def _modules():
    for path in sorted(PACKAGE.rglob("*.py")):
        parts = list(path.relative_to(REPO).with_suffix("").parts)
        if parts[-1] == "__init__":
            parts = parts[:-1]
        yield path, ".".join(parts), path.name == "__init__.py"


def _imports(path: Path, module: str, is_package: bool) -> set:
    """The epuckc modules `module` imports, as dotted names."""
    here = module.split(".") if is_package else module.split(".")[:-1]
    found = set()
    for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
        if isinstance(node, ast.Import):
            found |= {a.name for a in node.names if a.name.split(".")[0] == "epuckc"}
        elif isinstance(node, ast.ImportFrom):
            if node.level:
                base = here[:len(here) - node.level + 1]
                target = ".".join(base + ([node.module] if node.module else []))
            else:
                target = node.module or ""
            if target.split(".")[0] != "epuckc":
                continue
            # `from pkg import mod` imports the module pkg.mod when there is one
            for alias in node.names:
                candidate = f"{target}.{alias.name}"
                found.add(candidate if _exists(candidate) else target)
    return found


def _exists(dotted: str) -> bool:
    path = REPO.joinpath(*dotted.split("."))
    return path.with_suffix(".py").is_file() or (path / "__init__.py").is_file()


def _stage(dotted: str) -> str:
    parts = dotted.split(".")
    return parts[1] if len(parts) > 1 else "__init__"


GRAPH = {module: _imports(path, module, is_package) for path, module, is_package in _modules()}


def test_every_module_belongs_to_a_stage():
    strays = [m for m in GRAPH if _stage(m) not in ALLOWED and _stage(m) not in TOP_LEVEL]
    assert not strays, f"modules outside the stage folders (see docs/architecture.md): {strays}"


def test_imports_point_one_way():
    wrong = []
    for module, targets in GRAPH.items():
        stage = _stage(module)
        if stage in TOP_LEVEL:
            continue
        for target in targets:
            other = _stage(target)
            if other in TOP_LEVEL or other == stage:
                continue
            if other not in ALLOWED[stage]:
                wrong.append(f"{module} imports {target} ({stage} may import "
                             f"{', '.join(sorted(ALLOWED[stage])) or 'nothing of epuckc'})")
    assert not wrong, "\n".join(wrong)


def test_no_import_circle():
    """No module reaches itself through the modules it imports (Tarjan's
    strongly connected components; a component of two or more is a circle)."""
    index, low, on_stack, stack, circles = {}, {}, set(), [], []

    def visit(v):
        index[v] = low[v] = len(index)
        stack.append(v)
        on_stack.add(v)
        for w in GRAPH.get(v, ()):
            if w not in GRAPH:
                continue
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in on_stack:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            component = []
            while True:
                w = stack.pop()
                on_stack.discard(w)
                component.append(w)
                if w == v:
                    break
            if len(component) > 1:
                circles.append(sorted(component))

    for module in sorted(GRAPH):
        if module not in index:
            visit(module)
    assert not circles, f"import circles: {circles}"


def test_the_graph_is_read():
    """The checks above are not vacuous: the known edges are seen."""
    assert "epuckc.syntax.parser" in GRAPH["epuckc.check.frontend"]
    assert "epuckc.check.program" in GRAPH["epuckc.lower.program"]
    assert any(t.startswith("epuckc.build") for t in GRAPH["epuckc.cli.driver"])


def _python_sizes():
    for path, module, _ in _modules():
        text = path.read_text(encoding="utf-8")
        yield path, module, text.count("\n"), ast.parse(text)


@pytest.mark.parametrize("path,module,lines,tree", list(_python_sizes()),
                         ids=lambda v: v if isinstance(v, str) and v.startswith("epuckc") else "")
def test_module_and_class_sizes(path, module, lines, tree):
    assert lines <= MAX_MODULE_LINES, \
        f"{module} has {lines} lines (> {MAX_MODULE_LINES}): split it by concern"
    for node in ast.walk(tree):
        if isinstance(node, ast.ClassDef):
            size = node.end_lineno - node.lineno + 1
            assert size <= MAX_CLASS_LINES, \
                f"class {node.name} in {module} has {size} lines (> {MAX_CLASS_LINES})"


def test_c_file_sizes():
    sources = [p for p in list((REPO / "runtime_c").rglob("*.[ch]")) + list(PACKAGE.rglob("*.c"))
               if "build" not in p.relative_to(REPO).parts]
    assert sources
    big = {str(p.relative_to(REPO)): n for p in sources
           if (n := p.read_text(encoding="utf-8", errors="replace").count("\n")) > MAX_C_LINES}
    assert not big, f"C files over {MAX_C_LINES} lines: {big}"


def _defined_names(tree) -> set:
    """The names a module defines: its functions, classes, assigned
    attributes and variables, imported names and slot strings."""
    own = set()
    for node in ast.walk(tree):
        if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef, ast.ClassDef)):
            own.add(node.name)
        elif isinstance(node, ast.Attribute) and isinstance(node.ctx, (ast.Store, ast.Del)):
            own.add(node.attr)
        elif isinstance(node, ast.Name) and isinstance(node.ctx, ast.Store):
            own.add(node.id)
        elif isinstance(node, ast.Constant) and isinstance(node.value, str):
            own.add(node.value)
        elif isinstance(node, ast.alias):
            own.add(node.asname or node.name.split(".")[-1])
    return own


def _foreign_private_reads(path: Path) -> list:
    """`x._name` where x is not self, cls or super() and the module does not
    define `_name`: a private attribute of another module's object."""
    tree = ast.parse(path.read_text(encoding="utf-8"))
    own, out = _defined_names(tree), []
    for node in ast.walk(tree):
        if not (isinstance(node, ast.Attribute) and node.attr.startswith("_")
                and not node.attr.startswith("__")) or node.attr in own:
            continue
        base = node.value
        if isinstance(base, ast.Name) and base.id in ("self", "cls"):
            continue
        if isinstance(base, ast.Call) and getattr(base.func, "id", None) == "super":
            continue
        out.append(f"{path.relative_to(REPO)}:{node.lineno}: {ast.unparse(node)}")
    return out


def test_the_language_server_reads_no_private_attribute_of_another_modules_object():
    """The checker/ide boundary (issue 44): the language server asks the
    checker through its records (check/state.py) and its public methods
    (Checker.apart, evaluated, converted), and its own modules one
    another's public names; a private attribute is its module's."""
    found = [hit for path in sorted((PACKAGE / "ide").glob("*.py"))
             for hit in _foreign_private_reads(path)]
    assert not found, "\n".join(found)


def test_a_diagnostics_sink_is_given_and_never_swapped():
    """A Collector is given once (in an __init__) and kept: a step whose
    diagnostics are looked at apart says them into `Collector.capture()`,
    never into another collector put in the holder's attribute."""
    found = [f"{path.relative_to(REPO)}:{leaf.lineno}"
             for path in sorted(PACKAGE.rglob("*.py"))
             for fn, leaf in _attributes_assigned(path, ("diags",)) if fn.name != "__init__"]
    assert not found, found


def _attributes_assigned(path: Path, attrs: tuple):
    """(function, the Attribute node) of each assignment in a function of
    `path` to an attribute named one of `attrs`."""
    tree = ast.parse(path.read_text(encoding="utf-8"))
    for fn in ast.walk(tree):
        if not isinstance(fn, (ast.FunctionDef, ast.AsyncFunctionDef)):
            continue
        for node in ast.walk(fn):
            targets = node.targets if isinstance(node, ast.Assign) else \
                [node.target] if isinstance(node, (ast.AnnAssign, ast.AugAssign)) else []
            for t in targets:
                for leaf in ast.walk(t):
                    if isinstance(leaf, ast.Attribute) and leaf.attr in attrs:
                        yield fn, leaf


# the functions that move a variable's interval: the fixpoint's own iterates,
# on the VarInfo that the solve of a component made for it (check/ranges.py)
_INTERVAL_WRITERS = {("check/ranges.py", "_join_assigned"), ("check/ranges.py", "_narrow_ranges")}


def test_intervals_are_values_not_fields_narrowed_and_restored():
    """Issue 44: a condition that narrows variables gives them VarInfo of
    their own in a view of the table (base/views.Overlaid), it does not
    change the table's and restore them; only the fixpoint's iterates
    write a variable's `lo` and `hi` (an object's own __init__ sets its
    own)."""
    found = []
    for path in sorted([*(PACKAGE / "check").glob("*.py"), *(PACKAGE / "ide").glob("*.py")]):
        name = str(path.relative_to(PACKAGE))
        for fn, leaf in _attributes_assigned(path, ("lo", "hi")):
            own = fn.name == "__init__" and isinstance(leaf.value, ast.Name) \
                and leaf.value.id == "self"
            if not own and (name, fn.name) not in _INTERVAL_WRITERS:
                found.append(f"{name}:{leaf.lineno} in {fn.name}")
    assert not found, found


# ---- the C runtime's layers (issue 44) ---------------------------------------------

RUNTIME = REPO / "runtime_c"
# rt_platform.h and the e-puck library's headers are what every layer stands on
_BASE_HEADERS = {"rt_internal.h", "rt_platform.h", "epuckrt.h"}


def _layer_order() -> list:
    """The runtime's files, bottom layer first: the core in RUNTIME_CORE's
    order, then what a simulated platform adds and the devices."""
    from epuckc.base.resources import RUNTIME_CORE, RUNTIME_DEVICES, RUNTIME_SIMULATED
    return [*RUNTIME_CORE, *RUNTIME_SIMULATED, *RUNTIME_DEVICES]


def _symbols(tmp_path) -> tuple:
    """Which runtime file defines each external symbol, and which each file
    uses, read by nm from the files compiled as the host compiles them."""
    import subprocess
    from conftest import require_tool
    cc, nm = require_tool("cc"), require_tool("nm")
    defined, used = {}, {}
    for name in _layer_order():
        obj = tmp_path / (name + ".o")
        subprocess.run([cc, "-std=c99", "-c", f"-I{RUNTIME}", f"-I{RUNTIME / 'epuck_api'}",
                        f"-I{RUNTIME / 'host'}", str(RUNTIME / name), "-o", str(obj)], check=True)
        for line in subprocess.run([nm, str(obj)], capture_output=True, text=True,
                                   check=True).stdout.splitlines():
            fields = line.split()
            if len(fields) == 2 and fields[0] == "U":
                used.setdefault(name, set()).add(fields[1])
            elif len(fields) == 3 and fields[1] in "TDBRCG":
                defined[fields[2]] = name
    return defined, used


@pytest.fixture(scope="module")
def calls(tmp_path_factory) -> dict:
    """file -> {file it uses: the symbols}, among the runtime's files (the
    platforms, the providers of rt_platform.h both ways, are not in it);
    compiled once for the tests below."""
    defined, used = _symbols(tmp_path_factory.mktemp("runtime_objects"))
    calls = {}
    for name, symbols in used.items():
        for symbol in symbols:
            owner = defined.get(symbol)
            if owner is not None and owner != name:
                calls.setdefault(name, {}).setdefault(owner, set()).add(symbol)
    return calls


def test_the_runtimes_files_call_only_the_layers_below_them(calls):
    """No circle among the runtime's files: each uses only files listed
    before it (RUNTIME_CORE is bottom layer first), so the core can be read,
    tested and changed from the bottom up (docs/runtime.md)."""
    order = _layer_order()
    assert calls, "nm found no call between the runtime's files"
    upward = [f"{a} uses {b}'s {sorted(symbols)}" for a, targets in calls.items()
              for b, symbols in targets.items() if order.index(b) > order.index(a)]
    assert not upward, "\n".join(upward)


def _includes(path: Path) -> list:
    import re
    return re.findall(r'^#include "([\w/.]+)"', path.read_text(encoding="utf-8"), flags=re.M)


def _seen_headers(path: Path) -> set:
    """The runtime's headers a file includes, directly or through others."""
    seen, todo = set(), [path]
    while todo:
        for header in _includes(todo.pop()):
            if header not in seen and (RUNTIME / header).is_file():
                seen.add(header)
                todo.append(RUNTIME / header)
    return seen


def test_no_include_circle_and_each_file_sees_only_its_layers(calls):
    """The layers' headers (rt_clock.h ... rt_modes.h) include only the
    headers of layers below them, with no circle; a file that uses another
    layer's state or helpers sees them through that layer's header, and no
    file includes the header of a layer above it."""
    order = _layer_order()
    headers = {n[:-2] + ".h": n for n in order
               if (RUNTIME / (n[:-2] + ".h")).is_file() and n[:-2] + ".h" not in _BASE_HEADERS}
    assert len(headers) >= 5, headers
    # the header graph has no circle: a depth-first walk finds no back edge
    state = {}

    def visit(header, path):
        state[header] = "open"
        for child in _includes(RUNTIME / header):
            if child not in headers and child not in _BASE_HEADERS:
                continue
            assert state.get(child) != "open", f"include circle: {' -> '.join(path + [child])}"
            if child not in state:
                visit(child, path + [child])
        state[header] = "done"
    for header in headers:
        if header not in state:
            visit(header, [header])
    upward = []
    for name in order:
        for header in _seen_headers(RUNTIME / name) & set(headers):
            if order.index(headers[header]) > order.index(name):
                upward.append(f"{name} includes {header}, a layer above it")
    for a, targets in calls.items():
        for b in targets:
            own = b[:-2] + ".h"
            if own in headers and own not in _seen_headers(RUNTIME / a):
                upward.append(f"{a} uses {b} without its header {own}")
    assert not upward, "\n".join(upward)
