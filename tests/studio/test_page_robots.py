"""The page's Flash and Monitor in a real browser (Debian's Chromium driven
by Playwright, as tests/studio/test_page.py): Monitor shows a robot's run
in the arena as it comes from its port (a fake robot on a pty sending the
tracer's bytes from simavr), the same records `epuckc monitor` decodes;
Flash of a rule file builds it as `epuckc flash` does and shows what flash
said (here, with no XC16, the project written and the next command)."""
from __future__ import annotations

import os
import shutil
from pathlib import Path

import pytest

from conftest import REPO
from tests.support.studio import chromium_browser, playwright_or_skip

pytest.importorskip("aiohttp")
pytest.importorskip("serial")
EXAMPLES = REPO / "examples"


@pytest.fixture(scope="module")
def server(tmp_path_factory):
    from epuckc.studio.server import StudioThread
    root = tmp_path_factory.mktemp("robots") / "lab"
    root.mkdir()
    shutil.copy(EXAMPLES / "bump_counter.epk", root / "bump_counter.epk")
    studio = StudioThread(root)
    yield studio
    studio.close()


@pytest.fixture
def page(server):
    sync_playwright = playwright_or_skip()
    with sync_playwright() as p:
        browser = chromium_browser(p)
        context = browser.new_context(viewport={"width": 1400, "height": 860}, bypass_csp=True)
        page = context.new_page()
        errors = []
        page.on("pageerror", lambda e: errors.append(str(e)))
        page.goto(server.url)
        page.wait_for_function("document.body.dataset.ready === '1'", timeout=30000)
        page.click('#files li[data-path="bump_counter.epk"]')
        page.wait_for_function("studio.current && studio.current.path === 'bump_counter.epk'")
        yield page
        context.close()
        browser.close()
        assert not errors, errors


def test_monitor_shows_the_robots_run_in_the_arena(page):
    from tests.support.robot_trace import decode, program_of, require_simavr, robot_run
    from tests.support.serial_robot import FakeRobot
    from epuckc.build.trace_table import trace_table
    require_simavr()
    program = program_of(EXAMPLES / "bump_counter.epk")
    uart = robot_run(program, EXAMPLES / "bumps.scn", 6000).uart
    records = decode(trace_table(program), uart)
    assert page.is_visible("#flash") and page.is_visible("#monitor")
    robot = FakeRobot(uart)
    try:
        page.click("#monitor")
        assert page.is_visible("#robot") and not page.is_visible("#robot-id")
        page.fill("#robot-port", robot.port)
        page.click("#robot-go")
        page.wait_for_function("studio.run.stderr.includes('reading ')", timeout=60000)
        robot.run()
        page.wait_for_function("studio.run.state === 'ended'", timeout=120000)
    finally:
        robot.close()
    state = page.evaluate("({status: studio.run.status, end: studio.run.trace.end, "
                          "lines: studio.run.trace.lines, "
                          "sets: studio.run.trace.sets.length})")
    assert state["status"] == 0
    assert state["end"] == records[-1]["t_ms"]
    assert state["sets"] == len([r for r in records if r["kind"] == "set"])
    assert page.locator("g.robot").count() == 1         # the robot, by its odometry
    assert page.inner_text("#run-console").startswith(f"$ epuckc monitor {robot.port} "
                                                       "--program bump_counter.epk --trace -")


def test_flash_builds_the_rule_file_and_shows_what_flash_said(page, server, monkeypatch):
    from tests.support.fake_tinybld import FakeTinybld
    path = os.pathsep.join(p for p in os.environ.get("PATH", "").split(os.pathsep)
                           if p and not (Path(p) / "xc16-gcc").exists())
    monkeypatch.setenv("PATH", path)        # the server's children: no XC16
    monkeypatch.setenv("XC16_DIR", "")
    with FakeTinybld() as robot:
        page.click("#flash")
        page.fill("#robot-port", robot.port)
        page.select_option("#robot-target", "epuck")
        page.fill("#robot-id", "7")
        page.check("#robot-trace")
        page.click("#robot-go")
        page.wait_for_function("studio.robot.lastFlash !== null && !studio.robot.busy",
                               timeout=120000)
        assert robot.answers == []
    flashed = page.evaluate("studio.robot.lastFlash")
    assert flashed["status"] == 3
    assert flashed["command"] == (f"epuckc flash bump_counter.epk --port {robot.port} "
                                  "--target epuck --robot-id 7 --trace")
    shown = page.inner_text("#robot-output")
    assert "it was not built: xc16-gcc" in shown
    assert (f"epuckc flash {Path('build') / 'bump_counter-dspic' / 'bump_counter.hex'} "
            f"--port {robot.port} --robot-id 7") in shown
    built = server.studio.workspace.root / "build" / "bump_counter-dspic"
    assert (built / "bump_counter.trace.json").is_file()     # built with its tracer
