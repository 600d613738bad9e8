"""The result of checking a model: checked pages, transitions and arcs, and the scopes of the checker.

Imports `cpn.lang.ast`, `cpn.expr.evaluate`, `cpn.values` and layer 0.
"""

from __future__ import annotations

from dataclasses import dataclass, field

from cpn.arcs import ArcKind
from cpn.diagnostics import Diagnostic
from cpn.expr.evaluate import Evaluator
from cpn.lang import ast as A
from cpn.lang import types as T
from cpn.lang.symbols import Symbol
from cpn.values import colours as C


@dataclass(eq=False)
class ArcInfo:
    decl: A.ArcDecl
    kind: ArcKind
    place: str
    trans: str
    expr: A.Expr | None
    # an input arc's `e @+ k` (CPN Tools' preempting time stamps): k, a constant the lowering evaluates
    preempt: A.Expr | None = None


@dataclass(eq=False)
class TransInfo:
    decl: A.TransDecl
    arcs: list[ArcInfo] = field(default_factory=list)
    variables: list[str] = field(default_factory=list)  # every variable, sorted
    free: list[str] = field(default_factory=list)  # variables bound by enumerating their colour set
    ran: list[tuple[str, str]] = field(default_factory=list)  # (synthetic variable, colour set) for CS.ran()


@dataclass(eq=False)
class PageInfo:
    name: str
    decl: A.ModuleDecl | None
    params: list[Symbol]
    places: dict[str, A.PlaceDecl] = field(default_factory=dict)
    transitions: dict[str, TransInfo] = field(default_factory=dict)
    instances: list[A.InstanceDecl] = field(default_factory=list)
    order: list[str] = field(default_factory=list)  # transition names in declaration order
    incomplete: set[str] = field(default_factory=set)  # names of transitions with an arc in error


@dataclass(eq=False)
class CheckedModel:
    """A model whose names are resolved, types checked, colour sets built and constants evaluated."""

    model: A.Model
    net_name: str
    colsets: dict[str, C.ColourSet]
    cstypes: dict[str, T.Type]
    variables: dict[str, Symbol]
    globals: dict[str, Symbol]
    evaluator: Evaluator
    top: PageInfo
    modules: dict[str, PageInfo]
    warnings: list[Diagnostic]
    symmetries: list = field(default_factory=list)  # `symmetry` declarations: (colour set, kind)


class Env:
    """A chain of local scopes over the global scope."""

    __slots__ = ("names", "parent")

    def __init__(self, names=None, parent=None):
        self.names = names if names is not None else {}
        self.parent = parent

    def lookup(self, name):
        env = self
        while env is not None:
            if name in env.names:
                return env.names[name]
            env = env.parent
        return None

    def child(self, names=None):
        return Env(dict(names or {}), self)

    def local_types(self):
        env = self
        while env is not None:
            for s in env.names.values():
                if s.kind == "local":
                    yield s.type
            env = env.parent




class Abort(Exception):
    """Stop checking the current expression (its error is already recorded)."""
