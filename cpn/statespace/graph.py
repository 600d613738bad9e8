"""The occurrence graph as compact arrays: states (a `store`), CSR arcs and BFS parent pointers.

Arcs are stored per source state in breadth-first order, so the
arcs of state i are `dst[offsets[i]:offsets[i+1]]` (destinations) and `bes[...]` (binding elements).
"""

from __future__ import annotations

from array import array
from collections.abc import Sequence
from dataclasses import dataclass, field

from cpn.statespace.store import TupleStore


@dataclass
class StateGraph:
    """States (engine tuples) numbered 0.. in discovery order; arcs in CSR form.

    Only the first `expanded` states have their arcs; the rest are unexpanded (a limit stopped the
    search before they were reached). `parent[i]`/`parent_be[i]` give the BFS tree (-1 for state 0),
    so the path they describe is a shortest path from the initial state.
    """

    #: the states, numbered in discovery order (`cpn.statespace.store`: packed records or tuples)
    store: object = field(default_factory=TupleStore)
    offsets: array = field(default_factory=lambda: array("q", [0]))
    dst: array = field(default_factory=lambda: array("i"))
    # 16-bit binding-element ids until one does not fit (the explorer widens to 32 bits then):
    # saves 2 bytes per arc, 10 MB on MS(8).
    bes: array = field(default_factory=lambda: array("H"))
    parent: array = field(default_factory=lambda: array("i"))
    parent_be: array = field(default_factory=lambda: array("i"))
    #: the successor step of a quotient graph (`cpn.statespace.symmetry`), None for the full graph
    symmetry: object = None

    @property
    def states(self) -> Sequence:
        """The engine's state of every id (a sequence; a packed store decodes a state when it is read)."""
        return self.store.states

    @property
    def n_states(self) -> int:
        """The number of states found (expanded or not)."""
        return len(self.store)

    @property
    def n_arcs(self) -> int:
        """The number of arcs (occurrences of binding elements) recorded."""
        return len(self.dst)

    @property
    def expanded(self) -> int:
        """Number of states whose successors were computed (they are states 0..expanded-1)."""
        return len(self.offsets) - 1

    def is_expanded(self, i: int) -> bool:
        """Whether the successors of state i were computed."""
        return i < len(self.offsets) - 1

    def out_arcs(self, i: int) -> list[tuple[int, int]]:
        """(binding element, destination) of every arc leaving state i (empty if unexpanded)."""
        if i >= len(self.offsets) - 1:
            return []
        a, b = self.offsets[i], self.offsets[i + 1]
        return list(zip(self.bes[a:b], self.dst[a:b]))

    def state_id(self, state: tuple) -> int | None:
        """The number of an engine state in the graph, or None if it was not found."""
        return self.store.find(state)

    def dead_states(self) -> list[int]:
        """Expanded states with no outgoing arc, in increasing order (unexpanded states excluded)."""
        off = self.offsets
        return [i for i in range(len(off) - 1) if off[i] == off[i + 1]]
