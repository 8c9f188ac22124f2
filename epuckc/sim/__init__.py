"""Running programs on a simulated robot: the host harness (harness.py),
world files (world.py), Enki worlds with many robots (enki.py) and pictures
of a trace (plot.py).

May import: base, build.
"""
