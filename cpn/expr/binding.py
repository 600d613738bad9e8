"""Which variables an inscription or guard can bind: the analysis behind CPN Tools' binding rules.

A variable of a transition is bound by a *pattern position* of an input-arc inscription (a variable,
possibly inside tuples, records, lists and constructors, under ``n`...`` and ``++``), or by a guard
conjunct ``v = e`` whose right side is already bound, or else, if its colour set is small enough to
enumerate, by trying every value (a free variable, as CPN Tools does).

The one analysis for the type checker (on the typed tree, where a name not yet resolved has no `ref`)
and the engines (on the net's tree).

Examples
--------
>>> from cpn.expr.nodes import Const, Name, Ref, TupleE
>>> e = TupleE(None, [Name(None, "x", ref=Ref("x", "var", 7, "INT")), Const(None, 1, "int")])
>>> sorted(all_vars(e)), is_pattern(e)
(['x'], True)
"""

from __future__ import annotations

from cpn.expr import nodes as N
from cpn.expr.forms import form_of


def is_var(e: N.Expr) -> bool:
    """True if e is a transition variable."""
    return isinstance(e, N.Name) and e.ref is not None and e.ref.kind == "var"


def is_constructor_fn(e: N.Expr) -> bool:
    """True if e is a constructor that takes an argument (`ph`, `Req`)."""
    return isinstance(e, N.Name) and e.ref is not None and e.ref.kind == "con" and e.ref.data.kind in (
        "index", "union") and (e.ref.data.kind == "index" or e.ref.data.has_arg)


def pattern_vars(e: N.Expr) -> set[str]:
    """Transition variables in pattern positions of e (those a token can bind)."""
    if is_var(e):
        return {e.name}
    if isinstance(e, (N.TupleE, N.ListE)):
        out: set[str] = set()
        for x in e.items:
            out |= pattern_vars(x)
        return out
    if isinstance(e, N.RecordE):
        out = set()
        for _, x in e.fields:
            out |= pattern_vars(x)
        return out
    if isinstance(e, N.App) and is_constructor_fn(e.fn):
        return pattern_vars(e.arg)
    if isinstance(e, N.ToMs):
        return pattern_vars(e.expr)
    if isinstance(e, N.Annot):
        return pattern_vars(e.expr)
    if isinstance(e, N.BinOp):
        if e.op == "`":
            return pattern_vars(e.right)
        if e.op in ("++", "+++"):
            return pattern_vars(e.left) | pattern_vars(e.right)
        if e.op == "::":
            return pattern_vars(e.left) | pattern_vars(e.right)
    return set()


def is_pattern(e: N.Expr) -> bool:
    """True if e is built only from variables, constants, tuples, records, lists and constructors."""
    if is_var(e) or isinstance(e, N.Const):
        return True
    if isinstance(e, N.Name) and e.ref is not None and e.ref.kind in ("con", "val", "param"):
        return e.ref.kind != "con" or not e.ref.data.has_arg or e.ref.data.kind == "enum"
    if isinstance(e, (N.TupleE, N.ListE)):
        return all(is_pattern(x) for x in e.items)
    if isinstance(e, N.RecordE):
        return all(is_pattern(x) for _, x in e.fields)
    if isinstance(e, N.App) and is_constructor_fn(e.fn):
        return is_pattern(e.arg)
    if isinstance(e, N.Annot):
        return is_pattern(e.expr)
    if isinstance(e, N.BinOp) and e.op == "::":
        return is_pattern(e.left) and is_pattern(e.right)
    return False


def all_vars(e: N.Expr | None, acc: set[str] | None = None) -> set[str]:
    """Every transition variable occurring in an expression."""
    acc = set() if acc is None else acc
    stack = [e]  # iterative: an expression may be a chain thousands of terms long
    while stack:
        x = stack.pop()
        if x is None:
            continue
        if isinstance(x, N.Name):
            if x.ref is not None and x.ref.kind == "var":
                acc.add(x.name)
            continue
        stack.extend(children(x))
    return acc


def children(e: N.Expr) -> list[N.Expr]:
    """The subexpressions of e (the bodies of its rules and local declarations included)."""
    if isinstance(e, N.App):
        return [e.fn, e.arg]
    if isinstance(e, N.BinOp):
        return [e.left, e.right]
    form = form_of(e)  # a form that declares its own rules (cpn.expr.forms)
    return [] if form is None else form.children(e)


def has_delay(e: N.Expr) -> bool:
    """Whether `e` delays tokens: an `@+` or `@++` in it, through operators and the branches of an `if`."""
    stack = [e]  # iterative: an inscription may be a sum thousands of terms long
    while stack:
        x = stack.pop()
        if isinstance(x, N.BinOp):
            if x.op in ("@+", "@++"):
                return True
            stack += (x.left, x.right)
        elif isinstance(x, N.If):
            stack += (x.then, x.else_)
    return False


def guard_conjuncts(guards: list[N.Expr]) -> list[N.Expr]:
    """Split guards into conjuncts: `[a, b andalso c]` gives a, b, c."""
    out = []
    stack = list(reversed(guards))
    while stack:
        g = stack.pop()
        if isinstance(g, N.BinOp) and g.op == "andalso":
            stack.append(g.right)
            stack.append(g.left)
        elif isinstance(g, N.ListE):
            stack.extend(reversed(g.items))
        else:
            out.append(g)
    return out


def guard_binder(conj: N.Expr, bound: set[str]) -> tuple[N.Expr, N.Expr] | None:
    """If conj is `pattern = e` (either side) with unbound pattern variables and e bound, return
    (pattern, e); else None."""
    if not (isinstance(conj, N.BinOp) and conj.op == "="):
        return None
    for pat, expr in ((conj.left, conj.right), (conj.right, conj.left)):
        pv = pattern_vars(pat)
        if pv and not pv <= bound and is_pattern(pat) and all_vars(expr) <= bound and \
                all_vars(pat) == pv:
            return pat, expr
    return None
