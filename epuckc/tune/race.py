"""The search: Optuna's ask-and-tell, in rounds.

Up to `parallel` candidates are under way at once. In each round every
candidate runs its next design seeds (`min_seeds` at first, then one more),
all of the round's runs together on the engine; then, in the candidates'
order, each reports its running aggregate (the number of seeds so far is
the step) and stops there when Optuna's MedianPruner finds it worse than
the median of the finished candidates at that step (pruned), or is told
its value once every design seed has run (complete). A candidate starts
only when the budget's runs cover it and the rest of the candidates under
way; with a wall-clock budget, none starts after the time is up and those
under way stop. Nothing in a round depends on which run ends first or on
the number of workers, and the sampler is seeded: the same file gives the
same candidates, and the same history.

Every run is saved in DIR/runs as an experiment's are, and taken from
there when a candidate needs it again: the replay of an interrupted tune
asks the same candidates, finds their runs, and goes on where it stopped.
Optuna's journal (DIR/tune.journal) is written afresh by each replay, for
Optuna's own tools (optuna-dashboard) to read."""
from __future__ import annotations

import time
import warnings
from dataclasses import dataclass, field
from pathlib import Path
from typing import Optional

from ..experiment.plan import batches
from ..experiment.results import Saver, failed, load_done, read_saved
from ..experiment.spec import ExperimentError
from .objective import RunValueError, aggregate
from .space import Search, distributions

JOURNAL = "tune.journal"
STUDY = "epuckc-tune"


@dataclass
class Candidate:
    number: int
    values: dict                # searched constant -> value text
    job: object = None
    trial: object = None
    per_seed: list = field(default_factory=list)    # the objective on each design seed so far
    state: str = "running"      # complete, pruned, failed, stopped
    value: Optional[float] = None
    runs_at_end: int = 0
    note: str = ""


@dataclass
class TestRun:
    seed: int
    value: Optional[float]      # None: the run failed
    row: dict


@dataclass
class TuneResult:
    candidates: list
    runs: int                   # design runs the search took
    best: Optional[Candidate]
    test: dict                  # "best" / "program" -> [TestRun]
    test_seeds: list
    stopped: str                # what ended the search: "budget", "time"


def test_summary(runs: list) -> dict:
    """describe() of the test runs' values (those that did not fail)."""
    from ..experiment.stats import describe
    return describe([r.value for r in runs if r.value is not None])


def test_seeds(search: Search, design: list) -> list:
    """Fresh seeds for the best: the list given, or that many after the
    design seeds (as many as those, at least 10, by default)."""
    if isinstance(search.test_seeds, list):
        return list(search.test_seeds)
    count = search.test_seeds or max(10, len(design))
    start = max(design) + 1
    return list(range(start, start + count))


