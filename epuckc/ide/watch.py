"""What a rule looked up while it was checked, so that it can be replayed
(ide/recheck.py): its look-ups in the declarations' name tables noted
(_Watched, watched). What it said and found is the checker's
`Checker.apart` (each step with its own diagnostics, facts and memories,
so that it does all of its own look-ups and says all of its own
problems; what is said twice is dropped when the steps are put together,
IncrementalChecker._replay, as the whole file's check says it once)."""
from __future__ import annotations

from ..base.views import MISSING, NotingView
from ..check.state import Declarations


_MISSING = MISSING
_ALL = object()


class _Watched(NotingView):
    """A read-only view of one of the declarations' name tables that notes
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


def watched(decls: Declarations, deps: list) -> Declarations:
    """`decls` with each of its name tables (Declarations.TABLES, DERIVED) seen
    through a _Watched that notes into `deps`: what a rule reads instead
    of the declarations themselves (Checker.apart)."""
    out = Declarations(*(getattr(decls, f) for f in Declarations.__match_args__))
    for t in Declarations.TABLES + Declarations.DERIVED:
        setattr(out, t, _Watched(getattr(decls, t), t, deps))
    return out
