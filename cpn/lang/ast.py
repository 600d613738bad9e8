"""The abstract syntax of `.cpnet` models: declarations, net structure, expressions and patterns.

Every node keeps its `Span`. The type checker annotates expressions (`ty`) and names (`ref`) in place.
Imports `cpn.diagnostics` only.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

from cpn.diagnostics import Span

# ----------------------------------------------------------------------------- expressions


@dataclass(slots=True, eq=False)
class Expr:
    span: Span


@dataclass(slots=True, eq=False)
class Const(Expr):
    value: Any  # int, str, bool, float or () for unit
    kind: str  # 'int' 'string' 'bool' 'unit' 'real'
    ty: Any = None


@dataclass(slots=True, eq=False)
class Name(Expr):
    """An identifier: variable, constant, function, constructor, or library name (`Int.toString`)."""

    name: str
    ty: Any = None
    ref: Any = None  # set by the type checker: a Symbol


@dataclass(slots=True, eq=False)
class Select(Expr):
    """`#label`, a function selecting a record field or tuple component."""

    label: str
    ty: Any = None
    index: int | None = None  # position in the record/tuple value, set by the type checker


@dataclass(slots=True, eq=False)
class TupleE(Expr):
    items: list[Expr]
    ty: Any = None


@dataclass(slots=True, eq=False)
class RecordE(Expr):
    fields: list[tuple[str, Expr]]
    ty: Any = None


@dataclass(slots=True, eq=False)
class ListE(Expr):
    items: list[Expr]
    ty: Any = None


@dataclass(slots=True, eq=False)
class App(Expr):
    fn: Expr
    arg: Expr
    ty: Any = None
    ran_var: Any = None  # for CS.ran() in a transition: the free variable that replaces it


@dataclass(slots=True, eq=False)
class BinOp(Expr):
    """Infix operators: + - * / div mod ^ :: ^^ @ = <> < > <= >= andalso orelse ++ -- +++ ` @+ @@."""

    op: str
    left: Expr
    right: Expr
    ty: Any = None
    op_ty: Any = None  # operand type, for overloaded operators


@dataclass(slots=True, eq=False)
class Neg(Expr):
    operand: Expr
    ty: Any = None


@dataclass(slots=True, eq=False)
class If(Expr):
    cond: Expr
    then: Expr
    else_: Expr
    ty: Any = None


@dataclass(slots=True, eq=False)
class Case(Expr):
    subject: Expr
    rules: list[tuple[Pat, Expr]]
    ty: Any = None


@dataclass(slots=True, eq=False)
class Fn(Expr):
    rules: list[tuple[Pat, Expr]]
    ty: Any = None


@dataclass(slots=True, eq=False)
class Raise(Expr):
    """`raise e`: e is an exception value."""

    expr: Expr
    ty: Any = None


@dataclass(slots=True, eq=False)
class Handle(Expr):
    """`e handle pat => e1 | ...`: the rules see the exceptions raised by `raise` while evaluating e."""

    expr: Expr
    rules: list[tuple[Pat, Expr]]
    ty: Any = None


@dataclass(slots=True, eq=False)
class Let(Expr):
    decls: list[Decl]
    body: Expr
    ty: Any = None


@dataclass(slots=True, eq=False)
class Seq(Expr):
    items: list[Expr]
    ty: Any = None


@dataclass(slots=True, eq=False)
class Annot(Expr):
    expr: Expr
    type_expr: TypeExpr
    ty: Any = None


@dataclass(slots=True, eq=False)
class ToMs(Expr):
    """A single value used where a multiset is expected: ``1`value`` (inserted by the type checker)."""

    expr: Expr
    ty: Any = None


@dataclass(slots=True, eq=False)
class OpFun(Expr):
    """`op +`: an infix operator used as a function of a pair."""

    op: str
    ty: Any = None
    op_ty: Any = None


# ----------------------------------------------------------------------------- patterns


@dataclass(slots=True, eq=False)
class Pat:
    span: Span


@dataclass(slots=True, eq=False)
class PWild(Pat):
    ty: Any = None


@dataclass(slots=True, eq=False)
class PVar(Pat):
    """A name in a pattern: a variable, unless the type checker finds it is a constant constructor."""

    name: str
    ty: Any = None
    ref: Any = None  # Symbol of the bound variable, or of the constructor when it is one


@dataclass(slots=True, eq=False)
class PConst(Pat):
    value: Any
    kind: str
    ty: Any = None


@dataclass(slots=True, eq=False)
class PTuple(Pat):
    items: list[Pat]
    ty: Any = None


@dataclass(slots=True, eq=False)
class PList(Pat):
    items: list[Pat]
    ty: Any = None


@dataclass(slots=True, eq=False)
class PCons(Pat):
    head: Pat
    tail: Pat
    ty: Any = None


@dataclass(slots=True, eq=False)
class PCon(Pat):
    """A constructor applied to a pattern: `ph(i)`, `Req(a, f)`."""

    name: str
    arg: Pat
    ty: Any = None
    ref: Any = None


@dataclass(slots=True, eq=False)
class PRecord(Pat):
    fields: list[tuple[str, Pat]]
    flexible: bool
    ty: Any = None
    ty_labels: list[str] | None = None  # all labels of the record type, set by the type checker


@dataclass(slots=True, eq=False)
class PAs(Pat):
    name: str
    pat: Pat
    ty: Any = None
    ref: Any = None


@dataclass(slots=True, eq=False)
class PAnnot(Pat):
    pat: Pat
    type_expr: TypeExpr
    ty: Any = None


# ----------------------------------------------------------------------------- type expressions


@dataclass(slots=True, eq=False)
class TypeExpr:
    span: Span


@dataclass(slots=True, eq=False)
class TName(TypeExpr):
    name: str


@dataclass(slots=True, eq=False)
class TPost(TypeExpr):
    """`INT list`, `PH ms`."""

    arg: TypeExpr
    name: str


@dataclass(slots=True, eq=False)
class TTuple(TypeExpr):
    items: list[TypeExpr]


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
class Decl:
    span: Span


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
class ValDecl(Decl):
    """`val x = e` at top level (`pat` is a PVar) or `val pat = e` inside `let`."""

    pat: Pat
    expr: Expr
    type_expr: TypeExpr | None = None

    @property
    def name(self) -> str | None:
        return self.pat.name if isinstance(self.pat, PVar) else None


@dataclass(slots=True, eq=False)
class Clause:
    span: Span
    params: list[Pat]
    body: Expr
    result_type: TypeExpr | None = None


@dataclass(slots=True, eq=False)
class FunDecl(Decl):
    name: str
    clauses: list[Clause]
    ty: Any = None
    ref: Any = None


@dataclass(slots=True, eq=False)
class SymmetryDecl(Decl):
    """`symmetry PH, Q = permutations;`: colour sets whose values the net does not tell apart."""

    names: list[tuple[str, Span]]
    kind: str
    kind_span: Span


@dataclass(slots=True, eq=False)
class ExceptionDecl(Decl):
    """`exception E` or `exception E of T`: a new exception constructor."""

    name: str
    type_expr: TypeExpr | None = None
    ref: Any = None


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