class Tuner:
    """One tune of `exp` (an experiment whose `extra["search"]` is a
    Search) on an open engine, its runs in `folder`."""

    def __init__(self, exp, search: Search, planner, engine, folder: Path, say=None,
                 clock=time.monotonic, saves: bool = True):
        self.exp, self.search, self.planner, self.engine = exp, search, planner, engine
        self.folder = Path(folder)
        self.say = say or (lambda text: None)
        self.clock = clock
        self.saves = saves
        self.fixed = {k: v[0] for k, v in exp.params.items()}
        self.used = 0
        self.simulated = 0
        self.saved = {}
        self.tests = test_seeds(search, exp.seeds)
        overlap = set(self.tests) & set(exp.seeds)
        if overlap:
            raise ExperimentError(f"{exp.shown}: the test seeds and the design seeds share "
                                  f"{sorted(overlap)[0]}: the test seeds must be fresh")

    # ---- Optuna ------------------------------------------------------------------

    def _study(self):
        import optuna
        from optuna.storages import JournalStorage
        from optuna.storages.journal import JournalFileBackend
        optuna.logging.set_verbosity(optuna.logging.WARNING)
        warnings.filterwarnings("ignore", category=optuna.exceptions.ExperimentalWarning)
        journal = self.folder / JOURNAL
        for old in (journal, journal.with_name(JOURNAL + ".lock")):
            if old.exists():
                old.unlink()
        s = self.search
        sampler = (optuna.samplers.RandomSampler(seed=s.sampler_seed) if s.sampler == "random"
                   else optuna.samplers.TPESampler(seed=s.sampler_seed, multivariate=True))
        pruner = (optuna.pruners.NopPruner() if s.pruning == "none" else
                  optuna.pruners.MedianPruner(n_startup_trials=s.parallel,
                                              n_warmup_steps=s.min_seeds - 1))
        storage = JournalStorage(JournalFileBackend(str(journal)))
        return optuna.create_study(study_name=STUDY, storage=storage, sampler=sampler,
                                   pruner=pruner, direction=s.direction)

    # ---- the search ----------------------------------------------------------------

    def run(self) -> TuneResult:
        from optuna.trial import TrialState
        self.saved = read_saved(self.folder)
        study = self._study()
        dists = distributions(self.search)
        params = {p.name: p for p in self.search.params}
        seeds = self.exp.seeds
        start = self.clock()
        candidates, active = [], []
        stopped = "budget"
        while True:
            while len(active) < self.search.parallel and self._may_start(active, start):
                trial = study.ask(dists)
                values = {name: params[name].text(v) for name, v in trial.params.items()}
                cand = Candidate(trial.number, values, trial=trial)
                try:
                    cand.job = self.planner.job(trial.number, dict(self.fixed, **values))
                except ExperimentError:
                    cand.state, cand.note = "failed", "the program does not check with these values"
                    self._end(study, cand, TrialState.FAIL)
                    candidates.append(cand)
                    continue
                candidates.append(cand)
                active.append(cand)
            if not active:
                break
            if self.search.budget_s is not None and self.clock() - start >= self.search.budget_s:
                stopped = "time"
                for cand in active:
                    cand.state, cand.note = "stopped", "the time budget ran out"
                    self._end(study, cand, TrialState.FAIL)
                break
            plan = [(c, seeds[len(c.per_seed):len(c.per_seed) + (
                self.search.min_seeds if not c.per_seed else 1)]) for c in active]
            results = self._evaluate([(c.job, s) for c, s in plan])
            for cand, mine in plan:
                self.used += len(mine)
                self._score(study, cand, mine, results)
            active = [c for c in active if c.state == "running"]
            if self.search.budget_s is not None and self.clock() - start >= self.search.budget_s:
                stopped = "time"
        done = [c for c in candidates if c.state == "complete"]
        best = None
        if done:
            key = (lambda c: -c.value) if self.search.direction == "maximize" else (
                lambda c: c.value)
            best = min(done, key=lambda c: (key(c), c.number))
        return TuneResult(candidates, self.used, best, self._test(best), self.tests, stopped)

    def _may_start(self, active: list, start: float) -> bool:
        s = self.search
        if s.budget_runs is not None:
            reserved = sum(len(self.exp.seeds) - len(c.per_seed) for c in active)
            return self.used + reserved + len(self.exp.seeds) <= s.budget_runs
        return self.clock() - start < s.budget_s

    def _score(self, study, cand: Candidate, seeds: list, results: dict):
        from optuna.trial import TrialState
        for task in self.planner.tasks(cand.job, seeds):
            result = results[task.key]
            try:
                if failed(result):
                    raise RunValueError(result.error or next(
                        r["error"] for r in result.rows if r.get("error")))
                cand.per_seed.append(self.search.objective.value(result.rows[-1]))
            except RunValueError as exc:
                cand.state, cand.note = "failed", f"seed {task.seed}: {exc}"
                self._end(study, cand, TrialState.FAIL)
                return
        value = aggregate(cand.per_seed, self.search.aggregate)
        cand.value = value
        if len(cand.per_seed) == len(self.exp.seeds):
            cand.state = "complete"
            self._end(study, cand, TrialState.COMPLETE, value)
            return
        cand.trial.report(value, len(cand.per_seed))
        if cand.trial.should_prune():
            cand.state = "pruned"
            self._end(study, cand, TrialState.PRUNED)

    def _end(self, study, cand: Candidate, state, value=None):
        study.tell(cand.trial, value, state=state)
        cand.runs_at_end = self.used
        self.say(cand, self)

    def _evaluate(self, work: list) -> dict:
        """The runs of (job, seeds) pairs: key -> RunResult, those saved
        taken from DIR, the others run on the engine in one round."""
        tasks = [t for job, seeds in work for t in self.planner.tasks(job, seeds)]
        results = load_done(self.folder, tasks, self.saved)
        todo = [t for t in tasks if t.key not in results]
        if todo:
            round_ = batches(todo, max(len(s) for _, s in work))
            saver = Saver(self.folder, round_, enabled=self.saves)

            def done(task, result):
                results[task.key] = result
                saver(task, result)
                if not result.transient:
                    self.saved[task.key] = result
            self.engine.run(round_, done)
            self.simulated += len(todo)
        return results

    def _test(self, best: Optional[Candidate]) -> dict:
        """The best and the programs' own constants on the test seeds."""
        if best is None:
            return {}
        jobs = {"best": best.job}
        if self.search.baseline:
            jobs["program"] = self.planner.job(-1, dict(self.fixed))
        results = self._evaluate([(job, self.tests) for job in jobs.values()])
        out = {}
        for name, job in jobs.items():
            runs = []
            for task in self.planner.tasks(job, self.tests):
                result = results[task.key]
                row = result.rows[-1] if result.rows else {}
                try:
                    value = None if failed(result) else self.search.objective.value(row)
                except RunValueError:
                    value = None
                runs.append(TestRun(task.seed, value, row))
            out[name] = runs
        return out
