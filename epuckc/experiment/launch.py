"""An engine by its name (`--engine`): the local pool, Dask (engines.py)
or a SLURM job array (slurm.py), open for rounds of batches."""
from __future__ import annotations

from .engines import DaskEngine, LocalEngine


def open_engine(engine: str, workers: int, scheduler=None, **options):
    """An engine to run rounds of batches on; close() it at the end."""
    if engine == "dask":
        return DaskEngine(workers, scheduler)
    if engine == "slurm":
        from .slurm import SlurmEngine
        return SlurmEngine(workers, **options)
    return LocalEngine(workers)


def run(engine: str, batches: list, workers: int, scheduler, done, **options):
    """One round: every batch run, `done` called for each run."""
    session = open_engine(engine, workers, scheduler, **options)
    try:
        session.run(batches, done)
    finally:
        session.close()
