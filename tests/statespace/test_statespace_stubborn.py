"""Stubborn sets: the reduced graph has the full graph's dead markings and, with the
visibility condition, the same markings of the visible places (so the same invariant verdicts)."""

from __future__ import annotations

import os

import pytest

import cpn
from cpn.engine.stubborn import StubbornSets
from cpn.statespace import ExploreOptions, Explorer
from tests._shared import ROOT, SHARED, needs_shared
from tests.engine.randomnets import random_net
from tests.statespace._reduction import compare, dead_set, projections

# two independent components: a self-loop on A and a one-shot move B -> C
IGNORING = """colset U = unit; place A : U = 1`(); place B : U = 1`(); place C : U;
trans loop; trans move; arc A -> loop; arc loop -> A; arc B -> move; arc move -> C;"""

# a choice between two producers of the same place, and an independent two-step chain
CHAINS = """colset U = unit; place A : U = 1`(); place B : U = 1`(); place C : U; place D : U; place E : U;
trans a1; trans a2; trans b1; trans b2;
arc A -> a1; arc a1 -> C; arc A -> a2; arc a2 -> C; arc B -> b1; arc b1 -> D; arc D -> b2; arc b2 -> E;"""


def _run(engine, **opts):
    return Explorer(engine, ExploreOptions(**opts)).run()


def test_independent_transitions_are_interleaved_once():
    engine = cpn.loads(CHAINS).engine()
    full, red = _run(engine), _run(engine, reduction="stubborn")
    assert red.reduction == "stubborn" and full.reduction is None
    assert (full.n_states, red.n_states) == (6, 4)  # 2 x 3 interleavings against one path
    assert dead_set(red) == dead_set(full) and len(dead_set(full)) == 1


def test_the_cycle_proviso_prevents_ignoring_a_visible_transition():
    engine = cpn.loads(IGNORING).engine()
    c = next(p.index for p in engine.net.places if p.name == "Top'C 1")
    vis = _run(engine, reduction="stubborn", visible_places=frozenset({c}))
    full = _run(engine)
    # without the proviso the self-loop alone is stubborn in the initial state and C is never marked
    assert projections(vis, [c]) == projections(full, [c]) and len(projections(full, [c])) == 2
    assert vis.reduction_stats["fully_expanded_states"] >= 1


def test_visibility_refuses_a_set_with_a_visible_enabled_transition():
    net = cpn.loads(CHAINS).net
    c = net.place("Top'C 1").index
    s = StubbornSets(net, visible_places={c})
    names = [t.name for t in net.transitions]
    chosen = s.choose(frozenset({names.index("Top'a1 1"), names.index("Top'a2 1"), names.index("Top'b1 1")}))
    assert chosen == frozenset({names.index("Top'b1 1")})  # a1 and a2 change C: not alone, not with b1


def test_timed_nets_and_priorities_are_fully_expanded_and_say_so():
    timed = cpn.loads("colset T = unit timed; place A : T = 1`(); place B : T = 1`(); place C : T;"
                      " trans a; trans b; arc A -> a; arc a -> C : () @+ 1; arc B -> b; arc b -> C;").engine()
    x = _run(timed, reduction="stubborn")
    assert x.reduction is None and "timed" in x.notes[0] and x.n_states == _run(timed).n_states
    prio = cpn.loads("colset U = unit; val P_HIGH = 100; place A : U = 1`(); place B : U = 1`(); place C : U;"
                     " trans a priority P_HIGH; trans b; arc A -> a; arc a -> C; arc B -> b; arc b -> C;").net
    assert "priorities" in StubbornSets(prio).refusal


@pytest.mark.parametrize("chunk", range(4))
def test_random_nets_keep_dead_markings_and_visible_markings(chunk):
    compared = 0
    for seed in range(chunk * 25, chunk * 25 + 25):
        try:
            model = cpn.loads(random_net(seed))
        except cpn.ModelError:
            continue
        # the finite state spaces of these nets have at most 34 states: past 500 the net has no end (a
        # search to 3,000 states took most of the test's time)
        if compare(model.engine(), max_states=500, seed=seed) is not None:
            compared += 1
    assert compared >= 10


MODELS = [("models/examples/stations.cpnet", None), ("models/examples/broadcast.cpnet", None),
          ("models/examples/timer_cancel.cpnet", None), ("models/modbus/modbus_a.cpnet", None),
          ("bench/nets/dp.cpnet", "5"), ("bench/nets/ms.cpnet", "3")]


@pytest.mark.parametrize("path,n", MODELS, ids=[m[0].rsplit("/", 1)[-1] + (m[1] or "") for m in MODELS])
def test_repository_models(path, n):
    model = cpn.load(os.path.join(ROOT, path), set={"N": n} if n else None)
    assert compare(model.engine(), max_states=20000) is not None


CORPUS = ["CSRepetitions-COL-02", "CSRepetitions-PT-02", "DatabaseWithMutex-COL-02"]


@needs_shared
@pytest.mark.parametrize("name", CORPUS)
def test_validation_corpus_subset(name):
    folder = os.path.join(SHARED, "validation", name)
    if not os.path.isdir(folder):
        pytest.skip(f"no validation corpus at {folder}")
    path = os.path.join(folder, next(f for f in sorted(os.listdir(folder)) if f.endswith((".pnml", ".cpn"))))
    assert compare(cpn.load(path).engine(), max_states=20000) is not None


def test_a_transition_blocked_by_an_inhibitor_brings_the_transitions_that_empty_its_place():
    # c and t compete for A; t waits until u has emptied I: {c, t} alone is not stubborn (u can enable t)
    net = """colset U = unit; place A : U = 1`(); place I : U = 1`(); place Z : U; place Done : U;
    trans c; trans t; trans u; arc A -> c; arc c -> Z; arc A -> t; arc t -> Done; inhibitor I -> t; arc I -> u;"""
    engine = cpn.loads(net).engine()
    full, red = _run(engine), _run(engine, reduction="stubborn")
    assert dead_set(red) == dead_set(full) and len(dead_set(full)) == 2
