"""`Net`: a checked model lowered to place and transition instances with dense integer indices.

Expressions stay typed `cpn.lang.ast` nodes: the closed expression IR that the engine compiles.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

from cpn.diagnostics import Span
from cpn.values.colours import ColourSet


@dataclass(eq=False)
class PlaceInstance:
    index: int
    name: str  # "Page'Place 1"
    page: str
    place: str
    instance: int
    colour_set: ColourSet
    timed: bool
    initial: dict  # value -> count; for timed places (value, timestamp) -> count
    span: Span | None = None
    aliases: list[str] = field(default_factory=list)  # fused members and bound ports, "Page'Place n"

    @property
    def colset_name(self) -> str:
        return self.colour_set.name


@dataclass(eq=False)
class ArcInstance:
    place: int
    kind: str  # 'in' 'out' 'both' 'inhibitor' 'reset'
    expr: Any  # typed cpn.lang.ast.Expr or None
    span: Span | None = None
    label: str = ""  # "'Send' -> 'Bus'" for messages


@dataclass(eq=False)
class TransitionInstance:
    index: int
    name: str  # "Page'Trans 1"
    page: str
    transition: str
    instance: int
    guards: list
    delay: Any
    priority: Any
    arcs: list[ArcInstance]
    variables: list[str]  # every variable, sorted by name
    free: list[str]  # variables bound by trying every value of their colour set
    params: dict[int, Any]  # module parameter symbol uid -> value
    span: Span | None = None


@dataclass(eq=False)
class Net:
    name: str
    places: list[PlaceInstance]
    transitions: list[TransitionInstance]
    checked: Any  # cpn.lang.typecheck.CheckedModel
    source_file: str = ""

    @property
    def is_timed(self) -> bool:
        return any(p.timed for p in self.places)

    @property
    def colsets(self) -> dict:
        return self.checked.colsets

    @property
    def variables(self) -> dict:
        return self.checked.variables

    def place(self, name: str) -> PlaceInstance:
        for p in self.places:
            if p.name == name or name in p.aliases:
                return p
        raise KeyError(name)

    def transition(self, name: str) -> TransitionInstance:
        for t in self.transitions:
            if t.name == name:
                return t
        raise KeyError(name)
