"""The binding order of a transition: in which order its variables are bound and its guards tested.

A pure function of the transition's input-arc inscriptions, guard and variables, that the code generator
(`cpn.engine.codegen`) follows step by step, and that a native back end can follow the same way:

- `Loop` over the tokens of an input place that a pattern term matches (binding its variables),
- `Bind` the pattern side of a guard conjunct ``pattern = e`` to the value of ``e``,
- `Enumerate` the values of a free variable's colour set (a small colour set, as CPN Tools does),
- `Test` a guard conjunct as soon as all its variables are bound.

The rule: test every guard conjunct that is ready; then prefer a token loop (the first input term, in
arc order, that binds a new variable and whose coefficient is bound), then a guard binder, then the
first free variable by name.

Examples
--------
>>> import cpn
>>> net = cpn.loads("colset N = int with 0..3; var x, y : N; place P : N = 1`0;"
...                 " trans t [y = x + 1]; arc P -> t : x;").net
>>> t = net.transitions[0]
>>> [type(s).__name__ for s in binding_plan(input_terms(t, [t.arcs[0].place]), t.guards, t.variables, t.free)]
['Loop', 'Bind']
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

from cpn.expr import binding as B
from cpn.expr import nodes as A


@dataclass
class Term:
    """One summand of an inscription: `coef`value` (pattern or expression), or an opaque multiset."""

    coef: A.Expr | None  # None means 1
    value: A.Expr | None  # None for opaque terms
    opaque: A.Expr | None = None  # an expression evaluating to a multiset
    cond: list = field(default_factory=list)  # (expr, polarity) conditions from if-then-else


def terms(e: A.Expr, cond=None) -> list[Term]:
    """Flatten an untimed inscription into terms; `if` with multiset branches becomes conditional terms."""
    cond = cond or []
    if isinstance(e, A.BinOp) and e.op in ("++", "+++"):
        return terms(e.left, cond) + terms(e.right, cond)
    if isinstance(e, A.ToMs):
        return [Term(None, e.expr, cond=cond)]
    if isinstance(e, A.BinOp) and e.op == "`":
        return [Term(e.left, e.right, cond=cond)]
    if isinstance(e, A.Name) and e.ref.kind == "builtin" and e.name == "empty":
        return []
    if isinstance(e, A.If):
        return terms(e.then, cond + [(e.cond, True)]) + terms(e.else_, cond + [(e.cond, False)])
    return [Term(None, None, opaque=e, cond=cond)]


@dataclass(frozen=True)
class InputTerm:
    """A term of a consuming arc's inscription, on the place at position `place` of the read places."""

    place: int
    term: Term
    arc: Any  # the ArcInstance, for error messages


def input_terms(t, read: list[int]) -> list[InputTerm]:
    """The terms of transition t's consuming arcs, in arc order; `read` lists the places it reads."""
    pos = {p: i for i, p in enumerate(read)}
    return [InputTerm(pos[a.place], term, a) for a in t.arcs if a.kind.consumes and a.expr is not None
            for term in terms(a.expr)]


def matchable(e: A.Expr, bound: set) -> bool:
    """Whether a token can be matched against e once the variables `bound` are bound."""
    if B.is_var(e):
        return True
    if isinstance(e, (A.TupleE, A.ListE)):
        b = set(bound)
        ok = True
        for x in e.items:
            ok = ok and matchable(x, b)
            b |= B.pattern_vars(x)
        return ok
    if isinstance(e, A.RecordE):
        b = set(bound)
        ok = True
        for _, x in sorted(e.fields, key=lambda f: f[0]):
            ok = ok and matchable(x, b)
            b |= B.pattern_vars(x)
        return ok
    if isinstance(e, A.App) and B.is_constructor_fn(e.fn):
        return matchable(e.arg, bound)
    if isinstance(e, A.BinOp) and e.op == "::":
        return matchable(e.left, bound) and matchable(e.right, bound | B.pattern_vars(e.left))
    return B.all_vars(e) <= bound


@dataclass(frozen=True)
class Test:
    guard: int  # index into the guard conjuncts


@dataclass(frozen=True)
class Loop:
    term: int  # index into the input terms
    new: frozenset  # the variables it binds


@dataclass(frozen=True)
class Bind:
    guard: int  # index into the guard conjuncts
    pattern: A.Expr
    expr: A.Expr
    new: frozenset


@dataclass(frozen=True)
class Enumerate:
    var: str


class Unbindable(Exception):
    """Some variables of the transition cannot be bound (the checker rejects such models)."""


def binding_plan(in_terms: list[InputTerm], guards: list[A.Expr], variables: list[str],
                 free: list[str]) -> list[Test | Loop | Bind | Enumerate]:
    """The steps that bind every variable and test every guard conjunct of `guards`, in order."""
    conj = B.guard_conjuncts(guards)
    steps: list = []
    bound: set[str] = set()
    used_terms: set[int] = set()
    done: set[int] = set()

    def ready_guards():
        for i, g in enumerate(conj):
            if i not in done and B.all_vars(g) <= bound:
                done.add(i)
                steps.append(Test(i))

    all_vars = set(variables)
    ready_guards()
    while bound != all_vars:
        step = _token_loop(in_terms, used_terms, bound) or _guard_binder(conj, done, bound)
        if step is None:
            rest = sorted(v for v in free if v not in bound)
            if not rest:
                raise Unbindable(f"cannot bind variables {sorted(all_vars - bound)}")
            step = Enumerate(rest[0])
            bound.add(rest[0])
        elif isinstance(step, Loop):
            used_terms.add(step.term)
            bound |= step.new
        else:
            done.add(step.guard)
            bound |= step.new
        steps.append(step)
        ready_guards()
    ready_guards()
    return steps


def _token_loop(in_terms, used_terms, bound) -> Loop | None:
    for k, it in enumerate(in_terms):
        term = it.term
        if k in used_terms or term.value is None or term.cond:
            continue
        newv = B.pattern_vars(term.value) - bound
        if not newv or (term.coef is not None and not B.all_vars(term.coef) <= bound):
            continue
        if not matchable(term.value, bound):
            continue
        return Loop(k, frozenset(B.pattern_vars(term.value) - bound))
    return None


def _guard_binder(conj, done, bound) -> Bind | None:
    for i, g in enumerate(conj):
        if i in done:
            continue
        gb = B.guard_binder(g, bound)
        if gb is None:
            continue
        pat, expr = gb
        return Bind(i, pat, expr, frozenset(B.pattern_vars(pat) - bound))
    return None
