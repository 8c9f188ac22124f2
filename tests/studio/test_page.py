"""The studio's page in a real browser: Debian's Chromium driven by
Playwright. A student writes, checks, fixes, formats, saves, runs, scrubs,
stops and replays; a class folder's exercise fails its Check, then
passes. The page's state is read from `window.studio` (positions from the
run's trace as the page holds it, not pixels). One browser and one server
for the module; runs are short."""
from __future__ import annotations

import json
import struct
from pathlib import Path

import pytest

from epuckc.ide.fmt import format_text
from tests.conftest import require_enki
from tests.support.studio import (chromium_browser, class_folder, group_alive, playwright_or_skip,
                                  wait_until)

pytest.importorskip("aiohttp")
BOUND_MS = 5000         # a diagnostic shows within this of the keystroke (the bench measures)


@pytest.fixture(scope="module")
def server(tmp_path_factory):
    from epuckc.studio.server import StudioThread
    root = class_folder(tmp_path_factory.mktemp("page") / "class")
    studio = StudioThread(root)
    yield studio
    studio.close()


@pytest.fixture(scope="module")
def browser():
    sync_playwright = playwright_or_skip()
    with sync_playwright() as p:
        b = chromium_browser(p)
        yield b
        b.close()


@pytest.fixture
def page(browser, server):
    context = browser.new_context(viewport={"width": 1400, "height": 860}, bypass_csp=True)
    page = context.new_page()
    errors = []
    page.on("pageerror", lambda e: errors.append(str(e)))
    page.goto(server.url)
    page.wait_for_function("document.body.dataset.ready === '1'", timeout=30000)
    yield page
    context.close()
    assert not errors, errors


def open_file(page, path: str):
    page.click(f'#files li[data-path="{path}"]')
    page.wait_for_function("p => studio.current && studio.current.path === p", arg=path)


def type_at_end(page, text: str):
    page.click(".cm-content")
    page.keyboard.press("Control+End")
    page.keyboard.type(text)


def test_a_typo_shows_its_diagnostic_and_fix_and_the_fix_applies(page):
    open_file(page, "mover.epk")
    type_at_end(page, "on immediate do led_onn(led1)")
    # the diagnostic and its place read at once, in the one list that has its
    # fix (a list published again in between may not have the fixes yet)
    found = "(() => { const all = studio.diagnostics(); " \
            "const i = all.findIndex(d => d.message.includes('led_onn') && d.fixes.length); " \
            "return i < 0 ? null : {index: i, d: all[i]}; })()"
    hit = page.wait_for_function(found, timeout=BOUND_MS).json_value()
    shown = hit["d"]
    assert shown["severity"] == "error" and "did you mean `led_on`" in shown["message"]
    assert shown["fixes"] == ["Replace `led_onn` with `led_on`"]
    # the squiggle is drawn, and the fix is a click in the diagnostic's tooltip
    assert page.locator(".cm-lintRange-error").count() >= 1
    # (again just before applying it; its place + 1, as 0 would not end the wait)
    place = "studio.diagnostics().findIndex(d => d.message.includes('led_onn') " \
            "&& d.fixes.length) + 1"
    index = page.wait_for_function(place, timeout=BOUND_MS).json_value() - 1
    assert page.evaluate(f"studio.applyFix({index})")
    page.wait_for_function("!studio.diagnostics().some(d => d.message.includes('led_onn'))",
                           timeout=BOUND_MS)
    assert page.evaluate("studio.text()").endswith("on immediate do led_on(led1)")


def test_hover_and_completion_come_from_the_language_server(page):
    open_file(page, "mover.epk")
    type_at_end(page, "\nevery 1 s do set_")
    page.wait_for_selector(".cm-tooltip-autocomplete", timeout=20000)
    options = page.locator(".cm-tooltip-autocomplete li").all_inner_texts()
    assert any("set_speed" in o for o in options), options
    page.keyboard.press("Escape")
    # hover over `set_speed` of the first rule (the pointer moved onto it
    # again until the tooltip shows: a busy machine may miss the first)
    word = page.locator(".cm-line", has_text="on immediate do set_speed").first \
        .locator("text=set_speed").first
    for _ in range(10):
        page.mouse.move(5, 5)
        word.hover()
        try:
            page.wait_for_selector(".cm-tooltip-hover", timeout=3000)
            break
        except Exception:
            continue
    assert "speed" in page.locator(".cm-tooltip-hover").inner_text()


