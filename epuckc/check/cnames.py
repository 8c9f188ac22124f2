"""The names C already gives a meaning to, where an extern is declared.

An extern action or event is a C function of exactly its declared name, and
its parameters are the fields of a struct, both declared in the externs
header after `utility.h`. So an extern name must not be anything visible
there, nor anything the C library defines with external linkage (C99 7.1.3
reserves those whatever is included), and a parameter name must not be
something that changes how `int NAME;` parses: a keyword, a macro, a typedef.

Rather than a hand-kept list, the names are taken from the headers
themselves: a probe that includes the runtime's headers (utility.h, the
platform and stub headers, the e-puck API declarations) and every C99
standard header is preprocessed with the C compiler (`-E -dD`), and its
declarations are scanned for the identifiers they declare at file scope.
The result is cached in epuckc's cache folder under a hash of the headers
and the compiler. Without a C compiler, only the runtime's own headers are
scanned (nothing can be built then anyway).
"""
from __future__ import annotations

import os
import re
from functools import lru_cache
from pathlib import Path
from typing import Optional

from ..base.resources import runtime_dir

FORMAT = 2

# C's keywords (C99, C11, C23) and GNU C's plain-named ones: the language,
# not a header, so they are listed here.
KEYWORDS = frozenset("""
    auto break case char const continue default do double else enum extern float for
    goto if inline int long register restrict return short signed sizeof static struct
    switch typedef union unsigned void volatile while _Bool _Complex _Imaginary
    _Alignas _Alignof _Atomic _Generic _Noreturn _Static_assert _Thread_local
    alignas alignof bool constexpr false nullptr static_assert thread_local true
    typeof typeof_unqual _BitInt _Decimal32 _Decimal64 _Decimal128 asm
""".split())
# Predefined identifiers and macros that no header declares (C99 6.4.2.2,
# 6.10.8); all of them are also reserved identifiers.
PREDEFINED = frozenset("__func__ __FILE__ __LINE__ __DATE__ __TIME__ __STDC__ "
                       "__STDC_VERSION__ __STDC_HOSTED__".split())
# The C99 standard headers: their external names are reserved everywhere.
STANDARD_HEADERS = ("assert.h complex.h ctype.h errno.h fenv.h float.h inttypes.h iso646.h "
                    "limits.h locale.h math.h setjmp.h signal.h stdarg.h stdbool.h stddef.h "
                    "stdint.h stdio.h stdlib.h string.h tgmath.h time.h wchar.h wctype.h").split()


def is_reserved(name: str, file_scope: bool) -> bool:
    """C99 7.1.3: `__x` and `_X` are always reserved; any `_x` at file scope."""
    if name.startswith("__") or (name.startswith("_") and name[1:2].isupper()):
        return True
    return file_scope and name.startswith("_")


class CNames:
    """name -> the header that declares it. (A plain class: this module is
    imported on the `check` path, where a dataclass costs start-up time.)"""

    def __init__(self, ordinary=None, typedefs=None, macros=None, complete: bool = True):
        self.ordinary = ordinary or {}    # functions, objects, enum constants
        self.typedefs = typedefs or {}
        self.macros = macros or {}
        self.complete = complete          # False: no compiler, runtime headers only

    def declared(self, name: str) -> Optional[str]:
        """Where `name` is declared as anything, or None."""
        return self.macros.get(name) or self.typedefs.get(name) or self.ordinary.get(name)


# ---- scanning preprocessed C ----------------------------------------------------

_TOKEN_RE = r"""
    (?P<ws>\s+)
  | (?P<str>L?"(?:[^"\\\n]|\\.)*"|L?'(?:[^'\\\n]|\\.)*')
  | (?P<id>[A-Za-z_][A-Za-z0-9_]*)
  | (?P<num>\.?[0-9](?:[eEpP][+-]|[A-Za-z0-9_.])*)
  | (?P<punct>\.\.\.|->|[{}()\[\];,=*]|.)
"""
_MARKER_RE = r'#\s*(?:line\s+)?(\d+)\s+"((?:[^"\\]|\\.)*)"((?:\s+\d+)*)'
_DEFINE_RE = r"#\s*define\s+([A-Za-z_][A-Za-z0-9_]*)"
_TAG_KEYWORDS = {"struct", "union", "enum"}


