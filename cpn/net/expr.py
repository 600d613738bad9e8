"""The closed expression form of a `Net`: guards, arc inscriptions, delays, priorities and functions.

What the engines compile and interpret. It mirrors the typed CPN ML syntax tree of `cpn.lang.ast` node
for node, without the types and the type annotations, and every name is resolved to a `Ref`: a transition
variable, a module parameter, a global constant or function, a constructor, a library function or a
colour-set function. Nothing here points back into the language, so a back end needs only this module,
`cpn.net.model` and `cpn.values` (docs/internals.md).

Values follow docs/internals.md: a record is a tuple of its fields in the alphabetical order of their
labels, an enumeration constant is its position, a union value with data is ``(position, value)``.

Examples
--------
The inscription ``(x, 1)`` over a variable ``x`` of colour set ``INT``:

>>> x = Ref("x", "var", uid=7, data="INT")
>>> TupleE(None, [Name(None, "x", x), Const(None, 1, "int")]).items[0].ref.kind
'var'
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

from cpn.diagnostics import Span

# ----------------------------------------------------------------------------- references


@dataclass(slots=True, frozen=True)
class Constructor:
    """A constructor of a colour set: enumeration constant, index constructor (`ph`) or union constructor."""

    colset: str
    tag: int | str  # position (enumeration, union); unused for an index; "E#uid" for an exception
    kind: str  # 'enum' 'index' 'union'
    has_arg: bool


@dataclass(slots=True, eq=False)
class Ref:
    """What a name denotes.

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


@dataclass(slots=True, eq=False)
class Name(Expr):
    name: str
    ref: Ref


@dataclass(slots=True, eq=False)
class Select(Expr):
    """`#label`: the function selecting component `index` of a record or tuple value."""

    index: int
    label: str = ""


@dataclass(slots=True, eq=False)
class TupleE(Expr):
    items: list[Expr]


@dataclass(slots=True, eq=False)
class RecordE(Expr):
    fields: list[tuple[str, Expr]]  # in the order written; the value orders them by label


@dataclass(slots=True, eq=False)
class ListE(Expr):
    items: list[Expr]


@dataclass(slots=True, eq=False)
class App(Expr):
    fn: Expr
    arg: Expr


@dataclass(slots=True, eq=False)
class BinOp(Expr):
    """Infix operators: + - * / div mod ^ :: ^^ @ = <> < > <= >= andalso orelse ++ -- +++ ` @+."""

    op: str
    left: Expr
    right: Expr


@dataclass(slots=True, eq=False)
class Neg(Expr):
    operand: Expr


@dataclass(slots=True, eq=False)
class If(Expr):
    cond: Expr
    then: Expr
    else_: Expr


@dataclass(slots=True, eq=False)
class Case(Expr):
    subject: Expr
    rules: list[tuple[Pat, Expr]]


@dataclass(slots=True, eq=False)
class Fn(Expr):
    rules: list[tuple[Pat, Expr]]


@dataclass(slots=True, eq=False)
class Raise(Expr):
    """`raise e`: e is an exception value (the tag ``"E#uid"`` of its constructor, or ``(tag, argument)``)."""

    expr: Expr


@dataclass(slots=True, eq=False)
class Handle(Expr):
    """`e handle pat => e1 | ...`: the rules see the exceptions raised by `raise` while evaluating e."""

    expr: Expr
    rules: list[tuple[Pat, Expr]]


@dataclass(slots=True, eq=False)
class Let(Expr):
    decls: list[ValDecl | FunDecl]
    body: Expr


@dataclass(slots=True, eq=False)
class Seq(Expr):
    items: list[Expr]


@dataclass(slots=True, eq=False)
class ToMs(Expr):
    """A single value used where a multiset is expected: ``1`value``."""

    expr: Expr


@dataclass(slots=True, eq=False)
class OpFun(Expr):
    """`op +`: an infix operator used as a function of a pair."""

    op: str


# ----------------------------------------------------------------------------- patterns


@dataclass(slots=True, eq=False)
class Pat:
    span: Span | None


@dataclass(slots=True, eq=False)
class PWild(Pat):
    pass


@dataclass(slots=True, eq=False)
class PVar(Pat):
    """A variable bound by the pattern (`ref.kind == 'local'`) or a constant constructor (`'con'`)."""

    name: str
    ref: Ref


@dataclass(slots=True, eq=False)
class PConst(Pat):
    value: Any
    kind: str


@dataclass(slots=True, eq=False)
class PTuple(Pat):
    items: list[Pat]


@dataclass(slots=True, eq=False)
class PList(Pat):
    items: list[Pat]


@dataclass(slots=True, eq=False)
class PCons(Pat):
    head: Pat
    tail: Pat


@dataclass(slots=True, eq=False)
class PCon(Pat):
    """A constructor applied to a pattern: `ph(i)`, `Req(a, f)`."""

    name: str
    arg: Pat
    ref: Ref


@dataclass(slots=True, eq=False)
class PRecord(Pat):
    fields: list[tuple[str, Pat]]
    ty_labels: list[str]  # every label of the record's colour set, in value order


@dataclass(slots=True, eq=False)
class PAs(Pat):
    name: str
    pat: Pat
    ref: Ref


# ----------------------------------------------------------------------------- declarations


@dataclass(slots=True, eq=False)
class ValDecl:
    """`val pat = expr` (inside `let`), or a global constant whose value the front end could not give."""

    span: Span | None
    pat: Pat
    expr: Expr


@dataclass(slots=True, eq=False)
class Clause:
    span: Span | None
    params: list[Pat]
    body: Expr


@dataclass(slots=True, eq=False)
class FunDecl:
    """A function: global (`ref.kind == 'fun'`) or local to a `let` (`'local'`)."""

    span: Span | None
    name: str
    clauses: list[Clause]
    ref: Ref


@dataclass(eq=False)
class Globals:
    """The global declarations of a net, in declaration order, and the values of its constants.

    `constants` holds the value of every global `val` whose value is not a function (as the front end
    evaluated it, `--set` included); a function-valued `val` is evaluated from its declaration.
    """

    decls: list[ValDecl | FunDecl] = field(default_factory=list)
    constants: dict[int, Any] = field(default_factory=dict)  # uid of a val -> its value
