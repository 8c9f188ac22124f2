"""The editor's language server: `epuckc lsp`'s own server (ide/lsp.py, its
handlers and documents), one per page, fed from a WebSocket in this
process instead of standard input, so that an edit is analysed where the
last one was (the incremental analysis of ide/) and nothing is started per
keystroke.

What the page may send is narrowed first: every document it names must be
a file URI inside the folder (workspace.py's rules), and `exit`, which
would end the process, is answered by closing this socket only.
"""
from __future__ import annotations

import json
import logging
from pathlib import Path
from typing import Optional
from urllib.parse import unquote, urlparse

from .workspace import PathRefused, Workspace

log = logging.getLogger("epuckc.studio")


class _SocketWriter:
    """pygls's writer interface over an aiohttp WebSocket."""

    def __init__(self, ws):
        self.ws = ws

    def close(self):
        return self.ws.close()

    def write(self, data: bytes):
        if self.ws.closed:
            return None
        return self.ws.send_str(data.decode("utf-8"))


def _uris(value, found: list) -> list:
    """Every `uri` inside a message's params (textDocument.uri and the like)."""
    if isinstance(value, dict):
        for key, item in value.items():
            if key == "uri" and isinstance(item, str):
                found.append(item)
            else:
                _uris(item, found)
    elif isinstance(value, list):
        for item in value:
            _uris(item, found)
    return found


class LspSession:
    def __init__(self, workspace: Workspace, ws):
        from ..ide.lsp import create_server
        self.workspace = workspace
        self.ws = ws
        self.server = create_server()
        self.server.protocol.set_writer(_SocketWriter(ws), include_headers=False)

    def _inside(self, uri: str) -> bool:
        try:
            parsed = urlparse(uri)
        except ValueError:
            return False
        if parsed.scheme != "file" or parsed.netloc not in ("", "localhost"):
            return False
        try:
            rel = Path(unquote(parsed.path)).relative_to(self.workspace.root).as_posix()
            if rel == ".":
                return True         # the folder itself (a workspace folder, rootUri)
            self.workspace.resolve(rel, must_exist=False)
        except (ValueError, PathRefused):
            return False
        return True

    def refusal(self, message) -> Optional[str]:
        if not isinstance(message, dict):
            return "not a JSON-RPC message"
        if message.get("method") == "exit":
            return "exit"
        bad = [u for u in _uris(message.get("params"), []) if not self._inside(u)]
        if bad:
            return f"{bad[0]} is not a file of the studio's folder"
        return None

    async def receive(self, text: str) -> bool:
        """Hand one message to the server; False when the socket should close."""
        try:
            raw = json.loads(text)
        except ValueError:
            return True
        why = self.refusal(raw)
        if why == "exit":
            return False
        if why is not None:
            ident = raw.get("id") if isinstance(raw, dict) else None
            if ident is not None:
                await self.ws.send_str(json.dumps({"jsonrpc": "2.0", "id": ident, "error": {
                    "code": -32602, "message": why}}))
            return True
        protocol = self.server.protocol
        try:
            message = json.loads(text, object_hook=protocol.structure_message)
            protocol.handle_message(message)
        except Exception:           # ide/lsp.py answers what it can; the socket goes on
            log.exception("epuckc studio: a language server message failed")
        return True

    def close(self) -> None:
        for doc in list(self.server.docs.values()):
            if doc.timer is not None:
                doc.timer.cancel()
        self.server.docs.clear()
