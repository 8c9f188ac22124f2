"""A real client session with `epuckc lsp` running as a subprocess."""
from __future__ import annotations

import asyncio
import os
import sys
from pathlib import Path

import pytest_lsp
from lsprotocol import types as lsp
from pytest_lsp import ClientServerConfig, LanguageClient, client_capabilities

REPO = Path(__file__).resolve().parents[2]

CONFIG = ClientServerConfig(
    server_command=[sys.executable, "-m", "epuckc", "lsp"],
    server_env={**os.environ, "PYTHONPATH": str(REPO) + os.pathsep
                + os.environ.get("PYTHONPATH", "")})


@pytest_lsp.fixture(config=CONFIG)
async def client(lsp_client: LanguageClient):
    params = lsp.InitializeParams(capabilities=client_capabilities("visual-studio-code"),
                                  initialization_options={"debounceMs": 30})
    await lsp_client.initialize_session(params)
    yield
    await lsp_client.shutdown_session()


def expect_diagnostics(client: LanguageClient, uri: str, version=None,
                       timeout: float = 30.0) -> asyncio.Future:
    """A future of the next diagnostics published for `uri` (of `version`,
    when given). Call it before the notification that causes them, so
    that the publication cannot come before the wait."""
    async def wait():
        while True:
            params = await client.wait_for_notification(lsp.TEXT_DOCUMENT_PUBLISH_DIAGNOSTICS)
            if params.uri == uri and (version is None or params.version == version):
                return params.diagnostics
    return asyncio.ensure_future(asyncio.wait_for(wait(), timeout))


def open_doc(client: LanguageClient, path: Path, text: str, version: int = 1) -> str:
    uri = path.resolve().as_uri()
    client.text_document_did_open(lsp.DidOpenTextDocumentParams(
        lsp.TextDocumentItem(uri=uri, language_id="epuck", version=version, text=text)))
    return uri
