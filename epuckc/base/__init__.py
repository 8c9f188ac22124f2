"""The ground floor: what every stage uses and nothing above it.

- records.py: `@record`, light dataclass-like classes with slots;
- source.py: `SourceFile` and `Span` (1-based line and column);
- resources.py: where the grammar, templates, runtime and cache are;
- fingerprint.py: what epuckc's own files are, for the caches keyed on inputs;
- cache.py: the cache folder's rules for every cache (areas, whole entries,
  least-recently-used eviction under a bound, never an error);
- output.py: writing a file whole or not at all, `-` for standard output.

May import: nothing of epuckc.
"""
