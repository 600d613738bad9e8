"""The Model Checking Contest's global properties of a complete state space.

On the net as given (for a coloured net, its coloured places and transitions):

- OneSafe: no place ever holds two tokens;
- QuasiLiveness: every transition occurs somewhere;
- Liveness: every transition occurs in every terminal strongly connected component (so that from every
  reachable state it can occur again);
- StableMarking: some place holds the same number of tokens in every reachable state (for a coloured
  place the colours may change, as in TokenRing-COL).

Examples
--------
>>> import cpn
>>> from cpn.statespace import Explorer
>>> m = cpn.loads("colset U = unit; place A : U = 1`(); place B : U;"
...               " trans go; trans back; arc A -> go; arc go -> B; arc B -> back; arc back -> A;")
>>> global_properties(Explorer(m.engine()).run())
{'OneSafe': True, 'QuasiLiveness': True, 'Liveness': True, 'StableMarking': False}
"""

from __future__ import annotations

from cpn.checks._common import TransitionIndex
from cpn.checks.bounds import Boundedness, boundedness
from cpn.checks.liveness import SccSummary, dead_transitions, live_transitions, scc_summary
from cpn.statespace import Exploration

PROPERTIES: tuple[str, ...] = ("OneSafe", "QuasiLiveness", "Liveness", "StableMarking")


def global_properties(x: Exploration, bounds: Boundedness | None = None, scc: SccSummary | None = None,
                      tindex: TransitionIndex | None = None) -> dict[str, bool] | None:
    """The four global properties by name, or None on a partial state space (they say nothing then).

    `bounds`, `scc` and `tindex` may be given when already computed.
    """
    if not x.complete:
        return None
    engine = x.engine
    b = bounds or boundedness(x)
    tindex = tindex or TransitionIndex(engine)
    scc = scc or scc_summary(x)
    live = live_transitions(x, scc, tindex.arc_transitions(x.graph.bes))
    return {
        "OneSafe": b.max_tokens_in_place <= 1,
        "QuasiLiveness": not dead_transitions(x, tindex),
        "Liveness": live is not None and len(live) == len(engine.transitions),
        "StableMarking": any(p.upper == p.lower for p in b.places),
    }


def distinct_marking_pairs(x: Exploration) -> int:
    """The number of distinct (M, M') pairs joined by at least one arc (the contest counts arcs so)."""
    g = x.graph
    off, dst = g.offsets, g.dst
    return sum(len(set(dst[off[i]:off[i + 1]])) for i in range(g.expanded))


__all__ = ["PROPERTIES", "distinct_marking_pairs", "global_properties"]
