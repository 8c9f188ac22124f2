"""`epuckc lsp` end to end: a pytest-lsp client drives the server, which
runs as a subprocess, through a real session."""
from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import pytest
from lsprotocol import types as lsp

from .conftest import REPO, expect_diagnostics, open_doc

pytestmark = pytest.mark.asyncio

PROGRAM = """\
const D = 50 cm
const fast = 300 steps/s
action go = start_straight(fast, D)
rule patrol: on timer(2 s) repeat do set_timer, go
on immediate do start_sensor, set_timer, go
on sensor(ir0 > 300) priority 1 do cancel patrol, stop_motor
on stop_motor do exit_main
"""


def check_json(path: Path) -> list:
    out = subprocess.run([sys.executable, "-m", "epuckc", "check", "--format", "json", path.name],
                         cwd=path.parent, capture_output=True, text=True,
                         env={"PYTHONPATH": str(REPO), "PATH": "/usr/bin:/bin"})
    return json.loads(out.stdout)


def _epuckc_position(text: str, p: lsp.Position) -> tuple:
    """epuckc's (line, column) of an LSP position: LSP lines end at \r\n,
    \r or \n and count UTF-16 units; epuckc's lines are SourceFile's and
    count characters."""
    import bisect
    import re
    from epuckc.ide.statements import line_starts
    starts = [0] + [m.end() for m in re.finditer(r"\r\n|\r|\n", text)]
    offset = starts[p.line]
    units = 0
    while units < p.character:
        units += 2 if ord(text[offset]) > 0xFFFF else 1
        offset += 1
    ours = line_starts(text)
    line = bisect.bisect_right(ours, offset)
    return line, offset - ours[line - 1] + 1


def as_check(diags, text: str = None) -> list:
    """LSP diagnostics in `epuckc check --format json`'s terms."""
    out = []
    for d in diags:
        message, _, help_ = d.message.partition("\nhelp: ")
        message = message.split("\nnote: ")[0]
        if text is None:
            (line, column), (end_line, end_column) = [
                (p.line + 1, p.character + 1) for p in (d.range.start, d.range.end)]
        else:
            (line, column), (end_line, end_column) = [
                _epuckc_position(text, p) for p in (d.range.start, d.range.end)]
        out.append({"code": d.code, "severity": "error" if d.severity == 1 else "warning",
                    "message": message, "line": line, "column": column, "end_line": end_line,
                    "end_column": end_column, "help": help_ or None})
    return sorted(out, key=lambda d: (d["line"], d["column"], d["code"], d["message"]))


def from_check(items, text: str = None) -> list:
    keep = ("code", "severity", "message", "line", "column", "end_line", "end_column", "help")
    items = [{k: d[k] for k in keep} for d in items]
    if text is not None:
        # LSP has no position between the \r and the \n of a line end: such
        # a position can only be sent as the one before the \r
        from epuckc.ide.statements import line_starts
        starts = line_starts(text)
        for d in items:
            for line, column in (("line", "column"), ("end_line", "end_column")):
                offset = starts[d[line] - 1] + d[column] - 1
                if 0 < offset < len(text) and text[offset - 1] == "\r" and text[offset] == "\n":
                    d[column] -= 1
    return sorted(items, key=lambda d: (d["line"], d["column"], d["code"], d["message"]))


def pos(text: str, needle: str, nth: int = 0, shift: int = 0) -> lsp.Position:
    """The position of the nth occurrence of `needle`, plus `shift` characters."""
    at = -1
    for _ in range(nth + 1):
        at = text.index(needle, at + 1)
    at += shift
    line = text.count("\n", 0, at)
    return lsp.Position(line, at - (text.rfind("\n", 0, at) + 1))


async def test_diagnostics_after_open_are_those_of_check(client, tmp_path):
    text = ("const D = 5 cm\n"
            "action go = strat_straight(300, D)\n"
            "action go = stop_motor\n"
            "on immediate do go, start_curve(radius: 1 cm, degrees: 90 deg, sped: 200)\n")
    path = tmp_path / "bad.epk"
    path.write_text(text)
    uri = path.resolve().as_uri()
    waiting = expect_diagnostics(client, uri, 1)
    open_doc(client, path, text)
    diags = await waiting
    assert as_check(diags) == from_check(check_json(path))
    assert {d.code for d in diags} >= {"E011", "E015", "E014"}
    for d in diags:
        assert d.source == "epuckc"
        explained = Path(d.code_description.href.removeprefix("file://"))
        assert explained.name == f"{d.code}.md" and explained.read_text().startswith(f"# {d.code}:")
    twice = next(d for d in diags if d.code == "E015")
    (first,) = twice.related_information
    assert first.location.uri == uri and first.location.range.start == lsp.Position(1, 7)
    assert first.message == "first defined here"


