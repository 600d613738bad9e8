"""Which variables an inscription or guard can bind: the analysis behind CPN Tools' binding rules.

A variable of a transition is bound by a *pattern position* of an input-arc inscription (a variable,
possibly inside tuples, records, lists and constructors, under ``n`...`` and ``++``), or by a guard
conjunct ``v = e`` whose right side is already bound, or else, if its colour set is small enough to
enumerate, by trying every value (a free variable, as CPN Tools does).
"""

from __future__ import annotations

from cpn.lang import ast as A


def is_var(e: A.Expr) -> bool:
    return isinstance(e, A.Name) and e.ref is not None and e.ref.kind == "var"


def is_constructor_fn(e: A.Expr) -> bool:
    return isinstance(e, A.Name) and e.ref is not None and e.ref.kind == "con" and e.ref.data.kind in (
        "index", "union") and (e.ref.data.kind == "index" or e.ref.data.has_arg)


def pattern_vars(e: A.Expr) -> set[str]:
    """Transition variables in pattern positions of e (those a token can bind)."""
    if is_var(e):
        return {e.name}
    if isinstance(e, (A.TupleE, A.ListE)):
        out: set[str] = set()
        for x in e.items:
            out |= pattern_vars(x)
        return out
    if isinstance(e, A.RecordE):
        out = set()
        for _, x in e.fields:
            out |= pattern_vars(x)
        return out
    if isinstance(e, A.App) and is_constructor_fn(e.fn):
        return pattern_vars(e.arg)
    if isinstance(e, A.ToMs):
        return pattern_vars(e.expr)
    if isinstance(e, A.Annot):
        return pattern_vars(e.expr)
    if isinstance(e, A.BinOp):
        if e.op == "`":
            return pattern_vars(e.right)
        if e.op in ("++", "+++"):
            return pattern_vars(e.left) | pattern_vars(e.right)
        if e.op == "::":
            return pattern_vars(e.left) | pattern_vars(e.right)
    return set()


def is_pattern(e: A.Expr) -> bool:
    """True if e is built only from variables, constants, tuples, records, lists and constructors."""
    if is_var(e) or isinstance(e, A.Const):
        return True
    if isinstance(e, A.Name) and e.ref is not None and e.ref.kind in ("con", "val", "param"):
        return e.ref.kind != "con" or not e.ref.data.has_arg or e.ref.data.kind == "enum"
    if isinstance(e, (A.TupleE, A.ListE)):
        return all(is_pattern(x) for x in e.items)
    if isinstance(e, A.RecordE):
        return all(is_pattern(x) for _, x in e.fields)
    if isinstance(e, A.App) and is_constructor_fn(e.fn):
        return is_pattern(e.arg)
    if isinstance(e, A.Annot):
        return is_pattern(e.expr)
    if isinstance(e, A.BinOp) and e.op == "::":
        return is_pattern(e.left) and is_pattern(e.right)
    return False


def all_vars(e, acc: set[str] | None = None) -> set[str]:
    """Every transition variable occurring in an expression."""
    acc = set() if acc is None else acc
    stack = [e]  # iterative: an expression may be a chain thousands of terms long
    while stack:
        x = stack.pop()
        if x is None:
            continue
        if isinstance(x, A.Name):
            if x.ref is not None and x.ref.kind == "var":
                acc.add(x.name)
            continue
        stack.extend(children(x))
    return acc


def children(e: A.Expr):
    if isinstance(e, (A.TupleE, A.ListE, A.Seq)):
        return list(e.items)
    if isinstance(e, A.RecordE):
        return [x for _, x in e.fields]
    if isinstance(e, A.App):
        return [e.fn, e.arg]
    if isinstance(e, A.BinOp):
        return [e.left, e.right]
    if isinstance(e, A.Neg):
        return [e.operand]
    if isinstance(e, A.If):
        return [e.cond, e.then, e.else_]
    if isinstance(e, A.Case):
        return [e.subject] + [b for _, b in e.rules]
    if isinstance(e, A.Fn):
        return [b for _, b in e.rules]
    if isinstance(e, A.Raise):
        return [e.expr]
    if isinstance(e, A.Handle):
        return [e.expr] + [b for _, b in e.rules]
    if isinstance(e, A.Let):
        out = []
        for d in e.decls:
            if isinstance(d, A.ValDecl):
                out.append(d.expr)
            elif isinstance(d, A.FunDecl):
                out.extend(c.body for c in d.clauses)
        return out + [e.body]
    if isinstance(e, (A.Annot, A.ToMs)):
        return [e.expr]
    return []


def guard_conjuncts(guards: list[A.Expr]) -> list[A.Expr]:
    """Split guards into conjuncts: `[a, b andalso c]` gives a, b, c."""
    out = []
    stack = list(reversed(guards))
    while stack:
        g = stack.pop()
        if isinstance(g, A.BinOp) and g.op == "andalso":
            stack.append(g.right)
            stack.append(g.left)
        elif isinstance(g, A.ListE):
            stack.extend(reversed(g.items))
        else:
            out.append(g)
    return out


def guard_binder(conj: A.Expr, bound: set[str]):
    """If conj is `pattern = e` (either side) with unbound pattern variables and e bound, return
    (pattern, e); else None."""
    if not (isinstance(conj, A.BinOp) and conj.op == "="):
        return None
    for pat, expr in ((conj.left, conj.right), (conj.right, conj.left)):
        pv = pattern_vars(pat)
        if pv and not pv <= bound and is_pattern(pat) and all_vars(expr) <= bound and \
                all_vars(pat) == pv:
            return pat, expr
    return None
