"""Shared test helpers.

A test that needs an external tool (avr-gcc, a C compiler, ...) calls
`require_tool`: it skips with the reason when the tool is missing, except in
CI (EPUCKC_REQUIRE_ALL_TOOLS=1), where a missing tool is a failure, because
.ci/run installs every tool the tests need.
"""
import os
import random
import shutil
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parent.parent


def require_tool(name: str) -> str:
    path = shutil.which(name)
    if path:
        return path
    reason = f"{name} is not installed (CI installs it in .ci/run)"
    if os.environ.get("EPUCKC_REQUIRE_ALL_TOOLS"):
        pytest.fail(reason)
    pytest.skip(reason)


def require_checkout(variable: str, inside: str, reason: str) -> Path:
    """The folder an environment variable names (a user's checkout of
    GCtronic's library or firmware), holding `inside`; skips with the
    reason without it, fails in CI (.ci/run points at shared/third_party)."""
    folder = os.environ.get(variable)
    if folder and (Path(folder) / inside).exists():
        return Path(folder)
    if os.environ.get("EPUCKC_REQUIRE_ALL_TOOLS"):
        pytest.fail(reason)
    pytest.skip(reason)


def require_epuck_library(inside: str) -> Path:
    """The checkout of GCtronic's e-puck library that EPUCK_LIB names,
    holding `inside` (`library`, `program/DemoGCtronic-complete`); as
    require_checkout (.ci/run points it at shared/third_party)."""
    top = inside.split("/", 1)[0]
    return require_checkout(
        "EPUCK_LIB", inside,
        "EPUCK_LIB does not name a checkout of GCtronic's e-puck library (git clone "
        f"https://github.com/gctronic/e-puck-library; the folder that holds {top}/)")


def pytest_xdist_auto_num_workers(config):
    """`-n auto`: a worker per CPU this process may run on. pytest-xdist's
    own count asks psutil (installed with Dask) for the machine's physical
    cores, which a container limited to some of them, or a machine whose
    CPUs are hyperthreads, gets wrong both ways."""
    if hasattr(os, "sched_getaffinity"):
        return len(os.sched_getaffinity(0))
    return os.cpu_count() or 1


def pytest_addoption(parser):
    parser.addoption("--update-goldens", action="store_true", default=False,
                     help="rewrite golden files from the current output")


@pytest.fixture(autouse=True)
def _private_cache(tmp_path_factory, monkeypatch):
    """Host builds go to a cache of this test session, not the user's; so do
    ccache's objects (the e-puck2 firmware's, shared by its projects). Under
    pytest-xdist each worker has its own base folder, so its own caches."""
    monkeypatch.setenv("EPUCKC_CACHE_DIR", str(tmp_path_factory.getbasetemp() / "epuckc-cache"))
    monkeypatch.setenv("CCACHE_DIR", str(tmp_path_factory.getbasetemp() / "ccache"))


@pytest.fixture
def update_goldens(request) -> bool:
    return bool(request.config.getoption("--update-goldens"))


def require_enki():
    """Enki's headers and library and a C++ compiler (the world runner's
    build); skips without them, fails in CI, like require_tool."""
    from epuckc.sim.enki import ENKI_MISSING, enki_available
    if enki_available():
        return
    if os.environ.get("EPUCKC_REQUIRE_ALL_TOOLS"):
        pytest.fail(ENKI_MISSING)
    pytest.skip(ENKI_MISSING)


def require_physics(name: str):
    """A world runner's provider (`physics enki` or `physics chipmunk`):
    its headers and library and a C++ compiler; skips without them, fails
    in CI, like require_tool."""
    from epuckc.sim.enki import PROVIDERS, provider_available
    if provider_available(name):
        return
    if os.environ.get("EPUCKC_REQUIRE_ALL_TOOLS"):
        pytest.fail(PROVIDERS[name].missing)
    pytest.skip(PROVIDERS[name].missing)


def pytest_collection_modifyitems(config, items):
    """A runtime test marked `dynamic_only` is about the paper's arrays: it
    is not collected on the static registration path at all (deselected,
    not skipped, so that a run where nothing may skip stays clean)."""
    dropped = [item for item in items
               if item.get_closest_marker("dynamic_only")
               and "static" in getattr(getattr(item, "callspec", None), "params", {}).values()]
    if dropped:
        config.hook.pytest_deselected(items=dropped)
        items[:] = [item for item in items if item not in dropped]


# The fuzz tests (tests/emit/test_language_fuzz.py) run a fixed seed and a
# new one each run; the new one is printed at the end, to run it again:
# EPUCKC_FUZZ_SEED=N python3 -m pytest tests/emit/test_language_fuzz.py
# (kept in the environment, so that every import of this module agrees)
os.environ.setdefault("EPUCKC_FUZZ_SEED", str(random.SystemRandom().randrange(2 ** 32)))
FUZZ_SEED = int(os.environ["EPUCKC_FUZZ_SEED"])
FUZZ_FIXED_SEED = 20261125


def pytest_terminal_summary(terminalreporter):
    ran = [r for key in ("passed", "failed") for r in terminalreporter.stats.get(key, [])
           if "test_language_fuzz" in getattr(r, "nodeid", "")]
    if ran:
        terminalreporter.write_line(f"fuzz: fixed seed {FUZZ_FIXED_SEED} and new seed {FUZZ_SEED}"
                                    f" (to run it again: EPUCKC_FUZZ_SEED={FUZZ_SEED})")
