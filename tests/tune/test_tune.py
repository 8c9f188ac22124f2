"""`epuckc tune` on examples/avoider_tune.toml (the two gains of a
Braitenberg avoider): within its budget it finds gains whose fresh test
seeds beat the best point of a grid over the same ranges with as many
runs; the same seed gives the same history, on any number of workers; a
tune resumes from whatever runs are saved and ends as it would have."""
from __future__ import annotations

import os
import shutil
import statistics
import subprocess
import sys
import tomllib
from pathlib import Path

import pytest

from epuckc.tune.objective import parse
from tests.experiment.helpers import REPO, needs_enki, rows

pytestmark = needs_enki


@pytest.fixture(scope="module", autouse=True)
def _optuna():
    """Optuna (the `tune` extra): skips without it, fails in CI, as
    require_tool does."""
    try:
        import optuna  # noqa: F401
    except ImportError:
        reason = "Optuna is not installed (pip install -e '.[tune]'; CI installs it in .ci/run)"
        if os.environ.get("EPUCKC_REQUIRE_ALL_TOOLS"):
            pytest.fail(reason)
        pytest.skip(reason)

EXAMPLES = REPO / "examples"
OBJECTIVE = "distance - 500 * min(contacts, 1)"


def _env() -> dict:
    return dict(os.environ, PYTHONPATH=str(REPO) + os.pathsep + os.environ.get("PYTHONPATH", ""))


def epuckc(*args, check=True) -> subprocess.CompletedProcess:
    proc = subprocess.run([sys.executable, "-m", "epuckc", *map(str, args)], env=_env(),
                          capture_output=True, text=True, timeout=900)
    if check:
        assert proc.returncode == 0, proc.stderr
    return proc


def _folder(base: Path) -> Path:
    base.mkdir(parents=True, exist_ok=True)
    for name in ("avoider.epk", "clutter.world", "avoider_tune.toml"):
        shutil.copy(EXAMPLES / name, base / name)
    return base / "avoider_tune.toml"


@pytest.fixture(scope="module")
def tuned(tmp_path_factory, _optuna):
    """(the tune file, its folder, the command's stderr)."""
    base = tmp_path_factory.mktemp("tune")
    tune = _folder(base)
    proc = epuckc("tune", tune, "-o", base / "t", "--workers", "2")
    return tune, base / "t", proc.stderr


def test_the_tune_beats_the_grid_on_fresh_seeds(tuned, tmp_path):
    tune, out, err = tuned
    spec = tomllib.loads(tune.read_text())
    budget, seeds = spec["search"]["budget"], spec["seeds"]
    history = rows(out / "history.csv")
    # within the budget, and racing stopped some candidates early: more
    # candidates than the budget's runs would give without it
    assert max(int(h["runs"]) for h in history) <= budget
    assert sum(int(h["seeds"]) for h in history) <= budget
    assert any(h["state"] == "pruned" and int(h["seeds"]) < seeds for h in history)
    assert len(history) > budget // seeds
    # the grid over the same ranges with as many runs: 4 x 4 points x 6 seeds
    values = [round(128 * i / 3) for i in range(4)]
    assert len(values) ** 2 * seeds >= budget
    grid = tmp_path / "grid.toml"
    for name in ("avoider.epk", "clutter.world"):
        shutil.copy(tune.parent / name, tmp_path / name)
    axis = ", ".join(f'"{v} steps/s"' for v in values)
    grid.write_text(f'program = "avoider.epk"\nworld = "clutter.world"\nduration = "10 s"\n'
                    f'seeds = {seeds}\nmetrics = ["distance", "contacts"]\n'
                    f'[params]\nK_CROSS = [{axis}]\nK_SAME = [{axis}]\n')
    epuckc("experiment", grid, "-o", tmp_path / "grid", "--workers", "2")
    objective = parse(OBJECTIVE)
    by_point = {}
    for r in rows(tmp_path / "grid" / "runs.csv"):
        row = {"distance_mm": float(r["distance_mm"]), "contacts": int(r["contacts"])}
        by_point.setdefault((r["K_CROSS"], r["K_SAME"]), []).append(objective.value(row))
    assert len(by_point) == 16 and all(len(v) == seeds for v in by_point.values())
    best = max(by_point, key=lambda k: (statistics.mean(by_point[k]), k))
    # both on the tune's test seeds
    test = rows(out / "test.csv")
    tune_values = [float(r["objective"]) for r in test if r["candidate"] == "best"]
    test_seeds = [int(r["seed"]) for r in test if r["candidate"] == "best"]
    assert len(test_seeds) == 20 and not set(test_seeds) & set(range(1, seeds + 1))
    check = tmp_path / "check.toml"
    check.write_text(f'program = "avoider.epk"\nworld = "clutter.world"\nduration = "10 s"\n'
                     f'seeds = {test_seeds}\nmetrics = ["distance", "contacts"]\n'
                     f'[params]\nK_CROSS = "{best[0]}"\nK_SAME = "{best[1]}"\n')
    epuckc("experiment", check, "-o", tmp_path / "check", "--workers", "2")
    grid_values = [objective.value({"distance_mm": float(r["distance_mm"]),
                                    "contacts": int(r["contacts"])})
                   for r in rows(tmp_path / "check" / "runs.csv")]
    assert statistics.mean(tune_values) > statistics.mean(grid_values), (best, err)
    # the best as TOML for an experiment file, and as -D options
    params = tomllib.loads((out / "best.toml").read_text())["params"]
    assert set(params) == {"K_CROSS", "K_SAME"}
    chosen = {k: v for k, v in zip(("K_CROSS", "K_SAME"), _best_row(history))}
    assert params == chosen
    defines = (out / "best.defines").read_text().splitlines()
    assert defines == [f"-D '{k}={v}'" for k, v in chosen.items()]
    assert "on the test seeds 7..26, these values:" in (out / "best.toml").read_text()
    for picture in ("convergence.svg", "params.svg"):
        svg = (out / picture).read_text()
        assert svg.startswith("<svg") and svg.count("<circle") >= len(history)
    assert (out / "tune.journal").stat().st_size > 0