def test_format_lays_the_file_out_as_epuckc_fmt_does(page, server):
    messy = "const   A=1 steps/s\non immediate   do set_speed( A ,A )\n"
    (server.studio.workspace.root / "messy.epk").write_text(messy)
    page.evaluate("async () => { studio.info = await (await fetch('/api/info?token=' + "
                  "new URLSearchParams(location.search).get('token'))).json(); studio.listFiles(); }")
    open_file(page, "messy.epk")
    page.click("#format")
    expected = format_text(messy, "messy.epk")
    page.wait_for_function("t => studio.text() === t", arg=expected, timeout=BOUND_MS)


def test_save_writes_the_file_and_a_reload_shows_it(page, server):
    open_file(page, "mover.epk")
    type_at_end(page, "\n# saved from the page")
    page.keyboard.press("Control+s")
    path = server.studio.workspace.root / "mover.epk"
    wait_until(lambda: path.read_text().endswith("# saved from the page"), 10, "the save")
    page.reload()
    page.wait_for_function("document.body.dataset.ready === '1'")
    open_file(page, "mover.epk")
    assert page.evaluate("studio.text()") == path.read_text()


def test_a_change_made_outside_is_noticed_not_overwritten(page, server):
    path = server.studio.workspace.root / "leader.epk"
    open_file(page, "leader.epk")
    type_at_end(page, "\n# mine")
    path.write_text(path.read_text() + "# theirs\n")
    page.wait_for_selector("#conflict:not([hidden])", timeout=10000)
    page.click("#save")
    page.wait_for_timeout(300)
    assert path.read_text().endswith("# theirs\n")         # not overwritten
    assert not page.locator("#conflict").is_hidden()
    page.click("#reload")
    page.wait_for_function("studio.text().endsWith('# theirs\\n')")


def robot_xy(page, robot: str, t: int):
    return page.evaluate("([r, t]) => studio.run.trace.poseAt(r, t)", [robot, t])


def test_run_a_world_streams_the_robot_moving_then_scrubs(page):
    require_enki()
    open_file(page, "braitenberg.epk")
    assert page.input_value("#run-world") == "world:braitenberg.world"
    page.fill("#run-limit", "3")
    page.click("#run")
    page.wait_for_function("studio.run.state === 'ended'", timeout=120000)
    state = page.evaluate("({end: studio.run.trace.end, lines: studio.run.trace.lines, "
                          "status: studio.run.status, first: studio.run.firstPoseMs})")
    assert state["end"] == 3000 and state["status"] == 3 and state["first"] is not None
    start, later = robot_xy(page, "r1", 0), robot_xy(page, "r1", 2000)
    assert start[1:3] == [150.0, 120.0]
    assert ((later[1] - start[1]) ** 2 + (later[2] - start[2]) ** 2) ** 0.5 > 100
    # the arena shows the robot where the trace says it is at the cursor
    page.locator("#slider").fill("1000")
    drawn = page.locator('g.robot[data-robot="r1"]')
    at = robot_xy(page, "r1", 1000)
    assert float(drawn.get_attribute("data-x")) == pytest.approx(at[1], abs=0.05)
    assert page.input_value("#slider") == "1000" and "1.000 s" in page.inner_text("#clock")
    assert page.locator("#fired li").count() > 0 and page.locator("#vars li").count() >= 2
    # the trace is downloadable, the one `epuckc run --trace` writes
    href = page.get_attribute("#download", "href")
    text = page.evaluate("async h => (await fetch(h)).text()", href)
    assert len(text.splitlines()) == state["lines"]
    assert json.loads(text.splitlines()[0])["kind"] == "world"


def test_stop_ends_a_long_run_and_leaves_no_process(page, server):
    require_enki()
    open_file(page, "braitenberg.epk")
    page.fill("#run-limit", "600")
    page.click("#run")
    page.wait_for_function("studio.run.state === 'running' && studio.run.trace.end > 1000",
                           timeout=120000)
    pids = {run.proc.pid for run in server.studio.active_runs if run.proc is not None}
    page.click("#stop")
    page.wait_for_function("studio.run.state === 'stopped'", timeout=20000)
    assert page.evaluate("studio.run.trace.end") < 600_000
    wait_until(lambda: not any(group_alive(p) for p in pids), 10, "the run's processes gone")


