"""State spaces of translated CPN Tools nets against CPN Tools' and cpncheck's published figures.

A tiny BFS and an iterative Tarjan live here so that these tests depend only on the engine protocol
(`cpn.load(path).engine()`, `initial_state`, `successors`), not on the explorer's API.
"""

from __future__ import annotations

import os
import subprocess
import sys
from dataclasses import dataclass

import pytest

import cpn
from cpn.io.cpntools import translate
from tests._shared import SHARED, needs_shared

SAMPLES = SHARED + "/cpntools-samples"
LIMIT = SHARED + "/validation/CPNBook-LimitProtocol/7-2LimitProtocol.cpn"
MAKE_NETS = SHARED + "/bench/make_cpn_nets.py"
BENCH_NETS = os.path.join(os.path.dirname(__file__), "..", "..", "bench", "nets")


@dataclass
class Space:
    nodes: int
    arcs: int
    dead: int
    complete: bool
    scc_nodes: int = 0
    scc_arcs: int = 0  # arcs of the occurrence graph between two different SCCs (CPN Tools' SCC graph)


def explore(path: str, max_states: int = 100_000, scc: bool = True) -> Space:
    engine = cpn.load(path).engine()
    s0 = engine.initial_state()
    index = {s0: 0}
    succ: list[list[int]] = []
    frontier = [s0]
    arcs = 0
    complete = True
    i = 0
    while i < len(frontier):
        if len(index) > max_states:
            complete = False
            break
        out = []
        for _be, s1 in engine.successors(frontier[i]):
            j = index.get(s1)
            if j is None:
                j = index[s1] = len(frontier)
                frontier.append(s1)
            out.append(j)
        arcs += len(out)
        succ.append(out)
        i += 1
    dead = sum(1 for out in succ if not out)
    space = Space(len(index), arcs, dead, complete)
    if scc and complete:
        comp = _tarjan(succ)
        space.scc_nodes = max(comp) + 1 if comp else 0
        # CPN Tools keeps one SCC-graph arc per occurrence-graph arc between two SCCs: the limit
        # protocol's 37,312 SCC arcs join only 20,154 distinct pairs of SCCs.
        space.scc_arcs = sum(1 for a, out in enumerate(succ) for b in out if comp[a] != comp[b])
    return space


def _tarjan(succ: list[list[int]]) -> list[int]:
    n = len(succ)
    index = [-1] * n
    low = [0] * n
    comp = [-1] * n
    on = [False] * n
    stack: list[int] = []
    counter = 0
    ncomp = 0
    for root in range(n):
        if index[root] != -1:
            continue
        work = [(root, 0)]
        while work:
            v, k = work.pop()
            if k == 0:
                index[v] = low[v] = counter
                counter += 1
                stack.append(v)
                on[v] = True
            if k < len(succ[v]):
                work.append((v, k + 1))
                w = succ[v][k]
                if index[w] == -1:
                    work.append((w, 0))
                elif on[w]:
                    low[v] = min(low[v], index[w])
                continue
            if low[v] == index[v]:
                while True:
                    w = stack.pop()
                    on[w] = False
                    comp[w] = ncomp
                    if w == v:
                        break
                ncomp += 1
            if work:
                u = work[-1][0]
                low[u] = min(low[u], low[v])
    return comp


@needs_shared
def test_dining_philosophers_11_nodes_30_arcs_1_scc():
    s = explore(f"{SAMPLES}/DiningPhilosophers.cpn")
    assert (s.nodes, s.arcs, s.dead, s.scc_nodes) == (11, 30, 0, 1)


@needs_shared
def test_limit_protocol_matches_the_cpn_tools_report():
    s = explore(LIMIT, max_states=20_000)
    assert (s.nodes, s.arcs, s.dead, s.complete) == (13_215, 52_784, 1, True)
    assert (s.scc_nodes, s.scc_arcs) == (5_013, 37_312)


