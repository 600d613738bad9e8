"""Which properties a state space reduced by stubborn sets decides, and the places they read.

Stubborn sets (`cpn.engine.stubborn`) preserve the dead markings (so `deadlock_free` and
`dead_markings`, with its count and predicate), and, with the visibility condition on the places a
property reads, the markings of those places that are reachable (so `invariant` and `reachable`).
Every other kind, and a text that reads the enabled binding elements (the arcs of the reduced graph are
not those of the full one), gets `unknown` with the reason, never a verdict.
"""

from __future__ import annotations

from cpn.properties.kinds import Check, DeadlockFree, DeadMarkings, Invariant, Reachable

NOT_PRESERVED: str = "not preserved by stubborn sets"


def stubborn_plan(checks: list[Check]) -> tuple[frozenset | None, dict]:
    """(the visible places: those the invariants and reachability texts read, None when there is no
    such property; check -> why its verdict is not preserved)."""
    visible: set[int] = set()
    safety = False
    refused: dict = {}
    for c in checks:
        if isinstance(c, (DeadlockFree, DeadMarkings)):
            continue
        if isinstance(c, (Invariant, Reachable)):
            if c.pred.uses_enabled:
                refused[c] = (f"{NOT_PRESERVED}: the text reads the enabled binding elements, and the arcs of "
                              "the reduced graph are not those of the full graph")
                continue
            safety = True
            visible.update(c.pred.reads)
            continue
        refused[c] = (f"{NOT_PRESERVED}: a '{c.spec.kind}' property needs the full graph (stubborn sets keep "
                      "only the dead markings, invariants and reachability)")
    return (frozenset(visible) if safety else None), refused


__all__ = ["NOT_PRESERVED", "stubborn_plan"]
