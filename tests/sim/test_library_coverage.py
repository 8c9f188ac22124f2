"""The simulated library against GCtronic's, name by name, from the checkout
EPUCK_LIB names (skipped without it, failed in CI): every header of its
library/ has a counterpart at the same path, whose kind it takes:

- runtime_c/epuck_api/PATH: simulated;
- runtime_c/epuck_api_unsimulated/PATH with declarations: not simulated,
  builds and links, and a call of one of its functions ends the run naming
  its device (exit status 6);
- runtime_c/epuck_api_unsimulated/PATH that is an #error: a variant whose
  functions differ from the simulated ones' (the test shows that they do).

The real headers are read as C (gcc's preprocessor, then pycparser,
tests/support/gctronic.py), and for each: a file that includes our header
and declares again every function and object as the real one does (a
different declaration is an error of the compiler), compares its types and
structs member by member, and asks for every macro (the same parameters;
the same value where both are a number) is compiled; one program that takes
the address of every function and object of every header is linked with
the simulated library, together with the globals the simulated modules'
sources define (C and assembly) that programs declare themselves."""
import os
import re
import subprocess

import pytest

from conftest import REPO, require_checkout
from tests.support import gctronic

NUMBER = re.compile(r"\(?\s*([-+]?(?:0x[0-9A-Fa-f]+|[0-9]*\.?[0-9]+(?:[eE][-+]?[0-9]+)?))\s*\)?\Z")


@pytest.fixture(scope="module")
def library():
    root = require_checkout(
        "EPUCK_LIB", "library/motor_led/e_epuck_ports.h",
        "EPUCK_LIB does not name a checkout of GCtronic's e-puck library (git clone "
        "https://github.com/gctronic/e-puck-library; the folder that holds library/)")
    return root / "library"


def _ours(rel: str):
    """(our header, its kind: simulated, unsimulated, variant), or (None, None)."""
    for folder, kind in ((gctronic.SIMULATED, "simulated"), (gctronic.UNSIMULATED, "unsimulated")):
        path = folder / rel
        if path.is_file():
            text = re.sub(r"/\*.*?\*/", "", path.read_text(), flags=re.S)
            return path, "variant" if "#error" in text else kind
    return None, None


@pytest.fixture(scope="module")
def parsed(library):
    """(rel, kind, Header) of every header of the library."""
    out = []
    missing = []
    for rel in gctronic.headers(library):
        path, kind = _ours(rel)
        if path is None:
            missing.append(rel)
            continue
        out.append((rel, kind, gctronic.parse(library, rel)))
    assert not missing, (f"GCtronic's library has headers the simulated library has no "
                         f"counterpart of (runtime_c/epuck_api or epuck_api_unsimulated): "
                         f"{missing}")
    return out


def _includes():
    return [f"-I{REPO / 'runtime_c' / d}" for d in (".", "epuck_api", "host",
                                                   "epuck_api_unsimulated")]


def _macro_checks(header: gctronic.Header, ours: dict) -> list:
    """C preprocessor lines that fail to compile where a macro of the real
    header lacks in ours; the problems Python sees (parameters, values)."""
    lines, problems = [], []
    for name, (params, body) in header.macros.items():
        lines += [f"#ifndef {name}", f'#error "{header.path}: the macro {name} is not defined"',
                  "#endif"]
        mine = ours.get(name)
        if mine is None:
            continue            # the #error says it
        if (params is None) != (mine[0] is None) or (params and len(params) != len(mine[0])):
            problems.append(f"{header.path}: {name} takes {params} in the library, {mine[0]} here")
        real, here = NUMBER.match(body), NUMBER.match(mine[1])
        if real and here and _number(real.group(1)) != _number(here.group(1)):
            problems.append(f"{header.path}: {name} is {body} in the library, {mine[1]} here")
    return lines, problems


def _number(text: str) -> float:
    return float(int(text, 16)) if text.lower().startswith(("0x", "-0x", "+0x")) else float(text)


def _our_macros(rel: str) -> dict:
    text = subprocess.run(["gcc", "-E", "-dD", *_includes(), "-x", "c", "-"],
                          input=f"#include <{rel}>\n", capture_output=True, text=True).stdout
    found = {}
    for line in text.splitlines():
        m = gctronic._DEFINE.match(line)
        if m is not None:
            params = None if m.group(2) is None else \
                [p.strip() for p in m.group(3).split(",") if p.strip()]
            found[m.group(1)] = (params, m.group(4).strip())
    return found


def _type_checks(header: gctronic.Header) -> list:
    """Our typedefs and structs as the real ones: each real one again under
    a name of its own, its size, and each member's type and place."""
    lines = []
    for name, node in header.typedefs.items():
        lines.append(gctronic.renamed(node, "_real"))
        lines.append(f"_Static_assert(sizeof({name}) == sizeof({name}_real), "
                     f"\"{header.path}: {name}'s size\");")
        inner = node.type.type
        if hasattr(inner, "decls") and inner.decls:
            lines += [_member(name, f"{name}_real", m, header.path)
                      for m in gctronic.members(inner)]
    for tag, node in header.structs.items():
        lines.append(gctronic.renamed(node, "_real"))
        lines.append(f"_Static_assert(sizeof(struct {tag}) == sizeof(struct {tag}_real), "
                     f"\"{header.path}: struct {tag}'s size\");")
        lines += [_member(f"struct {tag}", f"struct {tag}_real", m, header.path)
                  for m in gctronic.members(node)]
    return lines


def _member(ours: str, real: str, member: str, where: str) -> str:
    return (f"_Static_assert(__builtin_types_compatible_p(__typeof__((({ours} *)0)->{member}), "
            f"__typeof__((({real} *)0)->{member})) && __builtin_offsetof({ours}, {member}) == "
            f"__builtin_offsetof({real}, {member}), \"{where}: {ours}.{member}\");")


