"""Builds of a C program (generated or hand-written): the host harness
executable with its cache (host.py, parallel.py, runcache.py), the e-puck's
XC16 project (dspic.py), and what they share (common.py).

May import: base. It knows C files and compilers, not rule files.
"""
