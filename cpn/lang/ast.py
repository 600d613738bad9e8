"""The abstract syntax of `.cpnet` models: the declarations and the net structure.

Expressions, patterns, type annotations and the declarations a `let` may hold are the one expression tree
of `cpn.expr.nodes`, named here too so that the language's modules read one syntax (`A.Const`). Every
node keeps its `Span`. The type checker annotates expressions (`ty`) and names (`ref`) in place.
Imports `cpn.expr.nodes` and `cpn.diagnostics` only.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

from cpn.diagnostics import Span
from cpn.expr.nodes import (  # noqa: F401 - the language's syntax tree is the one expression tree
    Annot,
    App,
    BinOp,
    Case,
    Clause,
    Const,
    Decl,
    ExceptionDecl,
    Expr,
    Fn,
    FunDecl,
    If,
    Let,
    ListE,
    Name,
    Neg,
    OpFun,
    PAnnot,
    PAs,
    Pat,
    PCon,
    PCons,
    PConst,
    PList,
    PRecord,
    PTuple,
    PVar,
    PWild,
    RecordE,
    Select,
    Seq,
    TName,
    ToMs,
    TPost,
    TTuple,
    TupleE,
    TypeExpr,
    ValDecl,
)

# ----------------------------------------------------------------------------- colour sets


@dataclass(slots=True, eq=False)
class ColsetBody:
    span: Span
    kind: str  # unit bool int string real time enum index product record list union subset_by subset_with alias
    names: list[str] = field(default_factory=list)  # enum constants, product components, alias/base/elem name
    fields: list[tuple[str, str | None]] = field(default_factory=list)  # record fields / union constructors
    low: Expr | None = None
    high: Expr | None = None
    pred: Expr | None = None  # subset by / with


# ----------------------------------------------------------------------------- declarations


@dataclass(slots=True, eq=False)
class NetHeader(Decl):
    name: str


@dataclass(slots=True, eq=False)
class ColsetDecl(Decl):
    name: str
    body: ColsetBody
    timed: bool


@dataclass(slots=True, eq=False)
class VarDecl(Decl):
    names: list[tuple[str, Span]]
    colset: str
    colset_span: Span


@dataclass(slots=True, eq=False)
class SymmetryDecl(Decl):
    """`symmetry PH, Q = permutations;`: colour sets whose values the net does not tell apart."""

    names: list[tuple[str, Span]]
    kind: str
    kind_span: Span


@dataclass(slots=True, eq=False)
class LocalDecl(Decl):
    """`local D1 in D2 end`: D1 is seen by D2 only, D2 is global."""

    private: list[Decl]
    public: list[Decl]


def flat_decls(decls: list) -> list:
    """The declarations with each `local` block replaced by its parts, in order (symbols are unique, so
    a later stage needs no scopes)."""
    out = []
    for d in decls:
        if isinstance(d, LocalDecl):
            out.extend(flat_decls(d.private))
            out.extend(flat_decls(d.public))
        else:
            out.append(d)
    return out


@dataclass(slots=True, eq=False)
class UseDecl(Decl):
    """`use "file.cpnet";`: replaced by the parser with the global declarations and modules of that file."""

    path: str
    path_span: Span


@dataclass(slots=True, eq=False)
class PlaceDecl(Decl):
    name: str
    name_span: Span
    colset: str
    colset_span: Span
    init: Expr | None
    fusion: str | None = None
    port: str | None = None  # 'in' 'out' 'io' for ports


@dataclass(slots=True, eq=False)
class TransDecl(Decl):
    name: str
    name_span: Span
    guards: list[Expr]
    delay: Expr | None
    priority: Expr | None
    # `output (x, y) action e`: CPN Tools' code segment, run once per occurrence before the output arcs
    action: Expr | None = None
    outputs: list[str] = field(default_factory=list)  # the variables the action's value binds
    action_span: Span | None = None  # the keyword 'action'


@dataclass(slots=True, eq=False)
class ArcDecl(Decl):
    kind: str  # '->' '<->' 'inhibitor' 'reset'
    src: str
    src_span: Span
    dst: str
    dst_span: Span
    expr: Expr | None
    src_kind: str | None = None  # 'place' or 'trans' where the arc says which (`arc place X -> trans X`)
    dst_kind: str | None = None


@dataclass(slots=True, eq=False)
class ModuleDecl(Decl):
    name: str
    params: list[tuple[str, str, Span]]  # (name, colour set, span)
    body: list[Decl]


@dataclass(slots=True, eq=False)
class InstanceDecl(Decl):
    name: str
    name_span: Span
    module: str
    module_span: Span
    args: list[tuple[str, Expr, Span]]
    binds: list[tuple[str, Span, str, Span]]  # (port, span, socket, span)


@dataclass(slots=True, eq=False)
class Model:
    file: str
    source: str
    decls: list[Decl]


@dataclass(slots=True, eq=False)
class InstanceFamilyDecl(InstanceDecl):
    """`instance Slave[i : 1..MAXS] = Slave(me = i) { ... };`: one instance per value of `var`, named `name`
    followed by the value (Slave1, Slave2, ...), `var` standing for the value in the arguments. The values
    are the integers `low..high` (constant expressions) or those of the colour set `colset`."""

    var: str = ""
    var_span: Span | None = None
    low: Expr | None = None
    high: Expr | None = None
    colset: str | None = None
    colset_span: Span | None = None


@dataclass(slots=True, eq=False)
class FamilyMember(InstanceDecl):
    """One instance of an `InstanceFamilyDecl`, made by the type checker: the family's variable has the
    value `value`; `env` maps its symbol's uid to the value, for evaluating the arguments."""

    family: InstanceFamilyDecl | None = None
    value: Any = None
    env: dict = field(default_factory=dict)
