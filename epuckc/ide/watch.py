"""What a rule looked up and said while it was checked, so that it can be
replayed (ide/recheck.py): its diagnostics and facts captured (_Capture),
its look-ups in the checker's tables noted (_Watched, _Watch)."""
from __future__ import annotations

from ..base.views import MISSING, NotingView
from ..check.checker import Checker
from ..diagnostics import Collector


class _Capture:
    """Run a step of the checker with fresh diagnostics and fresh sets of
    facts, and remember both, so that the step can be replayed.

    The checker's memories within one file (a constant's chain followed
    once, a problem of a definition said once) start empty too, so that
    the step does all its own lookups (and notes them, see _Watched) and
    says all its own diagnostics; what is said twice is dropped when the
    steps are put together (IncrementalChecker._replay), as the whole
    file's check says it once."""
    FACTS = ("called", "used_actions", "const_used", "vars_used", "vars_assigned",
             "devices_used")
    FRESH = ("_const_memo", "_const_reported", "_const_diagnostics")

    def __init__(self, checker: Checker):
        self.checker = checker

    def __enter__(self):
        c = self.checker
        fresh = [f for f in self.FRESH if hasattr(c, f)]
        self.saved = (c.diags, {f: getattr(c, f) for f in self.FACTS},
                      {f: getattr(c, f) for f in fresh})
        c.diags = Collector(c.diags.source)
        for f in self.FACTS:
            setattr(c, f, set())
        for f in fresh:
            setattr(c, f, type(getattr(c, f))())
        return self

    def __exit__(self, *exc):
        c = self.checker
        self.diags = c.diags.items
        self.facts = tuple((f, v) for f in self.FACTS if (v := getattr(c, f)))
        c.diags, saved_facts, saved_fresh = self.saved
        for f in self.FACTS:
            setattr(c, f, saved_facts[f])
        for f, value in saved_fresh.items():
            setattr(c, f, value)
        return False


_MISSING = MISSING
_ALL = object()
_TABLES = ("consts", "const_arrays", "actions", "externs", "broken_externs", "rule_names",
           "modes", "vars")


class _Watched(NotingView):
    """A read-only view of one of the checker's name tables that notes
    what a rule looked up in it: (table, name, what was found), or
    (table, _ALL, every entry) when it looked at the whole table (the
    candidates of a did-you-mean)."""
    __slots__ = ("_table", "_attr", "_deps")

    def __init__(self, table: dict, attr: str, deps: list):
        self._table, self._attr, self._deps = table, attr, deps

    def _all(self):
        self._deps.append((self._attr, _ALL, tuple(self._table.items())))
        return self._table

    def get(self, name, default=None):
        found = self._table.get(name, _MISSING)
        self._deps.append((self._attr, name, found))
        return default if found is _MISSING else found


class _Narrowing:
    """The watched table of variables as a guard's narrowing sees it
    (IncrementalChecker._guarded_body): its items are those of the
    variables the guard names, the only ones `conditions.narrowed` reads,
    so that the rule depends on them and not on every variable."""
    __slots__ = ("_watched", "_names")

    def __init__(self, watched: _Watched, names):
        self._watched, self._names = watched, sorted(names)

    def items(self):
        found = ((n, self._watched.get(n, _MISSING)) for n in self._names)
        return [(n, v) for n, v in found if v is not _MISSING]

    def get(self, name, default=None):
        return self._watched.get(name, default)

    def __contains__(self, name):
        return name in self._watched

    def __getitem__(self, name):
        return self._watched[name]

    def __iter__(self):
        return iter(self._watched)

    def __len__(self):
        return len(self._watched)

    def __getattr__(self, attr):
        return getattr(self._watched, attr)


class _Watch:
    """Check one rule with its name tables watched (see _Watched)."""

    def __init__(self, checker: Checker):
        self.checker = checker
        self.deps: list = []

    def __enter__(self):
        c = self.checker
        self.saved = [getattr(c, t) for t in _TABLES]
        for t, table in zip(_TABLES, self.saved):
            setattr(c, t, _Watched(table, t, self.deps))
        return self

    def __exit__(self, *exc):
        for t, table in zip(_TABLES, self.saved):
            setattr(self.checker, t, table)
        return False
