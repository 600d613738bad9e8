"""The one expression tree of CPN ML: expressions, patterns, type annotations and the declarations of a `let`.

The language's parser builds it and its type checker annotates it in place (`ty`, `op_ty`, `ref` as a
Symbol); the net holds it in closed form (`cpn.net.lower`: every name resolved to a `Ref`, annotations
dropped), which the engines compile and interpret. Nothing here points into the language or the engine,
so every layer above `cpn.values` may use it (docs/internals.md).

Values follow docs/internals.md: a record is a tuple of its fields in the alphabetical order of their
labels, an enumeration constant is its position, a union value with data is ``(position, value)``.

Examples
--------
The inscription ``(x, 1)`` over a variable ``x`` of colour set ``INT``:

>>> x = Ref("x", "var", uid=7, data="INT")
>>> TupleE(None, [Name(None, "x", ref=x), Const(None, 1, "int")]).items[0].ref.kind
'var'
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

from cpn.diagnostics import Span

# ----------------------------------------------------------------------------- references of a net


@dataclass(slots=True, frozen=True)
class Constructor:
    """A constructor of a colour set: enumeration constant, index constructor (`ph`) or union constructor."""

    colset: str
    tag: int | str  # position (enumeration, union); unused for an index; "E#uid" for an exception
    kind: str  # 'enum' 'index' 'union'
    has_arg: bool


@dataclass(slots=True, eq=False)
class Ref:
    """What a name of a net denotes (the language's `Symbol` without the front end's annotations).

    kind: 'var' (transition variable; data is its colour set's name), 'param' (module parameter), 'val'
    (global constant), 'fun' (global function), 'local' (bound by a pattern, a `let` or a `fn`), 'con'
    (data is a `Constructor`), 'builtin' (library function), 'csop' (data is (colour set, operation), as in
    `CS.all`). `uid` identifies variables, parameters, locals and globals in environments.
    """

    name: str
    kind: str
    uid: int = 0
    data: Any = None


# ----------------------------------------------------------------------------- expressions


@dataclass(slots=True, eq=False)
class Expr:
    span: Span | None


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
    ref: Any = None  # a Symbol of the language (set by the type checker), a Ref in a net


@dataclass(slots=True, eq=False)
class Select(Expr):
    """`#label`, a function selecting a record field or tuple component (`index` in the value)."""

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
    span: Span | None


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
    ty_labels: list[str] | None = None  # every label of the record's colour set in value order (type checker)


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
    span: Span | None


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


# ----------------------------------------------------------------------------- declarations of a let


@dataclass(slots=True, eq=False)
class Decl:
    span: Span | None


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
    span: Span | None
    params: list[Pat]
    body: Expr
    result_type: TypeExpr | None = None


@dataclass(slots=True, eq=False)
class FunDecl(Decl):
    """A function: global (`ref.kind == 'fun'`) or local to a `let` (`'local'`)."""

    name: str
    clauses: list[Clause]
    ty: Any = None
    ref: Any = None


@dataclass(slots=True, eq=False)
class ExceptionDecl(Decl):
    """`exception E` or `exception E of T`: a new exception constructor."""

    name: str
    type_expr: TypeExpr | None = None
    ref: Any = None


@dataclass(eq=False)
class Globals:
    """The global declarations of a net, in declaration order, and the values of its constants.

    `constants` holds the value of every global `val` whose value is not a function (as the front end
    evaluated it, `--set` included); a function-valued `val` is evaluated from its declaration.
    """

    decls: list[ValDecl | FunDecl] = field(default_factory=list)
    constants: dict[int, Any] = field(default_factory=dict)  # uid of a val -> its value
