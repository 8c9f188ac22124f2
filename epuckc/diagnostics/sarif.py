"""`epuckc check --format sarif`: diagnostics as a SARIF 2.1.0 log, the
format that code-scanning services of CI systems read.

One run; its tool's rules are the codes that occur, each with its short
description, the long explanation of `epuckc explain` as help (text and
Markdown) and its default level; each result points at its rule and its
region (lines and columns in Unicode code points, as epuckc counts them).
Notes with a position become related locations.
"""
from __future__ import annotations

import json
from pathlib import Path, PurePath
from urllib.parse import quote

from .. import __version__
from . import ERROR, Diagnostic, Report
from .codes import CODES, explanation

SCHEMA_URI = ("https://docs.oasis-open.org/sarif/sarif/v2.1.0/errata01/os/schemas/"
              "sarif-schema-2.1.0.json")
SRCROOT = "%SRCROOT%"


def _level(severity: str) -> str:
    return "error" if severity == ERROR else "warning"


def _first_paragraph(markdown: str) -> str:
    """The explanation's first paragraph after its `# CODE: title` line."""
    paragraphs = [p.strip() for p in markdown.split("\n\n") if p.strip()]
    body = [p for p in paragraphs if not p.startswith("#")]
    return " ".join(body[0].split()) if body else ""


def _rule(code: str, severity: str) -> dict:
    rule = {
        "id": code,
        "shortDescription": {"text": CODES.get(code, code)},
        "defaultConfiguration": {"level": _level(severity)},
    }
    text = explanation(code)
    if text:
        rule["fullDescription"] = {"text": _first_paragraph(text) or CODES.get(code, code)}
        rule["help"] = {"text": text, "markdown": text}
    return rule


def _artifact(file: str) -> dict:
    """A relative path stays relative to %SRCROOT% (the current folder);
    an absolute one becomes a file: URI."""
    path = PurePath(file)
    if path.is_absolute():
        return {"uri": Path(file).as_uri()}
    return {"uri": quote(path.as_posix()), "uriBaseId": SRCROOT}


def _region(span) -> dict:
    return {"startLine": span.line, "startColumn": span.column,
            "endLine": span.end_line, "endColumn": span.end_column}


def _location(file: str, span, message: str | None = None) -> dict:
    location = {"physicalLocation": {
        "artifactLocation": _artifact(file),
        "region": _region(span),
    }}
    if message is not None:
        location["message"] = {"text": message}
    return location


def _result(diag: Diagnostic, rule_index: int) -> dict:
    text = diag.message
    for note in diag.notes:
        if note.span is None:
            text += f"\nnote: {note.message}"
    if diag.help:
        text += f"\nhelp: {diag.help}"
    result = {
        "ruleId": diag.code,
        "ruleIndex": rule_index,
        "level": _level(diag.severity),
        "message": {"text": text},
        "locations": [_location(diag.file, diag.span)],
    }
    if diag.fixes:
        # SARIF's fix: the same edit the language server's quick fix makes
        result["fixes"] = [{
            "description": {"text": fix.help},
            "artifactChanges": [{
                "artifactLocation": _artifact(diag.file),
                "replacements": [{
                    "deletedRegion": _region(fix.span),
                    "insertedContent": {"text": fix.text},
                }],
            }],
        } for fix in diag.fixes]
    related = [note for note in diag.notes if note.span is not None]
    if related:
        result["relatedLocations"] = [
            dict(_location(diag.file, note.span, note.message), id=k)
            for k, note in enumerate(related)]
    return result


def sarif_log(report: Report, cwd: Path | None = None) -> dict:
    diags = report.sorted()
    codes = sorted({d.code for d in diags})
    severity = {d.code: d.severity for d in diags}
    index = {code: k for k, code in enumerate(codes)}
    root = (cwd or Path.cwd()).resolve().as_uri().rstrip("/") + "/"
    return {
        "$schema": SCHEMA_URI,
        "version": "2.1.0",
        "runs": [{
            "tool": {"driver": {
                "name": "epuckc",
                "version": __version__,
                "semanticVersion": __version__,
                "rules": [_rule(code, severity[code]) for code in codes],
            }},
            "originalUriBaseIds": {SRCROOT: {"uri": root}},
            "columnKind": "unicodeCodePoints",
            "results": [_result(d, index[d.code]) for d in diags],
        }],
    }


def render_sarif(report: Report) -> str:
    return json.dumps(sarif_log(report), indent=2, ensure_ascii=False) + "\n"
