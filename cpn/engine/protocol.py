"""`Engine`: the successor function of a net, as the state space and the checks see it.

Both engines (`compile_net(net)` and `compile_net(net, reference=True)`) implement it, and so may any
other back end: the explorer, the checks and the reports use nothing else (docs/internals.md).

Examples
--------
>>> import cpn
>>> engine = cpn.loads("colset U = unit; place A : U = 1`(); place B : U;"
...                    " trans t; arc A -> t; arc t -> B;").engine()
>>> s0 = engine.initial_state()
>>> [(engine.format_binding_element(be), engine.format_marking(s1, 1)) for be, s1 in engine.successors(s0)]
[("Top't 1: {}", '1`()')]
"""

from __future__ import annotations

from collections.abc import Hashable, Sequence
from typing import Any, Protocol


class Place(Protocol):
    """A place instance as an engine lists it: its name ("Page'Place 1") and whether it is timed."""

    name: str
    timed: bool


class Transition(Protocol):
    """A transition instance as an engine lists it: its name ("Page'Trans 1")."""

    name: str


class BindingElementLike(Protocol):
    transition: int  # index into engine.transitions
    binding: dict


class Engine(Protocol):
    """What the state space, the checks and the reports need of an engine.

    States are hashable values; the engines of this package use tuples of small integers, one per place
    (the place's marking id), plus the clock for timed nets. Binding elements are small integers, stable
    for the engine's lifetime.
    """

    places: Sequence[Place]
    transitions: Sequence[Transition]
    is_timed: bool
    reads_clock: bool  # timed nets: some transition reads the clock (intTime()); read only if is_timed
    clock_reads: dict  # timed nets: transition index -> where it first reads the clock (cpn.engine.clock)

    def initial_state(self) -> Hashable:
        """The initial marking (with the clock 0 for timed nets)."""

    def successors(self, state: Any) -> list[tuple[int, Any]]:
        """(binding element, successor state) of every enabled binding element, in a fixed order."""

    def binding_element(self, be: int) -> BindingElementLike:
        """The transition and the binding of a binding element id."""

    def format_binding_element(self, be: int) -> str:
        """CPN Tools' text of a binding element: ``Top'Send 1: {a=1, f=3}``."""

    def marking(self, state: Any) -> list[dict]:
        """One multiset (value -> count; timed places: (value, timestamp) -> count) per place."""

    def token_counts(self, state: Any) -> tuple[int, ...]:
        """The number of tokens on each place."""

    def untimed(self, state: Any) -> Hashable:
        """The state without timestamps and clock (the state itself for untimed nets)."""

    def clock(self, state: Any) -> int:
        """The global clock of a state (0 for untimed nets)."""

    def format_marking(self, state: Any, p: int) -> str:
        """CPN ML text of place p's marking, e.g. ``1`ph(1)++2`ph(2)``."""

    def format_multiset(self, p: int, ms: dict) -> str:
        """CPN ML text of an untimed multiset (value -> count) of place p's colour set."""

    # Optional: `successor_groups()`, the successor function as transition groups for the native search
    # (`cpn.engine.compiled.TransitionGroups`, or None), and `timed_groups()`, those of a timed net or a net
    # with priorities (`cpn.engine.timedgroups.TimedGroups`, or None); an engine without them is searched in
    # Python.


__all__ = ["BindingElementLike", "Engine", "Place", "Transition"]
