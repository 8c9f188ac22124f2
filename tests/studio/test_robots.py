"""The studio's Flash and Monitor (epuckc/studio/robots.py) against the
faithful stand-ins of tests/link: Flash puts a built program on a fake
e-puck bootloader on a pty (tests/support/fake_tinybld.py) through the
server's route, and the robot holds exactly the hex's program memory with
its reset vector patched; Monitor streams, over the run socket, the trace
a fake robot on a pty sends (the tracer's bytes from simavr), the records
`epuckc monitor` decodes from them; what may not be asked is refused
before any robot is touched."""
from __future__ import annotations

import asyncio
import json
import shutil

import pytest

aiohttp = pytest.importorskip("aiohttp")
pytest.importorskip("serial")

from conftest import REPO  # noqa: E402
from epuckc.studio.server import StudioThread  # noqa: E402
from tests.support.fake_tinybld import FakeTinybld  # noqa: E402
from tests.support.serial_robot import FakeRobot  # noqa: E402
from tests.support.xc16_hex import example_words, expected_memory, write_program  # noqa: E402

EXAMPLES = REPO / "examples"


@pytest.fixture(scope="module")
def studio(tmp_path_factory):
    root = tmp_path_factory.mktemp("robots") / "lab"
    root.mkdir()
    shutil.copy(EXAMPLES / "bump_counter.epk", root / "bump_counter.epk")
    server = StudioThread(root)
    yield server
    server.close()


def base(studio) -> str:
    return f"http://127.0.0.1:{studio.studio.port}"


async def _request(studio, method, route, body=None):
    async with aiohttp.ClientSession() as s:
        async with s.request(method, base(studio) + route, json=body,
                             headers={"X-Studio-Token": studio.studio.token}) as r:
            return r.status, await r.json()


def call(studio, method, route, body=None):
    return asyncio.run(_request(studio, method, route, body))


def test_the_page_is_offered_flash_and_monitor_and_the_ports_found(studio):
    status, info = call(studio, "GET", "/api/info")
    assert status == 200 and info["flash"] is True and info["monitor"] is True
    status, found = call(studio, "GET", "/api/ports")
    assert status == 200 and isinstance(found["ports"], list)      # none on this machine
    for port in found["ports"]:
        assert set(port["uses"]) <= {"flash", "monitor"} and port["kind"] in ("epuck", "epuck2")


def test_flash_puts_the_program_on_the_e_puck(studio):
    words = example_words(seed=9)
    write_program(studio.studio.workspace.root / "made.hex", words)
    with FakeTinybld() as robot:
        status, answer = call(studio, "POST", "/api/flash",
                              {"program": "made.hex", "port": robot.port, "robot_id": 1234})
        assert status == 200 and answer["status"] == 0, answer
        assert robot.errors == [] and robot.flash == expected_memory(words, 1234, {})
    assert answer["command"] == f"epuckc flash made.hex --port {robot.port} --robot-id 1234"
    assert f"flashed made.hex to the e-puck 1234 on {robot.port}" in answer["output"]
    assert "press the robot's reset button now" in answer["output"]


def test_flash_says_what_flash_says_when_it_cannot(studio):
    """--trace on a built program: `epuckc flash` refuses it, and the page
    gets its status and its line; the robot heard nothing."""
    write_program(studio.studio.workspace.root / "built.hex", example_words(seed=2))
    with FakeTinybld() as robot:
        status, answer = call(studio, "POST", "/api/flash", {
            "program": "built.hex", "port": robot.port, "robot_id": 1, "trace": True})
        assert robot.calls == 0 and robot.answers == []
    assert status == 200 and answer["status"] == 2
    assert "is built already, so --trace cannot build the robot's tracer" in answer["output"]