async def test_diagnostics_follow_edits(client, tmp_path):
    path = tmp_path / "prog.epk"
    uri = path.resolve().as_uri()
    waiting = expect_diagnostics(client, uri, 1)
    open_doc(client, path, PROGRAM)
    assert list(await waiting) == []
    # misspell `stop_motor` in the last-but-one rule, one keystroke at a time
    start = pos(PROGRAM, "stop_motor\n", 0, 5)
    waiting = expect_diagnostics(client, uri, 3)
    for version, (text, at) in enumerate((("e", start), ("r", lsp.Position(start.line, start.character + 1))), 2):
        client.text_document_did_change(lsp.DidChangeTextDocumentParams(
            lsp.VersionedTextDocumentIdentifier(uri=uri, version=version),
            [lsp.TextDocumentContentChangePartial(range=lsp.Range(at, at), text=text)]))
    diags = await waiting
    assert [(d.code, d.range.start.line) for d in diags] == [("E011", 5)]
    assert "did you mean `stop_motor`?" in diags[0].message
    # and the whole text replaced
    waiting = expect_diagnostics(client, uri, 4)
    client.text_document_did_change(lsp.DidChangeTextDocumentParams(
        lsp.VersionedTextDocumentIdentifier(uri=uri, version=4),
        [lsp.TextDocumentContentChangeWholeDocument(text=PROGRAM)]))
    assert list(await waiting) == []


async def _opened(client, tmp_path, text=PROGRAM, name="prog.epk"):
    path = tmp_path / name
    path.write_text(text)
    uri = path.resolve().as_uri()
    waiting = expect_diagnostics(client, uri, 1)
    open_doc(client, path, text)
    await waiting
    return uri


def _doc(uri):
    return lsp.TextDocumentIdentifier(uri=uri)


async def test_hover(client, tmp_path):
    uri = await _opened(client, tmp_path)
    hover = await client.text_document_hover_async(
        lsp.HoverParams(_doc(uri), pos(PROGRAM, "start_straight", 0, 3)))
    text = hover.contents.value
    assert "start_straight(speed: speed, distance: distance)" in text
    assert "drives straight" in text and "steps/s" in text and "[E030]" in text
    # an argument: what it becomes on the robot, by the checker's conversion
    hover = await client.text_document_hover_async(
        lsp.HoverParams(_doc(uri), pos(PROGRAM, "D)")))
    assert "D = 3,882 steps at this robot's geometry" in hover.contents.value
    assert "const D = 50 cm" in hover.contents.value
    # a const's definition
    hover = await client.text_document_hover_async(lsp.HoverParams(_doc(uri), pos(PROGRAM, "fast")))
    assert "300 steps/s = 300 steps/s" in hover.contents.value
    # a rule name after `cancel`: its rule
    hover = await client.text_document_hover_async(
        lsp.HoverParams(_doc(uri), pos(PROGRAM, "patrol", 1)))
    assert "rule patrol: on timer(2 s) repeat do set_timer, go" in hover.contents.value
    # nothing there
    assert await client.text_document_hover_async(
        lsp.HoverParams(_doc(uri), lsp.Position(0, 0))) is None


async def _complete(client, tmp_path, tail):
    text = PROGRAM + tail
    uri = await _opened(client, tmp_path, text, "c.epk")
    lines = text.split("\n")
    result = await client.text_document_completion_async(lsp.CompletionParams(
        _doc(uri), lsp.Position(len(lines) - 1, len(lines[-1]))))
    return [item.label for item in result.items]


