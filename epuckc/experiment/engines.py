"""Where the runs run. `local`: a process pool on this machine's cores (in
this process with one worker); `dask`: a Dask distributed cluster, at a
scheduler's address or, without one, a local cluster of `workers`
processes; `slurm` (slurm.py): a job array of a batch scheduler. Each
takes batches (plan.Batch: runs of one job, which travel together) and
calls `done(task, result)` in this process for each run as its batch
ends, in the order they end; the results do not depend on it (results.py
sorts them). A worker lost with its batch (a crash, a kill) gives each of
its runs a result with the error, marked to run again when the experiment
resumes. `open_engine` keeps a pool or a cluster's client open across
several rounds of batches (a tune's); `run` is one round (launch.py
chooses among these and slurm.py's).
"""
from __future__ import annotations

import os

from .task import execute_batch, lost, worker_started

DASK_MISSING = ("--engine dask needs Dask's distributed scheduler, which is not installed; "
                "install it with: pip install 'epuckc[cluster]' (or: pip install dask distributed)")


CONNECT_TIMEOUT_S = 10


class EngineError(Exception):
    """The engine cannot start; str() says why and what to do."""


def default_workers() -> int:
    try:
        return len(os.sched_getaffinity(0))
    except AttributeError:
        return os.cpu_count() or 1


class LocalEngine:
    """A process pool, started at the first round with more than one batch
    and kept for the next rounds; one worker runs in this process."""

    def __init__(self, workers: int):
        self.workers = workers
        self.pool = None

    def run(self, batches: list, done):
        if self.workers <= 1 or (len(batches) <= 1 and self.pool is None):
            for batch in batches:
                for task, result in zip(batch.tasks, execute_batch(batch)):
                    done(task, result)
            return
        from concurrent.futures import ProcessPoolExecutor, as_completed
        from concurrent.futures.process import BrokenProcessPool
        if self.pool is None:
            self.pool = ProcessPoolExecutor(max_workers=self.workers, mp_context=_pool_context(),
                                            initializer=worker_started)
        try:
            futures = {self.pool.submit(execute_batch, batch): batch for batch in batches}
            for future in as_completed(futures):
                batch = futures[future]
                try:
                    results = future.result()
                except BrokenProcessPool:
                    results = [lost(t, "the worker process running this run died")
                               for t in batch.tasks]
                    self.close()
                except Exception as exc:        # pickling and the like: this batch only
                    results = [lost(t, f"{type(exc).__name__}: {exc}") for t in batch.tasks]
                for task, result in zip(batch.tasks, results):
                    done(task, result)
        except BaseException:
            if self.pool is not None:
                self.pool.shutdown(wait=False, cancel_futures=True)
                self.pool = None
            raise

    def close(self):
        if self.pool is not None:
            self.pool.shutdown()
            self.pool = None
            _stop_fork_server()


def _pool_context():
    """How the pool's processes start. A fork of this process while it has
    a single thread (`epuckc experiment`): the workers have every module
    already, and start in no time (a fork server took 0.2-0.3 s of an
    experiment, 3-4 % of a thousand runs on two workers). Not a fork of a
    process with threads (a test runner, an embedding tool): a fork can
    inherit a lock held by another thread and hang. Then a fork server, a
    fresh interpreter that imports the workers' modules once and forks
    each worker from itself (single-threaded), where there is one: each
    worker then costs a fork, not an interpreter's start and imports
    (about 0.25 s of CPU each); elsewhere, fresh interpreters (spawn).
    (The pool starts all its processes before its own thread: see
    ProcessPoolExecutor's _safe_to_dynamically_spawn_children.)"""
    import multiprocessing
    import threading
    if threading.active_count() == 1 and "fork" in multiprocessing.get_all_start_methods():
        return multiprocessing.get_context("fork")
    if "forkserver" not in multiprocessing.get_all_start_methods():
        return multiprocessing.get_context("spawn")
    context = multiprocessing.get_context("forkserver")
    context.set_forkserver_preload(["epuckc.experiment.task", "epuckc.sim.enki",
                                    "epuckc.experiment.metrics"])
    return context


def _stop_fork_server():
    """The fork server ends with the command: stopped and waited for (its
    own stop, which CPython's tests use; without it the server outlives the
    command a moment and nobody counts its time)."""
    import multiprocessing
    if "forkserver" not in multiprocessing.get_all_start_methods():
        return
    from multiprocessing import forkserver
    stop = getattr(getattr(forkserver, "_forkserver", None), "_stop", None)
    if stop is not None:
        stop()


def dask_available() -> bool:
    try:
        import distributed  # noqa: F401
    except ImportError:
        return False
    return True


class DaskEngine:
    """A client of a Dask cluster (at `scheduler`, or a local one of
    `workers` processes), kept for the next rounds."""

    def __init__(self, workers: int, scheduler):
        try:
            from distributed import Client, LocalCluster
        except ImportError:
            raise EngineError(DASK_MISSING) from None
        self.cluster = None
        try:
            if scheduler:
                self.client = Client(scheduler, timeout=f"{CONNECT_TIMEOUT_S}s")
            else:
                self.cluster = LocalCluster(n_workers=workers, threads_per_worker=1,
                                            processes=True, dashboard_address=None)
                self.client = Client(self.cluster)
        except (OSError, TimeoutError) as exc:
            if self.cluster is not None:
                self.cluster.close()
            raise EngineError(f"cannot reach the Dask scheduler {scheduler or '(local)'} within "
                              f"{CONNECT_TIMEOUT_S} s: {exc}") from None

    def run(self, batches: list, done):
        from distributed import as_completed
        futures = []
        try:
            futures = self.client.map(execute_batch, batches,
                                      key=[f"epuckc-batch-{b.key}" for b in batches], pure=False)
            by_key = {f.key: b for f, b in zip(futures, batches)}
            for future in as_completed(futures):
                batch = by_key[future.key]
                try:
                    results = future.result()
                except Exception as exc:        # KilledWorker, a lost connection, ...
                    why = (f"the Dask worker was lost ({type(exc).__name__}: "
                           f"{str(exc).splitlines()[0] if str(exc) else ''})")
                    results = [lost(t, why) for t in batch.tasks]
                for task, result in zip(batch.tasks, results):
                    done(task, result)
        except BaseException:
            self.client.cancel(futures)
            raise

    def close(self):
        self.client.close()
        if self.cluster is not None:
            self.cluster.close()
