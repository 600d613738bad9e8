"""The Model Checking Contest's global properties (cpn.checks.mcc), computed where every property lives."""

import cpn
from cpn.checks.mcc import distinct_marking_pairs, global_properties
from cpn.statespace import ExploreOptions, Explorer


def _x(text, **opts):
    return Explorer(cpn.loads(text).engine(), ExploreOptions(**opts)).run()


def test_a_cycle_of_one_token():
    x = _x("colset U = unit; place A : U = 1`(); place B : U;"
           " trans go; trans back; arc A -> go; arc go -> B; arc B -> back; arc back -> A;")
    assert global_properties(x) == {"OneSafe": True, "QuasiLiveness": True, "Liveness": True,
                                    "StableMarking": False}


def test_two_tokens_a_dead_transition_and_a_dead_end():
    x = _x("colset U = unit; place A : U = 2`(); place B : U; place C : U;"
           " trans go; trans never; arc A -> go; arc go -> B; arc C -> never;")
    assert global_properties(x) == {"OneSafe": False, "QuasiLiveness": False, "Liveness": False,
                                    "StableMarking": True}  # C stays empty


def test_nothing_on_a_partial_state_space():
    x = _x("colset N = int; var n : N; place P : N = 1`0; trans inc; arc P -> inc : n; arc inc -> P : n + 1;",
           max_states=5)
    assert not x.complete and global_properties(x) is None


def test_distinct_marking_pairs_count_parallel_arcs_once():
    x = _x("colset N = int with 1..2; var n : N; colset U = unit; place P : N = 1`1 ++ 1`2; place Q : U;"
           " trans t; arc P -> t : n; arc t -> Q : ();")
    # from the initial marking, t with n=1 and n=2 lead to two different markings
    assert x.n_arcs == 4 and distinct_marking_pairs(x) == 4
    y = _x("colset N = int with 1..2; var n : N; colset U = unit; place Q : U;"
           " trans t; arc t -> Q : if n = 1 then 1`() else 1`();", max_states=3)
    assert y.n_arcs > distinct_marking_pairs(y)
