"""Properties that follow from the net's structure: an invariant whose text compares a weighted sum of
token counts, `k1 * size (P1) + k2 * size (P2) + ...`, with a constant, where the weights are a place
invariant of the net's incidence matrix (token counts: what each transition takes from and puts on each
place). Such a sum is the same in every marking reachable from any initial marking, whatever the
guards, the values of the tokens and the order of occurrences: the property cannot catch a mistake in
any of them.

Imports `cpn.net`, `cpn.lang.ast` and `cpn.checks` only.
"""

from __future__ import annotations

from cpn.arcs import ArcKind
from cpn.checks.properties import Invariant
from cpn.checks.verdict import Status
from cpn.lang import ast as A
from cpn.net import expr as E

_COMPARISONS = {"=", "<>", "<", "<=", ">", ">="}


def structural(check, view, verdict) -> list[str]:
    """Why a property that holds follows from the structure of the net (one sentence), or nothing."""
    if verdict.status is not Status.HOLDS or not isinstance(check, Invariant):
        return []
    lang = view.lang
    weights = []
    for conjunct in _conjuncts(check.pred.expr):
        w = _compared_sum(conjunct, lang)
        if w is None:
            return []
        weights.append(w)
    if not weights or not all(is_place_invariant(lang.net, w) for w in weights):
        return []
    return ["follows from the net's structure: the weighted sum of token counts it compares is a place invariant "
            "(the same in every reachable marking of any initial marking), so no guard, token value or order "
            "of occurrences can break it"]


def _conjuncts(e) -> list:
    if isinstance(e, A.Annot):
        return _conjuncts(e.expr)
    if isinstance(e, A.BinOp) and e.op == "andalso":
        return _conjuncts(e.left) + _conjuncts(e.right)
    return [e]


def _compared_sum(e, lang) -> dict | None:
    """The weights (place index -> integer) of `sum OP constant` (either side; both sides may hold token
    counts), or None when the text is not such a comparison or has no token count."""
    if not (isinstance(e, A.BinOp) and e.op in _COMPARISONS):
        return None
    left, right = _linear(e.left, lang), _linear(e.right, lang)
    if left is None or right is None:
        return None
    out = dict(left)
    for p, k in right.items():
        out[p] = out.get(p, 0) - k
    out = {p: k for p, k in out.items() if k}
    return out or None


def _linear(e, lang) -> dict | None:
    """`e` as a sum of integer multiples of token counts plus a constant: the weights by place, or None.
    A name or constant without a place in it is the constant part."""
    if isinstance(e, A.Annot):
        return _linear(e.expr, lang)
    if isinstance(e, A.Const):
        return {} if e.kind == "int" else None
    if isinstance(e, A.Name):
        return None if e.ref is None or e.ref.uid in lang.symbols else {}
    if isinstance(e, A.Neg):
        inner = _linear(e.operand, lang)
        return None if inner is None else {p: -k for p, k in inner.items()}
    if isinstance(e, A.BinOp) and e.op in ("+", "-"):
        a, b = _linear(e.left, lang), _linear(e.right, lang)
        if a is None or b is None:
            return None
        out = dict(a)
        for p, k in b.items():
            out[p] = out.get(p, 0) + (k if e.op == "+" else -k)
        return out
    if isinstance(e, A.BinOp) and e.op == "*":
        for const, term in ((e.left, e.right), (e.right, e.left)):
            if isinstance(const, A.Const) and const.kind == "int":
                inner = _linear(term, lang)
                return None if inner is None else {p: const.value * k for p, k in inner.items()}
        return None
    if isinstance(e, A.App) and isinstance(e.fn, A.Name) and e.fn.name in ("size", "Ms.size"):
        places = _places_of(e.arg, lang)
        return None if places is None else {p: 1 for p in places}
    return None


def _places_of(e, lang) -> list | None:
    """The place instances whose whole marking `e` is: `Page'P 1`, or `sum Page'P` (every instance)."""
    if isinstance(e, A.App) and isinstance(e.fn, A.Name) and e.fn.ref is not None and e.fn.ref.uid in lang.symbols:
        acc = lang.symbols[e.fn.ref.uid]
        if isinstance(e.arg, A.Const) and e.arg.kind == "int" and e.arg.value in acc.instances:
            return [acc.instances[e.arg.value]]
        return None
    if (isinstance(e, A.App) and isinstance(e.fn, A.Name) and "sum" in lang.special
            and e.fn.ref is lang.special["sum"] and isinstance(e.arg, A.Name) and e.arg.ref is not None
            and e.arg.ref.uid in lang.symbols):
        return list(lang.symbols[e.arg.ref.uid].places)
    return None


def is_place_invariant(net, weights: dict) -> bool:
    """Whether every transition instance leaves the weighted token count unchanged, for every binding:
    the weights are a left null vector of the incidence matrix of token counts. A transition whose arc to
    a weighted place takes or puts a number of tokens that depends on the binding, or resets the place,
    makes the answer no."""
    for t in net.transitions:
        change = 0
        for a in t.arcs:
            k = weights.get(a.place)
            if not k or a.kind in (ArcKind.BOTH, ArcKind.INHIBITOR):
                continue
            if a.kind is ArcKind.RESET:
                return False
            n = token_count(a.expr)
            if n is None:
                return False
            change += k * n if a.kind is ArcKind.OUT else -k * n
        if change:
            return False
    return True


def token_count(e) -> int | None:
    """The number of tokens an arc inscription denotes for every binding, or None if it depends on it."""
    if e is None:
        return 1
    if isinstance(e, E.ToMs):
        return 1
    if isinstance(e, E.BinOp):
        if e.op == "@+":
            return token_count(e.left)
        if e.op == "`":
            return e.left.value if isinstance(e.left, E.Const) and e.left.kind == "int" else None
        if e.op == "++":
            a, b = token_count(e.left), token_count(e.right)
            return None if a is None or b is None else a + b
        return None
    if isinstance(e, E.If):
        a, b = token_count(e.then), token_count(e.else_)
        return a if a is not None and a == b else None
    if isinstance(e, E.Name) and e.name == "empty":
        return 0
    return None
