"""`Engine`: the successor function of a net, as the state space and the checks see it.

Both engines (`compile_net(net)` and `compile_net(net, reference=True)`) implement it, and so may any
other back end: the explorer, the checks and the reports use nothing else, and of the optional
`Capabilities` only what an engine offers (docs/internals.md).

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


class Capabilities(Protocol):
    """What an engine may offer beyond `Engine`, and the upper layers use where it does (an engine without
    one is searched and checked without it: they look it up by these public names, never by private ones,
    `tests/test_layering.py`). The compiled engine offers all of them, the reference interpreter
    `reference`, `predicate_compiler` and `arc_tokens`/`binding_env` (`cpn.engine.reference.ReferenceEngine`).
    """

    net: Any  # the cpn.net.Net it runs: the reports draw it and replay traces with an engine of their own
    time_condensation: bool
    reference: bool  # the reference interpreter (the reports replay traces with the same kind of engine)
    functions: dict  # uid -> compiled function of the model (the property compiler calls them)
    store: Any  # the intern tables of place markings: store.views[p][id] (untimed dict), store.counts[p][id]

    def place_view(self, state: Any, p: int) -> dict:
        """The untimed multiset of place p (value -> count); not to be mutated."""

    def successor_groups(self) -> Any:
        """The successor function as transition groups for the native search
        (`cpn.engine.compiled.TransitionGroups`), or None (timed nets, priorities)."""

    def timed_groups(self) -> Any:
        """Those of a timed net or a net with priorities (`cpn.engine.timedgroups.TimedGroups`), or None."""

    def native_code(self) -> tuple:
        """(the C of the net's transitions, None), or (None, why not) (`cpn.engine.ccodegen`)."""

    def predicate_compiler(self, evaluator: Any, places: dict) -> Any:
        """A compiler of property texts (`cpn.engine.propertycode.PredicateCompiler`): closed expressions
        of the net's form into functions of a state id and a state; `places` maps the uid of a name that
        reads a place to its instances (instance number -> place index)."""

    def forget_memo(self) -> None:
        """Empty the memo tables of transition results: no result changes, only what is computed again
        (the sweep-line method calls it as it leaves markings behind)."""


#: the names `Capabilities` declares: the only ones `capability` and `has` answer for
CAPABILITIES: frozenset[str] = frozenset(
    {n for n in vars(Capabilities) if not n.startswith("_")} | set(Capabilities.__annotations__))


def capability(engine: Any, name: str, default: Any = None) -> Any:
    """The capability `name` of `engine` (a member `Capabilities` declares), or `default` where the engine
    does not offer it. The upper layers look capabilities up here, never by `getattr` on the engine, so
    that each one they use is declared; an undeclared name is a ValueError (a typo, or a member to
    declare first).

    >>> import cpn
    >>> engine = cpn.loads("colset U = unit; place A : U = 1`(); trans t; arc A -> t;").engine()
    >>> capability(engine, "time_condensation"), capability(object(), "place_view")
    (False, None)
    """
    if name not in CAPABILITIES:
        raise ValueError(f"'{name}' is not a capability declared in cpn.engine.protocol.Capabilities "
                         f"(declared: {', '.join(sorted(CAPABILITIES))})")
    return getattr(engine, name, default)


def has(engine: Any, name: str) -> bool:
    """Whether `engine` offers the capability `name` (declared in `Capabilities`, else a ValueError)."""
    return capability(engine, name, _MISSING) is not _MISSING


_MISSING = object()


__all__ = ["CAPABILITIES", "BindingElementLike", "Capabilities", "Engine", "Place", "Transition", "capability",
           "has"]
