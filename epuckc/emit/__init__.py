"""Emission: the lowered model printed as C through the Jinja2 templates in
templates/ (which hold no logic), and the header of a program's externs.

May import: base, check (its output type), lower.
"""
