"""`epuckc lsp`: the language server, on standard input and output.

Built on pygls and lsprotocol, which only this module and documents.py
(an open document: its text, positions, diagnostics' LSP form) import (the
other commands never load them). The server keeps each open document's text
itself, analyses it with epuckc.ide.incremental (the same front end as
`epuckc check`, reusing what an edit did not change) and answers from
epuckc.ide. Every handler is guarded: a failure inside epuckc is logged to
the client and answered with an error response (requests) or ignored
(notifications); the server itself never stops.

Decisions:
- diagnostics are published at once on open and save, and `DEBOUNCE_S`
  after the last change (a request that needs the analysis runs it at
  once);
- each diagnostic's code links to its explanation shipped inside the
  package (`file://.../epuckc/diagnostics/explanations/E011.md`, the text `epuckc
  explain` prints), which works offline and matches the installed version;
- the help line is appended to the message (LSP has no field for it), and
  notes with a position become related information.
"""
from __future__ import annotations

import functools
import logging
import sys
import traceback
from typing import Optional

from lsprotocol import types as lsp
from pygls.exceptions import JsonRpcException, JsonRpcInvalidParams
from pygls.lsp.server import LanguageServer
from pygls.protocol import LanguageServerProtocol, lsp_method

from .. import __version__
from ..syntax import ast

from . import navigate
from .completion import completions
from .fmt import line_edits
from .hover import hover as hover_at
from ..diagnostics.codes import explanation_path
from ..diagnostics import ERROR
from .documents import Document, Lines  # noqa: F401 (the server's documents; Lines for tests)
from .incremental import Analysis

DEBOUNCE_S = 0.15

log = logging.getLogger("epuckc.lsp")


class _RequestFailed(JsonRpcException):
    """LSP's RequestFailed: the request was valid but cannot be done (a
    refused rename)."""
    CODE = -32803
    MESSAGE = "request failed"


@functools.lru_cache(maxsize=None)
def _explanation_href(code: str) -> Optional[str]:
    """The URI of a code's explanation file (the files ship with epuckc)."""
    path = explanation_path(code)
    return path.as_uri() if path else None


# ---- the server ---------------------------------------------------------------------

class _Dropped:
    """A message that could not be read; pygls ignores messages of another
    JSON-RPC version."""
    jsonrpc = "dropped"


class EpuckProtocol(LanguageServerProtocol):
    """Documents are kept by the server (EpuckServer.docs), not by pygls's
    workspace, whose edits could raise on a bad range before our handler
    ran; the built-in handlers only pass the notification on."""

    def structure_message(self, data):
        """pygls drops a request whose parameters do not have the protocol's
        shape without answering it; answer it with the error instead."""
        try:
            return super().structure_message(data)
        except JsonRpcException as exc:
            ident = data.get("id") if isinstance(data, dict) else None
            if isinstance(ident, (int, str)) and not isinstance(ident, bool) \
                    and "method" in data:
                self._send_response(ident, None, exc.to_response_error())
            return _Dropped()

    @lsp_method(lsp.TEXT_DOCUMENT_DID_OPEN)
    def lsp_text_document__did_open(self, params):
        handler = self.fm.features.get(lsp.TEXT_DOCUMENT_DID_OPEN)
        if handler is not None:
            yield handler, (params,), None

    @lsp_method(lsp.TEXT_DOCUMENT_DID_CHANGE)
    def lsp_text_document__did_change(self, params):
        handler = self.fm.features.get(lsp.TEXT_DOCUMENT_DID_CHANGE)
        if handler is not None:
            yield handler, (params,), None

    @lsp_method(lsp.TEXT_DOCUMENT_DID_CLOSE)
    def lsp_text_document__did_close(self, params):
        handler = self.fm.features.get(lsp.TEXT_DOCUMENT_DID_CLOSE)
        if handler is not None:
            yield handler, (params,), None


