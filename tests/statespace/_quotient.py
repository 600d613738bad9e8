"""Cross-checks of a symmetry-reduced state space (the quotient) against the full one: what every symmetry
reduction preserves, for colour sets and for module instances alike."""

from __future__ import annotations

import pytest

from cpn.report import build_report
from cpn.statespace import ExploreOptions, Explorer, replay


def full_and_quotient(engine, scalars, max_states: int):
    """The full graph and the quotient under `scalars`, both complete; the test is skipped when the full
    graph has more than `max_states` states."""
    full = Explorer(engine, ExploreOptions(max_states=max_states)).run()
    if not full.complete:
        pytest.skip(f"more than {max_states} states")
    quot = Explorer(engine, ExploreOptions(reduction="symmetry", symmetry=tuple(scalars))).run()
    assert quot.complete
    return full, quot


def agree(engine, full, quot):
    """The full counts computed from the orbit sizes, the dead markings up to symmetry and their number in
    the full graph, the integer bounds, the token maxima and the dead transition instances of the quotient's
    report are the full graph's; the listed dead markings' traces are paths of the full graph into their
    orbits. Returns the two reports (full, quotient) for what only some reductions preserve."""
    st = quot.reduction_stats
    assert (st["full_states"], st["full_arcs"]) == (full.n_states, full.n_arcs)
    sym = quot.graph.symmetry
    full_dead = [full.graph.states[i] for i in full.graph.dead_states()]
    assert {sym.canonical(s) for s in full_dead} == {quot.graph.states[i] for i in quot.graph.dead_states()}
    rf, rq = build_report(full, trace_to_dead=False), build_report(quot, dead_listed=3)
    assert rq.full_dead_count == len(full_dead)
    assert [(b.place, b.upper, b.lower) for b in rf.bounds.places] == [(b.place, b.upper, b.lower)
                                                                      for b in rq.bounds.places]
    assert (rf.bounds.max_tokens_per_marking, rf.bounds.max_tokens_in_place) == \
        (rq.bounds.max_tokens_per_marking, rq.bounds.max_tokens_in_place)
    assert rf.dead_transitions == rq.dead_transitions
    for d in rq.dead_listed:
        assert replay(engine, quot.graph, d.trace)
    return rf, rq


def fewer_orbits(model, scalars, max_states: int) -> bool:
    """Whether the full graph has at most `max_states` states and more than the quotient has orbits (a
    cross-check on a net that is not reduced compares nothing)."""
    engine = model.engine()
    full = Explorer(engine, ExploreOptions(max_states=max_states)).run()
    quot = Explorer(engine, ExploreOptions(reduction="symmetry", symmetry=scalars)).run()
    return full.complete and quot.n_states < full.n_states


def check_canonical_forms(c, group: list, states) -> None:
    """Against brute force over the whole `group` of canonicaliser `c`: each state's representative is the
    same for every state of its orbit and lies in it; its stabiliser size is the number of renamings
    fixing the state."""
    for s in states:
        rep, stab = c.canonical(s)
        images = [c.apply(s, g) for g in group]
        assert rep in images
        assert stab == sum(1 for t in images if t == s)
        assert {c.canonical(t)[0] for t in images} == {rep}
