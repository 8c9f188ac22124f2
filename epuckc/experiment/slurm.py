"""The batch-scheduler engine, for clusters without a Dask service: the
batches go into a SLURM job array, and this process waits for their runs.

    DIR/jobs/element-I.pickle   the batches of array task I (plan.Batch)
    DIR/jobs/array.sh           the job script: `#SBATCH --array=0-(N-1)[%W]`,
                                each task `epuckc experiment --worker DIR/jobs --index I`
    DIR/jobs/submitted.json     the job's id, for a later command to find it
    DIR/jobs/logs/JOB_I.out     each array task's output

`sbatch --parsable` submits the script (with `--sbatch-options` before it);
`squeue -h -j JOB` says whether it still runs. Each array task runs its
batches (on $SLURM_CPUS_PER_TASK processes) and saves each batch's runs
in DIR/runs/BATCH.jsonl, as the other engines' results are saved (so DIR
must be on a file system the nodes share, as a cluster's home is); this
process reads them as they appear, and when the job has ended, a batch
without its file (a node that failed, a task killed at its time limit)
gives its runs a result with the error, run again by the next command. A
command that finds its job still running waits for it instead of
submitting again; `--detach` submits and returns, and `--report-only`
(or the same command) collects later."""
from __future__ import annotations

import json
import os
import pickle
import shlex
import shutil
import subprocess
import sys
import time
from pathlib import Path

from ..base.output import write_atomic
from .engines import EngineError, LocalEngine
from .results import load_done, read_file, save_batch
from .task import lost

MAX_ARRAY = 1000        # SLURM's default MaxArraySize is 1001
SLURM_MISSING = ("--engine slurm needs SLURM's sbatch and squeue on PATH (run it on the "
                 "cluster's login node)")


def poll_seconds() -> float:
    """How often the job is looked at (EPUCKC_SLURM_POLL_S: tests, busy clusters)."""
    try:
        return max(0.05, float(os.environ.get("EPUCKC_SLURM_POLL_S", "10")))
    except ValueError:
        return 10.0


