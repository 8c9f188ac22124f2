"""Where the runs run. `local`: a process pool on this machine's cores (in
this process with one worker); `dask`: a Dask distributed cluster, at a
scheduler's address or, without one, a local cluster of `workers`
processes. Either calls `done(task, result)` in this process as each run
ends, in the order they end; the results do not depend on it (results.py
sorts them). A worker lost with its run (a crash, a kill) gives a result
with the error, marked to run again when the experiment resumes."""
from __future__ import annotations

import os

from .task import execute, lost, worker_started

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


def run_local(tasks: list, workers: int, done):
    if workers <= 1 or len(tasks) <= 1:
        for task in tasks:
            done(task, execute(task))
        return
    from concurrent.futures import ProcessPoolExecutor, as_completed
    from concurrent.futures.process import BrokenProcessPool
    pool = ProcessPoolExecutor(max_workers=min(workers, len(tasks)), mp_context=_pool_context(),
                               initializer=worker_started)
    try:
        futures = {pool.submit(execute, task): task for task in tasks}
        for future in as_completed(futures):
            task = futures[future]
            try:
                result = future.result()
            except BrokenProcessPool:
                result = lost(task, "the worker process running this run died")
            except Exception as exc:        # pickling and the like: this run only
                result = lost(task, f"{type(exc).__name__}: {exc}")
            done(task, result)
    except BaseException:
        pool.shutdown(wait=False, cancel_futures=True)
        raise
    pool.shutdown()
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


def run_dask(tasks: list, workers: int, scheduler, done):
    try:
        from distributed import Client, LocalCluster, as_completed
    except ImportError:
        raise EngineError(DASK_MISSING) from None
    cluster = None
    try:
        if scheduler:
            client = Client(scheduler, timeout=f"{CONNECT_TIMEOUT_S}s")
        else:
            cluster = LocalCluster(n_workers=workers, threads_per_worker=1, processes=True,
                                   dashboard_address=None)
            client = Client(cluster)
    except (OSError, TimeoutError) as exc:
        raise EngineError(f"cannot reach the Dask scheduler {scheduler or '(local)'} within "
                          f"{CONNECT_TIMEOUT_S} s: {exc}") from None
    try:
        futures = client.map(execute, tasks, key=[f"epuckc-run-{t.key}" for t in tasks],
                             pure=False)
        by_key = {f.key: t for f, t in zip(futures, tasks)}
        for future in as_completed(futures):
            task = by_key[future.key]
            try:
                result = future.result()
            except Exception as exc:        # KilledWorker, a lost connection, ...
                result = lost(task, f"the Dask worker was lost ({type(exc).__name__}: "
                                    f"{str(exc).splitlines()[0] if str(exc) else ''})")
            done(task, result)
    except BaseException:
        client.cancel(futures) if "futures" in locals() else None
        raise
    finally:
        client.close()
        if cluster is not None:
            cluster.close()


def run(engine: str, tasks: list, workers: int, scheduler, done):
    if engine == "dask":
        return run_dask(tasks, workers, scheduler, done)
    return run_local(tasks, workers, done)