async def test_completion(client, tmp_path):
    # `enter` first, then the standard events of the table in its order
    from epuckc.stdlib.table import EVENTS
    assert await _complete(client, tmp_path, "on ") == ["enter"] + [
        e.name for e in EVENTS if not e.head and e.name != "enter"]
    labels = await _complete(client, tmp_path, "on immediate do ")
    assert {"cancel", "start_straight", "exit_main", "go"} <= set(labels)
    assert await _complete(client, tmp_path, "on immediate do cancel ") == ["patrol"]
    labels = await _complete(client, tmp_path, "on immediate do start_straight(speed: 3, ")
    assert labels == ["distance"]
    labels = await _complete(client, tmp_path, "on immediate do start_straight(")
    # the parameters and the constants first, then what an expression reads
    assert labels[:3] == ["speed", "distance", "fast"]
    assert {"ir0", "heading", "clamp", "random"} <= set(labels[3:])
    labels = await _complete(client, tmp_path, "on immediate do start_straight(300, 20 ")
    assert labels == ["cm", "m", "mm", "steps"]
    assert await _complete(client, tmp_path, "on timer(3 ") == ["ms", "s"]
    assert await _complete(client, tmp_path, "on sensor(ir1 > 30, ") == [
        "ir0", "ir2", "ir3", "ir4", "ir5", "ir6", "ir7"]
    assert await _complete(client, tmp_path, "on immediate ") == ["do", "if", "priority", "repeat"]


async def test_definition_references_and_symbols(client, tmp_path):
    uri = await _opened(client, tmp_path)
    found = await client.text_document_definition_async(
        lsp.DefinitionParams(_doc(uri), pos(PROGRAM, "go", 2)))
    assert found.uri == uri and found.range.start == pos(PROGRAM, "go")
    refs = await client.text_document_references_async(lsp.ReferenceParams(
        text_document=_doc(uri), position=pos(PROGRAM, "D)"),
        context=lsp.ReferenceContext(include_declaration=True)))
    assert [r.range.start for r in refs] == [pos(PROGRAM, "D ="), pos(PROGRAM, "D)")]
    symbols = await client.text_document_document_symbol_async(
        lsp.DocumentSymbolParams(_doc(uri)))
    assert [s.name for s in symbols] == ["D", "fast", "go", "patrol", "on immediate",
                                         "on sensor(ir0 > 300)", "on stop_motor"]


async def test_definition_of_an_extern_is_its_c_function(client, tmp_path):
    (tmp_path / "spin.c").write_text((REPO / "examples" / "spin.c").read_text())
    text = (REPO / "examples" / "extern_spin.epk").read_text()
    uri = await _opened(client, tmp_path, text, "extern_spin.epk")
    found = await client.text_document_definition_async(
        lsp.DefinitionParams(_doc(uri), pos(text, "spin(turns: 2")))
    c_file = next(f for f in found if f.uri.endswith("spin.c"))
    c_text = (tmp_path / "spin.c").read_text()
    assert c_file.range.start == pos(c_text, "spin(void *param)")


async def test_rename(client, tmp_path):
    uri = await _opened(client, tmp_path)
    edit = await client.text_document_rename_async(lsp.RenameParams(
        text_document=_doc(uri), position=pos(PROGRAM, "patrol", 1), new_name="guard"))
    edits = edit.changes[uri]
    assert sorted(e.range.start for e in edits) == [pos(PROGRAM, "patrol"), pos(PROGRAM, "patrol", 1)]
    assert all(e.new_text == "guard" for e in edits)
    for bad, why in (("2x", "is not a name"), ("on", "is a keyword")):
        with pytest.raises(Exception, match=why):
            await client.text_document_rename_async(lsp.RenameParams(
                text_document=_doc(uri), position=pos(PROGRAM, "patrol"), new_name=bad))
    with pytest.raises(Exception, match="already a const named `D`"):
        await client.text_document_rename_async(lsp.RenameParams(
            text_document=_doc(uri), position=pos(PROGRAM, "fast"), new_name="D"))
    with pytest.raises(Exception, match="standard action"):
        await client.text_document_rename_async(lsp.RenameParams(
            text_document=_doc(uri), position=pos(PROGRAM, "go = "), new_name="stop_motor"))
    with pytest.raises(Exception, match="standard"):
        await client.text_document_prepare_rename_async(lsp.PrepareRenameParams(
            _doc(uri), pos(PROGRAM, "set_timer")))


def _apply(text: str, edits) -> str:
    lines = text.split("\n")
    offsets = [0]
    for line in lines:
        offsets.append(offsets[-1] + len(line) + 1)
    def at(p):
        return offsets[p.line] + p.character
    for e in sorted(edits, key=lambda e: at(e.range.start), reverse=True):
        text = text[:at(e.range.start)] + e.new_text + text[at(e.range.end):]
    return text


