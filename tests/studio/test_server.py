"""The studio's server against a real HTTP and WebSocket client (aiohttp's):
the token, Host and Origin (DNS rebinding), the folder's confinement over
HTTP and in the language server's messages, and runs: streamed, stopped,
and stopped with nothing left behind when the page goes away mid-run."""
from __future__ import annotations

import asyncio
import json
from pathlib import Path

import pytest

aiohttp = pytest.importorskip("aiohttp")

from epuckc.studio.server import StudioThread  # noqa: E402
from tests.conftest import require_enki  # noqa: E402
from tests.support.studio import class_folder, group_alive, wait_until  # noqa: E402


@pytest.fixture(scope="module")
def studio(tmp_path_factory):
    root = class_folder(tmp_path_factory.mktemp("studio") / "class")
    (root.parent / "secret.epk").write_text("outside\n")
    (root / "out.epk").symlink_to(root.parent / "secret.epk")
    server = StudioThread(root)
    yield server
    server.close()


def call(coro):
    return asyncio.run(coro)


def base(studio) -> str:
    return f"http://127.0.0.1:{studio.studio.port}"


async def get(studio, route, token=True, headers=None, **params):
    if token:
        params["token"] = studio.studio.token
    async with aiohttp.ClientSession() as s:
        async with s.get(base(studio) + route, params=params, headers=headers or {}) as r:
            return r.status, await r.text()


def test_the_server_listens_on_loopback_only(studio):
    assert [a[0] for a in studio.studio.runner.addresses] == ["127.0.0.1"]


def test_without_the_token_or_with_another_nothing_is_served(studio):
    for path in ("/", "/api/info", "/api/file", "/static/studio.js", "/api/trace/1"):
        status, _ = call(get(studio, path, token=False, path="a.epk"))
        assert status == 403, path
        status, _ = call(get(studio, path, token=False, headers={
            "X-Studio-Token": studio.studio.token[:-1] + "x"}))
        assert status == 403, path
    status, text = call(get(studio, "/"))
    assert status == 200 and studio.studio.token in text
    status, text = call(get(studio, "/api/info"))
    assert status == 200 and "braitenberg.epk" in json.loads(text)["files"]


def test_a_rebinding_host_or_another_origin_is_refused(studio):
    port = studio.studio.port
    for headers in ({"Host": f"evil.example:{port}"}, {"Host": "127.0.0.1:1"},
                    {"Origin": "http://evil.example"}, {"Origin": "null"}):
        status, text = call(get(studio, "/api/info", headers=headers))
        assert status == 403, (headers, text)
    status, _ = call(get(studio, "/api/info", headers={"Host": f"localhost:{port}",
                                                       "Origin": f"http://localhost:{port}"}))
    assert status == 200

    async def socket_from(origin):
        async with aiohttp.ClientSession() as s:
            try:
                async with s.ws_connect(f"{base(studio)}/ws/run?token={studio.studio.token}",
                                        origin=origin):
                    return 101
            except aiohttp.WSServerHandshakeError as exc:
                return exc.status
    assert call(socket_from("http://evil.example")) == 403
    assert call(socket_from(base(studio))) == 101


@pytest.mark.parametrize("path", ["../secret.epk", "out.epk", "/etc/passwd", "lab1/../../secret.epk"])
def test_files_outside_the_folder_cannot_be_read_or_written(studio, path):
    status, text = call(get(studio, "/api/file", path=path))
    assert status in (403, 404) and "outside" not in text.replace("outside the folder", "")

    async def put():
        async with aiohttp.ClientSession() as s:
            async with s.put(base(studio) + "/api/file", params={"token": studio.studio.token},
                             json={"path": path, "text": "pwned\n", "version": None}) as r:
                return r.status
    assert call(put()) in (403, 404)
    assert (studio.studio.workspace.root.parent / "secret.epk").read_text() == "outside\n"


async def lsp_exchange(studio, messages, replies):
    async with aiohttp.ClientSession() as s:
        async with s.ws_connect(f"{base(studio)}/ws/lsp?token={studio.studio.token}",
                                origin=base(studio)) as ws:
            for m in messages:
                await ws.send_str(json.dumps(m))
            out = []
            while len(out) < replies:
                out.append(json.loads((await ws.receive(timeout=20)).data))
            await ws.send_str(json.dumps({"jsonrpc": "2.0", "method": "exit"}))
            closed = (await ws.receive(timeout=20)).type
            return out, closed


