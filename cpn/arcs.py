"""`ArcKind`: the kinds of arcs between a place and a transition, and what each does to its place.

The one vocabulary of every layer: the checker gives each arc its kind, the net keeps it, the engines
consume, produce, test and block by it. A kind is a string enumeration, so ``ArcKind.IN == "in"``.

Examples
--------
>>> ArcKind.BOTH.consumes, ArcKind.BOTH.produces, ArcKind.BOTH.syntax
(True, True, '<->')
>>> [k.value for k in ArcKind if k.reads]
['in', 'both', 'inhibitor', 'reset']
"""

from __future__ import annotations

from enum import StrEnum


class ArcKind(StrEnum):
    IN = "in"  # place -> transition: consumes the inscription
    OUT = "out"  # transition -> place: produces the inscription
    BOTH = "both"  # double arc (<->): consumes the inscription and puts it back
    INHIBITOR = "inhibitor"  # blocks the transition while the place holds the inscription (or any token)
    RESET = "reset"  # removes every token of the place when the transition occurs

    @property
    def consumes(self) -> bool:
        """The transition needs the inscription's tokens on the place and removes them."""
        return self in (ArcKind.IN, ArcKind.BOTH)

    @property
    def produces(self) -> bool:
        """The transition adds the inscription's tokens to the place."""
        return self in (ArcKind.OUT, ArcKind.BOTH)

    @property
    def blocks(self) -> bool:
        """The place's marking can disable the transition without being changed (an inhibitor arc)."""
        return self is ArcKind.INHIBITOR

    @property
    def empties(self) -> bool:
        """The transition empties the place (a reset arc)."""
        return self is ArcKind.RESET

    @property
    def reads(self) -> bool:
        """The place's marking is an input of the transition: its enabling or its effect depends on it."""
        return self is not ArcKind.OUT

    @property
    def syntax(self) -> str:
        """The arc's keyword or arrow in `.cpnet` (docs/language.md)."""
        return {ArcKind.IN: "->", ArcKind.OUT: "->", ArcKind.BOTH: "<->"}.get(self, self.value)

    @classmethod
    def written_from_the_place(cls, syntax: str) -> ArcKind | None:
        """The kind of an arc written `syntax` that must go from a place to a transition (every kind but
        the plain arc `->`, whose direction gives IN or OUT); None for `->`.

        >>> ArcKind.written_from_the_place("<->"), ArcKind.written_from_the_place("->")
        (<ArcKind.BOTH: 'both'>, None)
        """
        if syntax == "->":
            return None
        return next(k for k in cls if k.syntax == syntax)


__all__ = ["ArcKind"]
