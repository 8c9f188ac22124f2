"""What GCtronic's e-puck library declares, read from a checkout (EPUCK_LIB):
its headers parsed as C (the compiler's preprocessor, then pycparser), and
the globals its sources define. tests/sim/test_library_coverage.py holds the
simulated library (runtime_c/epuck_api*, runtime_c/host) to them."""
from __future__ import annotations

import re
import subprocess
from dataclasses import dataclass, field
from pathlib import Path

import pycparser
from pycparser import c_ast, c_generator

REPO = Path(__file__).resolve().parents[2]
RUNTIME = REPO / "runtime_c"
SIMULATED = RUNTIME / "epuck_api"
UNSIMULATED = RUNTIME / "epuck_api_unsimulated"
# what the library's headers include from outside it (XC16's device header,
# Microchip's DSP types): ours, after the library's own folder
OUTSIDE = [SIMULATED, UNSIMULATED]


@dataclass
class Header:
    """One header's own declarations: each as C text (regenerated from its
    syntax tree), by kind."""
    path: str
    functions: dict = field(default_factory=dict)       # name -> declaration
    objects: dict = field(default_factory=dict)         # name -> declaration (extern)
    typedefs: dict = field(default_factory=dict)        # name -> c_ast.Typedef
    structs: dict = field(default_factory=dict)         # tag -> c_ast.Struct (with members)
    macros: dict = field(default_factory=dict)          # name -> (parameters or None, body)
    guard: str = ""
    arity: dict = field(default_factory=dict)           # function -> its parameters' count
    signatures: dict = field(default_factory=dict)      # function -> its type, no names


def headers(library: Path) -> list:
    """Every header of the library's tree, by its path in library/."""
    return sorted(p.relative_to(library).as_posix() for p in library.rglob("*.h"))


def _preprocess(library: Path, rel: str, macros: bool) -> str:
    command = ["gcc", "-E", "-std=c99", f"-I{library}", *(f"-I{d}" for d in OUTSIDE)]
    if macros:
        command.append("-dD")
    result = subprocess.run(command + [str(library / rel)], capture_output=True, text=True,
                            errors="replace")
    if result.returncode != 0:
        raise AssertionError(f"gcc -E {rel}: {result.stderr}")
    return result.stdout


_LINE = re.compile(r'#\s*(\d+)\s+"([^"]*)"')
_DEFINE = re.compile(r"#define\s+(\w+)(\(([^)]*)\))?\s?(.*)")


def _own_macros(text: str, path: Path) -> dict:
    """The macros `path` itself defines (by the line markers of -dD's output)."""
    found, current = {}, None
    for line in text.splitlines():
        m = _LINE.match(line)
        if m is not None:
            current = m.group(2)
            continue
        m = _DEFINE.match(line)
        if m is not None and current is not None and Path(current) == path:
            params = None if m.group(2) is None else \
                [p.strip() for p in m.group(3).split(",") if p.strip()]
            found[m.group(1)] = (params, m.group(4).strip())
    return found


def _guard(path: Path) -> str:
    text = path.read_bytes().decode("latin-1")
    text = re.sub(r"/\*.*?\*/", "", text, flags=re.S)
    m = re.search(r"^\s*#\s*ifndef\s+(\w+)\s*\n\s*#\s*define\s+\1\b", text, re.M)
    return m.group(1) if m else ""


def parse(library: Path, rel: str) -> Header:
    """The header's own declarations, as the compiler and pycparser read it."""
    path = library / rel
    header = Header(rel, guard=_guard(path))
    header.macros = {name: value for name, value in
                     _own_macros(_preprocess(library, rel, True), path).items()
                     if name != header.guard}
    ast = pycparser.CParser().parse(_preprocess(library, rel, False), filename=str(path))
    generate = c_generator.CGenerator()
    for ext in ast.ext:
        if ext.coord is None or Path(ext.coord.file) != path:
            continue
        if isinstance(ext, c_ast.Typedef):
            header.typedefs[ext.name] = ext
            inner = ext.type.type
            if isinstance(inner, c_ast.Struct) and inner.name and inner.decls is not None:
                header.structs[inner.name] = inner
        elif isinstance(ext, c_ast.Decl):
            if isinstance(ext.type, c_ast.FuncDecl):
                header.functions[ext.name] = generate.visit(ext) + ";"
                header.arity[ext.name], header.signatures[ext.name] = _shape(ext)
            elif ext.name is not None:
                header.objects[ext.name] = generate.visit(ext) + ";"
            elif isinstance(ext.type, c_ast.Struct) and ext.type.name and ext.type.decls:
                header.structs[ext.type.name] = ext.type
    return header


