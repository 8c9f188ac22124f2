"""Running programs on a simulated robot: the host harness (harness.py),
scenario files checked before a run (scenario.py), world files (world.py),
Enki worlds with many robots (enki.py), pictures of a trace (plot.py) and
the page that replays a run (replay.py).

May import: base, build.
"""
