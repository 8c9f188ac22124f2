"""Running programs on a simulated robot: the host harness (harness.py),
scenario files checked before a run (scenario.py), world files (world.py;
robots too near each other: spacing.py), worlds with many robots on Enki or
Chipmunk (enki.py), contacts in words (contacts.py), pictures of a trace
(plot.py, as SVG text: svg.py) and
the page that replays a run (replay.py).

May import: base, build.
"""
