"""Symmetry of module instances, cross-checked against the full graph: on random nets
with one module instance per value of a symmetric colour set, and on a small client/lock net, the full
counts computed from the orbit sizes equal the full exploration's, the dead markings are the same up to
symmetry, the integer bounds and dead transition instances of the quotient's report are the full graph's,
the representative is the minimum of its orbit (brute force over the group), and traces replay."""

from __future__ import annotations

import pytest

import cpn
from cpn.engine.symmetry import Canonicaliser, Scalar
from cpn.statespace import ExploreOptions, Explorer
from tests.statespace._instance_nets import random_instance_net
from tests.statespace._quotient import agree, check_canonical_forms, fewer_orbits, full_and_quotient

MAX_STATES = 5000  # three random nets of the 80 have more: they are skipped

CLIENTS = """colset C = index c with 1..3;
colset U = unit;
var x : C;
place Lock : U = 1`();
place Req : C;
module Client(me : C) {
  port out Ask : C;
  port in Lk : U;
  place Idle : U = 1`();
  place Wait : U;
  place Crit : U;
  trans ask; arc Idle -> ask : (); arc ask -> Wait : (); arc ask -> Ask : me;
  trans enter [x = me]; arc Ask -> enter : x; arc Wait -> enter : (); arc Lk -> enter : (); arc enter -> Crit : ();
  trans leave; arc Crit -> leave : (); arc leave -> Lk : (); arc leave -> Idle : ();
}
instance Client1 = Client(me = c(1)) { Ask = Req, Lk = Lock };
instance Client2 = Client(me = c(2)) { Ask = Req, Lk = Lock };
instance Client3 = Client(me = c(3)) { Ask = Req, Lk = Lock };
"""


def _agree(model, scalars, max_states=MAX_STATES, reference=False):
    engine = model.engine(reference=reference)
    full, quot = full_and_quotient(engine, scalars, max_states)
    _rf, rq = agree(engine, full, quot)
    assert rq.live_transitions is None and rq.moves_instances  # not preserved: not reported
    return full, quot


#: (seed, rotations) -> whether the cross-check below found fewer orbits than states (what `fewer_orbits`
#: computes), kept so that test_some_random_instance_nets_are_really_reduced does not search again
_REDUCED: dict[tuple[int, bool], bool] = {}


def _spec(rotations: bool) -> str:
    return "S:rotations" if rotations else "S"


def _cross_check(seed: int, rotations: bool) -> None:
    model = cpn.loads(random_instance_net(seed, rotations=rotations), f"random-{seed}.cpnet")
    try:
        full, quot = _agree(model, model.symmetry(_spec(rotations)))
    except pytest.skip.Exception:  # more than MAX_STATES states: not reduced, as fewer_orbits says
        _REDUCED[seed, rotations] = False
        raise
    _REDUCED[seed, rotations] = quot.n_states < full.n_states


@pytest.mark.parametrize("seed", range(40))
def test_random_instance_nets_under_all_permutations(seed):
    _cross_check(seed, False)


@pytest.mark.parametrize("seed", range(40))
def test_random_instance_nets_under_rotations(seed):
    _cross_check(seed, True)


def test_some_random_instance_nets_are_really_reduced():
    """The cross-check is not vacuous: many random nets have fewer orbits than states. (The nets the tests
    above cross-checked are not searched again.)"""
    smaller = 0
    for seed in range(20):
        for rotations in (False, True):
            if (seed, rotations) not in _REDUCED:
                model = cpn.loads(random_instance_net(seed, rotations), f"random-{seed}.cpnet")
                _REDUCED[seed, rotations] = fewer_orbits(model, model.symmetry(_spec(rotations)), MAX_STATES)
            smaller += _REDUCED[seed, rotations]
    assert smaller >= 10  # 16 of the 40 when this was written


@pytest.mark.parametrize("reference", [False, True])
def test_clients_and_lock(reference):
    model = cpn.loads(CLIENTS, "clients.cpnet")
    full, quot = _agree(model, model.symmetry("C"), reference=reference)
    # each client idle, waiting or critical, at most one critical: 2^3 + 3 * 2^2 states; orbits: how many
    # wait, and whether one is critical
    assert (full.n_states, quot.n_states) == (20, 7)


def test_canonical_form_is_the_orbit_minimum_with_moved_instances():
    """Against brute force over the whole group: the representative is the same for every state of an
    orbit and lies in it; the stabiliser size is the number of renamings fixing the state."""
    for seed in range(16):
        rotations = seed % 2 == 1
        model = cpn.loads(random_instance_net(seed, rotations), "r.cpnet")
        engine = model.engine()
        x = Explorer(engine, ExploreOptions(max_states=60)).run()
        c = Canonicaliser(engine, [Scalar("S", "rotations" if rotations else "permutations")])
        assert c.families
        group = list(c.group())
        check_canonical_forms(c, group, list(x.graph.states)[:60])


def test_a_symmetry_the_check_refuses_would_give_wrong_counts():
    """Why the check matters (and that the cross-check can fail): client 1 may never enter; the check
    refuses the symmetry, and forcing the reduction past it gives full counts that are not the full
    graph's."""
    model = cpn.loads(CLIENTS.replace("trans enter [x = me];", "trans enter [x = me, me <> c(1)];"), "bad.cpnet")
    with pytest.raises(cpn.ModelError) as info:
        model.symmetry("C")
    assert [d.code for d in info.value.diagnostics] == ["E0602"]
    engine = model.engine()
    full = Explorer(engine, ExploreOptions()).run()
    forced = Explorer(engine, ExploreOptions(reduction="symmetry", symmetry=(Scalar("C"),))).run()
    assert forced.reduction_stats["full_states"] != full.n_states
