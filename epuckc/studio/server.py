"""The studio's web server (aiohttp): the page, its API and its sockets.

Every route but none is behind security.Guard (token, Host, Origin); the
files come from workspace.Workspace; the sockets are /ws/lsp (the editor's
language server, lspbridge.py) and /ws/run (runs.py). `Studio` is the
server as an object (start, the URL, close); `serve` is `epuckc studio`.

The page's API (JSON unless said):
  GET  /                          the page (static/index.html, the token in its links)
  GET  /static/NAME               the built front end (static/)
  GET  /api/info                  the folder: files, exercises, what the page may offer
  GET  /api/file?path=P           {text, version}
  GET  /api/version?path=P        {version}: the page polls it to notice outside changes
  PUT  /api/file {path, text, version}   {version}; 409 {version} when it changed on disk
  POST /api/world {path}          a new world file from the template
  POST /api/c {path, text, line}  the generated C and the parts of the statement at line
  POST /api/check {paths}         Check: the exercises' `epuckc test` cases
  GET  /api/ports                 the robots' serial ports found (robots.py)
  POST /api/flash {program, port, target?, robot_id?, trace?}   Flash: `epuckc flash`
  GET  /api/trace/ID              a run's JSON-lines trace (a download)
"""
from __future__ import annotations

import asyncio
import json
import os
import shutil
import socket
import tempfile
import threading
import weakref
from pathlib import Path
from typing import Optional

from aiohttp import WSMsgType, web

from .. import __version__
from .exercises import check_command, exercises
from .lspbridge import LspSession
from .robots import RobotRequestError, flash_command, link_available, robot_ports
from .runs import RunRequestError, Runs, child_env
from .security import TOKEN_HEADER, Guard, new_token
from .workspace import Conflict, PathRefused, Workspace

STATIC = Path(__file__).resolve().parent / "static"
DEFAULT_PORT = 8743
CHECK_TIMEOUT_S = 600
FLASH_TIMEOUT_S = 1200      # a build, a reset window and flash's own bound (2 min a robot)


def _json_error(status: int, message: str, **more) -> web.Response:
    return web.json_response({"error": message, **more}, status=status)


