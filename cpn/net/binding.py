"""Which variables an inscription or guard can bind: the analysis behind CPN Tools' binding rules.

A variable of a transition is bound by a *pattern position* of an input-arc inscription (a variable,
possibly inside tuples, records, lists and constructors, under ``n`...`` and ``++``), or by a guard
conjunct ``v = e`` whose right side is already bound, or else, if its colour set is small enough to
enumerate, by trying every value (a free variable, as CPN Tools does).

Examples
--------
>>> from cpn.expr.nodes import Const, Name, Ref, TupleE
>>> e = TupleE(None, [Name(None, "x", ref=Ref("x", "var", 7, "INT")), Const(None, 1, "int")])
>>> sorted(all_vars(e)), is_pattern(e)
(['x'], True)
"""

from __future__ import annotations

from cpn.expr import nodes as E


def is_var(e: E.Expr) -> bool:
    """True if e is a transition variable."""
    return isinstance(e, E.Name) and e.ref.kind == "var"


def is_constructor_fn(e: E.Expr) -> bool:
    """True if e is a constructor that takes an argument (`ph`, `Req`)."""
    return isinstance(e, E.Name) and e.ref.kind == "con" and (e.ref.data.kind == "index" or (
        e.ref.data.kind == "union" and e.ref.data.has_arg))


def pattern_vars(e: E.Expr) -> set[str]:
    """Transition variables in pattern positions of e (those a token can bind)."""
    if is_var(e):
        return {e.name}
    if isinstance(e, (E.TupleE, E.ListE)):
        out: set[str] = set()
        for x in e.items:
            out |= pattern_vars(x)
        return out
    if isinstance(e, E.RecordE):
        out = set()
        for _, x in e.fields:
            out |= pattern_vars(x)
        return out
    if isinstance(e, E.App) and is_constructor_fn(e.fn):
        return pattern_vars(e.arg)
    if isinstance(e, E.ToMs):
        return pattern_vars(e.expr)
    if isinstance(e, E.BinOp):
        if e.op == "`":
            return pattern_vars(e.right)
        if e.op in ("++", "+++", "::"):
            return pattern_vars(e.left) | pattern_vars(e.right)
    return set()


def is_pattern(e: E.Expr) -> bool:
    """True if e is built only from variables, constants, tuples, records, lists and constructors."""
    if is_var(e) or isinstance(e, E.Const):
        return True
    if isinstance(e, E.Name) and e.ref.kind in ("con", "val", "param"):
        return e.ref.kind != "con" or not e.ref.data.has_arg or e.ref.data.kind == "enum"
    if isinstance(e, (E.TupleE, E.ListE)):
        return all(is_pattern(x) for x in e.items)
    if isinstance(e, E.RecordE):
        return all(is_pattern(x) for _, x in e.fields)
    if isinstance(e, E.App) and is_constructor_fn(e.fn):
        return is_pattern(e.arg)
    if isinstance(e, E.BinOp) and e.op == "::":
        return is_pattern(e.left) and is_pattern(e.right)
    return False


def all_vars(e: E.Expr | None, acc: set[str] | None = None) -> set[str]:
    """Every transition variable occurring in an expression."""
    acc = set() if acc is None else acc
    stack = [e]  # iterative: an expression may be a chain thousands of terms long
    while stack:
        x = stack.pop()
        if x is None:
            continue
        if isinstance(x, E.Name):
            if x.ref.kind == "var":
                acc.add(x.name)
            continue
        stack.extend(children(x))
    return acc


def children(e: E.Expr) -> list[E.Expr]:
    """The subexpressions of e (the bodies of its rules and local declarations included)."""
    if isinstance(e, (E.TupleE, E.ListE, E.Seq)):
        return list(e.items)
    if isinstance(e, E.RecordE):
        return [x for _, x in e.fields]
    if isinstance(e, E.App):
        return [e.fn, e.arg]
    if isinstance(e, E.BinOp):
        return [e.left, e.right]
    if isinstance(e, E.Neg):
        return [e.operand]
    if isinstance(e, E.If):
        return [e.cond, e.then, e.else_]
    if isinstance(e, E.Case):
        return [e.subject] + [b for _, b in e.rules]
    if isinstance(e, E.Fn):
        return [b for _, b in e.rules]
    if isinstance(e, E.Raise):
        return [e.expr]
    if isinstance(e, E.Handle):
        return [e.expr] + [b for _, b in e.rules]
    if isinstance(e, E.Let):
        out = []
        for d in e.decls:
            if isinstance(d, E.ValDecl):
                out.append(d.expr)
            else:
                out.extend(c.body for c in d.clauses)
        return out + [e.body]
    if isinstance(e, E.ToMs):
        return [e.expr]
    return []


def guard_conjuncts(guards: list[E.Expr]) -> list[E.Expr]:
    """Split guards into conjuncts: `[a, b andalso c]` gives a, b, c."""
    out = []
    stack = list(reversed(guards))
    while stack:
        g = stack.pop()
        if isinstance(g, E.BinOp) and g.op == "andalso":
            stack.append(g.right)
            stack.append(g.left)
        elif isinstance(g, E.ListE):
            stack.extend(reversed(g.items))
        else:
            out.append(g)
    return out


def guard_binder(conj: E.Expr, bound: set[str]) -> tuple[E.Expr, E.Expr] | None:
    """If conj is `pattern = e` (either side) with unbound pattern variables and e bound, return
    (pattern, e); else None."""
    if not (isinstance(conj, E.BinOp) and conj.op == "="):
        return None
    for pat, expr in ((conj.left, conj.right), (conj.right, conj.left)):
        pv = pattern_vars(pat)
        if pv and not pv <= bound and is_pattern(pat) and all_vars(expr) <= bound and \
                all_vars(pat) == pv:
            return pat, expr
    return None
