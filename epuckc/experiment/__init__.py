"""Experiments at scale: the same world run for many seeds and a grid of
the programs' constants, in parallel, with metrics and their summary.

An experiment file (`spec.py`, TOML, errors as file:line:col) names the
programs, the world, the duration, the seeds, the metrics and the grid.
`plan.py` checks and compiles each program once per grid point (through a
loader the command line gives it, with `-D`-style constants) and makes
one self-contained task per (grid point, seed): the generated C, the
world and the settings travel with it, so a worker needs no shared file
system. `task.py` runs one task on a worker (the robot built and cached
there, the world simulated under a watchdog) and measures it with
`metrics.py`; `engines.py` spreads the tasks over a local process pool or
a Dask cluster; `results.py` writes runs.csv, summary.csv (with `stats.py`)
and resumes an interrupted experiment; `svg.py` draws summary.svg.

May import: base, build, check, sim.
"""
