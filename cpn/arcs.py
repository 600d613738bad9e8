"""`ArcKind`: the kinds of arcs between a place and a transition, and what each does to its place.

The one vocabulary of every layer: the checker gives each arc its kind, the net keeps it, the engines
consume, produce, test and block by it. A kind is a string enumeration, so ``ArcKind.IN == "in"``.

What a kind does is its effects, declared once in `EFFECTS` (`consumes`, `produces`, `blocks`, `empties`);
every module asks a kind for an effect (or for `reads` and `takes`, which follow from them), never for its
name, so a kind that combines existing effects is its member, its line in `EFFECTS` and its syntax.

Examples
--------
>>> ArcKind.BOTH.consumes, ArcKind.BOTH.produces, ArcKind.BOTH.syntax
(True, True, '<->')
>>> [k.value for k in ArcKind if k.reads]
['in', 'both', 'inhibitor', 'reset']
>>> [k.value for k in ArcKind if k.takes]
['in', 'both', 'reset']
"""

from __future__ import annotations

from enum import StrEnum


def _effect(name: str, doc: str) -> property:
    """The property of a kind telling whether it has the effect `name` (in `EFFECTS`)."""
    return property(lambda self: name in EFFECTS[self], doc=doc)


class ArcKind(StrEnum):
    IN = "in"  # place -> transition: consumes the inscription
    OUT = "out"  # transition -> place: produces the inscription
    BOTH = "both"  # double arc (<->): consumes the inscription and puts it back
    INHIBITOR = "inhibitor"  # blocks the transition while the place holds the inscription (or any token)
    RESET = "reset"  # removes every token of the place when the transition occurs

    consumes = _effect("consumes", "The transition needs the inscription's tokens on the place and removes them.")
    produces = _effect("produces", "The transition adds the inscription's tokens to the place.")
    blocks = _effect("blocks", "The place's marking can disable the transition without being changed (an inhibitor arc).")
    empties = _effect("empties", "The transition empties the place (a reset arc).")

    @property
    def reads(self) -> bool:
        """The place's marking is an input of the transition: its enabling or its effect depends on it."""
        return bool(EFFECTS[self] & {"consumes", "blocks", "empties"})

    @property
    def takes(self) -> bool:
        """The transition's occurrence removes tokens from the place (consumes them, or empties it)."""
        return bool(EFFECTS[self] & {"consumes", "empties"})

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


#: what each kind of arc does to its place (the properties of `ArcKind` read it)
EFFECTS: dict[ArcKind, frozenset[str]] = {
    ArcKind.IN: frozenset({"consumes"}),
    ArcKind.OUT: frozenset({"produces"}),
    ArcKind.BOTH: frozenset({"consumes", "produces"}),
    ArcKind.INHIBITOR: frozenset({"blocks"}),
    ArcKind.RESET: frozenset({"empties"}),
}


__all__ = ["EFFECTS", "ArcKind"]
