"""The studio for its tests: a folder of programs, the server on it in a
thread of the test process (epuckc/studio/server.py's StudioThread), and
Debian's Chromium driven by Playwright (from PyPI, which downloads no
browser here: it is launched on /usr/bin/chromium)."""
from __future__ import annotations

import os
import shutil
import time
from pathlib import Path

import pytest

from tests.conftest import require_tool
from tests.support.world import EXAMPLES

# as the machine's notes say: without the background-networking flags
# Chromium keeps trying hosts a closed network refuses
CHROMIUM_ARGS = ["--headless=new", "--no-sandbox", "--disable-gpu", "--disable-quic",
                 "--no-first-run", "--disable-background-networking",
                 "--disable-component-update", "--disable-sync", "--disable-dev-shm-usage"]

MOVER = """# drives ahead, then turns
const CRUISE = 400 steps/s
var turns = 0
on immediate do set_speed(CRUISE, CRUISE)
every 500 ms do turns += 1, led_toggle(led0)
"""


def class_folder(root: Path) -> Path:
    """A student's folder: programs, their worlds, and an exercise."""
    root.mkdir(parents=True, exist_ok=True)
    for name in ("braitenberg.epk", "braitenberg.world", "leader.epk", "follower.epk",
                 "follow.world", "obstacle.scn"):
        shutil.copy(EXAMPLES / name, root / name)
    (root / "mover.epk").write_text(MOVER, encoding="utf-8")
    lab = root / "lab1"
    lab.mkdir()
    (lab / "epuckc-test.toml").write_text(
        '# Lab 1: leave the start\ntime_limit = "2s"\nexpect = ["x > 100 mm at end"]\n',
        encoding="utf-8")
    (lab / "alice.epk").write_text("on immediate do set_speed(0 steps/s, 0 steps/s)\n",
                                   encoding="utf-8")
    (lab / "bob.epk").write_text("on immediate do set_speed(600 steps/s, 600 steps/s)\n",
                                 encoding="utf-8")
    return root


def chromium_browser(playwright):
    chromium = require_tool("chromium")
    return playwright.chromium.launch(executable_path=chromium, args=CHROMIUM_ARGS)


def wait_until(predicate, timeout_s: float = 20.0, what: str = "the condition"):
    deadline = time.monotonic() + timeout_s
    while time.monotonic() < deadline:
        value = predicate()
        if value:
            return value
        time.sleep(0.05)
    raise AssertionError(f"{what} did not hold within {timeout_s} s")


def group_alive(pgid: int) -> bool:
    """Some process of the group is still there (zombies aside: they ran
    to their end and only wait to be reaped)."""
    return any(_in_group(pid, pgid) for pid in _pids())


def _pids():
    return [int(p) for p in os.listdir("/proc") if p.isdigit()]


def _in_group(pid: int, pgid: int) -> bool:
    try:
        fields = Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[1].split()
    except OSError:
        return False
    return int(fields[2]) == pgid and fields[0] != "Z"


def playwright_or_skip():
    try:
        from playwright.sync_api import sync_playwright
    except ImportError:
        if os.environ.get("EPUCKC_REQUIRE_ALL_TOOLS"):
            pytest.fail("playwright is not installed (pip install playwright; .ci/run does)")
        pytest.skip("playwright is not installed")
    return sync_playwright
