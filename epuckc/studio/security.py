"""Who may talk to the studio: only a page the studio served to this user.

- The server listens on 127.0.0.1 only (server.py).
- A random token (secrets.token_urlsafe, 32 bytes) is printed in the URL,
  as Jupyter does; every request and every WebSocket carries it (the
  `token` query parameter, or the `X-Studio-Token` header the page's
  requests send); a request without it, or with another, is refused (403)
  before any handler runs. Tokens are compared in constant time.
- Host must name the loopback address and the studio's own port
  (`127.0.0.1:PORT` or `localhost:PORT`): a page of another site that a DNS
  rebinding made resolve to 127.0.0.1 sends its own host name, and is
  refused (a token in its hands would not help it either).
- Origin, when the browser sends one (every WebSocket and every request
  but a plain navigation), must be the studio's own origin: a page of
  another origin may not open the sockets nor post to the API.
"""
from __future__ import annotations

import hmac
import secrets
from typing import Optional

TOKEN_HEADER = "X-Studio-Token"


def new_token() -> str:
    return secrets.token_urlsafe(32)


class Guard:
    def __init__(self, token: str, port: int):
        self.token = token
        self.port = port

    def hosts(self) -> set:
        return {f"127.0.0.1:{self.port}", f"localhost:{self.port}"}

    def origins(self) -> set:
        return {f"http://{h}" for h in self.hosts()}

    def refusal(self, host: Optional[str], origin: Optional[str],
                token: Optional[str]) -> Optional[str]:
        """Why a request is refused, or None when it may go on."""
        if host is None or host.lower() not in self.hosts():
            return "the Host header does not name this studio (127.0.0.1 and its port)"
        if origin is not None and origin.lower() not in self.origins():
            return "the request comes from a page of another origin"
        if not token or not hmac.compare_digest(token.encode(), self.token.encode()):
            return "the studio's token is missing or wrong: open the URL `epuckc studio` printed"
        return None
