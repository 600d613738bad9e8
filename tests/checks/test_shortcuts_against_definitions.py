"""The report's shortcuts agree with the plain definitions of docs/statespace.md.

Fairness is decided with SCC shortcuts, walks and confined searches (cpn/checks/fairness.py); here it
is compared on random labelled graphs with the definitions applied literally (networkx on G - t).
Bounds are read from the distinct markings of each place; here they are compared with a pass over
every state's marking, on the compiled and on the reference engine.
"""

from __future__ import annotations

import importlib
import os
import sys
from array import array
from contextlib import contextmanager
from types import SimpleNamespace

import networkx as nx
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from cpn.checks import Fairness, TransitionIndex, boundedness, fairness
from cpn.statespace import ExploreOptions, Explorer, graphnative
from cpn.statespace.graph import StateGraph
from cpn.statespace.scc import strongly_connected_components
from cpn.statespace.store import TupleStore

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "statespace"))
fairness_module = importlib.import_module("cpn.checks.fairness")  # the module, not the function


# ---------------------------------------------------------------------- fairness on random graphs

def _graph(n: int, arcs: list[tuple[int, int, int]]) -> StateGraph:
    arcs = sorted(arcs, key=lambda a: a[0])  # CSR: the arcs of each state together, in a stable order
    g = StateGraph(store=TupleStore(states=list(range(n))))
    g.offsets = array("q", [0])
    g.dst = array("i")
    g.bes = array("i")
    for v in range(n):
        for s, d, t in arcs:
            if s == v:
                g.dst.append(d)
                g.bes.append(t)
        g.offsets.append(len(g.dst))
    return g


def _plain(n: int, arcs, ntrans: int) -> dict[int, Fairness] | None:
    """The definitions of docs/statespace.md, literally."""
    whole = nx.DiGraph()
    whole.add_nodes_from(range(n))
    whole.add_edges_from((s, d) for s, d, _ in arcs)
    if nx.is_directed_acyclic_graph(whole):
        return None
    out = {}
    for t in range(ntrans):
        enabled = {s for s, _, lab in arcs if lab == t}
        g_t = nx.DiGraph()
        g_t.add_nodes_from(range(n))
        g_t.add_edges_from((s, d) for s, d, lab in arcs if lab != t)
        if nx.is_directed_acyclic_graph(g_t):
            out[t] = Fairness.IMPARTIAL
            continue
        nontrivial = [c for c in nx.strongly_connected_components(g_t)
                      if len(c) > 1 or any(g_t.has_edge(v, v) for v in c)]
        if not any(c & enabled for c in nontrivial):
            out[t] = Fairness.FAIR
        elif nx.is_directed_acyclic_graph(g_t.subgraph(enabled)):
            out[t] = Fairness.JUST
        else:
            out[t] = Fairness.NONE
    return out


def _ours(n: int, arcs, ntrans: int, native: bool = False):
    """The report's fairness: the Python code (the reference of the native one), or the native code."""
    g = _graph(n, arcs)
    x = SimpleNamespace(graph=g, engine=SimpleNamespace(transitions=list(range(ntrans))), complete=True)
    with native_for_every_size():
        dec = strongly_connected_components(n, g.offsets, g.dst, native=native)
        if native:
            assert graphnative.library() is not None, "no native code to test here"
        return fairness(x, dec, array("BHi"[ntrans % 3], g.bes), native=native)  # every label width


@contextmanager
def native_for_every_size():
    """Native code even for the small graphs of the tests (it is left to Python below MIN_ITEMS)."""
    saved = graphnative.MIN_ITEMS
    graphnative.MIN_ITEMS = 0
    try:
        yield
    finally:
        graphnative.MIN_ITEMS = saved


@contextmanager
def _walks_everywhere():
    """Walk in every nontrivial SCC, however small (the default walks only the larger ones)."""
    saved = fairness_module.WALK_MIN_STATES
    fairness_module.WALK_MIN_STATES = 1
    try:
        yield
    finally:
        fairness_module.WALK_MIN_STATES = saved


@st.composite
def labelled_graphs(draw, max_states=12, max_trans=4):
    n = draw(st.integers(1, max_states))
    ntrans = draw(st.integers(1, max_trans))
    arcs = draw(st.lists(st.tuples(st.integers(0, n - 1), st.integers(0, n - 1), st.integers(0, ntrans - 1)),
                         max_size=4 * n))
    return n, arcs, ntrans