async def test_quick_fixes(client, tmp_path):
    text = ("const D = 5 cm\n"
            "on immediate strat_sensor, start_straight(speed = 300, distance: D)\n"
            "on sensor(ir8 > 300.5) priority 1 do stop_motr\n")
    uri = await _opened(client, tmp_path, text, "fix.epk")
    fixed = text
    for _ in range(10):     # apply the first quick fix until none is left
        path = tmp_path / "fix.epk"
        path.write_text(fixed)
        waiting = expect_diagnostics(client, uri)
        client.text_document_did_save(lsp.DidSaveTextDocumentParams(text_document=_doc(uri), text=fixed))
        diags = await waiting
        actions = await client.text_document_code_action_async(lsp.CodeActionParams(
            text_document=_doc(uri), range=lsp.Range(lsp.Position(0, 0), lsp.Position(3, 0)),
            context=lsp.CodeActionContext(diagnostics=list(diags))))
        if not actions:
            break
        action = actions[0]
        assert action.kind == lsp.CodeActionKind.QuickFix and action.diagnostics
        fixed = _apply(fixed, action.edit.changes[uri])
    assert fixed == ("const D = 5 cm\n"
                     "on immediate do start_sensor, start_straight(speed: 300, distance: D)\n"
                     "on sensor(ir7 > 301) priority 1 do stop_motor\n")
    assert check_json(tmp_path / "fix.epk") == []


# ---- it never dies --------------------------------------------------------------