class SlurmEngine:
    """`run` submits the batches as a job array and waits for them (or,
    detached, returns once submitted: `detached` is then True)."""
    saves = True            # the array's tasks save the runs themselves

    def __init__(self, workers, folder: Path, sbatch_options: str = "", detach: bool = False,
                 name: str = "epuckc", stream=None):
        for tool in ("sbatch", "squeue"):
            if shutil.which(tool) is None:
                raise EngineError(SLURM_MISSING)
        self.workers = workers
        self.folder = Path(folder)
        self.jobs = self.folder / "jobs"
        self.options = shlex.split(sbatch_options or "")
        self.detach = detach
        self.detached = False
        self.name = name
        self.stream = stream if stream is not None else sys.stderr

    def say(self, text: str):
        self.stream.write(text + "\n")
        self.stream.flush()

    def run(self, batches: list, done):
        tasks = [t for b in batches for t in b.tasks]
        earlier = self._submitted()
        if earlier and active(earlier["job"]):
            if self.detach:
                self.say(f"the job array {earlier['job']} submitted before still runs; "
                         "nothing more was submitted")
                self.detached = True
                return
            self.say(f"waiting for the job array {earlier['job']} submitted before")
            self._wait(earlier["job"], [], done)
        saved = load_done(self.folder, tasks)
        for task in tasks:
            if task.key in saved:
                done(task, saved[task.key])
        batches = [b for b in batches if any(t.key not in saved for t in b.tasks)]
        for b in batches:
            b.tasks = [t for t in b.tasks if t.key not in saved]
        if not batches:
            return
        job = self._submit(batches)
        if self.detach:
            self.say(f"submitted the job array {job} ({len(batches)} batches); the same "
                     f"command, or --report-only, collects its runs")
            self.detached = True
            return
        self.say(f"submitted the job array {job}; waiting for its {len(batches)} batches")
        self._wait(job, batches, done)

    def _submitted(self):
        try:
            return json.loads((self.jobs / "submitted.json").read_text(encoding="utf-8"))
        except (OSError, ValueError):
            return None

    def _submit(self, batches: list) -> str:
        elements = min(len(batches), MAX_ARRAY)
        for old in self.jobs.glob("element-*.pickle"):
            old.unlink()
        (self.jobs / "logs").mkdir(parents=True, exist_ok=True)
        for i in range(elements):
            (self.jobs / f"element-{i}.pickle").write_bytes(
                pickle.dumps(batches[i::elements], protocol=pickle.HIGHEST_PROTOCOL))
        limit = f"%{self.workers}" if self.workers else ""
        script = "\n".join([
            "#!/bin/bash",
            f"#SBATCH --job-name={self.name}",
            f"#SBATCH --array=0-{elements - 1}{limit}",
            f"#SBATCH --output={self.jobs / 'logs' / '%A_%a.out'}",
            "# written by `epuckc experiment --engine slurm`: each array task runs its",
            "# batches of runs and saves them in the experiment's folder",
            f"cd {shlex.quote(os.getcwd())}",
            f"exec {shlex.quote(sys.executable)} -m epuckc experiment --worker "
            f"{shlex.quote(str(self.jobs))} --index \"$SLURM_ARRAY_TASK_ID\"", ""])
        write_atomic(self.jobs / "array.sh", script)
        try:
            proc = subprocess.run(["sbatch", "--parsable", *self.options,
                                   str(self.jobs / "array.sh")],
                                  capture_output=True, text=True, timeout=120)
        except (OSError, subprocess.TimeoutExpired) as exc:
            raise EngineError(f"sbatch did not run: {exc}") from None
        if proc.returncode != 0:
            why = (proc.stderr or proc.stdout).strip().splitlines()
            raise EngineError(f"sbatch refused the job array: {why[-1] if why else proc.returncode}")
        job = proc.stdout.strip().split(";")[0]
        write_atomic(self.jobs / "submitted.json",
                     json.dumps({"job": job, "elements": elements}) + "\n")
        return job

    def _wait(self, job: str, batches: list, done):
        """Until every batch's runs are saved or the job has ended; the
        batches without their file then lost."""
        pending = {b.key: b for b in batches}
        while True:
            running = active(job)
            for key in [k for k, b in pending.items()
                        if (self.folder / "runs" / f"{k}.jsonl").is_file()]:
                batch = pending.pop(key)
                found = load_done(self.folder, batch.tasks,
                                  read_file(self.folder / "runs" / f"{key}.jsonl"))
                for task in batch.tasks:
                    done(task, found.get(task.key) or lost(
                        task, f"its batch's file holds no run for it (job {job})"))
            if not running or (batches and not pending):
                break
            time.sleep(poll_seconds())
        for batch in pending.values():
            for task in batch.tasks:
                done(task, lost(task, f"its job array task ended without saving its runs "
                                      f"(job {job}; see {self.jobs / 'logs'})"))

    def close(self):
        pass


def active(job: str) -> bool:
    """The job (or a task of its array) is still queued or running."""
    try:
        proc = subprocess.run(["squeue", "-h", "-j", job, "-o", "%i %t"], capture_output=True,
                              text=True, timeout=60)
    except (OSError, subprocess.TimeoutExpired):
        return True         # cannot tell: wait on
    # a job no longer known (ended and purged) is an error of squeue's
    return proc.returncode == 0 and bool(proc.stdout.strip())


def run_worker(jobs: Path, index: int, stream=None) -> int:
    """One array task (`epuckc experiment --worker JOBS --index I`): its
    batches run, each batch's runs saved as soon as it ends."""
    stream = stream if stream is not None else sys.stderr
    path = Path(jobs) / f"element-{index}.pickle"
    try:
        batches = pickle.loads(path.read_bytes())
    except (OSError, pickle.UnpicklingError, EOFError, AttributeError, ImportError) as exc:
        stream.write(f"epuckc: error: cannot read the job array's task {path}: {exc}\n")
        return 1
    folder = Path(jobs).parent
    try:
        workers = max(1, int(os.environ.get("SLURM_CPUS_PER_TASK", "1")))
    except ValueError:
        workers = 1
    waiting = {b.key: (b, {}) for b in batches}
    by_task = {t.key: b.key for b in batches for t in b.tasks}

    def done(task, result):
        batch, got = waiting[by_task[task.key]]
        got[task.key] = result
        if len(got) == len(batch.tasks):
            save_batch(folder, batch.key, [(t, got[t.key]) for t in batch.tasks])
            stream.write(f"batch {batch.key}: {len(got)} runs saved\n")
            stream.flush()

    engine = LocalEngine(workers)
    try:
        engine.run(batches, done)
    finally:
        engine.close()
    return 0