def test_every_header_has_its_counterpart_and_declares_what_the_librarys_does(parsed, tmp_path):
    failures, checked = [], 0
    for rel, kind, header in parsed:
        if kind == "variant":
            continue
        macro_lines, problems = _macro_checks(header, _our_macros(rel))
        failures += problems
        text = "\n".join([f"#include <{rel}>"] + macro_lines
                         + list(header.functions.values()) + list(header.objects.values())
                         + _type_checks(header)) + "\n"
        check = tmp_path / (rel.replace("/", "_") + ".c")
        check.write_text(text)
        result = subprocess.run(["gcc", "-std=gnu11", "-fsyntax-only", "-w", *_includes(),
                                 str(check)], capture_output=True, text=True)
        if result.returncode != 0:
            failures.append(f"{rel}:\n{result.stderr}")
        checked += len(header.functions) + len(header.objects) + len(header.macros)
    assert not failures, "\n".join(failures)
    assert checked > 500        # the library declares that many names


def test_each_variant_differs_from_what_is_simulated(parsed, library):
    """An #error header is only for a variant that declares one of the
    simulated functions differently (so it could not link with them)."""
    simulated = {}
    for rel, kind, header in parsed:
        if kind == "simulated":
            simulated.update(header.signatures)
    variants = 0
    for rel, kind, header in parsed:
        if kind != "variant":
            continue
        variants += 1
        clash = [name for name, signature in header.signatures.items()
                 if name in simulated and signature != simulated[name]]
        assert clash, f"{rel} is an #error here, but its functions do not clash: simulate it"
    assert variants >= 3


SIMULATED_SOURCES = ["a_d/advance_ad_scan", "acc_gyro", "codec", "uart", "motor_led",
                     "motor_led/advance_one_timer", "utility"]


def _program(parsed, library, tmp_path) -> str:
    """One program: every header's functions and objects, and the sources'
    globals, used; with EPUCK_CALL=N, a call of the N-th function that is
    not simulated (with zeros)."""
    includes, uses, calls = [], [], []
    simulated_functions = {n for _, k, h in parsed if k == "simulated" for n in h.functions}
    for rel, kind, header in parsed:
        if kind == "variant":
            continue
        includes.append(f"#include <{rel}>")
        uses += [f"(void (*)(void)){name}" for name in header.functions]
        uses += [f"(void (*)(void))(size_t)&{name}" for name in header.objects]
        if kind == "unsimulated":
            calls += [(name, gctronic.zero_call(name, header.arity[name]), rel)
                      for name in header.functions
                      if name not in simulated_functions and name not in [c[0] for c in calls]]
    # the globals the simulated modules' sources define, as they define them
    source = {}
    for folder in SIMULATED_SOURCES:
        source.update(gctronic.source_globals(library / folder))
    extern = "\n".join(source.values())
    assembly = sorted(set().union(*(gctronic.assembly_globals(library / f)
                                    for f in SIMULATED_SOURCES)))
    (tmp_path / "sources.c").write_text(
        "/* the sources' globals, as they define them, against library_sim.h */\n"
        "#include \"library_sim.h\"\n#include <stddef.h>\n" + extern + "\n"
        + "void *sources_globals[] = {\n"
        + "".join(f"    (void *)&{name},\n" for name in source) + "};\n")
    (tmp_path / "assembly.c").write_text(
        "/* the names the assembly makes global: they link */\n#include <stddef.h>\n"
        + "".join(f"extern char {name}[];\n" for name in assembly)
        + "void *assembly_globals[] = {\n"
        + "".join(f"    (void *){name},\n" for name in assembly) + "};\n")
    switch = "".join(f"    case {i}: {call}; break;\n" for i, (_, call, _) in enumerate(calls))
    (tmp_path / "main.c").write_text(
        "#include <stddef.h>\n#include <stdlib.h>\n" + "\n".join(includes) + "\n"
        + "void (*const uses[])(void) = {\n" + ",\n".join(f"    {u}" for u in uses) + "\n};\n"
        + "extern void *sources_globals[], *assembly_globals[];\n"
        + "int main(void)\n{\n    const char *call = getenv(\"EPUCK_CALL\");\n"
        + "    if (call == NULL)\n        return uses[0] != NULL && sources_globals[0] != NULL"
        + " && assembly_globals[0] != NULL ? 0 : 1;\n"
        + "    switch (atoi(call)) {\n" + switch + "    default: break;\n    }\n"
        + "    return 0;\n}\n")
    return calls


def test_every_name_links_and_what_is_not_simulated_ends_the_run_naming_it(parsed, library,
                                                                        tmp_path):
    from epuckc.build.common import Program
    from epuckc.build.host import build_host
    calls = _program(parsed, library, tmp_path)
    files = [tmp_path / "sources.c", tmp_path / "assembly.c"]
    program = Program("coverage", "", tmp_path, files, generated=False,
                      source_path=tmp_path / "main.c", inputs=[tmp_path / "main.c", *files])
    exe = build_host(program, tmp_path / "built")
    env = dict(os.environ, EPUCK_TIME_LIMIT_MS="100", EPUCK_QUIET="1")
    assert subprocess.run([str(exe)], env=env).returncode == 0
    assert len(calls) > 100
    for i, (name, _, rel) in enumerate(calls):
        run = subprocess.run([str(exe)], env=dict(env, EPUCK_CALL=str(i)), capture_output=True,
                             text=True)
        assert run.returncode == 6, (name, rel, run.stderr)
        assert f"epuckc: {name}: " in run.stderr and "is not simulated" in run.stderr, run.stderr