def _utf16_position(text: str, offset: int) -> lsp.Position:
    """LSP position (lines end at \\r\\n, \\r or \\n; UTF-16 columns)."""
    import re
    line, start = 0, 0
    for m in re.finditer(r"\r\n|\r|\n", text[:offset]):
        line, start = line + 1, m.end()
    before = text[start:offset]
    return lsp.Position(line, len(before.encode("utf-16-le")) // 2)


FRAGMENTS = ["on ", "rule r", ": ", "do ", "then ", ", ", "(", ")", "start_straight(300, 2 m)",
             "stop_motor", "cancel r", "const K = 5 cm\n", "action a = ", "timer(2 s)", "sensor(",
             "ir0 > 300", "\n", "\r\n", "\r", "#", " # é comment\n", "\"x.c\"", "extern action e() from ",
             "é", "\U0001F600", "@", "robot { axle: 53 mm }", "=", ":", "-", "1.5", "steps/s",
             "repeat ", "exit_main", "K", "a", "\t", "}", "{", "\"", "999999999999 m"]


async def test_a_burst_of_random_edits_leaves_it_alive_and_right(client, tmp_path):
    import random
    rng = random.Random(8)
    path = tmp_path / "fuzz.epk"
    text = PROGRAM
    uri = await _opened(client, tmp_path, text, "fuzz.epk")
    version = 1
    for step in range(250):
        start = rng.randint(0, len(text))
        end = min(len(text), start + rng.choice([0, 0, 1, 2, 5, 20]))
        # never cut a \r\n in two: LSP positions cannot point between them
        while 0 < start < len(text) and text[start - 1] == "\r" and text[start] == "\n":
            start -= 1
        while 0 < end < len(text) and text[end - 1] == "\r" and text[end] == "\n":
            end += 1
        end = max(start, end)
        new = "".join(rng.choice(FRAGMENTS) for _ in range(rng.choice([0, 1, 1, 2, 3])))
        change = lsp.TextDocumentContentChangePartial(
            range=lsp.Range(_utf16_position(text, start), _utf16_position(text, end)), text=new)
        text = text[:start] + new + text[end:]
        version += 1
        client.text_document_did_change(lsp.DidChangeTextDocumentParams(
            lsp.VersionedTextDocumentIdentifier(uri=uri, version=version), [change]))
        if step % 10 == 0:      # requests at random places while the text changes
            where = _utf16_position(text, rng.randint(0, len(text)))
            doc = _doc(uri)
            await client.text_document_hover_async(lsp.HoverParams(doc, where))
            await client.text_document_completion_async(lsp.CompletionParams(doc, where))
            await client.text_document_definition_async(lsp.DefinitionParams(doc, where))
            await client.text_document_references_async(lsp.ReferenceParams(
                text_document=doc, position=where,
                context=lsp.ReferenceContext(include_declaration=True)))
            await client.text_document_document_symbol_async(lsp.DocumentSymbolParams(doc))
            await client.text_document_code_action_async(lsp.CodeActionParams(
                text_document=doc, range=lsp.Range(lsp.Position(0, 0), where),
                context=lsp.CodeActionContext(diagnostics=[])))
            try:
                await client.text_document_rename_async(lsp.RenameParams(
                    text_document=doc, position=where, new_name="zz"))
            except Exception as exc:
                assert "failed:" not in str(exc)        # a refusal, not a crash
    waiting = expect_diagnostics(client, uri, version + 1)
    client.text_document_did_change(lsp.DidChangeTextDocumentParams(
        lsp.VersionedTextDocumentIdentifier(uri=uri, version=version + 1),
        [lsp.TextDocumentContentChangePartial(
            range=lsp.Range(_utf16_position(text, len(text)), _utf16_position(text, len(text))),
            text="\n")]))
    text += "\n"
    diags = await waiting
    path.write_text(text, encoding="utf-8", newline="")
    assert as_check(diags, text) == from_check(check_json(path), text)


async def test_unknown_documents_bad_positions_and_bad_requests(client, tmp_path):
    uri = await _opened(client, tmp_path)
    unknown = _doc("file:///nowhere/never-opened.epk")
    with pytest.raises(Exception, match="not open"):
        await client.text_document_hover_async(lsp.HoverParams(unknown, lsp.Position(0, 0)))
    # notifications about unknown documents are ignored
    client.text_document_did_change(lsp.DidChangeTextDocumentParams(
        lsp.VersionedTextDocumentIdentifier(uri=unknown.uri, version=3),
        [lsp.TextDocumentContentChangeWholeDocument(text="on")]))
    client.text_document_did_close(lsp.DidCloseTextDocumentParams(unknown))
    client.text_document_did_save(lsp.DidSaveTextDocumentParams(text_document=unknown))
    # positions far outside the text are clamped
    far = lsp.Position(10_000, 10_000)
    await client.text_document_hover_async(lsp.HoverParams(_doc(uri), far))
    await client.text_document_completion_async(lsp.CompletionParams(_doc(uri), far))
    client.text_document_did_change(lsp.DidChangeTextDocumentParams(
        lsp.VersionedTextDocumentIdentifier(uri=uri, version=2),
        [lsp.TextDocumentContentChangePartial(range=lsp.Range(far, lsp.Position(0, 0)),
                                              text="# reversed range\n")]))
    # still alive and answering
    waiting = expect_diagnostics(client, uri, 3)
    client.text_document_did_change(lsp.DidChangeTextDocumentParams(
        lsp.VersionedTextDocumentIdentifier(uri=uri, version=3),
        [lsp.TextDocumentContentChangeWholeDocument(text="on immediate do strat_sensor\n")]))
    assert [d.code for d in await waiting] == ["E011"]
    client.text_document_did_close(lsp.DidCloseTextDocumentParams(_doc(uri)))


async def test_formatting(client, tmp_path):
    from epuckc.ide.fmt import format_text
    text = ("# a messy file\n"
            "const   D=50 cm\n\n\n"
            "on immediate do start_straight( 300 steps / s,D ) # go\n"
            "on stop_motor   do exit_main\n")
    uri = await _opened(client, tmp_path, text, "messy.epk")
    edits = await client.text_document_formatting_async(lsp.DocumentFormattingParams(
        text_document=_doc(uri), options=lsp.FormattingOptions(tab_size=4, insert_spaces=True)))
    assert edits and _apply(text, edits) == format_text(text, "messy.epk")
    assert len(edits) < len(text.split("\n"))       # the unchanged lines are left alone
    # a file with syntax errors is not formatted, and the error says why
    waiting = expect_diagnostics(client, uri, 2)
    client.text_document_did_change(lsp.DidChangeTextDocumentParams(
        lsp.VersionedTextDocumentIdentifier(uri=uri, version=2),
        [lsp.TextDocumentContentChangeWholeDocument(text="on immediate start_sensor\n")]))
    await waiting
    with pytest.raises(Exception, match="syntax errors .line 1: expected"):
        await client.text_document_formatting_async(lsp.DocumentFormattingParams(
            text_document=_doc(uri), options=lsp.FormattingOptions(tab_size=4, insert_spaces=True)))
