"""The explorer's successor step under a partial-order reduction: `ReducedSuccessors`.

Wraps the engine's successor function: in each state only the binding elements of the transition
instances a `cpn.engine.stubborn.StubbornSets` chooses are followed. With the visibility condition on
(invariants), the cycle proviso for breadth-first search is applied here: a state one of whose reduced
successors is already stored is fully expanded, so every cycle of the reduced graph holds a fully
expanded state (the last-stored state of a cycle has its successor on the cycle stored before it).
"""

from __future__ import annotations


class ReducedSuccessors:
    """`successors(state)` of the reduced graph; `index` is the store's state -> id map (the proviso)."""

    def __init__(self, engine, sets, index: dict):
        self.engine = engine
        self.sets = sets
        self.index = index
        self.proviso = sets.preserves_invariants
        self.full_expansions = 0  # states with more than one enabled transition instance, fully expanded
        self.reduced = 0  # states expanded with a proper subset of their enabled transition instances
        self._transition: dict[int, int] = {}
        self._scapegoats = sorted(sets.scapegoat_places)  # places whose emptiness the sets look at

    def __call__(self, state):
        out = self.engine.successors(state)
        if len(out) < 2:
            return out
        of = self._transition
        enabled = set()
        for be, _ in out:
            t = of.get(be)
            if t is None:
                t = of[be] = self.engine.binding_element(be).transition
            enabled.add(t)
        chosen = None
        if len(enabled) > 1:
            empty = frozenset()
            if self._scapegoats:
                counts = self.engine.token_counts(state)
                empty = frozenset(p for p in self._scapegoats if not counts[p])
            chosen = self.sets.choose(frozenset(enabled), empty)
        if chosen is None:
            self.full_expansions += len(enabled) > 1
            return out
        reduced = [(be, t) for be, t in out if of[be] in chosen]
        if self.proviso:
            index = self.index
            if any(t in index for _, t in reduced):
                self.full_expansions += 1
                return out
        self.reduced += 1
        return reduced


__all__ = ["ReducedSuccessors"]