def _best_row(history: list) -> tuple:
    done = [h for h in history if h["state"] == "complete"]
    best = max(done, key=lambda h: (float(h["objective"]), -int(h["trial"])))
    return best["K_CROSS"], best["K_SAME"]


def test_the_same_seed_gives_the_same_history(tuned, tmp_path):
    """Replayed from the saved runs on one worker: nothing simulated, the
    same candidates in the same order, byte for byte."""
    tune, out, _ = tuned
    again = tmp_path / "again"
    shutil.copytree(out / "runs", again / "runs")
    proc = epuckc("tune", tune, "-o", again, "--workers", "1")
    assert "; 0 runs simulated now" in proc.stderr
    for name in ("history.csv", "best.toml", "best.defines", "test.csv", "convergence.svg"):
        assert (again / name).read_bytes() == (out / name).read_bytes(), name


def test_a_tune_resumes_from_the_runs_it_saved(tuned, tmp_path):
    """What an interrupted tune leaves (some of its runs) is where the same
    command goes on from; it ends as the uninterrupted tune."""
    tune, out, _ = tuned
    half = tmp_path / "half"
    (half / "runs").mkdir(parents=True)
    files = sorted((out / "runs").iterdir())
    kept = files[::2]
    for path in kept:
        shutil.copy(path, half / "runs" / path.name)
    total = sum(len(p.read_text().splitlines()) for p in files)
    saved = sum(len(p.read_text().splitlines()) for p in kept)
    proc = epuckc("tune", tune, "-o", half, "--workers", "2")
    assert f"; {total - saved} runs simulated now" in proc.stderr
    assert (half / "history.csv").read_bytes() == (out / "history.csv").read_bytes()


def test_another_sampler_seed_asks_other_candidates(tuned, tmp_path):
    tune, out, _ = tuned
    other = _folder(tmp_path / "other")
    other.write_text(other.read_text().replace("sampler_seed = 7", "sampler_seed = 8")
                     .replace("budget = 96", "budget = 12"))
    epuckc("tune", other, "-o", tmp_path / "o", "--workers", "2")
    mine = [(h["K_CROSS"], h["K_SAME"]) for h in rows(tmp_path / "o" / "history.csv")]
    first = [(h["K_CROSS"], h["K_SAME"]) for h in rows(out / "history.csv")][:len(mine)]
    assert len(mine) == 2 and mine != first


def test_bad_tune_files_and_values_the_checker_refuses(tmp_path):
    tune = _folder(tmp_path)
    text = tune.read_text()
    tune.write_text(text.replace('K_CROSS = { low = "0 steps/s", high = "128 steps/s" }',
                                 'K_CROSS = { low = "0 cm", high = "12 cm" }'))
    proc = epuckc("tune", tune, "-o", tmp_path / "o", check=False)
    assert proc.returncode == 1 and "error[E048]" in proc.stderr, proc.stderr
    assert "the search reaches these values: K_CROSS=0 cm" in proc.stderr
    tune.write_text(text.replace("K_SAME = {", "K_SAMEX = {"))
    proc = epuckc("tune", tune, "-o", tmp_path / "o", check=False)
    assert proc.returncode == 2 and "no program of the experiment has a constant K_SAMEX" in \
        proc.stderr
    tune.write_text(text + '[params]\nCRUISE = ["500 steps/s", "600 steps/s"]\n')
    proc = epuckc("tune", tune, "-o", tmp_path / "o", check=False)
    assert proc.returncode == 2 and "a tune searches [search]: CRUISE has 2 values" in proc.stderr
    assert not (tmp_path / "o" / "history.csv").exists()


def test_a_time_budget_stops_the_search(tmp_path):
    """With a wall-clock budget no candidate starts after the time is up and
    those under way stop (a clock that moves 1 s at each look, so that
    nothing depends on this machine's speed)."""
    from epuckc.cli.experiment import program_loader
    from epuckc.cli.tune import _read
    from epuckc.experiment.engines import LocalEngine
    from epuckc.experiment.plan import Planner
    from epuckc.tune.race import Tuner
    tune = _folder(tmp_path)
    tune.write_text(tune.read_text().replace("budget = 96", 'budget = "5 s"')
                    .replace('"10 s"', '"500 ms"').replace("test_seeds = 20", "test_seeds = 2"))
    exp, search = _read(tune, "t.toml")
    assert search.budget_s == 5 and search.budget_runs is None
    ticks = iter(range(10 ** 6))
    engine = LocalEngine(1)
    ended = []
    tuner = Tuner(exp, search, Planner(exp, program_loader()), engine, tmp_path / "o",
                  say=lambda cand, _: ended.append(cand.state), clock=lambda: next(ticks))
    (tmp_path / "o" / "runs").mkdir(parents=True)
    result = tuner.run()
    assert result.stopped == "time"
    assert 1 <= len(result.candidates) <= search.parallel * 5
    assert "stopped" in {c.state for c in result.candidates}
    assert all(c.state != "running" for c in result.candidates)
    assert len(ended) == len(result.candidates)