class _Scanner:
    """Collects the identifiers that declarations declare at file scope:
    declarators outside any braces and parentheses (or in `(*name)`),
    typedef names, and enumeration constants. Struct members and the
    parameters of prototypes are not visible names, so they are skipped."""

    def __init__(self, names: CNames, where):
        self.names = names
        self.where = where          # () -> the header being read
        self.braces: list = []      # per open brace: "enum" or "other"
        self.parens = 0
        self.in_typedef = False
        self.prev = ["", ""]        # the two tokens before this one
        self.after_tag = False

    def feed(self, text: str):
        for m in re.finditer(_TOKEN_RE, text, re.VERBOSE | re.DOTALL):
            kind = m.lastgroup
            if kind == "ws":
                continue
            tok = m.group()
            if kind == "id":
                self.identifier(tok)
            elif kind == "punct":
                self.punct(tok)
            self.after_tag = kind == "id" and tok in _TAG_KEYWORDS
            self.prev = [self.prev[1], tok if kind != "str" else '""']

    def identifier(self, tok: str):
        if tok in KEYWORDS or self.after_tag:
            if tok == "typedef" and not self.braces and self.parens == 0:
                self.in_typedef = True
            return
        if self.braces:
            if self.braces[-1] == "enum" and self.parens == 0 and self.prev[1] in ("{", ","):
                self.names.ordinary.setdefault(tok, self.where())
            return
        at_top = self.parens == 0 or (self.parens == 1 and self.prev == ["(", "*"])
        if not at_top:
            return
        table = self.names.typedefs if self.in_typedef else self.names.ordinary
        table.setdefault(tok, self.where())

    def punct(self, tok: str):
        if tok == "{":
            enum = self.prev[1] == "enum" or self.prev[0] == "enum"
            self.braces.append("enum" if enum else "other")
        elif tok == "}":
            if self.braces:
                self.braces.pop()
        elif tok == "(":
            if not self.braces:
                self.parens += 1
        elif tok == ")":
            if not self.braces and self.parens:
                self.parens -= 1
        elif tok == ";" and not self.braces and self.parens == 0:
            self.in_typedef = False


def scan(preprocessed: str, names: CNames, label) -> None:
    """Scan `cc -E -dD` output (or a header's raw text). `label(path,
    stack)` names the header a declaration comes from."""
    stack: list = ["<probe>"]
    scanner = _Scanner(names, lambda: label(stack[-1], stack))
    for line in preprocessed.splitlines():
        stripped = line.lstrip()
        if stripped.startswith("#"):
            marker = re.match(_MARKER_RE, stripped)
            if marker:
                path, flags = marker.group(2), marker.group(3).split()
                if "1" in flags:
                    stack.append(path)
                elif "2" in flags:
                    while len(stack) > 1 and stack[-1] != path:
                        stack.pop()
                else:
                    stack[-1] = path
                continue
            define = re.match(_DEFINE_RE, stripped)
            if define:
                names.macros.setdefault(define.group(1), label(stack[-1], stack))
            continue
        scanner.feed(line + "\n")


# ---- the probe ---------------------------------------------------------------------

def _runtime_headers() -> list:
    """The runtime's headers, relative to runtime_c/, in include order."""
    rt = runtime_dir()
    found = ["utility.h", "epuckrt.h", "rt_internal.h", "rt_clock.h", "rt_sensors.h",
             "rt_registry.h", "rt_odometry.h", "rt_motion.h", "rt_modes.h", "rt_platform.h",
             "host/epuck_stub.h", "host/stub_ground.h", "host/host_harness.h",
             "host/library_sim.h"]
    found += sorted(p.relative_to(rt / "epuck_api").as_posix()
                    for p in (rt / "epuck_api").rglob("*.h"))
    return found


