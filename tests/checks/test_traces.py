"""Counterexamples replay through the engine and are shortest; partial searches never hold."""


from hypothesis import given, settings
from hypothesis import strategies as st

from cpn.checks.verdict import Status
from cpn.gate.run import run_scenario
from cpn.gate.scenario import loads_scenario
from tests._graphs import bfs_distances
from tests.engine.randomnets import random_net


def _run(tmp_path, seed, body, **overrides):
    model = tmp_path / f"r{seed}.cpnet"
    model.write_text(random_net(seed), encoding="utf-8")
    s = loads_scenario(f'model = "{model.name}"\n' + body, str(tmp_path / "r.toml"))
    return run_scenario(s, s.runs[0], {"max_states": 3000, **overrides})


def _replays(engine, g, ev) -> bool:
    state = g.states[0]
    steps = list(zip(ev.path[1:], ev.arcs)) + list(zip(ev.cycle, ev.cycle_arcs))
    for v, be in steps:
        nxt = [t for b, t in engine.successors(state) if b == be]
        if g.states[v] not in nxt:
            return False
        state = g.states[v]
    return not ev.cycle or state == g.states[ev.path[-1]]


BODY = """
[[property]]
name = "small"
kind = "invariant"
expr = "size (Top'p0 1) <= {k}"

[[property]]
name = "big"
kind = "reachable"
expr = "size (Top'p1 1) >= {k}"

[[property]]
name = "deadlock"
kind = "deadlock_free"

[[property]]
name = "cycle"
kind = "no_livelock"

[[property]]
name = "af"
kind = "ctl"
formula = "AF (size (Top'p0 1) = {k})"
"""


@settings(max_examples=40, deadline=None)
@given(st.integers(0, 10**6), st.integers(0, 2))
def test_traces_replay_and_are_shortest(tmp_path_factory, seed, k):
    tmp = tmp_path_factory.mktemp("t")
    r = _run(tmp, seed, BODY.format(k=k))
    g = r.exploration.graph
    dist = bfs_distances(g)
    by = {p.spec.name: p.verdict for p in r.results}
    pred = [sum(r.engine.marking(s)[0].values()) <= k for s in g.states]
    for name, v in by.items():
        if v.evidence is not None:
            assert v.evidence.path[0] == 0
            assert _replays(r.engine, g, v.evidence), name
    small = by["small"]
    if small.status is Status.VIOLATED:
        t = small.evidence.target
        assert not pred[t]
        assert len(small.evidence.path) - 1 == dist[t] == min(dist[i] for i in range(g.n_states) if not pred[i])
    elif r.exploration.complete:
        assert all(pred)
    dead = [i for i in range(g.expanded) if not g.out_arcs(i)]
    if by["deadlock"].status is Status.VIOLATED:
        assert len(by["deadlock"].evidence.path) - 1 == min(dist[i] for i in dead)
    if by["cycle"].status is Status.VIOLATED:
        assert by["cycle"].evidence.cycle and by["cycle"].evidence.cycle[-1] == by["cycle"].evidence.path[-1]
    if not r.exploration.complete:
        assert all(v.status is not Status.HOLDS or name == "big" for name, v in by.items())


@settings(max_examples=30, deadline=None)
@given(st.integers(0, 10**6), st.integers(1, 30))
def test_a_partial_search_never_holds(tmp_path_factory, seed, limit):
    tmp = tmp_path_factory.mktemp("p")
    r = _run(tmp, seed, BODY.format(k=1), max_states=limit)
    for p in r.results:
        if p.verdict.status is Status.HOLDS:
            # only a witness (reachable) may hold on a partial graph; everything else needs the whole graph
            assert r.exploration.complete or (p.spec.kind == "reachable" and p.verdict.evidence is not None)
        if not r.exploration.complete and p.verdict.status is Status.UNKNOWN:
            assert "partial" in p.verdict.message or "so far" in p.verdict.message


@settings(max_examples=25, deadline=None)
@given(st.integers(0, 10**6))
def test_stopping_at_the_first_violation_finds_the_same_violation(tmp_path_factory, seed):
    tmp = tmp_path_factory.mktemp("f")
    body = BODY.format(k=0).split("[[property]]\nname = \"deadlock\"")[0]  # the invariant and a witness
    full = _run(tmp, seed, body)
    fly = _run(tmp, seed, "[explore]\nstop_at_first_violation = true\n" + body)
    a = {p.spec.name: p.verdict for p in full.results}["small"]
    b = {p.spec.name: p.verdict for p in fly.results}["small"]
    if a.status is Status.VIOLATED:
        assert b.status is Status.VIOLATED
        assert a.evidence == b.evidence
        assert fly.exploration.n_states <= full.exploration.n_states