class Studio:
    def __init__(self, root: Path, port: int = 0, token: Optional[str] = None):
        self.workspace = Workspace(root)
        self.requested_port = port
        self.token = token or new_token()
        self.guard: Optional[Guard] = None
        self.state_dir = Path(tempfile.mkdtemp(prefix="epuckc-studio-"))
        self.runs = Runs(self.state_dir)
        self.active_runs: weakref.WeakSet = weakref.WeakSet()
        self.sockets: set = set()
        self.children: set = set()      # Check's processes under way
        self.runner: Optional[web.AppRunner] = None
        self.port: Optional[int] = None
        self.link = link_available()

    # ---- the server ---------------------------------------------------------

    def _bind(self) -> socket.socket:
        sock = socket.socket(socket.AF_INET, socket.SOCK_STREAM)
        sock.setsockopt(socket.SOL_SOCKET, socket.SO_REUSEADDR, 1)
        try:
            sock.bind(("127.0.0.1", self.requested_port))
        except OSError:
            if not self.requested_port:
                raise
            sock.bind(("127.0.0.1", 0))     # taken: any free port
        sock.listen(128)
        sock.setblocking(False)
        return sock

    async def start(self) -> str:
        sock = self._bind()
        self.port = sock.getsockname()[1]
        self.guard = Guard(self.token, self.port)
        app = web.Application(middlewares=[self._guarded], client_max_size=4 * 2 ** 20)
        app.add_routes([
            web.get("/", self.index), web.get("/static/{name}", self.static),
            web.get("/api/info", self.info), web.get("/api/file", self.get_file),
            web.get("/api/version", self.get_version), web.put("/api/file", self.put_file),
            web.post("/api/world", self.new_world), web.post("/api/c", self.c_code),
            web.post("/api/check", self.check), web.get("/api/trace/{id}", self.trace),
            web.get("/api/ports", self.ports), web.post("/api/flash", self.flash),
            web.get("/ws/lsp", self.ws_lsp), web.get("/ws/run", self.ws_run)])
        self.runner = web.AppRunner(app, access_log=None, handle_signals=False)
        await self.runner.setup()
        await web.SockSite(self.runner, sock).start()
        return self.url

    @property
    def url(self) -> str:
        return f"http://127.0.0.1:{self.port}/?token={self.token}"

    async def close(self):
        for run in list(self.active_runs):
            await run.stop()
        for proc in list(self.children):
            _kill_group(proc)
        for ws in list(self.sockets):
            await ws.close()
        if self.runner is not None:
            await self.runner.cleanup()
        shutil.rmtree(self.state_dir, ignore_errors=True)

    @web.middleware
    async def _guarded(self, request: web.Request, handler):
        token = request.query.get("token") or request.headers.get(TOKEN_HEADER)
        why = self.guard.refusal(request.headers.get("Host"), request.headers.get("Origin"),
                                 token)
        if why is not None:
            return _json_error(403, why)
        try:
            response = await handler(request)
        except PathRefused as exc:
            return _json_error(404 if exc.missing else 403, str(exc))
        response.headers.setdefault("Cache-Control", "no-store")
        response.headers.setdefault("X-Content-Type-Options", "nosniff")
        response.headers.setdefault("Referrer-Policy", "no-referrer")
        return response

    # ---- the page -----------------------------------------------------------

    async def index(self, request):
        text = (STATIC / "index.html").read_text(encoding="utf-8")
        page = text.replace("%TOKEN%", self.token)
        return web.Response(text=page, content_type="text/html", headers={
            "Content-Security-Policy": "default-src 'self'; style-src 'self' 'unsafe-inline'; "
                                       "img-src 'self' data:; frame-src 'self'; "
                                       "connect-src 'self' ws://127.0.0.1:* ws://localhost:*"})

    async def static(self, request):
        name = request.match_info["name"]
        path = STATIC / name
        if "/" in name or name.startswith(".") or not path.is_file() or name == "index.html":
            raise web.HTTPNotFound()
        return web.FileResponse(path)

    async def info(self, request):
        ws = self.workspace
        return web.json_response({
            "version": __version__, "name": ws.root.name, "root_uri": ws.root.as_uri(),
            "files": ws.files(), "exercises": exercises(ws),
            # the robot link's buttons appear where these are true (pyserial there)
            "flash": self.link, "monitor": self.link})

    # ---- files ----------------------------------------------------------------

    async def get_file(self, request):
        text, version = self.workspace.read(request.query.get("path", ""))
        return web.json_response({"text": text, "version": version})

    async def get_version(self, request):
        return web.json_response(
            {"version": self.workspace.current_version(request.query.get("path", ""))})

    async def _body(self, request) -> dict:
        try:
            body = await request.json()
        except (ValueError, UnicodeDecodeError):
            raise web.HTTPBadRequest(text="a JSON body") from None
        if not isinstance(body, dict):
            raise web.HTTPBadRequest(text="a JSON object")
        return body

    async def put_file(self, request):
        body = await self._body(request)
        text, base = body.get("text"), body.get("version")
        if not isinstance(text, str) or not (base is None or isinstance(base, str)):
            return _json_error(400, "{path, text, version}")
        try:
            version = self.workspace.save(str(body.get("path", "")), text, base)
        except Conflict as exc:
            return _json_error(409, str(exc), version=exc.version)
        except OSError as exc:
            return _json_error(500, f"cannot save: {exc.strerror or exc}")
        return web.json_response({"version": version})

    async def new_world(self, request):
        body = await self._body(request)
        try:
            version = self.workspace.new_world(str(body.get("path", "")))
        except Conflict:
            return _json_error(409, "a file of that name exists")
        return web.json_response({"version": version})

    async def c_code(self, request):
        from .ccode import NoC, generated_c
        body = await self._body(request)
        rel = str(body.get("path", ""))
        path = self.workspace.resolve(rel, must_exist=False)
        text, line = body.get("text"), body.get("line", 1)
        if not isinstance(text, str) or not isinstance(line, int):
            return _json_error(400, "{path, text, line}")
        try:
            return web.json_response(generated_c(path, text, line))
        except NoC as exc:
            return _json_error(422, "the program has errors", diagnostics=str(exc))

    async def trace(self, request):
        try:
            path = self.runs.trace(int(request.match_info["id"]))
        except ValueError:
            path = None
        if path is None:
            raise web.HTTPNotFound()
        return web.FileResponse(path, headers={
            "Content-Type": "application/x-ndjson",
            "Content-Disposition": f'attachment; filename="trace-{request.match_info["id"]}.jsonl"'})

    # ---- Check ----------------------------------------------------------------

    async def check(self, request):
        body = await self._body(request)
        paths = body.get("paths")
        if not isinstance(paths, list) or not all(isinstance(p, str) for p in paths) or not paths:
            return _json_error(400, "{paths: [file or exercise folder, ...]}")
        argv = check_command(self.workspace, paths)
        proc, out, err = await self._child(argv, self.workspace.root, CHECK_TIMEOUT_S)
        if proc.returncode != 0:
            return _json_error(500, "Check failed: " + err.decode("utf-8", "replace")[-2000:])
        results = json.loads(out)
        for result in results:
            trace = result.pop("trace", "")
            result["trace"] = self._keep_trace(trace) if trace else None
        return web.json_response({"results": results})

    async def _child(self, argv: list, cwd: Path, timeout_s: float) -> tuple:
        """(process, stdout, stderr) of a child epuckc run to its end, its
        whole group killed if it outlives `timeout_s` or the request is
        cancelled (the page went away)."""
        proc = await asyncio.create_subprocess_exec(
            *argv, cwd=str(cwd), env=child_env(),
            stdin=asyncio.subprocess.DEVNULL, stdout=asyncio.subprocess.PIPE,
            stderr=asyncio.subprocess.PIPE, start_new_session=True)
        self.children.add(proc)
        try:
            out, err = await asyncio.wait_for(proc.communicate(), timeout_s)
        except BaseException:
            _kill_group(proc)
            await proc.wait()
            raise
        finally:
            self.children.discard(proc)
        return proc, out, err

    # ---- the robots -----------------------------------------------------------

    async def ports(self, request):
        if not self.link:
            return _json_error(501, "the robot link needs pyserial: pip install pyserial")
        ports = await asyncio.get_running_loop().run_in_executor(None, robot_ports)
        return web.json_response({"ports": ports})

    async def flash(self, request):
        """Flash: `epuckc flash` on a program of DIR, to its end (the page
        says to press an e-puck's reset while it waits); its status and
        what it printed."""
        if not self.link:
            return _json_error(501, "the robot link needs pyserial: pip install pyserial")
        body = await self._body(request)
        try:
            argv, cwd = flash_command(self.workspace, body)
        except RobotRequestError as exc:
            return _json_error(400, str(exc))
        proc, out, err = await self._child(argv, cwd, FLASH_TIMEOUT_S)
        return web.json_response({
            "status": proc.returncode, "command": " ".join(["epuckc"] + argv[3:]),
            "output": out.decode("utf-8", "replace") + err.decode("utf-8", "replace")})

    def _keep_trace(self, text: str) -> int:
        ident, path = self.runs.new_trace()
        path.write_text(text, encoding="utf-8")
        return ident

    # ---- sockets --------------------------------------------------------------

    async def ws_lsp(self, request):
        ws = web.WebSocketResponse(max_msg_size=8 * 2 ** 20)
        await ws.prepare(request)
        self.sockets.add(ws)
        session = LspSession(self.workspace, ws)
        try:
            async for msg in ws:
                if msg.type != WSMsgType.TEXT or not await session.receive(msg.data):
                    break
        finally:
            session.close()
            self.sockets.discard(ws)
            await ws.close()
        return ws

    async def ws_run(self, request):
        ws = web.WebSocketResponse(max_msg_size=2 ** 20, heartbeat=20)
        await ws.prepare(request)
        self.sockets.add(ws)
        current = None

        async def send(message):
            if not ws.closed:
                await ws.send_str(json.dumps(message))
        try:
            async for msg in ws:
                if msg.type != WSMsgType.TEXT:
                    break
                try:
                    request_ = json.loads(msg.data)
                except ValueError:
                    continue
                if not isinstance(request_, dict):
                    continue
                if current is not None:
                    await current.stop()
                    current = None
                if request_.get("type") in ("run", "monitor"):
                    try:
                        if request_["type"] == "monitor" and not self.link:
                            raise RunRequestError("the robot link needs pyserial: pip "
                                                  "install pyserial")
                        current = self.runs.new(self.workspace, request_, send)
                    except (RunRequestError, RobotRequestError, PathRefused) as exc:
                        await send({"type": "refused", "error": str(exc)})
                        continue
                    self.active_runs.add(current)
                    await current.start()
                    await send({"type": "started", "run": current.id,
                                "command": " ".join(["epuckc"] + current.argv[3:])})
        finally:
            if current is not None:     # the page went away: its run with it
                await current.stop()
            self.sockets.discard(ws)
            await ws.close()
        return ws


