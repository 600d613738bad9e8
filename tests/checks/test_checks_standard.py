"""Each standard-report property on small hand-worked nets."""

from _toy import dining_philosophers
from nets import coloured_register, counter, just_net, livelock, timed_cycle, timed_merge, two_terminal_sccs

from cpn.checks import (
    Fairness,
    TransitionIndex,
    boundedness,
    dead_markings,
    dead_transitions,
    fairness,
    home_markings,
    live_transitions,
    scc_summary,
)
from cpn.statespace import ExploreOptions, Explorer


def _analyse(engine, **opts):
    x = Explorer(engine, ExploreOptions(**opts)).run()
    ti = TransitionIndex(engine)
    arc_t = ti.arc_transitions(x.graph.bes)
    scc = scc_summary(x)
    return x, ti, arc_t, scc


def _names(engine, ts):
    return [engine.transitions[t].name for t in ts]


def test_two_terminal_sccs():
    e = two_terminal_sccs()
    x, ti, arc_t, scc = _analyse(e)
    assert (x.n_states, x.n_arcs) == (4, 4)
    assert (scc.nodes, scc.terminal, scc.nontrivial) == (3, 2, 1)
    assert scc.arcs == 2 and scc.arc_pairs == 2
    home = home_markings(x, scc)
    assert home.states == [] and home.initial_is_home is False
    dead = dead_markings(x)
    assert dead.count == 1 and e.token_counts(x.graph.states[dead.states[0]]) == (0, 0, 1, 0)
    assert live_transitions(x, scc, arc_t) == []
    assert dead_transitions(x, ti) == []
    f = fairness(x, scc.decomposition, arc_t)
    assert f == {0: Fairness.FAIR, 1: Fairness.FAIR, 2: Fairness.IMPARTIAL, 3: Fairness.IMPARTIAL}


def test_livelock_fairness_and_home():
    e = livelock()
    x, ti, arc_t, scc = _analyse(e)
    assert (x.n_states, x.n_arcs) == (3, 3)
    f = fairness(x, scc.decomposition, arc_t)
    assert f == {0: Fairness.FAIR, 1: Fairness.IMPARTIAL, 2: Fairness.NONE}
    home = home_markings(x, scc)
    assert list(home.states) == dead_markings(x).states


def test_just_but_not_fair():
    e = just_net()
    x, ti, arc_t, scc = _analyse(e)
    f = fairness(x, scc.decomposition, arc_t)
    assert f == {0: Fairness.IMPARTIAL, 1: Fairness.IMPARTIAL, 2: Fairness.JUST}
    assert dead_markings(x).count == 0
    # two cycles: (A,X)<->(B,X) and (A,Y)<->(B,Y); t leads from the first to the second
    assert (scc.nodes, scc.terminal) == (2, 1)
    assert live_transitions(x, scc, arc_t) == [0, 1]


def test_no_infinite_sequences():
    e = timed_merge()
    x, ti, arc_t, scc = _analyse(e)
    assert fairness(x, scc.decomposition, arc_t) is None


def test_dead_transitions_and_live_all():
    e = dining_philosophers(3)
    x, ti, arc_t, scc = _analyse(e)
    assert dead_transitions(x, ti) == []
    e2 = coloured_register()
    x2, ti2, arc_t2, scc2 = _analyse(e2)
    assert live_transitions(x2, scc2, arc_t2) == [0, 1]
    assert list(home_markings(x2, scc2).states) == [0, 1]


def test_integer_and_multiset_bounds():
    e = coloured_register()
    x = Explorer(e).run()
    b = boundedness(x)
    (r,) = b.places
    assert (r.upper, r.lower) == (2, 2)
    assert r.upper_multiset == {"a": 1, "b": 1, "c": 1}
    assert r.lower_multiset == {"c": 1}
    assert r.upper_text == "1`a++1`b++1`c" and r.lower_text == "1`c"
    assert (b.max_tokens_per_marking, b.max_tokens_in_place, b.max_of_one_colour_in_place) == (2, 2, 1)


def test_bounds_dining_philosophers():
    e = dining_philosophers(5)
    b = boundedness(Explorer(e).run())
    assert [(p.place, p.upper, p.lower) for p in b.places] == [
        ("Top'Think 1", 5, 0), ("Top'HasLeft 1", 5, 0), ("Top'Eat 1", 2, 0), ("Top'Forks 1", 5, 0)]
    assert b.max_tokens_per_marking == 10


def test_timed_dead_markings_merge_modulo_time():
    e = timed_merge()
    x, ti, arc_t, scc = _analyse(e)
    dead = dead_markings(x)
    assert dead.count == 2 and dead.untimed_count == 1
    assert home_markings(x, scc).initial_is_home is False
    b = boundedness(x)
    assert [(p.upper, p.lower) for p in b.places] == [(1, 0), (1, 0)]
    assert b.places[1].upper_text == "1`()"


def test_timed_initial_home_marking():
    x, ti, arc_t, scc = _analyse(timed_cycle())
    assert home_markings(x, scc).initial_is_home is True


def test_partial_search_reports_no_dead_markings_and_no_liveness():
    x, ti, arc_t, scc = _analyse(counter(), max_states=5)
    assert not x.complete
    dead = dead_markings(x)
    assert dead.count == 0 and dead.unexpanded == 1
    assert live_transitions(x, scc, arc_t) is None
    assert home_markings(x, scc).states is None
