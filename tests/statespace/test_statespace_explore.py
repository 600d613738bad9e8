"""Exploration on hand-written toy engines: counts, limits, partial results, traces."""

import subprocess
import sys

import pytest
from _toy import Mode, ToyEngine, ToyPlace, ToyTransition, dining_philosophers, pt_net

from cpn.statespace import ExploreOptions, Explorer, StopReason, replay, shortest_trace
from tests._shared import SHARED, needs_shared

REFERENCE = SHARED + "/bench/reference_counts.py"


def _reference(net, n):
    out = subprocess.run([sys.executable, REFERENCE, net, str(n)], capture_output=True, text=True, check=True)
    fields = dict(kv.split("=") for kv in out.stdout.split()[2:])
    return int(fields["states"]), int(fields["arcs"]), int(fields["dead"])


@needs_shared
@pytest.mark.parametrize("n", [3, 5, 8])
def test_dining_philosophers_counts_match_reference(n):
    x = Explorer(dining_philosophers(n)).run()
    assert x.stop_reason is StopReason.COMPLETE
    assert (x.n_states, x.n_arcs, len(x.graph.dead_states())) == _reference("dp", n)
    assert x.unexpanded == 0


def test_self_loops_and_parallel_arcs_count():
    # T0 and T1 both move the token P0 -> P1 (parallel arcs); T2 is a self-loop on P1.
    e = pt_net([[1, 0], [1, 0], [0, 1]], [[0, 1], [0, 1], [0, 1]], [1, 0])
    x = Explorer(e).run()
    assert (x.n_states, x.n_arcs) == (2, 3)
    assert x.graph.out_arcs(0) == [(0, 1), (1, 1)]
    assert x.graph.out_arcs(1) == [(2, 1)]


def _counter(limit=None):
    # An unbounded counter: T0 adds a token to P0 for ever.
    return pt_net([[0]], [[1]], [0])


def test_max_states_gives_partial_result_without_false_dead_markings():
    x = Explorer(_counter(), ExploreOptions(max_states=10)).run()
    assert x.stop_reason is StopReason.MAX_STATES
    assert not x.complete
    assert x.n_states == 10
    assert x.unexpanded == 1
    assert x.graph.dead_states() == []


def test_max_arcs_and_predicate():
    x = Explorer(_counter(), ExploreOptions(max_arcs=5)).run()
    assert x.stop_reason is StopReason.MAX_ARCS and x.n_arcs == 5
    e = _counter()
    x = Explorer(e, ExploreOptions(stop_predicate=lambda s: e.token_counts(s)[0] == 4)).run()
    assert x.stop_reason is StopReason.PREDICATE
    assert e.token_counts(x.graph.states[x.predicate_state]) == (4,)
    assert x.graph.dead_states() == []


def test_max_seconds_stops():
    x = Explorer(_counter(), ExploreOptions(max_seconds=0.05)).run()
    assert x.stop_reason is StopReason.MAX_SECONDS
    assert x.unexpanded >= 1


def test_max_memory_stops():
    x = Explorer(_counter(), ExploreOptions(max_memory_mb=1)).run()
    assert x.stop_reason is StopReason.MAX_MEMORY


def test_keyboard_interrupt_gives_partial_result():
    e = _counter()
    real = e.successors
    calls = {"n": 0}

    def successors(s):
        calls["n"] += 1
        if calls["n"] == 20:
            raise KeyboardInterrupt
        return real(s)

    e.successors = successors
    x = Explorer(e).run()
    assert x.stop_reason is StopReason.INTERRUPTED
    assert x.graph.expanded == 19 and x.unexpanded == 1
    assert x.graph.dead_states() == []


def test_progress_hook_is_called():
    seen = []
    Explorer(dining_philosophers(5), progress=seen.append).run()
    assert seen and seen[-1].states == 82 and seen[-1].arcs == 265 and seen[-1].queue == 0


@pytest.mark.parametrize("n", [4, 6])
def test_traces_are_shortest_and_replay(n):
    e = dining_philosophers(n)
    x = Explorer(e).run()
    g = x.graph
    # BFS distances computed independently
    dist = {0: 0}
    frontier = [0]
    while frontier:
        nxt = []
        for v in frontier:
            for _be, w in g.out_arcs(v):
                if w not in dist:
                    dist[w] = dist[v] + 1
                    nxt.append(w)
        frontier = nxt
    for target in range(g.n_states):
        tr = shortest_trace(g, target, e)
        assert len(tr) == dist[target]
        assert replay(e, g, tr)
    dead = g.dead_states()[0]
    tr = shortest_trace(g, dead, e)
    assert tr.steps[0].text.startswith("Top'TakeLeft 1: {p=")
    assert all(step.changes for step in tr.steps)


def test_replay_rejects_a_wrong_trace():
    e = dining_philosophers(3)
    x = Explorer(e).run()
    tr = shortest_trace(x.graph, 5, e)
    from cpn.statespace import Step, Trace

    bad = Trace(tr.target, (Step(999, 0, tr.steps[0].target),) + tr.steps[1:])
    assert not replay(e, x.graph, bad)


def _ticker():
    # A timed place with one token that a transition puts back 1 time unit later: infinite in time.
    places = [ToyPlace("Top'Clock 1", "UNIT", timed=True)]
    modes = [Mode(0, {}, {0: {(): 1}}, {0: {(): 1}}, delay=1)]
    return ToyEngine(places, [ToyTransition("Top'Tick 1")], modes, [{((), 0): 1}], is_timed=True)


def test_time_growth_is_detected():
    x = Explorer(_ticker(), ExploreOptions(max_states=10_000)).run()
    assert x.stop_reason is StopReason.TIME_GROWS
    assert x.untimed_states == 1
    assert x.time_growth["untimed_markings"] == 1
    assert x.n_states < 100


def test_time_growth_detection_can_be_disabled():
    x = Explorer(_ticker(), ExploreOptions(max_states=200, detect_time_growth=False)).run()
    assert x.stop_reason is StopReason.MAX_STATES


def test_large_binding_element_ids_widen_the_arc_array():
    base = dining_philosophers(3)

    class Wide:
        places, transitions, is_timed = base.places, base.transitions, False
        initial_state = staticmethod(base.initial_state)

        def successors(self, s):
            return [(be * 30_000, t) for be, t in base.successors(s)]

    x = Explorer(Wide()).run()
    ref = Explorer(dining_philosophers(3)).run()
    assert x.graph.bes.typecode == "i"
    assert list(x.graph.bes) == [be * 30_000 for be in ref.graph.bes]
    assert list(x.graph.parent_be) == [be * 30_000 if be >= 0 else -1 for be in ref.graph.parent_be]