# Samples with a finite state space that cpncheck explored completely (CPNCHECK.md), and ours:
# (nodes, arcs, SCC nodes, dead markings).
FINITE = {
    "DiningPhilosophers_ASKCTL": (8, 10, 6, 2),
    "DiningPhilosophers_COMM_Mon": (243, 945, 3, 2),
    # cpncheck refuses the code segments (acceptConnection); with them emptied it gives these figures
    "DiningPhilosophers_COMM": (245, 948, 5, 1),
    "DistributedDataBase": (109, 224, 1, 0),
    "DistributedDataBase_OG": (28, 42, 1, 0),
    "ResourceAllocation_OG": (13, 20, 1, 0),
    "ResourceAllocation_OG_Graphviz": (13, 20, 1, 0),
    "SimpleProtocol_OG": (428, 1130, 182, 1),
    "priorities": (50, 77, 50, 1),
}


@needs_shared
@pytest.mark.parametrize("name", sorted(FINITE))
def test_finite_samples_match_cpncheck(name):
    s = explore(f"{SAMPLES}/{name}.cpn", max_states=5_000)
    assert s.complete
    assert (s.nodes, s.arcs, s.scc_nodes, s.dead) == FINITE[name]


# Samples whose state space is large or infinite: the first states explore without an error.
LARGE = ["HierarchicalProtocol", "ProtocolWithTimer", "ResourceAllocation", "RingProtocol",
         "SimpleProtocol", "SimpleProtocol_RP", "Telephones", "TimedProtocol", "TimedResourceAlloc"]


@needs_shared
@pytest.mark.parametrize("name", LARGE)
def test_large_samples_explore(name):
    s = explore(f"{SAMPLES}/{name}.cpn", max_states=1_500, scc=False)
    assert s.nodes > 1


@needs_shared
def test_round_trip_through_cpnet_text_gives_the_same_state_space(tmp_path):
    for name in ["DiningPhilosophers", "ResourceAllocation_OG", "SimpleProtocol_OG", "priorities"]:
        path = tmp_path / f"{name}.cpnet"
        path.write_text(translate(f"{SAMPLES}/{name}.cpn"))
        a = explore(f"{SAMPLES}/{name}.cpn", max_states=5_000)
        b = explore(str(path), max_states=5_000)
        assert (a.nodes, a.arcs, a.dead, a.scc_nodes) == (b.nodes, b.arcs, b.dead, b.scc_nodes), name


@pytest.fixture(scope="module")
def bench_cpn(tmp_path_factory):
    out = tmp_path_factory.mktemp("cpnnets")
    subprocess.run([sys.executable, MAKE_NETS, str(out)], check=True)
    return out


# Figures of shared/bench/BENCHMARKS.md (reference_counts.py).
BENCH = {("dp", 5): (82, 265), ("dp", 8): (1_154, 5_968), ("ms", 4): (3_321, 17_172)}


@needs_shared
@pytest.mark.parametrize("net,n", sorted(BENCH))
def test_bench_nets_match_the_published_counts(bench_cpn, net, n):
    s = explore(str(bench_cpn / f"{net}_{n}.cpn"), scc=False)
    assert (s.nodes, s.arcs) == BENCH[(net, n)]


@needs_shared
@pytest.mark.parametrize("net,n", [("dp", 5), ("ms", 3)])
def test_bench_cpn_equals_our_cpnet_version(bench_cpn, net, n):
    ours = os.path.join(BENCH_NETS, f"{net}.cpnet")
    model = cpn.load(ours, set={"N": n})
    a = explore(str(bench_cpn / f"{net}_{n}.cpn"), scc=False)
    b = _explore_model(model)
    assert (a.nodes, a.arcs, a.dead) == (b.nodes, b.arcs, b.dead)


def _explore_model(model) -> Space:
    engine = model.engine()
    s0 = engine.initial_state()
    seen = {s0}
    frontier = [s0]
    arcs = dead = 0
    while frontier:
        nxt = []
        for s in frontier:
            succ = list(engine.successors(s))
            arcs += len(succ)
            dead += not succ
            for _be, s1 in succ:
                if s1 not in seen:
                    seen.add(s1)
                    nxt.append(s1)
        frontier = nxt
    return Space(len(seen), arcs, dead, True)
