"""Editors: incremental analysis that re-checks only what an edit touched
(incremental.py), the language features as plain functions over it
(features.py: completion, hover, definitions, rename, symbols, fixes),
the formatter (fmt.py), and the JSON-RPC glue of `epuckc lsp` (lsp.py).

May import: base, diagnostics, stdlib, syntax, check.
"""
