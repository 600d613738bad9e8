"""The Model Checking Contest's global properties of a complete state space.

On the net as given (for a coloured net, its coloured places and transitions):

- OneSafe: no place ever holds two tokens;
- QuasiLiveness: every transition occurs somewhere;
- Liveness: every transition occurs in every terminal strongly connected component (so that from every
  reachable state it can occur again);
- StableMarking: some place holds the same number of tokens in every reachable state (for a coloured
  place the colours may change, as in TokenRing-COL).

Each is a `Verdict` (`cpn.checks.verdict`): holds, violated (OneSafe with the shortest path to a marking
with two tokens on a place), or unknown with the reason on a partial state space.

Examples
--------
>>> import cpn
>>> from cpn.statespace import Explorer
>>> m = cpn.loads("colset U = unit; place A : U = 1`(); place B : U;"
...               " trans go; trans back; arc A -> go; arc go -> B; arc B -> back; arc back -> A;")
>>> {name: v.status.value for name, v in global_properties(Explorer(m.engine()).run()).items()}
{'OneSafe': 'holds', 'QuasiLiveness': 'holds', 'Liveness': 'holds', 'StableMarking': 'violated'}
"""

from __future__ import annotations

from cpn.checks.bounds import Boundedness, boundedness
from cpn.checks.columns import TransitionIndex
from cpn.checks.liveness import SccSummary, dead_transitions, live_transitions, scc_summary
from cpn.checks.verdict import Evidence, Verdict, evidence_to
from cpn.statespace import Exploration

PROPERTIES: tuple[str, ...] = ("OneSafe", "QuasiLiveness", "Liveness", "StableMarking")


def global_properties(x: Exploration, bounds: Boundedness | None = None, scc: SccSummary | None = None,
                      tindex: TransitionIndex | None = None) -> dict[str, Verdict]:
    """The four global properties by name (`PROPERTIES` order), each a `Verdict`.

    `bounds`, `scc` and `tindex` may be given when already computed. On a partial state space every
    property is unknown: a maximum or a transition may come later.
    """
    if not x.complete:
        reason = f"the state space is partial ({x.stop_reason.describe(x.options)})"
        return {name: Verdict.unknown(reason) for name in PROPERTIES}
    engine = x.engine
    b = bounds or boundedness(x)
    tindex = tindex or TransitionIndex(engine)
    scc = scc or scc_summary(x)
    names = [t.name for t in engine.transitions]
    out: dict[str, Verdict] = {}
    crowded = [p for p in b.places if p.upper > 1]
    if crowded:
        out["OneSafe"] = Verdict.violated(f"place {crowded[0].place} holds up to {crowded[0].upper} tokens",
                                          _first_crowded(x))
    else:
        out["OneSafe"] = Verdict.holds("no place ever holds two tokens")
    dead = dead_transitions(x, tindex)
    out["QuasiLiveness"] = (Verdict.violated(f"transition {names[dead[0]]} never occurs", dead=[names[t] for t in dead])
                            if dead else Verdict.holds("every transition occurs"))
    live = set(live_transitions(x, scc, tindex.arc_transitions(x.graph.bes)) or ())
    not_live = [t for t in range(len(names)) if t not in live]
    out["Liveness"] = (Verdict.violated(f"transition {names[not_live[0]]} does not occur in every terminal strongly "
                                        "connected component", not_live=[names[t] for t in not_live])
                       if not_live else Verdict.holds("every transition occurs in every terminal component"))
    stable = [p.place for p in b.places if p.upper == p.lower]
    out["StableMarking"] = (Verdict.holds(f"place {stable[0]} always holds the same number of tokens")
                            if stable else Verdict.violated("the number of tokens of every place changes"))
    return out


def _first_crowded(x: Exploration) -> Evidence | None:
    """The shortest path to the first state (in BFS order) where some place holds two tokens."""
    counts = x.engine.token_counts
    for i, s in enumerate(x.graph.states):
        if max(counts(s), default=0) > 1:
            return evidence_to(x.graph, i)
    return None


def distinct_marking_pairs(x: Exploration) -> int:
    """The number of distinct (M, M') pairs joined by at least one arc (the contest counts arcs so)."""
    g = x.graph
    off, dst = g.offsets, g.dst
    return sum(len(set(dst[off[i]:off[i + 1]])) for i in range(g.expanded))


__all__ = ["PROPERTIES", "distinct_marking_pairs", "global_properties"]