@pytest.mark.parametrize("body, says", [
    ({"program": "bump_counter.epk", "port": "/dev/ttyNOTHERE", "target": "epuck"},
     "/dev/ttyNOTHERE is not there"),
    ({"program": "bump_counter.epk", "port": "/etc/passwd", "target": "epuck"},
     "is not a serial port"),
    ({"program": "bump_counter.epk", "port": "PORT", "target": "epuck"}, "is not a serial port"),
    ({"program": "bump_counter.epk", "port": "/dev/null"}, "which robot is the program for?"),
    ({"program": "bump_counter.epk", "port": "/dev/null", "target": "nxt"}, "epuck or epuck2"),
    ({"program": "bump_counter.epk", "port": "/dev/null", "target": "epuck",
      "robot_id": 70000}, "0 to 65535"),
    ({"program": "notes.txt", "port": "/dev/null"}, "Flash takes a program"),
])
def test_what_may_not_be_flashed_is_refused(studio, body, says):
    (studio.studio.workspace.root / "notes.txt").write_text("x\n")
    status, answer = call(studio, "POST", "/api/flash", body)
    assert status == 400 and says in answer["error"], answer


def test_a_program_outside_the_folder_is_not_flashed(studio):
    status, _ = call(studio, "POST", "/api/flash", {"program": "../x.hex", "port": "/dev/null"})
    assert status in (403, 404)


async def _monitor(studio, request, robot):
    """Monitor over the run socket: the robot starts sending once the
    monitor has its port open; every message until the end."""
    messages = []
    async with aiohttp.ClientSession() as s:
        ws = await s.ws_connect(f"{base(studio)}/ws/run?token={studio.studio.token}",
                                origin=base(studio))
        await ws.send_str(json.dumps({"type": "monitor", **request}))
        said = ""
        while True:
            m = json.loads((await ws.receive(timeout=120)).data)
            messages.append(m)
            if m["type"] == "stderr":
                if "reading " not in said and "reading " in said + m["text"] and robot:
                    robot.run()
                said += m["text"]
            if m["type"] in ("end", "refused"):
                await ws.close()
                return messages


def test_monitor_streams_the_robots_trace_as_a_run(studio):
    from tests.support.robot_trace import decode, program_of, require_simavr, robot_run
    from epuckc.build.trace_table import trace_table
    require_simavr()
    program = program_of(EXAMPLES / "bump_counter.epk")
    uart = robot_run(program, EXAMPLES / "bumps.scn", 6000).uart
    robot = FakeRobot(uart)
    try:
        messages = asyncio.run(_monitor(studio, {"program": "bump_counter.epk",
                                                 "port": robot.port}, robot))
    finally:
        robot.close()
    assert messages[0]["type"] == "started"
    assert messages[0]["command"] == (f"epuckc monitor {robot.port} --program "
                                      "bump_counter.epk --trace -")
    end = messages[-1]
    assert end["type"] == "end" and end["status"] == 0 and not end["stopped"], messages[-3:]
    streamed = [json.loads(line) for m in messages if m["type"] == "records"
                for line in m["lines"] if line]
    expected = decode(trace_table(program), uart)
    assert [r for r in streamed if r["kind"] != "pose"] == \
        [r for r in expected if r["kind"] != "pose"]
    assert streamed[-1]["kind"] == "exit"
    assert any(r["kind"] == "pose" for r in streamed)       # the arena draws the robot
    # and the trace is the page's to download, as a run's
    async def download():
        async with aiohttp.ClientSession() as s:
            async with s.get(base(studio) + end["trace"],
                             headers={"X-Studio-Token": studio.studio.token}) as r:
                return await r.text()
    assert [json.loads(line) for line in asyncio.run(download()).splitlines()] == streamed


def test_monitor_of_a_port_that_is_not_there_is_refused(studio):
    messages = asyncio.run(_monitor(studio, {"program": "bump_counter.epk",
                                             "port": "/dev/ttyNOTHERE"}, None))
    assert messages[-1]["type"] == "refused" and "is not there" in messages[-1]["error"]