@settings(max_examples=400, deadline=None)
@given(labelled_graphs())
@pytest.mark.parametrize("native", [False, True], ids=["python", "native"])
def test_fairness_matches_the_definitions_on_random_graphs(native, case):
    n, arcs, ntrans = case
    assert _ours(n, arcs, ntrans, native) == _plain(n, arcs, ntrans)


@settings(max_examples=300, deadline=None)
@given(labelled_graphs())
def test_fairness_with_walks_in_every_component_matches_the_definitions(case):
    n, arcs, ntrans = case
    with _walks_everywhere():
        assert _ours(n, arcs, ntrans) == _plain(n, arcs, ntrans)


@st.composite
def cyclic_graphs(draw):
    """Larger graphs made of a few rings with chords: big nontrivial SCCs, where the walks and the
    confined searches do the work."""
    ntrans = draw(st.integers(1, 6))
    n = draw(st.integers(17, 60))
    arcs = []
    cuts = sorted(set(draw(st.lists(st.integers(1, n - 1), max_size=3))))
    bounds = [0, *cuts, n]
    for lo, hi in zip(bounds, bounds[1:]):
        for v in range(lo, hi):
            arcs.append((v, lo + (v + 1 - lo) % (hi - lo), draw(st.integers(0, ntrans - 1))))
    for _ in range(draw(st.integers(0, 2 * n))):
        arcs.append((draw(st.integers(0, n - 1)), draw(st.integers(0, n - 1)), draw(st.integers(0, ntrans - 1))))
    return n, arcs, ntrans


@settings(max_examples=200, deadline=None)
@given(cyclic_graphs())
@pytest.mark.parametrize("native", [False, True], ids=["python", "native"])
def test_fairness_on_larger_cyclic_graphs_matches_the_definitions(native, case):
    n, arcs, ntrans = case
    assert _ours(n, arcs, ntrans, native) == _plain(n, arcs, ntrans)


def test_the_shortcuts_decide_without_a_search(monkeypatch):
    """Transitions settled by the SCC decomposition or by a walk never reach a confined search."""
    calls = []
    real = fairness_module.has_cycle

    def counting(n, off, dst, labels, avoid, keep, roots):
        roots = list(roots)
        calls.append((avoid, len(roots)))
        return real(n, off, dst, labels, avoid, keep, roots)

    monkeypatch.setattr(fairness_module, "has_cycle", counting)
    # states 0 -> 1 (t0, never again), a ring 1 -> 2 -> ... -> 20 -> 1 by t1, t2 alternately, t3 enabled
    # on the ring but leaving it (2 -> 21), t4 never enabled on the ring
    arcs = [(0, 1, 0), (0, 22, 4)] + [(v, v + 1 if v < 20 else 1, 1 + v % 2) for v in range(1, 21)] + [(2, 21, 3)]
    result = _ours(23, arcs, 5)
    assert result == _plain(23, arcs, 5)
    assert result[0] == Fairness.FAIR and result[4] == Fairness.FAIR  # never enabled in a nontrivial SCC
    assert result[3] == Fairness.JUST  # enabled in an SCC where it has no arc inside: not fair
    # t1 and t2 are impartial: one search each over the ring; t3 only the search for a cycle among the
    # states enabling it (one state); t0 and t4 none
    assert sorted(calls) == [(1, 20), (2, 20), (3, 1)]


# ---------------------------------------------------------------------- bounds against every state

def _plain_bounds(engine, states):
    def untimed(p, ms):
        out: dict = {}
        timed = getattr(engine.places[p], "timed", False) and getattr(engine, "is_timed", False)
        for k, c in ms.items():
            v = k[0] if timed else k
            out[v] = out.get(v, 0) + c
        return {v: c for v, c in out.items() if c}

    markings = [[untimed(p, ms) for p, ms in enumerate(engine.marking(s))] for s in states]
    per_place = []
    for p in range(len(engine.places)):
        counts = [sum(m[p].values()) for m in markings]
        colours = {v for m in markings for v in m[p]}
        upper = {v: max(m[p].get(v, 0) for m in markings) for v in colours}
        lower = {v: min(m[p].get(v, 0) for m in markings) for v in colours}
        per_place.append((max(counts), min(counts), upper, {v: c for v, c in lower.items() if c}))
    per_marking = max(sum(sum(m[p].values()) for p in range(len(engine.places))) for m in markings)
    return per_place, per_marking


