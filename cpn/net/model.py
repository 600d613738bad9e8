"""`Net`: a checked model lowered to place and transition instances with dense integer indices.

A `Net` is everything an engine needs: its colour sets, variables, global constants and functions, and
its guards and inscriptions in the closed expression form of `cpn.expr.nodes`.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

from cpn.arcs import ArcKind
from cpn.diagnostics import Span
from cpn.expr import nodes as E
from cpn.values.colours import ColourSet


@dataclass(eq=False)
class PlaceInstance:
    """One place of the flattened net: a place of a page instance, with its fused places and ports.

    `initial` is the initial marking as value -> count ((value, timestamp) -> count for a timed place).
    """

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
    """An arc between a transition instance and the place instance `place` (an index into `Net.places`)."""

    place: int
    kind: ArcKind
    expr: E.Expr | None
    span: Span | None = None
    label: str = ""  # "'Send' -> 'Bus'" for messages
    # an input arc's `e @+ k` (CPN Tools' preempting time stamps): its tokens may be removed up to k time
    # units before their timestamps (docs/semantics.md, Time); `expr` is e
    preemption: int = 0


@dataclass(eq=False)
class TransitionInstance:
    """One transition of the flattened net, with its guard conjuncts, delay, priority and arcs.

    `variables` are all its variables by name; `free` those bound by trying every value of their colour
    set (CPN Tools' rule for variables no input arc or guard binds); `params` the values of the module
    parameters of its page instance, by symbol uid.
    """

    index: int
    name: str  # "Page'Trans 1"
    page: str
    transition: str
    instance: int
    guards: list[E.Expr]
    delay: E.Expr | None
    priority: E.Expr | None
    arcs: list[ArcInstance]
    variables: list[str]  # every variable, sorted by name
    free: list[str]  # variables bound by trying every value of their colour set
    params: dict[int, Any]  # module parameter symbol uid -> value
    span: Span | None = None
    # `output (x, y) action e`: run once per occurrence, before the delay and the output arcs, its value
    # binding `outputs` (no part of the binding); simulation only, so only the reference interpreter runs it
    action: E.Expr | None = None
    outputs: tuple[str, ...] = ()


@dataclass(eq=False)
class PageInstance:
    """One instance of a page in the flattened net: its place and transition instances by local name.

    `places` maps each place of the page to its place instance (a port bound to a socket and a fused place
    map to the shared one); `children` are the indices (into `Net.instances`) of the instances it declares,
    in declaration order; `decl` is the instance declaration (None for the top page).
    """

    index: int
    page: str
    number: int  # the n of "Page'Place n"
    params: dict[int, Any]  # module parameter symbol uid -> value
    places: dict[str, int]
    transitions: dict[str, int]
    parent: int | None = None
    children: list[int] = field(default_factory=list)
    decl: Any = None  # cpn.lang.ast.InstanceDecl


@dataclass(eq=False)
class Net:
    """A flattened net: place and transition instances, and the declarations their inscriptions use.

    Examples
    --------
    >>> import cpn
    >>> net = cpn.loads("colset N = int with 0..3; var x : N; place P : N = 1`0;"
    ...                 " trans inc [x < 3]; arc P -> inc : x; arc inc -> P : x + 1;").net
    >>> [t.name for t in net.transitions], net.place("Top'P 1").colour_set.name
    (["Top'inc 1"], 'N')
    >>> [(a.kind.value, a.place) for a in net.transition("Top'inc 1").arcs]
    [('in', 0), ('out', 0)]
    """

    name: str
    places: list[PlaceInstance]
    transitions: list[TransitionInstance]
    colsets: dict[str, ColourSet]  # colour set name -> colour set
    variables: dict[str, E.Ref]  # variable name -> Ref (kind 'var', data: its colour set's name)
    globals: E.Globals  # global constants (evaluated) and functions
    source: str = ""  # the model's text, quoted by error messages
    source_file: str = ""
    checked: Any = None  # the front end's checked model, for writers that print the model back (PNML)
    instances: list[PageInstance] = field(default_factory=list)  # page instances, the top page first

    @property
    def is_timed(self) -> bool:
        return any(p.timed for p in self.places)

    def place(self, name: str) -> PlaceInstance:
        """The place instance called `name` (or fused with, or bound to, a place of that name)."""
        for p in self.places:
            if p.name == name or name in p.aliases:
                return p
        raise KeyError(name)

    def transition(self, name: str) -> TransitionInstance:
        """The transition instance called `name` ("Page'Trans 1")."""
        for t in self.transitions:
            if t.name == name:
                return t
        raise KeyError(name)
