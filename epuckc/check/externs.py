"""Extern actions and events: C names the runtime and the C compiler accept,
parameter types, the C file beside the rule file."""
from __future__ import annotations

import os
from pathlib import Path
from typing import Optional

from ..diagnostics import Note
from ..stdlib.table import EXTERN_TYPES, Param
from ..syntax import ast
from .messages import _clip, _code, did_you_mean
from .program import ExternInfo


class Externs:
    """The checker's extern declarations (a part of Checker)."""

    def _extern(self, stmt: ast.ExternDef, claim):
        # only for externs: a program without them is checked without it
        from .cnames import extern_name_problem, parameter_name_problem
        if self._clashes_with_standard(stmt.name, stmt.kind):
            return
        # an extern is a C function of exactly this name, its parameters the
        # fields of a struct, both declared after utility.h (cnames.py)
        problem = extern_name_problem(stmt.name.name, bool(stmt.params))
        if problem is not None:
            self.diags.error("E027", stmt.name.span,
                             f"an extern {stmt.kind} cannot be named {_code(stmt.name.name)}: "
                             f"{problem}",
                             help=f"rename it in both files, e.g. `my_{stmt.name.name}`")
            self.broken_externs[stmt.name.name] = stmt.kind
            return
        first = self.extern_c_names.get(stmt.name.name)
        if first is not None and first.kind != stmt.kind:
            self.diags.error("E015", stmt.name.span,
                             f"{_code(stmt.name.name)} is already an extern {first.kind}: "
                             "both would be the C function of that name",
                             help="rename one of them in both files",
                             notes=[Note("first declared here", first.name.span)])
            return
        self.extern_c_names.setdefault(stmt.name.name, stmt)
        params, ok = [], True
        names: dict = {}
        for p in stmt.params:
            problem = parameter_name_problem(p.name.name)
            if problem is not None:
                self.diags.error("E027", p.name.span,
                                 f"a parameter cannot be named {_code(p.name.name)}: {problem}",
                                 help=f"rename it in the declaration and in your C, "
                                      f"e.g. `{p.name.name.strip('_') or 'value'}_value`")
                ok = False
            if p.type.name not in EXTERN_TYPES:
                self.diags.error("E026", p.type.span, f"unknown type {_code(p.type.name)}",
                                 help=did_you_mean(p.type, EXTERN_TYPES)
                                 or "the types are " + ", ".join(map(_code, EXTERN_TYPES)))
                ok = False
            if p.name.name in names:
                self.diags.error("E015", p.name.span,
                                 f"parameter {_code(p.name.name)} is declared twice",
                                 notes=[Note("first declared here", names[p.name.name].span)])
                ok = False
            names[p.name.name] = p.name
            params.append(Param(p.name.name, p.type.name))
        unterminated = any(d.code == "E003" and d.span == stmt.file_span for d in self.diags.items)
        if self.base_dir is not None and not unterminated:
            self._extern_file(stmt)
        if claim(stmt.kind, stmt.name, f"{stmt.kind}"):
            if ok:
                self.externs[stmt.name.name] = ExternInfo(stmt.kind, stmt.name.name,
                                                          tuple(params), stmt.file, stmt)
            else:       # reported above; its uses are not errors of their own
                self.broken_externs[stmt.name.name] = stmt.kind

    def _extern_file(self, stmt: ast.ExternDef):
        looked = self.base_dir / stmt.file
        problem = extern_file_problem(looked)
        if problem is not None:
            self.diags.error("E040", stmt.file_span,
                             f"the C file {_code(_clip(stmt.file, 60))} {problem}",
                             help=f"epuckc looked for `{_clip(str(looked), 100)}`: the path is "
                                  "relative to the folder of the rule file")


def extern_file_problem(looked: Path) -> Optional[str]:
    """What is wrong with an extern's C file (E040), or None: all the
    checker asks of the file system (check/cache.py asks it again)."""
    try:
        os.stat(looked)
        return None if looked.is_file() else "is not a file"
    except FileNotFoundError:
        return "does not exist"
    except OSError as exc:      # a name longer than NAME_MAX, a loop of links, ...
        return f"cannot be used: {exc.strerror or exc}"
    except ValueError:          # a NUL byte
        return "cannot be used: it contains a NUL character"
