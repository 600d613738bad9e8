"""The report's graph algorithms in C (`cpn.statespace.graphnative`) against the Python
reference on random graphs: the same SCCs numbered the same way, the same SCC-graph arcs, dead states,
live transition instances, arc labels, and the same place columns of packed states."""

from __future__ import annotations

import random
from array import array
from types import SimpleNamespace

import pytest

from cpn.checks.liveness import SccSummary, live_transitions
from cpn.statespace import graphnative
from cpn.statespace.graph import StateGraph
from cpn.statespace.scc import scc_graph_arcs, strongly_connected_components
from cpn.statespace.store import PackedStore, TupleStore, pack

pytestmark = pytest.mark.skipif(graphnative.library() is None, reason="no native code here")


@pytest.fixture(autouse=True)
def every_size(monkeypatch):
    monkeypatch.setattr(graphnative, "MIN_ITEMS", 0)


def _random_graph(rng: random.Random, partial: bool):
    """A random multigraph with self-loops; with `partial`, only the first states have arcs."""
    n = rng.randint(1, 60)
    expanded = rng.randint(0, n) if partial else n
    off, dst, lab = array("q", [0]), array("i"), array("i")
    ntrans = rng.randint(1, 5)
    for v in range(expanded):
        for _ in range(rng.choice((0, 1, 1, 2, 3, 5))):
            w = v if rng.random() < 0.05 else rng.randrange(n) if rng.random() < 0.5 else min(n - 1, v + rng.randint(-3, 3) % n)
            dst.append(w)
            lab.append(rng.randrange(ntrans))
        off.append(len(dst))
    return n, off, dst, lab, ntrans


def _decomposition(d):
    return (d.comp.tolist(), d.members.tolist(), d.start.tolist(), bytes(d.terminal), bytes(d.nontrivial))


@pytest.mark.parametrize("seed", range(300))
def test_native_sccs_are_the_python_ones(seed):
    rng = random.Random(seed)
    n, off, dst, _lab, _nt = _random_graph(rng, partial=seed % 3 == 0)
    native = strongly_connected_components(n, off, dst)
    python = strongly_connected_components(n, off, dst, native=False)
    assert _decomposition(native) == _decomposition(python)
    assert graphnative.scc(n, off, dst) is not None  # the native code did run
    assert scc_graph_arcs(native, off, dst) == scc_graph_arcs(python, off, dst, native=False)
    assert graphnative.scc_arcs(off, dst, native.comp, native.members, native.start) is not None


@pytest.mark.parametrize("seed", range(100))
def test_native_dead_states_and_live_transitions_are_the_python_ones(seed):
    rng = random.Random(1000 + seed)
    n, off, dst, lab, ntrans = _random_graph(rng, partial=False)
    g = StateGraph(store=TupleStore(states=list(range(n))), offsets=off, dst=dst)
    assert graphnative.dead_states(off) == g.dead_states()
    dec = strongly_connected_components(n, off, dst, native=False)
    x = SimpleNamespace(graph=g, engine=SimpleNamespace(transitions=list(range(ntrans))), complete=True)
    scc = SccSummary(dec, dec.count, 0, 0, 0, 0, 0.0)
    for code in "BHi":
        labels = array(code, lab)
        assert live_transitions(x, scc, labels) == live_transitions(x, scc, labels, native=False)
    assert graphnative.live(off, array("B", lab), ntrans, dec.comp, dec.members, dec.start, dec.terminal) is not None


@pytest.mark.parametrize("code", ["H", "i"])
def test_native_arc_ids(code):
    rng = random.Random(7)
    ids = array(code, [rng.randrange(300) for _ in range(2000)])
    table = [rng.randrange(200) for _ in range(300)]
    assert graphnative.distinct_ids(ids) == sorted(set(ids))
    assert graphnative.distinct_ids(array(code)) == []
    for out in "BHi":
        assert graphnative.map_ids(ids, table, out) == array(out, (table[i] for i in ids))


def test_native_place_columns_of_packed_states():
    rng = random.Random(3)
    # fields of 1, 2 and 4 bytes (values up to 70,000), then widened by a larger state
    states = [(rng.randrange(5), rng.randrange(300), rng.randrange(70000), rng.randrange(2)) for _ in range(500)]
    store = pack(TupleStore(states=list(dict.fromkeys(states))))
    assert isinstance(store, PackedStore) and store.kind == "packed"
    caps = [5, 300, 70000, 2]
    columns = graphnative.place_columns(store, caps)
    assert columns == [sorted({s[f] for s in store.states}) for f in range(4)]
    assert graphnative.place_columns(store, caps[:2]) == columns[:2]
    assert graphnative.place_columns(store, [5, 299, 70000, 2]) is None  # a value beyond its table
    tables = [[rng.randrange(10) for _ in range(c)] for c in caps]
    for fields in ([0], [1, 2], [0, 1, 2, 3]):
        want = max(sum(tables[f][s[f]] for f in fields) for s in store.states)
        assert graphnative.max_sum(store, fields, [tables[f] for f in fields]) == want
    assert graphnative.place_columns(TupleStore(states=states), caps) is None  # tuples: the Python code


def test_disabled_native_code_leaves_everything_to_python(monkeypatch):
    monkeypatch.setattr(graphnative, "enabled", False)
    off, dst = array("q", [0, 1, 2]), array("i", [1, 0])
    assert graphnative.scc(2, off, dst) is None and graphnative.dead_states(off) is None
    d = strongly_connected_components(2, off, dst)
    assert d.count == 1 and list(d.nontrivial) == [1]