def _check_bounds(engine):
    x = Explorer(engine, ExploreOptions(max_states=5000)).run()
    per_place, per_marking = _plain_bounds(engine, x.graph.states)
    # the columns of packed states read in C, and in Python
    for b in (_native_bounds(x), boundedness(x)):
        assert [(pb.upper, pb.lower, pb.upper_multiset, pb.lower_multiset) for pb in b.places] == per_place
        assert b.max_tokens_per_marking == per_marking
        assert b.max_of_one_colour_in_place == max((max(u.values(), default=0) for _, _, u, _ in per_place),
                                                   default=0)


def _native_bounds(x):
    calls = []
    real = graphnative.place_columns

    def counting(store, caps):
        out = real(store, caps)
        calls.append(out is not None)
        return out

    graphnative.place_columns = counting
    try:
        with native_for_every_size():
            b = boundedness(x)
    finally:
        graphnative.place_columns = real
    # packed states (the native search of an untimed net with the compiled engine) are read in C
    if x.graph.store.kind == "packed" and graphnative.library() is not None:
        assert calls == [True]
    return b


def test_bounds_match_every_state_on_the_toy_nets():
    import nets

    for make in (nets.two_terminal_sccs, nets.livelock, nets.just_net, nets.coloured_register, nets.timed_merge,
                 nets.timed_cycle, nets.counter):
        _check_bounds(make())


def test_bounds_match_every_state_on_compiled_and_reference_engines():
    import cpn

    text = """
colset UNIT = unit;
colset P = index p with 1..3;
colset PP = product P * P;
var x, y : P;
place Idle : P = P.all();
place Busy : PP;
place Count : UNIT = 2`();
trans Grab [x <> y];
arc Idle -> Grab : 1`x ++ 1`y;
arc Grab -> Busy : 1`(x, y);
arc Count -> Grab : 1`();
trans Drop;
arc Busy -> Drop : 1`(x, y);
arc Drop -> Idle : 1`x ++ 1`y;
arc Drop -> Count : 1`();
"""
    model = cpn.loads(text)
    compiled, reference = model.engine(), model.engine(reference=True)
    assert Explorer(model.engine()).run().graph.store.kind == "packed"  # the C reading of the columns runs
    _check_bounds(compiled)
    _check_bounds(reference)
    bc, br = boundedness(Explorer(compiled).run()), boundedness(Explorer(reference).run())
    assert [(b.upper, b.lower, b.upper_multiset, b.lower_multiset) for b in bc.places] == \
        [(b.upper, b.lower, b.upper_multiset, b.lower_multiset) for b in br.places]
    assert bc.max_tokens_per_marking == br.max_tokens_per_marking


def test_transition_index_is_unchanged():
    # the arc-transition table the fairness shortcuts read is the engine's own mapping
    import nets

    e = nets.livelock()
    x = Explorer(e).run()
    arc_t = TransitionIndex(e).arc_transitions(x.graph.bes)
    assert [e.binding_element(be).transition for be in x.graph.bes] == list(arc_t)


# ---------------------------------------------------------------------- seconds and progress of the report

def test_report_gives_each_part_its_seconds_and_calls_progress():
    import nets

    from cpn.report import build_report, to_json
    from cpn.report.model import REPORT_PARTS

    calls = []
    x = Explorer(nets.just_net()).run()
    report = build_report(x, progress=lambda part, done, total: calls.append((part, done, total)))
    assert list(report.part_seconds) == list(REPORT_PARTS)
    assert all(s >= 0 for s in report.part_seconds.values())
    data = to_json(report)
    assert list(data["report_part_seconds"]) == list(REPORT_PARTS)
    assert isinstance(data["report_seconds"], float)  # the existing key keeps its meaning
    # every part starts (0/1) and ends (1/1), in order; fairness counts its transition instances
    assert [c[0] for c in calls if c[1:] == (0, 1)] == list(REPORT_PARTS)
    assert [c[0] for c in calls if c[1:] == (1, 1)] == list(REPORT_PARTS)
    ntrans = len(x.engine.transitions)
    steps = [c[1] for c in calls if c[0] == "fairness" and c[2] == ntrans]
    # the Python code reports each transition instance, the native code all of them at once
    assert steps in ([ntrans], list(range(1, ntrans + 1)))
    assert steps == sorted(steps) and steps[-1] == ntrans