class EpuckServer(LanguageServer):
    def __init__(self):
        super().__init__("epuckc", __version__, protocol_cls=EpuckProtocol,
                         text_document_sync_kind=lsp.TextDocumentSyncKind.Incremental)
        self.docs: dict = {}
        self.debounce = DEBOUNCE_S

    @property
    def encoding(self) -> str:
        try:
            enc = self.workspace.position_encoding
        except Exception:       # not initialised yet
            enc = None
        return str(getattr(enc, "value", enc) or "utf-16")

    def report_server_error(self, error, source):
        # a refusal or a request about a closed document is an answer, not a failure
        if not isinstance(error, (_RequestFailed, JsonRpcInvalidParams)):
            log.error("%s", error)

    def doc(self, uri) -> Document:
        doc = self.docs.get(uri)
        if doc is None:
            raise JsonRpcInvalidParams(f"the document {uri} is not open")
        return doc

    # conversions

    def range(self, doc: Document, analysis: Analysis, span) -> lsp.Range:
        """The LSP range of a span (of the AST's virtual lines, or real)."""
        span = analysis.real(span)
        lines = doc.lines(self.encoding)
        start = analysis.offset(span.line, span.column)
        end = analysis.offset(span.end_line, span.end_column)
        return lsp.Range(lines.position(start), lines.position(max(start, end)))

    def point(self, doc: Document, analysis: Analysis, pos: lsp.Position) -> tuple:
        """epuckc's (line, column) of an LSP position."""
        offset = doc.lines(self.encoding).offset(pos)
        return analysis.position(offset)

    def diagnostic(self, doc: Document, analysis: Analysis, d) -> lsp.Diagnostic:
        """The LSP diagnostic of `d` (real lines). Kept by the document
        while `d` is the same object (the incremental checker hands the same
        objects again for what an edit did not reach) and the lines its
        ranges are on have the same text."""
        lines = doc.lines(self.encoding)
        if lines.has_cr:     # (lines counted as the checker counts them only without \r)
            return self._diagnostic(doc, analysis, d)
        spans = (d.span,) + tuple(n.span for n in d.notes if n.span is not None)
        count = len(lines.starts)       # (a span past the end is clamped to the last line)
        texts = tuple((lines.text_of(span.line - 1, span.end_line - 1), span.end_line > count
                       and count) for span in spans)
        cache = doc.lsp_diagnostics
        hit = cache.get(id(d))
        if hit is not None and hit[0] is d and hit[1] == texts:
            return hit[2]
        converted = self._diagnostic(doc, analysis, d)
        if len(cache) > 2 * len(analysis.diagnostics) + 100:
            live = {id(x) for x in analysis.diagnostics}
            doc.lsp_diagnostics = cache = {k: v for k, v in cache.items() if k in live}
        cache[id(d)] = (d, texts, converted)
        return converted

    def diagnostics(self, doc: Document, analysis: Analysis) -> list:
        """The LSP form of every diagnostic of the analysis, as published:
        those of the last analysis kept (documents.Conversions)."""
        return doc.conversions.all(analysis, doc.lines(self.encoding),
                                   lambda d: self._diagnostic(doc, analysis, d))

    def _diagnostic(self, doc: Document, analysis: Analysis, d) -> lsp.Diagnostic:
        message = d.message
        related = []
        for note in d.notes:
            if note.span is None:
                message += f"\nnote: {note.message}"
            else:
                related.append(lsp.DiagnosticRelatedInformation(
                    lsp.Location(doc.uri, self.range(doc, analysis, note.span)), note.message))
        if d.help:
            message += f"\nhelp: {d.help}"
        href = _explanation_href(d.code)
        return lsp.Diagnostic(
            range=self.range(doc, analysis, d.span), message=message,
            severity=lsp.DiagnosticSeverity.Error if d.severity == ERROR
            else lsp.DiagnosticSeverity.Warning,
            code=d.code, source="epuckc",
            code_description=lsp.CodeDescription(href=href) if href else None,
            related_information=related or None)

    def publish(self, doc: Document):
        if self.docs.get(doc.uri) is not doc:
            return          # closed meanwhile
        analysis = doc.analyse()
        if doc.published is doc.text:
            return
        doc.published = doc.text
        diagnostics = self.diagnostics(doc, analysis)
        self.text_document_publish_diagnostics(lsp.PublishDiagnosticsParams(
            uri=doc.uri, diagnostics=diagnostics, version=doc.version))

    def schedule(self, doc: Document, delay: float):
        import asyncio
        if doc.timer is not None:
            doc.timer.cancel()
            doc.timer = None
        if delay <= 0:
            self.publish(doc)
            return
        loop = asyncio.get_event_loop()
        doc.timer = loop.call_later(delay, _guarded(self, "publishing diagnostics",
                                                    lambda: self.publish(doc)))


