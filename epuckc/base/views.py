"""A read-only view of a dict that notes what is read of it: a subclass
says what a look-up of one name notes (`get`) and what a look at the whole
table notes (`_all`, which returns the dict); the rest of a dict's reading
(`in`, `[]`, iteration, `len`, items(), keys(), values(), ...) goes
through those two. The checker's intervals (check/ranges.py) and the
language server's watched tables (ide/watch.py) are such views; `Overlaid`
is a table with some of its entries replaced (the variables a condition
narrows, each a VarInfo of its own)."""
from __future__ import annotations

MISSING = object()      # what `get` finds for a name the table lacks


class NotingView:
    __slots__ = ()

    def get(self, name, default=None):
        raise NotImplementedError

    def _all(self) -> dict:
        raise NotImplementedError

    def __getitem__(self, name):
        found = self.get(name, MISSING)
        if found is MISSING:
            raise KeyError(name)
        return found

    def __contains__(self, name):
        return self.get(name, MISSING) is not MISSING

    def __iter__(self):
        return iter(self._all())

    def __len__(self):
        return len(self._all())

    def __getattr__(self, attr):        # items(), keys(), values(), ...
        return getattr(self._all(), attr)


class Overlaid(NotingView):
    """`table` with the entries of `over` in place of its own for the
    names it has (each look-up goes to `table` first, so that a view
    there notes it as it would)."""
    __slots__ = ("_table", "_over")

    def __init__(self, table, over: dict):
        self._table, self._over = table, over

    def get(self, name, default=None):
        found = self._table.get(name, MISSING)
        if found is MISSING:
            return default
        return self._over.get(name, found)

    def _all(self) -> dict:
        table = self._table
        return {**(table._all() if isinstance(table, NotingView) else table), **self._over}
