"""The suite's own `-n auto` (the README's test command): one pytest-xdist
worker per CPU the process may run on (tests/conftest.py), not psutil's
count of the machine's physical cores."""
import os
import subprocess
import sys

import pytest

from conftest import REPO


@pytest.mark.skipif(not hasattr(os, "sched_setaffinity"), reason="no CPU affinity here")
def test_auto_gives_a_worker_per_cpu_the_process_may_use():
    pytest.importorskip("xdist")
    one = sorted(os.sched_getaffinity(0))[:1]
    r = subprocess.run(
        [sys.executable, "-m", "pytest", "-p", "no:cacheprovider", "-n", "auto",
         "tests/build/test_epuck2.py::test_the_platform_layer_sleeps_and_never_spins"],
        cwd=REPO, capture_output=True, text=True, preexec_fn=lambda: os.sched_setaffinity(0, one))
    assert r.returncode == 0, r.stdout + r.stderr
    assert "created: 1/1 worker" in r.stdout, r.stdout
