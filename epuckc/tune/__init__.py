"""`epuckc tune FILE.toml`: a search over the programs' constants for the
values that make an objective over the metrics best, on the experiment
engines (local pool, Dask), with racing by seeds.

The file is an experiment file (experiment/spec.py) with a `[search]`
table (`space.py`: each constant's range, ints, quantities with their
unit, log scale or choices, and the settings: the objective, an
arithmetic expression over the metrics read by `objective.py`, its
direction and aggregate over the design seeds, the budget, the sampler's
seed). `race.py` drives Optuna's ask-and-tell in rounds: each candidate's
seeds run one step at a time and a candidate whose running value is worse
than the median of the finished ones at the same step stops there
(Optuna's MedianPruner); the rounds do not depend on the engine or the
number of workers, and the sampler is seeded, so a tune repeats, and
resumes by replaying its saved runs. The best candidate is run again on
fresh test seeds, beside the programs' own constants. `report.py` writes
history.csv, best.toml, best.defines and test.csv; `svg.py` the
convergence and parameter pictures.

May import: base, build, check, sim, experiment (and Optuna)."""
