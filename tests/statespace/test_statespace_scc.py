"""Tarjan on CSR arrays against networkx on random multigraphs (with avoided labels and dropped states)."""

import random
from array import array

import networkx as nx
import pytest

from cpn.statespace.scc import has_cycle, scc_graph_arcs, strongly_connected_components


def _random_graph(rng):
    n = rng.randint(1, 25)
    adj = [[(rng.randrange(n), rng.randrange(3)) for _ in range(rng.randint(0, 4))] for _ in range(n)]
    off, dst, lab = array("q", [0]), array("i"), array("B")
    for arcs in adj:
        dst.extend(w for w, _ in arcs)
        lab.extend(label for _, label in arcs)
        off.append(len(dst))
    return n, adj, off, dst, lab


@pytest.mark.parametrize("seed", range(40))
def test_tarjan_matches_networkx(seed):
    rng = random.Random(seed)
    n, adj, off, dst, lab = _random_graph(rng)
    for avoid in (None, 0, 1):
        keep = bytearray(rng.random() < 0.8 for _ in range(n)) if avoid == 1 else None
        d = strongly_connected_components(n, off, dst, lab if avoid is not None else None,
                                          avoid if avoid is not None else -1, keep)
        G = nx.MultiDiGraph()
        G.add_nodes_from(v for v in range(n) if keep is None or keep[v])
        G.add_edges_from((v, w) for v, arcs in enumerate(adj) for w, label in arcs
                         if label != avoid and (keep is None or (keep[v] and keep[w])))
        sccs = [frozenset(c) for c in nx.strongly_connected_components(G)]
        assert {frozenset(d.nodes(c)) for c in range(d.count)} == set(sccs)
        C = nx.condensation(nx.DiGraph(G), sccs)
        terminal = {frozenset(C.nodes[c]["members"]) for c in C if C.out_degree(c) == 0}
        assert {frozenset(d.nodes(c)) for c in d.terminal_components()} == terminal
        nontrivial = {c for c in sccs if len(c) > 1 or any(G.has_edge(v, v) for v in c)}
        assert {frozenset(d.nodes(c)) for c in range(d.count) if d.nontrivial[c]} == nontrivial
        assert has_cycle(n, off, dst, lab if avoid is not None else None,
                         avoid if avoid is not None else -1, keep) == bool(nontrivial)
        if avoid is None:
            between, pairs = scc_graph_arcs(d, off, dst)
            assert pairs == C.number_of_edges()
            comp = {v: i for i, c in enumerate(sccs) for v in c}
            assert between == sum(1 for v, w in G.edges() if comp[v] != comp[w])


def test_unexpanded_states_have_no_arcs():
    # 3 states, only state 0 expanded (0 -> 1, 0 -> 2): three trivial SCCs, two terminal
    d = strongly_connected_components(3, array("q", [0, 2]), array("i", [1, 2]))
    assert d.count == 3 and sorted(d.terminal_components()) == [0, 1]
