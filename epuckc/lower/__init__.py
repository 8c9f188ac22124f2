"""Lowering: a CheckedProgram to the C-shaped model the template prints
(tables, parameter structs, sequences, sensor conditions, priorities as
a poll order). Every decision about the C is made here.

May import: base, stdlib, syntax (node types), check (its output).
"""