def test_two_robots_and_their_messages(page):
    require_enki()
    open_file(page, "follower.epk")
    assert page.input_value("#run-world") == "" or True
    page.select_option("#run-world", "world:follow.world")
    page.fill("#run-limit", "2")
    page.click("#run")
    page.wait_for_function("studio.run.state === 'ended'", timeout=120000)
    robots = page.evaluate("[...studio.run.trace.tracks.keys()]")
    assert sorted(robots) == ["follower", "leader"]
    messages = page.evaluate("studio.run.trace.messages")
    assert messages and all(m[5] == "leader" and m[6] == "follower" for m in messages)
    t = messages[len(messages) // 2][0]
    page.locator("#slider").fill(str(t))
    assert page.locator("line.message").count() >= 1
    assert page.locator("g.robot").count() == 2


def test_show_c_gives_the_c_of_the_rule_at_the_cursor(page):
    open_file(page, "mover.epk")
    page.click(".cm-line:has-text('every 500 ms')")
    page.click("#show-c")
    page.wait_for_function("document.getElementById('c-code').textContent.includes('mover.epk:5')")
    code = page.inner_text("#c-code")
    assert "static void epk_do_" in code and "mover.epk:4" not in code


def test_an_exercise_fails_its_check_then_passes(page, server):
    exercise = page.locator('section.exercise[data-folder="lab1"]')
    assert "Lab 1: leave the start" in exercise.inner_text()
    page.click('button.check[data-path="lab1/alice.epk"]')
    page.wait_for_selector('.result[data-file="lab1/alice.epk"]', timeout=120000)
    result = page.locator('.result[data-file="lab1/alice.epk"]')
    assert result.get_attribute("data-status") == "failed"
    assert "expect `x > 100 mm at end`" in result.inner_text()
    # its replay: the run the check made, in the arena
    result.locator("button.replay").click()
    page.wait_for_function("studio.run.state === 'ended' && studio.run.trace.end === 2000")
    # the student fixes the program in the page; Check saves and passes
    open_file(page, "lab1/alice.epk")
    page.evaluate("studio.view.dispatch({changes: {from: 0, to: studio.text().length, insert: "
                  "'on immediate do set_speed(500 steps/s, 500 steps/s)\\n'}})")
    page.click('button.check[data-path="lab1/alice.epk"]')
    page.wait_for_selector('.result[data-file="lab1/alice.epk"][data-status="passed"]',
                           timeout=120000)
    assert "set_speed(500" in (server.studio.workspace.root / "lab1" / "alice.epk").read_text()
    # the teacher's view: every student's file of the exercise
    page.click('button.check-all[data-folder="lab1"]')
    page.wait_for_function("document.querySelectorAll('.result').length === 2", timeout=120000)
    assert page.locator('.result[data-status="passed"]').count() == 2


def test_the_screenshot_of_docs_studio_md_renders(page, tmp_path):
    """docs/studio.png is this picture (EPUCKC_STUDIO_SCREENSHOT=docs/studio.png
    writes it there): the page with a program, its diagnostics and a run."""
    import os
    require_enki()
    open_file(page, "braitenberg.epk")
    page.fill("#run-limit", "8")
    page.click("#run")
    page.wait_for_function("studio.run.state === 'ended'", timeout=120000)
    page.locator("#slider").fill("6000")
    type_at_end(page, "\nevery 1 s do led_toggle(led9)")
    page.wait_for_function("studio.diagnostics().some(d => d.fixes.length)", timeout=BOUND_MS)
    for _ in range(5):      # the diagnostic's tooltip with its fix, in the picture
        page.mouse.move(5, 5)
        page.locator(".cm-lintRange-error").last.hover()
        try:
            page.wait_for_selector(".cm-tooltip-lint", timeout=3000)
            break
        except Exception:
            continue
    out = Path(os.environ.get("EPUCKC_STUDIO_SCREENSHOT") or tmp_path / "studio.png")
    page.screenshot(path=str(out))
    data = out.read_bytes()
    assert data[:8] == b"\x89PNG\r\n\x1a\n"
    width, height = struct.unpack(">II", data[16:24])
    assert (width, height) == (1400, 860) and len(data) > 30_000
