"""`epuckc lsp` at the protocol's edges: messages no client library would
send, and what importing the command line loads."""
from __future__ import annotations

import json
import subprocess
import sys

from .conftest import REPO


def test_importing_the_cli_does_not_import_pygls():
    code = ("import sys, epuckc.cli, epuckc.check.frontend, epuckc.cli.driver; "
            "print(sorted(m for m in sys.modules if m.split('.')[0] in "
            "('pygls', 'lsprotocol', 'cattrs') or m in ('epuckc.ide.lsp', 'epuckc.ide.hover', 'epuckc.ide.completion', 'epuckc.ide.navigate')))")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         env={"PYTHONPATH": str(REPO), "PATH": "/usr/bin:/bin"}, check=True)
    assert out.stdout.strip() == "[]"


class _Raw:
    """A hand-made JSON-RPC session, for messages no client library sends."""

    def __init__(self):
        env = {"PYTHONPATH": str(REPO), "PATH": "/usr/bin:/bin"}
        self.proc = subprocess.Popen([sys.executable, "-m", "epuckc", "lsp"], env=env,
                                     stdin=subprocess.PIPE, stdout=subprocess.PIPE,
                                     stderr=subprocess.DEVNULL)

    def send_bytes(self, body: bytes):
        self.proc.stdin.write(b"Content-Length: %d\r\n\r\n" % len(body) + body)
        self.proc.stdin.flush()

    def send(self, message: dict):
        self.send_bytes(json.dumps({"jsonrpc": "2.0", **message}).encode())

    def receive(self) -> dict:
        length = None
        while True:
            line = self.proc.stdout.readline()
            assert line, "the server closed its output"
            if line in (b"\r\n", b"\n"):
                break
            if line.lower().startswith(b"content-length:"):
                length = int(line.split(b":")[1])
        return json.loads(self.proc.stdout.read(length))

    def response(self, ident) -> dict:
        while True:
            message = self.receive()
            if message.get("id") == ident and "method" not in message:
                return message


def test_malformed_messages_get_error_responses_and_the_server_lives_on():
    raw = _Raw()
    try:
        raw.send({"id": 1, "method": "initialize", "params": {"capabilities": {}}})
        assert "capabilities" in raw.response(1)["result"]
        raw.send({"method": "initialized", "params": {}})
        uri = "file:///nowhere/raw.epk"
        raw.send({"method": "textDocument/didOpen", "params": {"textDocument": {
            "uri": uri, "languageId": "epuck", "version": 1, "text": "action go = stop_motor\non immediate do go\n"}}})
        bad = [
            {"id": 2, "method": "textDocument/hover", "params": {"textDocument": 5}},
            {"id": 3, "method": "textDocument/definition", "params": None},
            {"id": 4, "method": "epuckc/noSuchRequest", "params": {}},
            {"id": 5, "method": "textDocument/rename", "params": {
                "textDocument": {"uri": uri}, "position": {"line": -4, "character": "x"},
                "newName": 7}},
            {"id": 6, "method": "textDocument/hover", "params": {
                "textDocument": {"uri": "file:///not/open.epk"},
                "position": {"line": 0, "character": 0}}},
        ]
        for message in bad:
            raw.send(message)
            assert "error" in raw.response(message["id"]), message
        raw.send_bytes(b"{this is not json")
        raw.send({"method": "textDocument/didChange", "params": {"garbage": True}})
        raw.send({"id": 7, "method": "textDocument/hover", "params": {
            "textDocument": {"uri": uri}, "position": {"line": 1, "character": 17}}})
        assert "Named action, line 1" in raw.response(7)["result"]["contents"]["value"]
        raw.send({"id": 8, "method": "shutdown"})
        assert "error" not in raw.response(8)
        raw.send({"method": "exit"})
        assert raw.proc.wait(timeout=10) == 0
    finally:
        if raw.proc.poll() is None:
            raw.proc.kill()
