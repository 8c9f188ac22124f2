"""Editors: incremental analysis that re-checks only what an edit touched
(statements.py, pieces.py, incremental.py, recheck.py, passes.py,
watch.py, showing.py, documents.py), the language features as plain
functions over it (completion.py, hover.py, navigate.py: definitions,
references, rename, symbols), the formatter (fmt.py over layout.py), the
editors' word lists generated from the lexer and the table (wordlists.py),
and the JSON-RPC glue of `epuckc lsp` (lsp.py, the only module that
imports pygls).

May import: base, diagnostics, stdlib, syntax, check.
"""
