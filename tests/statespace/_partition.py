"""Cross-checks of the partitioned search against the one-process search: the same states, arcs, dead
markings, levels and standard report (node numbers aside: the partitioned search numbers states in
another breadth-first order)."""

from __future__ import annotations

from collections import Counter

from cpn.report import build_report, to_json
from cpn.statespace import ExploreOptions, Explorer
from cpn.statespace.trace import shortest_trace


class Observer:
    """An observing stop predicate that records every state it is asked about."""

    may_stop = False  # it never ends the search: the partitioned search calls it afterwards

    def __init__(self):
        self.seen = []

    def __call__(self, s):
        self.seen.append(s)
        return False


def canonical(engine, s) -> tuple:
    return tuple(frozenset(d.items()) for d in engine.marking(s)) + ((engine.clock(s),) if engine.is_timed else ())


def summary(x) -> dict:
    """What must not depend on the search: every figure, with states named by their markings."""
    e, g = x.engine, x.graph
    names = [canonical(e, s) for s in g.states]
    arcs = Counter()
    text: dict = {}  # each binding element formatted once (ms.cpnet N=5: 76,545 arcs, 95 binding elements)
    for i in range(g.expanded):
        for be, d in g.out_arcs(i):
            if be not in text:
                text[be] = e.format_binding_element(be)
            arcs[(names[i], text[be], names[d])] += 1
    # the BFS tree gives shortest paths: every state's depth is the same in both searches
    depth = {}
    for i in range(g.n_states):
        p = g.parent[i]
        depth[names[i]] = 0 if p < 0 else depth[names[p]] + 1
    # the counts as plain dicts (each count at least 1): their == is dict's, in C; Counter's == compares
    # element by element in Python (5.6 s of one test's 13 on ms.cpnet N=5)
    return {"states": dict(Counter(names)), "expanded": dict(Counter(names[:g.expanded])), "arcs": dict(arcs),
            "dead": sorted(map(repr, (names[i] for i in g.dead_states()))), "depth": depth,
            "stop": x.stop_reason, "levels": x.levels, "initial": names[0]}


def consistent(x) -> None:
    """The graph is one the one-process search could have made: the expanded states first, each with
    exactly the engine's successors (as a multiset), arcs in range, and BFS parents giving shortest paths."""
    e, g = x.engine, x.graph
    assert len(g.offsets) == g.expanded + 1 and g.offsets[0] == 0 and g.offsets[-1] == g.n_arcs
    assert len(g.parent) == len(g.parent_be) == g.n_states and g.parent[0] == -1
    assert all(0 <= d < g.n_states for d in g.dst)
    states = list(g.states)
    names = [canonical(e, s) for s in states]
    assert len(set(names)) == g.n_states  # no state stored twice
    # a successor is most often a state of the graph, whose marking is already read (`canonical` is a
    # function of the engine's state); another is read here
    known = dict(zip(states, names))

    def name(t):
        return known[t] if t in known else canonical(e, t)

    for i in range(g.expanded):
        want = Counter((be, name(t)) for be, t in e.successors(states[i]))
        assert Counter((be, names[d]) for be, d in g.out_arcs(i)) == want, f"state {i}"
    depth = [0] * g.n_states
    for i in range(1, g.n_states):
        p = g.parent[i]
        assert 0 <= p < i and p < g.expanded, "a parent comes earlier and is expanded"
        assert (g.parent_be[i], i) in g.out_arcs(p), "the parent's arc leads to the state"
        depth[i] = depth[p] + 1
    assert depth == sorted(depth), "the states are in breadth-first order"


def report_figures(x) -> dict:
    """The standard report as JSON, node numbers replaced by markings and traces by their length."""
    r = to_json(build_report(x))
    e, g = x.engine, x.graph

    def name(i):
        return repr(canonical(e, g.states[i - 1]))  # the report numbers nodes from 1

    for key in ("report_seconds", "report_part_seconds", "notes", "backend_notes"):
        r.pop(key, None)
    st = r["statespace"]
    for key in ("seconds", "peak_memory_mb"):
        st.pop(key, None)
    r["scc"].pop("seconds", None)
    dm = r["dead_markings"]
    ex = dm["examples"] or []
    dm["examples"] = sorted(name(i) for i in ex) if len(ex) == dm["count"] else len(ex)
    dm["trace"] = len(dm["trace"] or [])
    listed = dm.get("listed") or []
    dm["listed"] = (sorted((name(d["node"]), len(d.get("trace") or [])) for d in listed)
                    if len(listed) == dm["count"] else len(listed))
    hm = r["home_markings"]
    if hm:
        # the examples listed are the first nodes by number when there are more than the report lists
        ex = hm["examples"] or []
        hm["examples"] = sorted(name(i) for i in ex) if len(ex) == hm["count"] else len(ex)
    return r


def compare(model, workers=(1, 2), ray=None, threads=False, **opts) -> dict:
    """The one-process search and the partitioned one with each number of workers (processes, or threads
    where the net allows them if `threads`): identical figures and report. Returns the one-process
    summary, with the backends that ran under "backends"."""
    base = Explorer(model.engine(), ExploreOptions(**opts)).run()
    want, want_report = summary(base), report_figures(base)
    backends = []
    for n in workers:
        x = Explorer(model.engine(), ExploreOptions(workers=n, ray=ray, threads=threads, **opts)).run()
        backends.append(x.backend)
        expected = ("ray",) if ray else ("threads", "workers") if threads else ("workers",)
        assert x.backend in expected or x.engine.is_timed, x.notes
        got = summary(x)
        for key in want:
            assert got[key] == want[key], f"{key} differs with {n} workers"
        assert report_figures(x) == want_report, f"the report differs with {n} workers"
        for i in x.graph.dead_states()[:3]:
            assert len(shortest_trace(x.graph, i, x.engine).steps) == want["depth"][canonical(x.engine,
                                                                                                x.graph.states[i])]
    return {**want, "backends": backends}
