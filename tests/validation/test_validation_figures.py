"""The figures and MCC global properties that `cpn-verify validate` computes, on hand-made nets."""

from __future__ import annotations

import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "statespace"))

from _toy import dining_philosophers, pt_net  # noqa: E402

from cpn.cli.validate import compare, explore_figures, found_figures  # noqa: E402


def test_cycle_with_a_constant_place():
    # p0 -> t0 -> p1 -> t1 -> p0 with one token; p2 holds 2 tokens and is never touched
    eng = pt_net([[1, 0, 0], [0, 1, 0]], [[0, 1, 0], [1, 0, 0]], [1, 0, 2])
    f = explore_figures(eng)
    assert (f.states, f.arcs, f.max_tokens_per_marking, f.max_tokens_in_place, f.dead_markings) == (2, 2, 3, 2, 0)
    assert f.properties == {"OneSafe": False, "QuasiLiveness": True, "Liveness": True, "StableMarking": True}


def test_dead_end_and_never_enabled_transition():
    # t0 moves the token from p0 to p1; t1 needs 2 tokens in p0 and never fires
    eng = pt_net([[1, 0], [2, 0]], [[0, 1], [0, 0]], [1, 0])
    f = explore_figures(eng)
    assert (f.states, f.arcs, f.dead_markings, f.deadlock_reachable) == (2, 1, 1, True)
    assert f.properties == {"OneSafe": True, "QuasiLiveness": False, "Liveness": False, "StableMarking": False}


def test_liveness_needs_every_terminal_component():
    # t0 and t1 choose between two self-contained cycles (t2 on p1, t3 on p2): no transition is live
    eng = pt_net([[1, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]],
                 [[0, 1, 0], [0, 0, 1], [0, 1, 0], [0, 0, 1]], [1, 0, 0])
    f = explore_figures(eng)
    assert (f.states, f.arcs) == (3, 4)
    assert f.properties["QuasiLiveness"] and not f.properties["Liveness"]


def test_coloured_max_of_one_colour_and_comparison():
    eng = dining_philosophers(3)
    f = explore_figures(eng)
    assert f.max_tokens_in_place == 3 and f.max_of_one_colour_in_place == 1
    found = found_figures(f, "pnml-col")
    assert found["max_tokens_in_place"] == 1
    assert found_figures(f, "pnml-pt")["max_tokens_in_place"] == 3
    assert compare({"states": f.states, "arcs": f.arcs + 1, "mcc_global_properties": {"OneSafe": True}}, found) \
        == [f"arcs: expected {f.arcs + 1}, found {f.arcs}", "OneSafe: expected True, found False"]


def test_partial_exploration_has_no_properties():
    eng = dining_philosophers(4)
    f = explore_figures(eng, max_states=5)
    assert not f.complete and f.properties == {}
    assert "mcc_global_properties" not in found_figures(f, "pnml-col")


def test_parallel_arcs_and_self_loops_count_once_as_marking_pairs():
    # t0 and t1 both move the token from p0 to p1; t2 is a self-loop on p1
    eng = pt_net([[1, 0], [1, 0], [0, 1]], [[0, 1], [0, 1], [0, 1]], [1, 0])
    f = explore_figures(eng)
    assert (f.states, f.arcs, f.arcs_distinct_marking_pairs) == (2, 3, 2)
    assert (f.scc_nodes, f.scc_arcs) == (2, 2)
    found = found_figures(f, "pnml-pt")
    assert compare({"arcs_distinct_marking_pairs": 2, "scc_graph": {"nodes": 2, "arcs": 1}}, found) \
        == ["scc_graph arcs: expected 1, found 2"]
    assert compare({"arcs_distinct_marking_pairs": None}, found) == []
