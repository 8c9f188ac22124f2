"""Compiling translation units in parallel: a step per unit, a pool of
workers, and the first failing unit in order reported whichever fails first."""
from __future__ import annotations

import os
import shlex
import subprocess
import sys
from dataclasses import dataclass
from typing import Callable, Optional

from .common import BuildError, _compiler_missing


@dataclass
class CompileStep:
    """One translation unit: its compiler command, what to call it in a
    message, a hint for when it fails, and its source's size (the biggest
    start first, so that the longest compile does not start last), and
    what follows the command once it succeeded, on the same worker
    (`post(stdout, stderr)` -> (status, stdout, stderr): the user's C is
    compiled to assembly, rewritten and assembled, build/dspic_asm.py)."""
    command: list
    what: str
    hint: str = ""
    size: int = 0
    post: Optional[Callable] = None


def compile_jobs() -> int:
    """How many compilers run at once: the processors this process may use."""
    try:
        return max(1, len(os.sched_getaffinity(0)))
    except (AttributeError, OSError):
        return max(1, os.cpu_count() or 1)


class _Job:
    """One step given to a pool: its result is (status, stdout, stderr), or
    the OSError that kept the compiler from starting; None if cancelled."""

    def __init__(self, step: CompileStep, done):
        self.step = step
        self.done = done                # a threading.Event
        self.result = None
        self.proc = None
        self.cancelled = False


class CompilerPool:
    """Runs compile steps on `jobs` worker threads, the biggest waiting step
    first; a job can be waited for or cancelled (which kills its compiler).
    The workers are daemon threads, idle when there is nothing to do."""

    def __init__(self, jobs: int):
        import threading
        self._event = threading.Event
        self._cond = threading.Condition()
        self._waiting = []              # a heap of (-size, order, job)
        self._order = 0
        for _ in range(jobs):
            threading.Thread(target=self._work, daemon=True).start()

    def submit(self, step: CompileStep) -> _Job:
        import heapq
        job = _Job(step, self._event())
        with self._cond:
            self._order += 1
            heapq.heappush(self._waiting, (-step.size, self._order, job))
            self._cond.notify()
        return job

    def cancel(self, job: _Job) -> None:
        """A job not started never starts; a running one is killed with the
        processes it started (gcc's cc1 and as: its process group)."""
        import signal
        with self._cond:
            job.cancelled = True
            if job.proc is not None and job.proc.poll() is None:
                try:
                    os.killpg(job.proc.pid, signal.SIGKILL)
                except OSError:
                    job.proc.kill()

    def _work(self):
        import heapq
        while True:
            with self._cond:
                while not self._waiting:
                    self._cond.wait()
                job = heapq.heappop(self._waiting)[2]
                if job.cancelled:
                    job.done.set()
                    continue
                try:
                    # a process group of its own, so that cancel stops all of it
                    job.proc = subprocess.Popen(job.step.command, stdin=subprocess.DEVNULL,
                                                stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                                                text=True, errors="replace",
                                                start_new_session=True)
                except OSError as exc:
                    job.result = exc
                    job.done.set()
                    continue
            try:
                out, err = job.proc.communicate()
                job.result = (job.proc.returncode, out, err)
                if job.proc.returncode == 0 and job.step.post is not None \
                        and not job.cancelled:
                    job.result = job.step.post(out, err)
            except Exception as exc:        # reported to whoever waits for it
                job.result = OSError(str(exc))
            job.done.set()


_POOL = None


def compiler_pool() -> CompilerPool:
    """The process's pool: as many compilers at once as it has processors."""
    global _POOL
    if _POOL is None:
        _POOL = CompilerPool(compile_jobs())
    return _POOL


def wait_jobs(jobs: list, pool: CompilerPool) -> list:
    """The jobs' results, once all are done. An interruption (Ctrl-C,
    SIGTERM) cancels them all, killing the compilers still running,
    before it goes on."""
    try:
        for job in jobs:
            job.done.wait()
    except BaseException:
        cancel_jobs(jobs, pool)
        raise
    return [job.result for job in jobs]


def cancel_jobs(jobs: list, pool: CompilerPool) -> None:
    """Cancel the jobs and wait until none of their compilers runs."""
    for job in jobs:
        pool.cancel(job)
    for job in jobs:
        if job.proc is not None:
            try:
                job.proc.wait(10)
            except subprocess.TimeoutExpired:
                pass


def report_results(steps: list, results: list) -> None:
    """In the steps' order, the warnings of those that succeeded are shown
    and the first that failed raises BuildError: the same message
    whichever compiler finished first."""
    for step, result in zip(steps, results):
        if isinstance(result, FileNotFoundError):
            raise _compiler_missing(step.command)
        if isinstance(result, OSError):
            raise BuildError(f"cannot run the C compiler `{step.command[0]}`: "
                             f"{result.strerror or result}")
        if result is None:
            raise BuildError(f"the C compiler was stopped before it built {step.what}")
        status, out, err = result
        if status == 0:
            if err:
                sys.stderr.write(err)        # warnings in the user's C
            continue
        output = (out + err).rstrip()
        raise BuildError(f"the C compiler failed to build {step.what}:\n{output}\n"
                         f"command: {shlex.join(step.command)}{step.hint}")


def run_compile_steps(steps: list, jobs: Optional[int] = None) -> None:
    """Run the steps, each to its end, on the process's pool (or on a pool
    of `jobs` workers); then report_results."""
    pool = CompilerPool(jobs) if jobs else compiler_pool()
    report_results(steps, wait_jobs([pool.submit(step) for step in steps], pool))