def _guarded(server: EpuckServer, what: str, func):
    def run():
        try:
            return func()
        except Exception:
            log.error("epuckc lsp: %s failed:\n%s", what, traceback.format_exc())
            try:
                server.window_log_message(lsp.LogMessageParams(
                    lsp.MessageType.Error, f"epuckc: {what} failed (a bug in epuckc):\n"
                                           f"{traceback.format_exc()}"))
            except Exception:
                pass
    return run


def create_server() -> EpuckServer:
    server = EpuckServer()

    def request(method, options=None):
        """Register a request handler whose unexpected failures become an
        error response (pygls does that too) and a log message."""
        def wrap(func):
            def handler(ls, params):
                try:
                    return func(ls, params)
                except JsonRpcException:
                    raise
                except Exception as exc:
                    log.error("epuckc lsp: %s failed:\n%s", method, traceback.format_exc())
                    raise JsonRpcException(message=f"epuckc: {method} failed: {exc}",
                                           code=-32603) from None
            server.feature(method, options)(handler)
            return func
        return wrap

    def notification(method, options=None):
        def wrap(func):
            def handler(ls, params):
                _guarded(ls, method, lambda: func(ls, params))()
            server.feature(method, options)(handler)
            return func
        return wrap

    @notification(lsp.INITIALIZED)
    def initialized(ls: EpuckServer, params):
        pass

    @request(lsp.INITIALIZE)
    def initialize(ls: EpuckServer, params: lsp.InitializeParams):
        options = params.initialization_options
        if isinstance(options, dict):
            debounce = options.get("debounceMs")
            if isinstance(debounce, (int, float)) and 0 <= debounce <= 10_000:
                ls.debounce = debounce / 1000

    @notification(lsp.TEXT_DOCUMENT_DID_OPEN)
    def did_open(ls: EpuckServer, params: lsp.DidOpenTextDocumentParams):
        item = params.text_document
        old = ls.docs.get(item.uri)
        if old is not None and old.timer is not None:
            old.timer.cancel()
        doc = Document(item.uri, item.text, item.version, ls)
        ls.docs[item.uri] = doc
        ls.schedule(doc, 0)

    @notification(lsp.TEXT_DOCUMENT_DID_CHANGE)
    def did_change(ls: EpuckServer, params: lsp.DidChangeTextDocumentParams):
        doc = ls.docs.get(params.text_document.uri)
        if doc is None:
            return          # a change to a document that is not open: nothing to do
        for change in params.content_changes:
            doc.apply(change, ls.encoding)
        doc.version = params.text_document.version
        ls.schedule(doc, ls.debounce)

    @notification(lsp.TEXT_DOCUMENT_DID_SAVE, lsp.SaveOptions(include_text=True))
    def did_save(ls: EpuckServer, params: lsp.DidSaveTextDocumentParams):
        doc = ls.docs.get(params.text_document.uri)
        if doc is None:
            return
        if params.text is not None:
            doc.text = params.text
        doc.published = None        # the C files next to it may have changed (E040)
        doc.analysis = None
        ls.schedule(doc, 0)

    @notification(lsp.TEXT_DOCUMENT_DID_CLOSE)
    def did_close(ls: EpuckServer, params: lsp.DidCloseTextDocumentParams):
        doc = ls.docs.pop(params.text_document.uri, None)
        if doc is None:
            return
        if doc.timer is not None:
            doc.timer.cancel()
        ls.text_document_publish_diagnostics(lsp.PublishDiagnosticsParams(
            uri=doc.uri, diagnostics=[]))

    @request(lsp.TEXT_DOCUMENT_HOVER)
    def hover(ls: EpuckServer, params: lsp.HoverParams):
        doc = ls.doc(params.text_document.uri)
        analysis = doc.analyse()
        found = hover_at(analysis, *ls.point(doc, analysis, params.position))
        if found is None:
            return None
        markdown, span = found
        return lsp.Hover(lsp.MarkupContent(lsp.MarkupKind.Markdown, markdown),
                         ls.range(doc, analysis, span))

    kinds = {"keyword": lsp.CompletionItemKind.Keyword, "action": lsp.CompletionItemKind.Function,
             "event": lsp.CompletionItemKind.Event, "param": lsp.CompletionItemKind.Property,
             "unit": lsp.CompletionItemKind.Unit, "const": lsp.CompletionItemKind.Constant,
             "rule": lsp.CompletionItemKind.Reference, "sensor": lsp.CompletionItemKind.Field,
             "variable": lsp.CompletionItemKind.Variable,
             "function": lsp.CompletionItemKind.Function}

    @request(lsp.TEXT_DOCUMENT_COMPLETION,
             lsp.CompletionOptions(trigger_characters=[" ", "(", ",", ":", "/"]))
    def completion(ls: EpuckServer, params: lsp.CompletionParams):
        doc = ls.doc(params.text_document.uri)
        analysis = doc.analyse()
        items = completions(analysis, *ls.point(doc, analysis, params.position))
        return lsp.CompletionList(is_incomplete=False, items=[
            lsp.CompletionItem(label=c.label, kind=kinds.get(c.kind), detail=c.detail or None,
                               insert_text=c.insert,
                               documentation=c.doc or None) for c in items])

    @request(lsp.TEXT_DOCUMENT_DEFINITION)
    def definition(ls: EpuckServer, params: lsp.DefinitionParams):
        doc = ls.doc(params.text_document.uri)
        analysis = doc.analyse()
        occ = navigate.occurrence_at(analysis, *ls.point(doc, analysis, params.position))
        target = navigate.resolve(analysis, occ) if occ is not None else None
        if target is None or target.statement is None:
            return None
        here = lsp.Location(doc.uri, ls.range(doc, analysis, target.ident.span))
        if isinstance(target.statement, ast.ExternDef):
            found = navigate.extern_location(analysis, target.statement, doc.base_dir())
            if found is not None:
                path, line, column, end = found
                position = lsp.Position(line - 1, column - 1)
                return [lsp.Location(path.resolve().as_uri(), lsp.Range(
                    position, lsp.Position(line - 1, end - 1))), here]
        return here

    @request(lsp.TEXT_DOCUMENT_REFERENCES)
    def references(ls: EpuckServer, params: lsp.ReferenceParams):
        doc = ls.doc(params.text_document.uri)
        analysis = doc.analyse()
        occ = navigate.occurrence_at(analysis, *ls.point(doc, analysis, params.position))
        target = navigate.resolve(analysis, occ) if occ is not None else None
        if target is None or target.statement is None:
            return []
        include = params.context.include_declaration if params.context else True
        return [lsp.Location(doc.uri, ls.range(doc, analysis, o.ident.span))
                for o in navigate.references(analysis, target, include)]

    symbol_kinds = {"robot": lsp.SymbolKind.Object, "const": lsp.SymbolKind.Constant,
                    "variable": lsp.SymbolKind.Variable,
                    "action": lsp.SymbolKind.Function, "extern action": lsp.SymbolKind.Function,
                    "extern event": lsp.SymbolKind.Event, "rule": lsp.SymbolKind.Event,
                    "mode": lsp.SymbolKind.Namespace}

    @request(lsp.TEXT_DOCUMENT_DOCUMENT_SYMBOL)
    def document_symbols(ls: EpuckServer, params: lsp.DocumentSymbolParams):
        doc = ls.doc(params.text_document.uri)
        analysis = doc.analyse()
        out = []
        for s in navigate.symbols(analysis):
            out.append(lsp.DocumentSymbol(
                name=s.name, detail=s.detail or s.kind, kind=symbol_kinds[s.kind],
                range=ls.range(doc, analysis, s.span),
                selection_range=ls.range(doc, analysis, s.selection)))
        return out

    @request(lsp.TEXT_DOCUMENT_PREPARE_RENAME)
    def prepare_rename(ls: EpuckServer, params: lsp.PrepareRenameParams):
        doc = ls.doc(params.text_document.uri)
        analysis = doc.analyse()
        occ = navigate.occurrence_at(analysis, *ls.point(doc, analysis, params.position))
        try:
            navigate.renameable(analysis, occ)
        except navigate.RenameError as exc:
            raise _RequestFailed(message=str(exc)) from None
        return lsp.PrepareRenamePlaceholder(ls.range(doc, analysis, occ.ident.span),
                                            occ.ident.name)

    @request(lsp.TEXT_DOCUMENT_RENAME, lsp.RenameOptions(prepare_provider=True))
    def rename(ls: EpuckServer, params: lsp.RenameParams):
        doc = ls.doc(params.text_document.uri)
        analysis = doc.analyse()
        occ = navigate.occurrence_at(analysis, *ls.point(doc, analysis, params.position))
        try:
            target = navigate.renameable(analysis, occ)
            edits = navigate.rename_edits(analysis, target, params.new_name)
        except navigate.RenameError as exc:
            raise _RequestFailed(message=str(exc)) from None
        return lsp.WorkspaceEdit(changes={doc.uri: [
            lsp.TextEdit(ls.range(doc, analysis, span), text) for span, text in edits]})

    @request(lsp.TEXT_DOCUMENT_CODE_ACTION,
             lsp.CodeActionOptions(code_action_kinds=[lsp.CodeActionKind.QuickFix]))
    def code_action(ls: EpuckServer, params: lsp.CodeActionParams):
        doc = ls.doc(params.text_document.uri)
        analysis = doc.analyse()
        lines = doc.lines(ls.encoding)
        first, last = lines.offset(params.range.start), lines.offset(params.range.end)
        actions = []
        for d in analysis.diagnostics:
            start = analysis.offset(d.span.line, d.span.column)
            end = analysis.offset(d.span.end_line, d.span.end_column)
            if end < first or start > last or not d.fixes:
                continue
            for fix in d.fixes:
                edit = lsp.TextEdit(ls.range(doc, analysis, fix.span), fix.text)
                old = analysis.text[analysis.offset(fix.span.line, fix.span.column):
                                    analysis.offset(fix.span.end_line, fix.span.end_column)]
                actions.append(lsp.CodeAction(
                    title=_fix_title(old, fix.text), kind=lsp.CodeActionKind.QuickFix,
                    diagnostics=[ls.diagnostic(doc, analysis, d)], is_preferred=len(d.fixes) == 1,
                    edit=lsp.WorkspaceEdit(changes={doc.uri: [edit]})))
        return actions

    @request(lsp.TEXT_DOCUMENT_FORMATTING)
    def formatting(ls: EpuckServer, params: lsp.DocumentFormattingParams):
        from .fmt import FormatError, format_text
        doc = ls.doc(params.text_document.uri)
        text = doc.text
        try:
            formatted = format_text(text, doc.path.name if doc.path else doc.uri)
        except FormatError as exc:
            first = exc.diagnostics[0] if exc.diagnostics else None
            where = f" (line {first.span.line}: {first.message})" if first else ""
            raise _RequestFailed(message=f"cannot format a file with syntax errors{where}") \
                from None
        lines = doc.lines(ls.encoding)
        return [lsp.TextEdit(lsp.Range(lines.position(start), lines.position(end)), new)
                for start, end, new in line_edits(text, formatted)]

    return server


def _fix_title(old: str, new: str) -> str:
    if not old:
        return f"Insert `{new.strip()}`"
    if not new:
        return f"Remove `{old}`"
    return f"Replace `{old}` with `{new}`"


def main() -> int:
    logging.basicConfig(level=logging.WARNING, stream=sys.stderr,
                        format="epuckc lsp: %(levelname)s: %(message)s")
    # pygls logs every error response with a traceback; ours are logged above
    logging.getLogger("pygls").setLevel(logging.CRITICAL)
    create_server().start_io()
    return 0
