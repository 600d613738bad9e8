"""The standard report's properties on small .cpnet models worked out by hand (see each model's comment)."""

import os

import cpn
from cpn.checks import Fairness
from cpn.report import build_report
from cpn.statespace import ExploreOptions, Explorer
from tests._shared import SHARED, needs_shared

MODELS = os.path.join(os.path.dirname(__file__), "..", "statespace", "models")
NETS = os.path.join(os.path.dirname(__file__), "..", "..", "bench", "nets")


def report(name, directory=MODELS, sets=None, **opts):
    e = cpn.load(os.path.join(directory, name), set=sets or {}).engine(time_condensation=False)
    return build_report(Explorer(e, ExploreOptions(**opts)).run(), model=name)


def test_two_terminal_sccs():
    r = report("two_terminal.cpnet")
    assert (r.exploration.n_states, r.exploration.n_arcs) == (4, 4)
    assert (r.scc.nodes, r.scc.terminal, r.scc.arcs) == (3, 2, 2)
    assert r.home.states == [] and r.live_transitions == [] and r.dead_transitions == []
    assert r.dead.count == 1
    assert {k: v for k, v in r.fairness.items()} == {
        "Top'Go 1": Fairness.FAIR, "Top'Stop 1": Fairness.FAIR,
        "Top'Tick 1": Fairness.IMPARTIAL, "Top'Tock 1": Fairness.IMPARTIAL}


def test_livelock():
    r = report("livelock.cpnet")
    assert r.fairness == {"Top'Start 1": Fairness.FAIR, "Top'Spin 1": Fairness.IMPARTIAL,
                          "Top'Exit 1": Fairness.NONE}
    assert list(r.home.states) == r.dead.states and r.dead.count == 1


def test_timed_dead_markings_merge_modulo_time():
    r = report("timed_merge.cpnet")
    assert r.dead.count == 2 and r.dead.untimed_count == 1
    assert r.home.initial_is_home is False
    assert r.fairness is None  # no infinite occurrence sequence
    assert [(b.place, b.upper, b.lower) for b in r.bounds.places] == [("Top'P 1", 1, 0), ("Top'Q 1", 1, 0)]


def test_multiset_bounds_strings():
    r = report("register.cpnet")
    (b,) = r.bounds.places
    assert (b.upper, b.lower) == (2, 2)
    assert b.upper_multiset == {"a": 1, "b": 1, "c": 1} and b.lower_multiset == {"c": 1}
    assert b.lower_text == '1`"c"'
    assert list(r.home.states) == [0, 1] and r.live_transitions == ["Top'Flip 1", "Top'Flop 1"]


def test_partial_reports_unexpanded_not_dead():
    r = report("counter.cpnet", max_states=30)
    assert not r.exploration.complete
    assert r.dead.count == 0 and r.dead.unexpanded == 1
    assert r.home.states is None and r.live_transitions is None and r.fairness is None


def test_dining_philosophers_report():
    r = report("dp.cpnet", NETS, {"N": "5"})
    assert r.dead.count == 1 and r.scc.nodes == 2 and r.scc.terminal == 1
    assert [(b.place, b.upper, b.lower) for b in r.bounds.places] == [
        ("DP'Think 1", 5, 0), ("DP'HasLeft 1", 5, 0), ("DP'Eat 1", 2, 0), ("DP'Forks 1", 5, 0)]
    assert set(r.fairness.values()) == {Fairness.IMPARTIAL}


def test_ms_report():
    r = report("ms.cpnet", NETS, {"N": "3"})
    assert r.dead.count == 0 and r.scc.nodes == 1 and list(r.home.states) == list(range(837))
    assert r.live_transitions == ["MS'Send 1", "MS'Receive 1", "MS'Reply 1", "MS'Collect 1", "MS'Update 1"]
    assert set(r.fairness.values()) == {Fairness.NONE}  # cpncheck 0.2.1 agrees on MS(4)
    bounds = {b.place: (b.upper, b.lower) for b in r.bounds.places}
    assert bounds["MS'Catalog 1"] == (6, 6) and bounds["MS'Reg 1"] == (3, 3)
    assert r.bounds.max_tokens_per_marking == 6 + 3 + 3 + 1


LIMIT = os.path.join(SHARED, "validation", "CPNBook-LimitProtocol", "7-2LimitProtocol.cpn")


@needs_shared
def test_limit_protocol_matches_the_published_cpn_tools_report():
    e = cpn.load(LIMIT).engine(time_condensation=False)
    r = build_report(Explorer(e).run(), model="7-2LimitProtocol.cpn")
    x = r.exploration
    assert (x.n_states, x.n_arcs) == (13_215, 52_784)
    assert (r.scc.nodes, r.scc.arcs) == (5_013, 37_312)  # CPN Tools counts arcs between SCCs, not pairs
    assert r.dead.count == 1
    assert [i + 1 for i in r.home.states] == [4868]  # the published home (and dead) marking
    assert r.dead_transitions == [] and r.live_transitions == []
    published = {"Packets_To_Send": (6, 6), "Data_Received": (1, 1), "NextSend": (1, 1), "NextRec": (1, 1),
                 "A": (3, 0), "B": (3, 0), "C": (3, 0), "D": (3, 0), "Limit": (3, 0)}
    found = {b.place.split("'")[1].rsplit(" ", 1)[0]: (b.upper, b.lower) for b in r.bounds.places}
    assert {k.replace("_", ""): v for k, v in found.items()} == {k.replace("_", ""): v for k, v in published.items()}
    assert r.bounds.max_tokens_per_marking == 12
