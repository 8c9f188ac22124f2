"""The variables' components kept in place after an edit
(check/dependencies.py, `regraph_in_place`, issue 31): when it says it
could, the components are exactly those found afresh (the same members,
each as `components` orders them), in an order where what a component
reads comes before it, with each component's reads and the readers of
each variable those of the new graph."""
from __future__ import annotations

import random

from hypothesis import given, settings
from hypothesis import strategies as st

from epuckc.check.dependencies import components, order_components, regraph_in_place


def _graph(rng: random.Random, names: list, density: float) -> dict:
    return {n: sorted(m for m in names if rng.random() < density) for n in names}


def _check(order: list, readers: dict, place: dict, graph: dict) -> None:
    fresh, fresh_readers, _ = order_components(graph)
    assert sorted(c[0] for c in order) == sorted(c[0] for c in fresh)
    for at, (members, inside, reads) in enumerate(order):
        assert inside == frozenset(members)
        assert reads == inside.union(*(graph[m] for m in members))
        assert all(place[m] == at for m in members)
        assert all(place[v] <= at for m in members for v in graph[m])    # dependencies first
    by_members = {c[0]: at for at, c in enumerate(order)}
    assert {n: sorted(ats) for n, ats in readers.items()} == {
        n: sorted(by_members[fresh[at][0]] for at in ats) for n, ats in fresh_readers.items()}


@settings(max_examples=300, deadline=None)
@given(seed=st.integers(0, 10**6), size=st.integers(1, 14), density=st.floats(0.0, 0.4),
       edits=st.integers(1, 6))
def test_components_kept_in_place_are_those_found_afresh(seed, size, density, edits):
    rng = random.Random(seed)
    names = [f"v{i}" for i in range(size)]
    graph = _graph(rng, names, density)
    order, readers, place = order_components(graph)
    for _ in range(edits):
        new = dict(graph)
        changed = rng.sample(names, rng.randint(1, min(3, size)))
        for name in changed:
            deps = set(new[name])
            for m in rng.sample(names, rng.randint(0, size)):
                if rng.random() < 0.5:
                    deps.symmetric_difference_update({m})
            new[name] = sorted(deps)
        if regraph_in_place(order, readers, place, new, graph, changed):
            _check(order, readers, place, new)
        else:
            order, readers, place = order_components(new)
        graph = new


def test_a_component_that_splits_or_joins_is_found_afresh():
    """(The property compares something: edges that split a component, or
    join two, are refused; one taken out of a cycle that stays is not.)"""
    cycle = {"a": ["b"], "b": ["c"], "c": ["a", "b"], "d": ["a"]}
    order, readers, place = order_components(cycle)
    split = dict(cycle, c=["b"])        # c no longer reads a: a, then b and c
    assert not regraph_in_place(list(order), dict(readers), dict(place), split, cycle, ["c"])
    joined = dict(cycle, a=["b", "d"])  # d reads a, a now reads d
    assert not regraph_in_place(list(order), dict(readers), dict(place), joined, cycle, ["a"])
    kept = dict(cycle, c=["a"])         # a -> b -> c -> a still
    assert regraph_in_place(order, readers, place, kept, cycle, ["c"])
    _check(order, readers, place, kept)
    assert len(components(kept)) == 2