def renamed(node, suffix: str):
    """A copy of a struct's or typedef's declaration under names of its own
    (the tag and the typedef name, + suffix), to compare member by member."""
    import copy
    node = copy.deepcopy(node)
    for sub in _walk(node):
        if isinstance(sub, c_ast.Struct) and sub.name and sub.decls is not None:
            sub.name += suffix
        if isinstance(sub, c_ast.Typedef):
            sub.name += suffix
            sub.type.declname += suffix
    return c_generator.CGenerator().visit(node) + ";"


def _walk(node):
    yield node
    for _, child in node.children():
        yield from _walk(child)


def members(struct: c_ast.Struct) -> list:
    """The names of a struct's members."""
    return [d.name for d in struct.decls if d.name]


def _shape(decl: c_ast.Decl) -> tuple:
    """(the count of a function's parameters, its type without their names)."""
    import copy
    decl = copy.deepcopy(decl)
    params = decl.type.args.params if decl.type.args else []
    count = 0
    for p in params:
        t = getattr(p, "type", None)
        if not (isinstance(t, c_ast.TypeDecl) and isinstance(t.type, c_ast.IdentifierType)
                and t.type.names == ["void"]):
            count += 1
        node = p
        while hasattr(node, "type") and not isinstance(node, c_ast.TypeDecl):
            node = node.type
        if isinstance(node, c_ast.TypeDecl):
            node.declname = None
        if hasattr(p, "name"):
            p.name = None
    return count, re.sub(r"\s+", " ", c_generator.CGenerator().visit(decl))


def zero_call(name: str, arity: int) -> str:
    """A call of the function with a zero for each parameter."""
    return f"{name}({', '.join(['0'] * arity)})"


# ---- the globals the sources define ---------------------------------------------

_C_GLOBAL = re.compile(r"^(?!static|extern|typedef|return)((?:unsigned |signed )?(?:int|char|long|"
                       r"short|float|double)(?: int)?)\s+([^;(]*);", re.M)


def source_globals(folder: Path) -> dict:
    """name -> `extern TYPE NAME[...];` for the file-scope objects the C
    files of a folder define (at brace depth 0, not static)."""
    found = {}
    for source in sorted(folder.glob("*.c")):
        text = subprocess.run(["gcc", "-fpreprocessed", "-E", "-P", "-x", "c", str(source)],
                              capture_output=True, text=True, errors="replace").stdout
        depth, top = 0, []
        for line in text.splitlines():
            if depth == 0:
                top.append(line)
            depth += line.count("{") - line.count("}")
        for m in _C_GLOBAL.finditer("\n".join(top)):
            for declarator in m.group(2).split(","):
                declarator = declarator.split("=")[0].strip()
                name = re.match(r"\w+", declarator)
                if name is not None:
                    found.setdefault(name.group(0), f"extern {m.group(1)} {declarator};")
    return found


def assembly_globals(folder: Path) -> set:
    """The C names (`_name` in the assembly) that a folder's assembly files
    make global (the reserved ones, interrupts, left out)."""
    names = set()
    for source in sorted(folder.glob("*.s")):
        text = source.read_bytes().decode("latin-1")
        for m in re.finditer(r"^\s*\.global\s+(.+)$", text, re.M):
            for symbol in re.split(r"[,\s]+", m.group(1).split(";")[0].strip()):
                if symbol.startswith("_") and not symbol.startswith("__"):
                    names.add(symbol[1:])
    return names
