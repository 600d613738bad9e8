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