def _kill_group(proc) -> None:
    import signal
    if proc.returncode is None:
        try:
            os.killpg(proc.pid, signal.SIGKILL)
        except (ProcessLookupError, PermissionError):
            pass


class StudioThread:
    """A studio served from a thread of its own (tests, the bench)."""

    def __init__(self, root: Path, port: int = 0):
        self.studio = Studio(root, port)
        self.loop = asyncio.new_event_loop()
        self._ready = threading.Event()
        self.thread = threading.Thread(target=self._main, daemon=True)
        self.thread.start()
        self._ready.wait(30)

    def _main(self):
        asyncio.set_event_loop(self.loop)
        self.loop.run_until_complete(self.studio.start())
        self._ready.set()
        self.loop.run_forever()

    @property
    def url(self) -> str:
        return self.studio.url

    def close(self):
        asyncio.run_coroutine_threadsafe(self.studio.close(), self.loop).result(30)
        self.loop.call_soon_threadsafe(self.loop.stop)
        self.thread.join(30)


def serve(root: Path, port: int = DEFAULT_PORT, open_browser: bool = True) -> int:
    """`epuckc studio`: serve until Ctrl-C."""
    import signal

    async def main():
        studio = Studio(root, port)
        url = await studio.start()
        print(f"epuckc studio: serving {studio.workspace.root}\n"
              f"    open {url}\n(Ctrl-C stops it)", flush=True)
        if open_browser:
            import webbrowser
            threading.Thread(target=webbrowser.open, args=(url,), daemon=True).start()
        stop = asyncio.Event()
        loop = asyncio.get_running_loop()
        for sig in (signal.SIGINT, signal.SIGTERM):
            loop.add_signal_handler(sig, stop.set)
        await stop.wait()
        await studio.close()
    asyncio.run(main())
    return 0
