"""The C-shaped program that lowering makes and templates/program.c.j2
prints: one dataclass per thing the C has (a parameter struct, a generated
function, a sequence, an entry of the action or event table, ...)."""
from __future__ import annotations

from dataclasses import dataclass, field
from typing import Optional


# ---- the C-shaped program ------------------------------------------------------

@dataclass
class CStruct:
    """A parameter struct: `static const TYPE NAME = INIT; /* COMMENT */`
    (const: XC16 keeps it in program memory)."""
    ctype: str
    name: str
    init: str
    comment: str


@dataclass
class CFunction:
    """A generated action: runs `statements` in order."""
    name: str
    comment: str
    statements: list


@dataclass
class CEventFunction:
    """A generated event function (a `when` condition, a guard):
    `static void NAME(void *epk_param, void *epk_status)` running
    `statements`."""
    name: str
    comment: str
    statements: list


@dataclass
class CVariable:
    """`static int NAME = INIT; /* COMMENT */`, traced as `label`."""
    name: str
    init: str
    comment: str
    label: str


@dataclass
class CSequence:
    steps_name: str
    name: str
    entries: list          # "{function, &param}" initialisers
    comment: str
    names_name: str = ""   # its steps' texts for the host's trace (name_steps)
    labels: list = field(default_factory=list)     # C strings, one a step
    action_id: int = -1    # the action that runs it


@dataclass
class CAction:
    """An entry of the action table: `{function, param}`; its id is its index."""
    function: str
    param: str             # "&name" or "NULL"
    comment: str
    action_label: str      # C string: its name in the host's trace


@dataclass
class CEvent:
    """An entry of the event table; its id is its index."""
    function: str          # "NULL": a compiled sensor condition
    param: str
    action: int            # index in the action table
    flags: str             # "RT_REPEAT", "RT_HOLD_WHILE", "RT_HOLD_GUARD" joined with |, or "0"
    memory: str            # index in epk_event_memory, or "RT_NO_MEMORY"
    comment: str
    event_label: str
    priority: int = 0      # the rule's priority
    mode: int = 0          # its mode's number, 0: none


@dataclass
class CCondition:
    """`if (condition) epk_c[word] |= bit;`, setting one event's bit."""
    statement: str
    comment: str


@dataclass
class CConditionWord:
    """One word of the conditions function: `epk_c[index]`, its CConditions."""
    index: int
    terms: list


@dataclass
class CExternStruct:
    name: str
    fields: list           # (ctype, field name)


@dataclass
class CExtern:
    """A prototype in the externs header."""
    kind: str              # "action" | "event"
    name: str
    comment: str
    param_doc: str         # what its first argument points to


@dataclass
class CProgram:
    source_name: str       # for comments: already safe inside /* */
    version: str
    externs_header: Optional[str] = None       # its file name, when there are externs
    header_guard: str = ""
    extern_structs: list = field(default_factory=list)
    externs: list = field(default_factory=list)
    structs: list = field(default_factory=list)
    variables: list = field(default_factory=list)     # CVariable, every one (the trace's)
    declared_variables: list = field(default_factory=list)   # those the C declares
    functions: list = field(default_factory=list)
    event_functions: list = field(default_factory=list)   # CEventFunction
    sequences: list = field(default_factory=list)
    rule_ids: list = field(default_factory=list)     # (C name, event id) for `cancel RULE`
    actions: list = field(default_factory=list)      # CAction
    events: list = field(default_factory=list)       # CEvent
    conditions: list = field(default_factory=list)   # CConditionWord
    sensors: str = "0x00"                             # the IRs the conditions read
    condition_locals: list = field(default_factory=list)   # the readings it reads, as locals
    conditions_comment: list = field(default_factory=list)  # its comment's lines
    memory_slots: int = 0                             # longs of epk_event_memory
    geometry: Optional[str] = None   # set_robot_geometry arguments, for a robot block
    modes: list = field(default_factory=list)       # (id, C string of its name)
    initial_mode: Optional[tuple] = None            # (id, name)
    odometry: bool = False          # some expression reads x, y or heading


