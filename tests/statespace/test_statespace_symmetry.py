"""Symmetry reduction, cross-checked against the full graph: the full counts computed
from the orbit sizes equal the full exploration's, the dead markings are the same up to symmetry, and the
integer bounds, token maxima, dead and live transition instances and fairness are equal; every lifted
trace replays in the full graph. On random symmetric nets and on the corpus's symmetric nets."""

from __future__ import annotations

import os

import pytest

import cpn
from cpn.engine.symmetry import Canonicaliser, Scalar
from cpn.statespace import ExploreOptions, Explorer, replay, shortest_trace
from tests._shared import SHARED, needs_shared
from tests.statespace._quotient import agree, check_canonical_forms, fewer_orbits, full_and_quotient
from tests.statespace._symmetric_nets import random_symmetric_net

MAX_STATES = 5000  # four random nets of the 80 have more: they are skipped


def _agree(model, scalars, max_states=MAX_STATES):
    """Every figure the quotient claims to preserve, against the full graph; the orbit counts. Besides
    what every symmetry reduction preserves (`agree`): the most tokens of one colour on a place, the live
    transition instances and fairness."""
    engine = model.engine()
    full, quot = full_and_quotient(engine, scalars, max_states)
    rf, rq = agree(engine, full, quot)
    assert rf.bounds.max_of_one_colour_in_place == rq.bounds.max_of_one_colour_in_place
    assert rf.live_transitions == rq.live_transitions
    assert rf.fairness == rq.fairness
    return full, quot


#: (seed, rotations) -> whether the cross-check below found fewer orbits than states (what `fewer_orbits`
#: computes), kept so that test_some_random_nets_are_really_reduced does not search again
_REDUCED: dict[tuple[int, bool], bool] = {}


def _spec(seed: int, rotations: bool) -> str:
    """The symmetry the cross-check of random net `seed` uses."""
    if not rotations:
        return "S,R"
    return "S:rotations,R" if seed % 2 else "S:rotations"


def _cross_check(seed: int, rotations: bool) -> None:
    model = cpn.loads(random_symmetric_net(seed, rotations=rotations), f"random-{seed}.cpnet")
    try:
        full, quot = _agree(model, model.symmetry(_spec(seed, rotations)))
    except pytest.skip.Exception:  # more than MAX_STATES states: not reduced, as fewer_orbits says
        _REDUCED[seed, rotations] = False
        raise
    _REDUCED[seed, rotations] = quot.n_states < full.n_states


@pytest.mark.parametrize("seed", range(40))
def test_random_symmetric_nets_under_all_permutations(seed):
    _cross_check(seed, False)


@pytest.mark.parametrize("seed", range(40))
def test_random_symmetric_nets_under_rotations(seed):
    _cross_check(seed, True)


def test_some_random_nets_are_really_reduced():
    """The cross-check is not vacuous: most random nets have fewer orbits than states under the symmetry
    the tests above check them with. (The nets those tests cross-checked are not searched again.)"""
    smaller = 0
    for seed in range(40):
        for rotations in (False, True):
            if (seed, rotations) not in _REDUCED:
                model = cpn.loads(random_symmetric_net(seed, rotations), f"random-{seed}.cpnet")
                _REDUCED[seed, rotations] = fewer_orbits(model, model.symmetry(_spec(seed, rotations)), MAX_STATES)
            smaller += _REDUCED[seed, rotations]
    assert smaller >= 20  # 26 of the 80 when this was written (and under S:rotations for every rotated net)


CORPUS = [("Philosophers-COL-000005", "Philo:rotations", 51), ("SharedMemory-COL-000005", "P", 51),
          ("DatabaseWithMutex-COL-02", "file", 77), ("Referendum-COL-0010", "Voters", 67),
          ("CSRepetitions-COL-02", "Client,Server", 352), ("DrinkVendingMachine-COL-02", "Products,Options", 576)]


@needs_shared
@pytest.mark.parametrize("name,spec,orbits", CORPUS)
def test_corpus_symmetric_nets(name, spec, orbits):
    path = os.path.join(SHARED, "validation", name, "model.pnml")
    if not os.path.exists(path):
        pytest.skip("no validation corpus")
    model = cpn.load(path)
    assert [str(s) for s in model.symmetry("auto")] == spec.split(",")
    full, quot = _agree(model, model.symmetry(spec), max_states=100_000)
    assert quot.n_states == orbits < full.n_states


def test_canonical_form_is_the_orbit_minimum_of_the_fixed_order():
    """Against brute force over the whole group: the representative is the same for every state of an
    orbit, lies in the orbit, and the stabiliser size is the number of renamings fixing the state."""
    for seed in range(12):
        rotations = seed % 2 == 1
        model = cpn.loads(random_symmetric_net(seed, rotations), "r.cpnet")
        engine = model.engine()
        x = Explorer(engine, ExploreOptions(max_states=60)).run()
        c = Canonicaliser(engine, [Scalar("S", "rotations" if rotations else "permutations"), Scalar("R")])
        group = list(c.group())
        assert len(group) == c.group_order
        check_canonical_forms(c, group, list(x.graph.states)[:60])


@needs_shared
def test_lifted_traces_replay_in_the_full_graph():
    model = cpn.load(os.path.join(SHARED, "validation", "SharedMemory-COL-000005", "model.pnml"))
    engine = model.engine()
    quot = Explorer(engine, ExploreOptions(reduction="symmetry", symmetry=model.symmetry("P"))).run()
    for target in range(0, quot.n_states, 5):
        trace = shortest_trace(quot.graph, target, engine)
        assert replay(engine, quot.graph, trace)
        assert len(trace) == len([v for v in _bfs_path(quot.graph, target)]) - 1


def _bfs_path(g, v):
    out = [v]
    while out[-1] > 0:
        out.append(g.parent[out[-1]])
    return out


TIMED = """colset C = with a | b | c;
colset CT = C timed;
var x : C;
place Idle : CT = CT.all();
place Busy : CT;
trans go @+ 2;
trans back;
arc Idle -> go : x;
arc go -> Busy : x;
arc Busy -> back : x;
arc back -> Idle : x @+ 1;
"""


@pytest.mark.parametrize("reference", [False, True])
def test_timed_nets_and_the_reference_engine(reference):
    """Timestamps ride along with the renamed values; the reference interpreter's states (frozensets)
    are canonicalised the same way."""
    model = cpn.loads(TIMED, "t.cpnet")
    engine = model.engine(time_condensation=True, reference=reference)
    full = Explorer(engine, ExploreOptions()).run()
    quot = Explorer(engine, ExploreOptions(reduction="symmetry", symmetry=model.symmetry("C"))).run()
    assert (full.n_states, full.n_arcs) == (15, 27) and quot.n_states == 7
    assert (quot.reduction_stats["full_states"], quot.reduction_stats["full_arcs"]) == (15, 27)