def test_the_language_server_answers_for_the_folder_and_refuses_files_outside(studio):
    root = studio.studio.workspace.root
    init = {"jsonrpc": "2.0", "id": 1, "method": "initialize",
            "params": {"processId": None, "rootUri": root.as_uri(), "capabilities": {},
                       "initializationOptions": {"debounceMs": 0}}}
    inside = (root / "new.epk").as_uri()
    outside = (root.parent / "secret.epk").as_uri()
    replies, closed = call(lsp_exchange(studio, [
        init, {"jsonrpc": "2.0", "method": "initialized", "params": {}},
        {"jsonrpc": "2.0", "method": "textDocument/didOpen", "params": {"textDocument": {
            "uri": inside, "languageId": "epuck", "version": 1,
            "text": "on immediate do set_sped(1 steps/s, 1 steps/s)\n"}}},
        {"jsonrpc": "2.0", "id": 2, "method": "textDocument/hover", "params": {
            "textDocument": {"uri": outside}, "position": {"line": 0, "character": 1}}}], 3))
    by_id = {r.get("id"): r for r in replies}
    assert "capabilities" in by_id[1]["result"]
    assert "not a file of the studio's folder" in by_id[2]["error"]["message"]
    published = [r for r in replies if r.get("method") == "textDocument/publishDiagnostics"][0]
    assert published["params"]["uri"] == inside
    assert "set_speed" in published["params"]["diagnostics"][0]["message"]
    # `exit` closed that socket only: the studio still serves
    assert closed in (aiohttp.WSMsgType.CLOSE, aiohttp.WSMsgType.CLOSED, aiohttp.WSMsgType.CLOSING)
    assert call(get(studio, "/api/info"))[0] == 200


async def run_until(studio, request, stop_after_records=None, leave=False):
    """Send a run; collect its messages until its end (or, with
    stop_after_records, send Stop, or with leave, close the socket)."""
    messages = []
    async with aiohttp.ClientSession() as s:
        ws = await s.ws_connect(f"{base(studio)}/ws/run?token={studio.studio.token}",
                                origin=base(studio))
        await ws.send_str(json.dumps({"type": "run", **request}))
        records = 0
        while True:
            m = json.loads((await ws.receive(timeout=120)).data)
            messages.append(m)
            if m["type"] == "records":
                records += len(m["lines"])
                if stop_after_records is not None and records >= stop_after_records:
                    if leave:
                        await ws.close()
                        return messages
                    await ws.send_str(json.dumps({"type": "stop"}))
                    stop_after_records = None
            if m["type"] in ("end", "refused"):
                await ws.close()
                return messages


def run_pids(studio) -> set:
    return {run.proc.pid for run in list(studio.studio.active_runs) if run.proc is not None}


def test_a_run_streams_the_trace_epuckc_run_writes(studio, tmp_path):
    require_enki()
    messages = call(run_until(studio, {"program": "follower.epk", "world": "follow.world",
                                       "time_limit_ms": 2000}))
    end = messages[-1]
    assert end["type"] == "end" and end["status"] == 3 and not end["stopped"]
    streamed = [line for m in messages if m["type"] == "records" for line in m["lines"]]
    assert sum(m["type"] == "records" for m in messages) >= 1
    status, text = call(get(studio, end["trace"]))
    assert status == 200 and text.splitlines() == streamed
    # the same bytes as `epuckc run --trace FILE` in the program's folder
    from tests.support.world import epuckc
    root = studio.studio.workspace.root
    out = tmp_path / "t.jsonl"
    result = epuckc("run", "follower.epk", "--world", "follow.world", "--time-limit", "2000ms",
                    "--pose-interval", "50ms", "--trace", out, cwd=root)
    assert result.returncode == 3, result.stderr
    assert out.read_text() == text
    robots = {json.loads(line).get("robot") for line in streamed[1:]}
    assert robots == {"leader", "follower"}
    assert any(m["type"] == "stderr" and "no collision" in m["text"] for m in messages)


def test_a_run_with_a_scenario_streams_the_host_harness_trace(studio, tmp_path):
    root = studio.studio.workspace.root
    (root / "avoid.epk").write_text((Path(__file__).resolve().parents[2] / "examples" /
                                     "obstacle_avoidance.epk").read_text())
    messages = call(run_until(studio, {"program": "avoid.epk", "scenario": "obstacle.scn",
                                       "time_limit_ms": 3000, "seed": 7}))
    end = messages[-1]
    assert end["type"] == "end" and end["status"] == 3
    streamed = [line for m in messages if m["type"] == "records" for line in m["lines"]]
    from tests.support.world import epuckc
    out = tmp_path / "t.jsonl"
    result = epuckc("run", "avoid.epk", "--scenario", "obstacle.scn", "--time-limit", "3000ms",
                    "--seed", "7", "--pose-interval", "50ms", "--trace", out, cwd=root)
    assert result.returncode == 3, result.stderr
    assert out.read_text().splitlines() == streamed
    assert any(json.loads(line)["kind"] == "pose" for line in streamed)