def _unsimulated_headers() -> list:
    """The headers of what the simulation does not model but links
    (host/unsimulated.c defines their functions and objects), relative to
    runtime_c/: their names with external linkage are taken too (an extern
    of that name would not link); their macros are not where an extern is
    declared."""
    rt = runtime_dir()
    return sorted(p.relative_to(rt).as_posix()
                  for p in (rt / "epuck_api_unsimulated").rglob("*.h")
                  if b"#error" not in p.read_bytes())


def _include_dirs() -> list:
    rt = runtime_dir()
    return [rt, rt / "epuck_api", rt / "host", rt / "epuck_api_unsimulated"]


def _compiler() -> list:
    import shlex
    return shlex.split(os.environ.get("CC") or "cc")


def _label_factory():
    roots = sorted((str(d) + os.sep for d in _include_dirs()), key=len, reverse=True)

    def label(path: str, stack: list) -> str:
        for root in roots:
            if path.startswith(root):
                return path[len(root):]
        # a system header: name the standard header that brought it in
        for entry in stack[1:]:
            if not any(entry.startswith(r) for r in roots):
                return "<" + entry.rsplit("/include/", 1)[-1] + ">"
        return "<" + path.rsplit("/include/", 1)[-1] + ">"
    return label


def _cache_key(compiler: list) -> str:
    import hashlib
    import shlex
    import shutil
    h = hashlib.sha256(f"{FORMAT}\0{shlex.join(compiler)}\0".encode())
    binary = shutil.which(compiler[0]) if compiler else None
    if binary:
        st = os.stat(binary)
        h.update(f"{os.path.realpath(binary)}\0{st.st_size}\0{st.st_mtime_ns}".encode())
    rt = runtime_dir()
    for rel in _runtime_headers():
        base = rt / "epuck_api" if (rt / "epuck_api" / rel).is_file() else rt
        h.update(rel.encode() + b"\0" + (base / rel).read_bytes())
    for rel in _unsimulated_headers():
        h.update(rel.encode() + b"\0" + (rt / rel).read_bytes())
    return h.hexdigest()[:24]


def _extract_with_compiler(compiler: list) -> Optional[CNames]:
    import subprocess
    import tempfile
    probe = "".join(f'#include "{h}"\n' for h in _runtime_headers()) + \
        "".join(f"#include <{h}>\n" for h in STANDARD_HEADERS)
    names = CNames()
    label = _label_factory()
    with tempfile.TemporaryDirectory() as tmp:
        src = Path(tmp) / "probe.c"
        src.write_text(probe)
        flags = ["-std=c99"] + [f"-I{d}" for d in _include_dirs()]
        try:
            declared = subprocess.run(compiler + flags + ["-E", "-dD", str(src)],
                                      capture_output=True, text=True)
            predefined = subprocess.run(compiler + flags + ["-E", "-dM", str(src)],
                                        capture_output=True, text=True)
        except OSError:
            return None
    if declared.returncode != 0 or predefined.returncode != 0:
        return None
    scan(declared.stdout, names, label)
    linked = _linked_names(compiler, flags, label)
    if linked is None:
        return None
    for name, where in linked.ordinary.items():
        names.ordinary.setdefault(name, where)
    for m in re.finditer(_DEFINE_RE, predefined.stdout):
        names.macros.setdefault(m.group(1), "the compiler (predefined)")
    return names


def _linked_names(compiler: list, flags: list, label) -> Optional[CNames]:
    """The names of _unsimulated_headers(), scanned on their own."""
    import subprocess
    import tempfile
    names = CNames()
    with tempfile.TemporaryDirectory() as tmp:
        src = Path(tmp) / "linked.c"
        src.write_text("".join(f'#include "{h}"\n' for h in _unsimulated_headers()))
        try:
            done = subprocess.run(compiler + flags + ["-E", str(src)], capture_output=True,
                                  text=True)
        except OSError:
            return None
    if done.returncode != 0:
        return None
    scan(done.stdout, names, label)
    return names