def test_report_progress_line_on_a_terminal_only(monkeypatch, capsys, tmp_path):
    import argparse
    import io

    from _toy import dining_philosophers

    import cpn.cli.explore as explore

    clock = iter(range(0, 10_000, 2))  # every reading two seconds later: the line shows at once
    monkeypatch.setattr(explore.time, "perf_counter", lambda: float(next(clock)))

    class Terminal(io.StringIO):
        def isatty(self):
            return True

    def run(quiet: bool, terminal: bool) -> str:
        err = Terminal() if terminal else io.StringIO()
        monkeypatch.setattr(sys, "stderr", err)
        args = argparse.Namespace(model=str(tmp_path / "toy.cpnet"), set=[], max_states=None, max_arcs=None,
                                  max_seconds=None, max_memory=None, time_condensation=False,
                                  no_time_growth_check=False, json=None, dot=None, graphml=None, quiet=quiet,
                                  trace_to_dead=False)
        assert explore.explore_engine(dining_philosophers(3), args) == 0
        return err.getvalue()

    shown = run(quiet=False, terminal=True)
    assert "report" in shown and "fairness" in shown
    assert run(quiet=True, terminal=True) == ""
    # off a terminal: no progress line (a note such as which back end searched may still be said)
    assert [line for line in run(quiet=False, terminal=False).splitlines() if not line.startswith("note: ")] == []


# ---------------------------------------------------------------------- home markings and liveness

@settings(max_examples=200, deadline=None)
@given(labelled_graphs(max_states=20))
def test_home_markings_and_live_transitions_match_the_definitions(case):
    """Home markings: the states reachable from every state (the report takes the unique terminal SCC);
    live transition instances: those that can occur again from every state (the report: an arc inside
    every terminal SCC). The Python and the native code against the definitions."""
    from cpn.checks import home_markings, live_transitions, scc_summary

    n, arcs, ntrans = case
    g = _graph(n, arcs)
    x = SimpleNamespace(graph=g, engine=SimpleNamespace(transitions=list(range(ntrans)), is_timed=False),
                        complete=True)
    whole = nx.MultiDiGraph()
    whole.add_nodes_from(range(n))
    whole.add_edges_from((s, d, t) for s, d, t in arcs)
    reach = {v: nx.descendants(whole, v) | {v} for v in range(n)}
    homes = [h for h in range(n) if all(h in reach[v] for v in range(n))]
    live = [t for t in range(ntrans)
            if all(any(lab == t for s, _d, lab in arcs if s in reach[v]) for v in range(n))]
    for native in (False, True):
        with native_for_every_size():
            scc = scc_summary(x) if native else None
            if not native:
                graphnative.enabled = False
                try:
                    scc = scc_summary(x)
                finally:
                    graphnative.enabled = True
            assert list(home_markings(x, scc).states) == homes
            assert live_transitions(x, scc, array("B", g.bes), native=native) == live


# ---------------------------------------------------------------------- the whole report, native and Python

def _figures(data):
    """A report's JSON without its timings."""
    timing = {"seconds", "report_seconds", "report_part_seconds", "peak_memory_mb"}
    if isinstance(data, dict):
        return {k: _figures(v) for k, v in data.items() if k not in timing}
    if isinstance(data, list):
        return [_figures(v) for v in data]
    return data


@pytest.mark.parametrize("net, n", [("ms", "4"), ("dp", "6")])
def test_the_report_is_the_same_with_and_without_native_code(net, n, monkeypatch):
    import cpn
    from cpn.report import build_report, to_json

    if graphnative.library() is None:
        pytest.skip("no native code here")
    root = os.path.join(os.path.dirname(__file__), "..", "..")
    model = cpn.load(os.path.join(root, "bench", "nets", f"{net}.cpnet"), set={"N": n})
    x = Explorer(model.engine()).run()
    used = []
    for name in ("scc", "fairness", "live", "place_columns"):
        real = getattr(graphnative, name)
        monkeypatch.setattr(graphnative, name, lambda *a, _real=real, _name=name: used.append(_name) or _real(*a))
    with native_for_every_size():
        native = _figures(to_json(build_report(x, "m")))
        assert {"scc", "fairness", "live", "place_columns"} <= set(used)
        graphnative.enabled = False
        try:
            python = _figures(to_json(build_report(x, "m")))
        finally:
            graphnative.enabled = True
    assert native == python
