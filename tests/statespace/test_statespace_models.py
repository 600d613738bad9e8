"""Exploration of real .cpnet models through cpn.load: benchmark counts, limits, time, traces."""

import os
import subprocess
import sys

import pytest

import cpn
from cpn.statespace import ExploreOptions, Explorer, StopReason, replay, shortest_trace
from tests._shared import SHARED, needs_shared

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
MODELS = os.path.join(HERE, "models")
NETS = os.path.join(ROOT, "bench", "nets")
REFERENCE = os.path.join(SHARED, "bench", "reference_counts.py")


def engine(path, **sets):
    return cpn.load(path, set={k: str(v) for k, v in sets.items()}).engine(time_condensation=False)


def _reference(net, n):
    out = subprocess.run([sys.executable, REFERENCE, net, str(n)], capture_output=True, text=True, check=True)
    fields = dict(kv.split("=") for kv in out.stdout.split()[2:])
    return int(fields["states"]), int(fields["arcs"]), int(fields["dead"])


@needs_shared
@pytest.mark.parametrize("net,n", [("dp", 5), ("dp", 8), ("ms", 3), ("ms", 4)])
def test_benchmark_counts_match_reference(net, n):
    x = Explorer(engine(os.path.join(NETS, f"{net}.cpnet"), N=n)).run()
    assert x.complete
    assert (x.n_states, x.n_arcs, len(x.graph.dead_states())) == _reference(net, n)


def test_dead_marking_trace_replays_and_is_shortest():
    e = engine(os.path.join(NETS, "dp.cpnet"), N=5)
    x = Explorer(e).run()
    (dead,) = x.graph.dead_states()
    tr = shortest_trace(x.graph, dead, e)
    assert len(tr) == 5  # each philosopher takes its left fork once
    assert replay(e, x.graph, tr)
    assert all(step.text.startswith("DP'TakeLeft 1: ") for step in tr.steps)


def test_partial_search_has_no_dead_markings():
    x = Explorer(engine(os.path.join(MODELS, "counter.cpnet")), ExploreOptions(max_states=20)).run()
    assert x.stop_reason is StopReason.MAX_STATES and x.unexpanded == 1
    assert x.graph.dead_states() == []


def test_time_growth_detected_and_condensation_makes_it_finite():
    path = os.path.join(MODELS, "ticker.cpnet")
    x = Explorer(engine(path), ExploreOptions(max_states=10_000)).run()
    assert x.stop_reason is StopReason.TIME_GROWS and x.untimed_states == 1
    e = cpn.load(path).engine(time_condensation=True)
    x = Explorer(e, ExploreOptions(max_states=10_000, time_condensation=True)).run()
    # {()@0} at clock 0, then {()@1} at clock 0 again and again after condensation
    assert x.complete and (x.n_states, x.n_arcs) == (2, 2)


def test_evaluation_error_carries_the_trace_to_the_failing_state():
    from cpn.errors import EvaluationError

    with pytest.raises(EvaluationError) as info:
        Explorer(engine(os.path.join(MODELS, "div_zero.cpnet"))).run()
    assert info.value.trace == ["Top'Step 1: {n=2}", "Top'Step 1: {n=1}"]
    assert "reached after 2 steps" in info.value.render()