def test_a_run_of_a_file_with_errors_says_why_and_a_bad_request_is_refused(studio):
    root = studio.studio.workspace.root
    (root / "broken.epk").write_text("on immediate do set_sped(1 steps/s, 1 steps/s)\n")
    messages = call(run_until(studio, {"program": "broken.epk"}))
    assert messages[-1]["type"] == "end" and messages[-1]["status"] == 1
    assert "did you mean `set_speed`" in "".join(m.get("text", "") for m in messages)
    for bad in ({"program": "../secret.epk"}, {"program": "follow.world"},
                {"program": "mover.epk", "time_limit_ms": 10 ** 9},
                {"program": "mover.epk", "world": "out.epk"}):
        assert call(run_until(studio, bad))[-1]["type"] == "refused", bad


def test_stop_ends_the_run_and_its_processes(studio):
    require_enki()
    seen = []

    async def run_and_stop():
        task = asyncio.ensure_future(run_until(studio, {
            "program": "braitenberg.epk", "world": "braitenberg.world",
            "time_limit_ms": 600_000}, stop_after_records=200))
        while not task.done():
            seen.extend(run_pids(studio))
            await asyncio.sleep(0.02)
        return await task
    messages = call(run_and_stop())
    end = messages[-1]
    assert end["type"] == "end" and end["stopped"]
    assert seen
    wait_until(lambda: not any(group_alive(p) for p in seen), 10, "the run's processes gone")


def test_a_page_that_goes_away_mid_run_stops_the_simulation(studio):
    require_enki()
    seen = []

    async def run_and_leave():
        task = asyncio.ensure_future(run_until(studio, {
            "program": "braitenberg.epk", "world": "braitenberg.world",
            "time_limit_ms": 600_000}, stop_after_records=200, leave=True))
        while not task.done():
            seen.extend(run_pids(studio))
            await asyncio.sleep(0.02)
        return await task
    messages = call(run_and_leave())
    assert messages[-1]["type"] == "records"        # it left before the end
    assert seen
    wait_until(lambda: not any(group_alive(p) for p in seen), 10, "the run's processes gone")
    wait_until(lambda: not run_pids(studio) or all(
        run.proc.returncode is not None for run in studio.studio.active_runs), 10,
        "the run reaped")
    # and no world runner nor harness of this folder is left
    import os
    for pid in os.listdir("/proc"):
        if pid.isdigit():
            try:
                cwd = os.readlink(f"/proc/{pid}/cwd")
            except OSError:
                continue
            assert Path(cwd) != studio.studio.workspace.root or int(pid) == os.getpid()


def test_epuckc_studio_prints_its_url_serves_it_and_stops_on_ctrl_c(tmp_path):
    import os
    import re
    import signal
    import subprocess
    import sys
    import urllib.request
    from tests.support.world import REPO
    (tmp_path / "a.epk").write_text("on immediate do set_speed(1 steps/s, 1 steps/s)\n")
    env = dict(os.environ, PYTHONPATH=str(REPO))
    proc = subprocess.Popen([sys.executable, "-m", "epuckc", "studio", str(tmp_path),
                             "--no-browser", "--port", "0"], stdout=subprocess.PIPE,
                            stderr=subprocess.PIPE, text=True, env=env)
    try:
        url = None
        for line in proc.stdout:
            m = re.search(r"open (http://127\.0\.0\.1:\d+/\?token=[\w-]+)", line)
            if m:
                url = m.group(1)
                break
        assert url, proc.stderr.read()
        with urllib.request.urlopen(url, timeout=20) as r:
            assert r.status == 200 and b"studio.js" in r.read()
        bare = url.split("?")[0] + "api/info"
        with pytest.raises(urllib.error.HTTPError) as refused:
            urllib.request.urlopen(bare, timeout=20)
        assert refused.value.code == 403
    finally:
        proc.send_signal(signal.SIGINT)
        assert proc.wait(timeout=30) == 0
    assert "Traceback" not in proc.stderr.read()


def test_epuckc_studio_of_a_missing_folder_is_a_usage_error(tmp_path):
    from tests.support.world import epuckc
    result = epuckc("studio", tmp_path / "nope", "--no-browser")
    assert result.returncode == 2 and "is not a folder" in result.stderr
    result = epuckc("studio", tmp_path, "--port", "http")
    assert result.returncode == 2 and "is not a port" in result.stderr
