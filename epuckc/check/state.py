"""The checker's state as records, each with its owner and its lifetime.

- `Declarations`: what declaring a program leaves (its name tables, the
  robot's geometry, the initial mode, the trace ids given): built once per
  program by `Checker._declarations`, then only read (a rule's check reads
  it; the language server watches what a rule looks up in it, and puts a
  program's declarations back whole while its declaring statements are
  the same).
- `Facts`: the names and devices the steps used and assigned, which the
  whole-program checks read (unused names, W009, devices). A step checked
  apart (`Checker.apart`) has its own, and the union of the steps' facts is
  the program's.
- `Memories`: what one file's check remembers so as to say a problem once
  (a constant's chain followed, a definition's problem said, a device
  reported); a step checked apart starts with empty ones, so that it says
  all of its own problems and does all of its own look-ups.

A new piece of state goes into one of these (or into the Checker's
per-check scratch, which declaring must not write:
tests/check/test_state.py), so that the language server, which copies and
replays them by their fields, cannot miss it.
"""
from __future__ import annotations

from typing import Optional

from ..base.records import field, record
from ..stdlib.units import Geometry


@record
class Declarations:
    consts: dict = field(default_factory=dict)          # name -> ConstDef
    const_arrays: dict = field(default_factory=dict)    # name -> (ConstDef, element Exprs)
    actions: dict = field(default_factory=dict)         # name -> ActionDef
    externs: dict = field(default_factory=dict)         # name -> ExternInfo
    broken_externs: dict = field(default_factory=dict)  # name -> kind, of bad declarations
    extern_c_names: dict = field(default_factory=dict)  # C name -> first ExternDef
    rule_names: dict = field(default_factory=dict)      # name -> Rule
    modes: dict = field(default_factory=dict)           # name -> ModeDef
    vars: dict = field(default_factory=dict)            # name -> VarInfo
    geo: Geometry = field(default_factory=Geometry)
    initial_mode: Optional[str] = None
    trace_ids: int = 0      # the trace's ids given to variables (an array: one each)
    # named action -> its depth once spliced where it is called (splice.py):
    # derived from the actions when they are resolved, after declaring
    action_depths: dict = field(default_factory=dict)

    # the name tables a rule looks names up in (what the language server watches)
    TABLES = ("consts", "const_arrays", "actions", "externs", "broken_externs", "rule_names",
              "modes", "vars")
    # tables derived from the declarations when the named actions are
    # resolved: a rule looks names up in them (watched, as TABLES), but they
    # are not part of what the declarations are (the server's key)
    DERIVED = ("action_depths",)
    # the others: what declaring alone reads, and the geometry (compared whole)
    NOT_LOOKED_UP = ("extern_c_names", "geo", "initial_mode", "trace_ids")

    def copy(self) -> "Declarations":
        """A copy whose tables are new dicts (of the same entries)."""
        return Declarations(*(_copy(getattr(self, f)) for f in self.__match_args__))


@record
class Facts:
    called: set = field(default_factory=set)            # standard actions called
    used_actions: set = field(default_factory=set)      # named actions called
    const_used: set = field(default_factory=set)
    vars_used: set = field(default_factory=set)
    vars_assigned: set = field(default_factory=set)
    devices_used: set = field(default_factory=set)

    def items(self) -> tuple:
        """(field, its set) of those not empty: what a step found."""
        return tuple((f, v) for f in self.__match_args__ if (v := getattr(self, f)))

    def update(self, items) -> None:
        """Adds a step's `items()`."""
        for f, values in items:
            getattr(self, f).update(values)

    def copy(self) -> "Facts":
        return Facts(*(set(getattr(self, f)) for f in self.__match_args__))


@record
class Memories:
    const_memo: dict = field(default_factory=dict)      # constant -> (Number, negated, problem)
    const_reported: set = field(default_factory=set)    # a constant's problem, said
    const_diagnostics: set = field(default_factory=set)  # a definition's diagnostics, said
    device_reported: set = field(default_factory=set)   # (device, name) [E070], device [W070]

    def copy(self) -> "Memories":
        return Memories(*(_copy(getattr(self, f)) for f in self.__match_args__))


@record
class Step:
    """What a step checked apart said and found (Checker.apart)."""
    diags: list = field(default_factory=list)
    facts: tuple = ()       # Facts.items()


def _copy(value):
    cls = value.__class__
    if cls is dict:
        return dict(value)
    if cls is set:
        return set(value)
    if cls is list:
        return list(value)
    return value
