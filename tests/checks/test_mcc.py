"""The Model Checking Contest's global properties (cpn.checks.mcc): one Verdict each, where every property
lives."""

import cpn
from cpn.checks.mcc import PROPERTIES, distinct_marking_pairs, global_properties
from cpn.checks.verdict import Status, bfs_path
from cpn.statespace import ExploreOptions, Explorer


def _x(text, **opts):
    return Explorer(cpn.loads(text).engine(), ExploreOptions(**opts)).run()


def _status(x):
    return {name: v.status.value for name, v in global_properties(x).items()}


def test_a_cycle_of_one_token():
    x = _x("colset U = unit; place A : U = 1`(); place B : U;"
           " trans go; trans back; arc A -> go; arc go -> B; arc B -> back; arc back -> A;")
    assert _status(x) == {"OneSafe": "holds", "QuasiLiveness": "holds", "Liveness": "holds",
                          "StableMarking": "violated"}


def test_two_tokens_a_dead_transition_and_a_dead_end():
    x = _x("colset U = unit; place A : U = 1`(); place B : U; place C : U;"
           " trans go; trans never; arc A -> go; arc go -> B; arc go -> B; arc C -> never;")
    v = global_properties(x)
    assert _status(x) == {"OneSafe": "violated", "QuasiLiveness": "violated", "Liveness": "violated",
                          "StableMarking": "holds"}  # C stays empty
    # the evidence of OneSafe is the shortest path to a marking with two tokens on a place
    ev = v["OneSafe"].evidence
    assert list(ev.path) == bfs_path(x.graph, 1) and max(x.engine.token_counts(x.graph.states[ev.target])) == 2
    assert v["QuasiLiveness"].details["dead"] == ["Top'never 1"] and "B" in v["OneSafe"].message


def test_unknown_with_the_reason_on_a_partial_state_space():
    x = _x("colset N = int; var n : N; place P : N = 1`0; trans inc; arc P -> inc : n; arc inc -> P : n + 1;",
           max_states=5)
    v = global_properties(x)
    assert not x.complete and list(v) == list(PROPERTIES)
    assert all(r.status is Status.UNKNOWN and "partial" in r.message for r in v.values())


def test_distinct_marking_pairs_count_parallel_arcs_once():
    x = _x("colset N = int with 1..2; var n : N; colset U = unit; place P : N = 1`1 ++ 1`2; place Q : U;"
           " trans t; arc P -> t : n; arc t -> Q : ();")
    assert x.n_arcs == 4 and distinct_marking_pairs(x) == 4
    y = _x("colset N = int with 1..2; var n : N; colset U = unit; place Q : U;"
           " trans t; arc t -> Q : if n = 1 then 1`() else 1`();", max_states=3)
    assert y.n_arcs > distinct_marking_pairs(y)
