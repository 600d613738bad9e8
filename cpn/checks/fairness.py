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
from cpn.statespace.scc import SccDecomposition, has_cycle


class Fairness(enum.Enum):
    IMPARTIAL = "Impartial"
    FAIR = "Fair"
    JUST = "Just"
    NONE = "No Fairness"


def fairness(x: Exploration, dec: SccDecomposition, arc_transitions: array) -> dict[int, Fairness] | None:
    """Fairness class of each transition instance, or None when there is no infinite sequence."""
    if not any(dec.nontrivial):
        return None
    g = x.graph
    n = g.n_states
    off, dst = g.offsets, g.dst
    # Cycles only live inside nontrivial SCCs: every search below is confined to them.
    cyclic = bytearray(map(dec.nontrivial.__getitem__, dec.comp))
    src = g.arc_sources()
    result: dict[int, Fairness] = {}
    ntrans = len(x.engine.transitions)
    for t in range(ntrans):
        skip = bytearray(map(t.__eq__, arc_transitions))
        enabled = bytearray(n)
        for v in compress(src, skip):
            enabled[v] = 1
        keep = cyclic
        witness = {}

        def avoid_t(nodes, enabled=enabled, witness=witness):
            witness["cycle"] = True
            if any(map(enabled.__getitem__, nodes)):
                witness["enabled"] = True
                return True
            return False

        has_cycle(n, off, dst, skip_arc=skip, keep_node=keep, within=avoid_t)
        if not witness.get("cycle"):
            result[t] = Fairness.IMPARTIAL
        elif not witness.get("enabled"):
            result[t] = Fairness.FAIR
        else:
            keep_enabled = bytearray(a & b for a, b in zip(cyclic, enabled))
            if has_cycle(n, off, dst, skip_arc=skip, keep_node=keep_enabled):
                result[t] = Fairness.NONE
            else:
                result[t] = Fairness.JUST
    return result