def _extract_from_runtime_headers() -> CNames:
    names = CNames(complete=False)
    rt = runtime_dir()
    for rel in _runtime_headers():
        path = rt / "epuck_api" / rel if (rt / "epuck_api" / rel).is_file() else rt / rel
        scan(path.read_text(encoding="utf-8"), names, lambda *_: rel)
    return names


@lru_cache(maxsize=1)
def names_key() -> str:
    """What the names an extern may not take are extracted from (the C
    compiler and the runtime's headers), as a string: what a result that
    used them depends on (check/cache.py)."""
    return _cache_key(_compiler())


@lru_cache(maxsize=1)
def visible_names() -> CNames:
    """The names, from the cache when the headers and compiler are the
    same as when they were extracted."""
    import json
    from ..base import cache
    compiler = _compiler()
    key = _cache_key(compiler)
    path = cache.area("cnames") / f"{key}.json"
    try:
        data = json.loads(path.read_text(encoding="utf-8"))
        names = CNames(data["ordinary"], data["typedefs"], data["macros"], data["complete"])
        cache.used(path)
        return names
    except (OSError, ValueError, KeyError, TypeError):
        pass
    names = _extract_with_compiler(compiler)
    if names is None:
        return _extract_from_runtime_headers()      # not cached: a compiler may come
    cache.write_entry(path, json.dumps({"ordinary": names.ordinary, "typedefs": names.typedefs,
                                        "macros": names.macros, "complete": names.complete},
                                       sort_keys=True).encode("utf-8"))
    return names


# ---- what an extern may be called ------------------------------------------------

GENERATED_PREFIX = "epk_"       # lower.PREFIX: every name epuckc makes up
STRUCT_PREFIX = "param_"        # an extern NAME's parameter struct is param_NAME
LIBRARY_PREFIX = "e_"           # the e-puck library's functions (more than epuck_api/ declares)


def extern_name_problem(name: str, has_params: bool) -> Optional[str]:
    """Why an extern (a C function of exactly this name, declared after
    utility.h) cannot be called `name`, or None."""
    if name in KEYWORDS:
        return f"`{name}` is a C keyword"
    if name == "main":
        return "`main` is the program's own function"
    if name in PREDEFINED or is_reserved(name, file_scope=True):
        return "names starting with `_` are reserved for the C compiler and library"
    if name.lower().startswith(GENERATED_PREFIX):
        return f"names starting with `{GENERATED_PREFIX}` are the ones epuckc generates"
    if name.startswith(STRUCT_PREFIX):
        return (f"names starting with `{STRUCT_PREFIX}` are the parameter structs of externs "
                f"(`{STRUCT_PREFIX}NAME` is extern `NAME`'s)")
    if name.startswith(LIBRARY_PREFIX):
        return f"names starting with `{LIBRARY_PREFIX}` belong to the e-puck library"
    names = visible_names()
    where = names.declared(name)
    if where is not None:
        return f"{where} already declares `{name}`"
    struct = STRUCT_PREFIX + name
    where = names.declared(struct) if has_params else None
    if where is not None:
        return f"its parameter struct would be `{struct}`, which {where} already declares"
    return None


def parameter_name_problem(name: str) -> Optional[str]:
    """Why a field of an extern's parameter struct cannot be called
    `name`, or None: only what changes how `int NAME;` parses matters."""
    if name in KEYWORDS:
        return f"`{name}` is a C keyword"
    if name in PREDEFINED or is_reserved(name, file_scope=False):
        return "names starting with `__` or `_` and a capital are reserved for the C compiler"
    names = visible_names()
    if name in names.macros:
        return f"`{name}` is a macro of {names.macros[name]}"
    if name in names.typedefs:
        return f"`{name}` is a type of {names.typedefs[name]}"
    return None
