"""Fairness of transition instances (CPN Tools' TIsFairness), decided on the SCCs of the graph.

Imports `cpn.statespace` only. For a transition instance t and the infinite occurrence sequences:
- impartial: t occurs infinitely often in every infinite occurrence sequence;
- fair: t occurs infinitely often in every infinite sequence in which it is enabled infinitely often;
- just: t occurs infinitely often in every infinite sequence in which it is, from some point on,
  continuously enabled.
On a finite graph an infinite sequence ends up cycling in a strongly connected set, so the witnesses
against each class are cycles that avoid t's arcs: any such cycle (not impartial), one through a state
where t is enabled (not fair), one whose states all enable t (not just). See docs/statespace.md.
"""

from __future__ import annotations

import enum
from array import array
from itertools import compress

from cpn.statespace import Exploration
from cpn.statespace.scc import SccDecomposition, first_cycle_component, has_cycle


class Fairness(enum.Enum):
    IMPARTIAL = "Impartial"
    FAIR = "Fair"
    JUST = "Just"
    NONE = "No Fairness"


def fairness(x: Exploration, dec: SccDecomposition, arc_transitions: array) -> dict[int, Fairness] | None:
    """Fairness class of each transition instance, or None when there is no infinite sequence.

    Per transition instance t, at most three searches, all confined to the nontrivial SCCs:
    1. a cycle avoiding t: if there is none, t is impartial;
    2. a cycle avoiding t among the states where t is enabled: t is not just (No Fairness);
    3. otherwise the SCCs of the graph less t's arcs: one holding a state that enables t means just,
       none means fair.
    1 and 2 are depth-first searches that stop at their first back arc: the common answers
    (impartial, no fairness) cost one or two such searches, and only 1 may have to visit everything.
    """
    if not any(dec.nontrivial):
        return None
    g = x.graph
    n = g.n_states
    off, dst = g.offsets, g.dst
    ntrans = len(x.engine.transitions)
    cyclic = bytearray(map(dec.nontrivial.__getitem__, dec.comp))
    enabled = _enabled_in_cycles(g, cyclic, arc_transitions, ntrans)
    result: dict[int, Fairness] = {}
    for t in range(ntrans):
        if not has_cycle(n, off, dst, arc_transitions, t, cyclic):
            result[t] = Fairness.IMPARTIAL
            continue
        en = enabled[t]
        if any(en) and has_cycle(n, off, dst, arc_transitions, t, en):
            result[t] = Fairness.NONE
            continue

        def through_enabled(nodes, en=en):
            return any(map(en.__getitem__, nodes))

        found = first_cycle_component(n, off, dst, through_enabled, arc_transitions, t, cyclic)
        result[t] = Fairness.JUST if found is not None else Fairness.FAIR
    return result


def _enabled_in_cycles(g, cyclic: bytearray, arc_transitions: array, ntrans: int) -> list[bytearray]:
    """Per transition instance, a bytearray over states: enabled there, and the state lies on a cycle."""
    n = g.n_states
    enabled = [bytearray(n) for _ in range(ntrans)]
    off = g.offsets
    expanded = g.expanded
    for v in compress(range(min(n, expanded)), cyclic):
        a, b = off[v], off[v + 1]
        if b - a == 1:
            enabled[arc_transitions[a]][v] = 1
        else:
            for t in set(arc_transitions[a:b]):
                enabled[t][v] = 1
    return enabled
