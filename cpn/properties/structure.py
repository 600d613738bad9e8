"""Properties that follow from the net's structure: an invariant whose text compares a weighted sum of
token counts, `k1 * size (P1) + k2 * size (P2) + ...`, with a constant, where the weights are a place
invariant of the net's incidence matrix (token counts: what each transition takes from and puts on each
place). Such a sum is the same in every marking reachable from any initial marking, whatever the
guards, the values of the tokens and the order of occurrences: the property cannot catch a mistake in
any of them. Likewise a `bound` of one place that its semi-positive place invariants (Farkas's
algorithm) and the initial marking imply.

Imports `cpn.net`, `cpn.lang.ast` and `cpn.checks` only.
"""

from __future__ import annotations

import weakref

from cpn.checks.verdict import Status
from cpn.expr import nodes as E
from cpn.lang import ast as A
from cpn.properties.kinds import Bound, Invariant

_COMPARISONS = {"=", "<>", "<", "<=", ">", ">="}


def structural(check, view, verdict) -> list[str]:
    """Why a property that holds follows from the structure of the net (one sentence), or nothing."""
    if verdict.status is not Status.HOLDS:
        return []
    if isinstance(check, Bound):
        return _bound(check, view.lang)
    if not isinstance(check, Invariant):
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
            if not k:
                continue
            if a.kind.empties:
                return False
            if a.kind.consumes == a.kind.produces:  # puts back what it takes, or takes nothing
                continue
            n = token_count(a.expr)
            if n is None:
                return False
            change += k * n if a.kind.produces else -k * n
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


# ---------------------------------------------------------------------------------------------- bounds

# Farkas's algorithm can produce exponentially many rows: past this many, no bound is claimed
MAX_ROWS = 2_000


def _bound(check, lang) -> list[str]:
    """A bound of one place whose every integer limit follows from the place invariants and the initial
    marking: `at_most k` (the structural bound is at most k), `upper_equals k` (the same, and the initial
    marking has k tokens there), `lower_equals k` and `at_least k` (the place's token count never changes)."""
    if check.multiset_limits or not check.limits:
        return []
    if check.places is not None:
        if len(check.places) != 1:
            return []
        p = check.places[0]
    else:
        w = _linear(check.fn.expr, lang)
        if w is None or len(w) != 1 or next(iter(w.values())) != 1:
            return []
        p = next(iter(w))
    net = lang.net
    upper, constant = structural_bound(net, p)
    m0 = initial_count(net, p)
    for key, want in check.limits.items():
        if key == "at_most" and not (upper is not None and upper <= want):
            return []
        if key == "upper_equals" and not (upper is not None and upper <= want and m0 == want):
            return []
        if key == "lower_equals" and not (constant and m0 == want):
            return []
        if key == "at_least" and not (constant and m0 >= want):
            return []
    return [f"follows from the net's structure: place invariants of the incidence matrix and the initial marking "
            f"give the bound ({'the token count never changes' if constant else f'at most {upper}'}), so no "
            f"guard, token value or order of occurrences can break it"]


def initial_count(net, p: int) -> int:
    return sum(net.places[p].initial.values())


def structural_bound(net, p: int) -> tuple[int | None, bool]:
    """(the smallest upper bound of place p's token count that a minimal semi-positive place invariant and
    the initial marking give, or None; whether some invariant is p alone: its count never changes)."""
    invariants = semi_positive_invariants(net)
    if invariants is None:
        return None, False
    m0 = [initial_count(net, q) for q in range(len(net.places))]
    best = None
    constant = False
    for y in invariants:
        k = y.get(p, 0)
        if not k:
            continue
        if set(y) == {p}:
            constant = True
        b = sum(w * m0[q] for q, w in y.items()) // k
        best = b if best is None else min(best, b)
    return best, constant


def semi_positive_invariants(net) -> list[dict] | None:
    """The minimal-support semi-positive place invariants (place -> weight) of the incidence matrix of
    token counts, by Farkas's algorithm; places an arc of binding-dependent size or a reset arc touches
    take no part. None when the computation grows past MAX_ROWS rows. Computed once per net."""
    try:
        return _INVARIANTS[net]
    except KeyError:
        pass
    except TypeError:  # a net that cannot be weakly referenced: no cache
        return _farkas(net)
    got = _INVARIANTS[net] = _farkas(net)
    return got


_INVARIANTS: weakref.WeakKeyDictionary = weakref.WeakKeyDictionary()


def _farkas(net) -> list[dict] | None:
    from math import gcd

    n = len(net.places)
    excluded = set()
    columns = []
    for t in net.transitions:
        col: dict[int, int] = {}
        for a in t.arcs:
            if a.kind.consumes == a.kind.produces and not a.kind.empties:
                continue
            size = None if a.kind.empties else token_count(a.expr)
            if size is None:
                excluded.add(a.place)
                continue
            col[a.place] = col.get(a.place, 0) + (size if a.kind.produces else -size)
        columns.append(col)
    # a row: (the incidence part by column, the weights by place, the support as a bit mask)
    rows = [({j: col[p] for j, col in enumerate(columns) if col.get(p)}, {p: 1}, 1 << p)
            for p in range(n) if p not in excluded]
    for j in range(len(columns)):
        pos = [r for r in rows if r[0].get(j, 0) > 0]
        neg = [r for r in rows if r[0].get(j, 0) < 0]
        if not pos and not neg:
            continue
        new = [r for r in rows if not r[0].get(j, 0)]
        if not pos or not neg:  # the rows that meet column j go; the others stay minimal
            rows = new
            continue
        for a in pos:
            for b in neg:
                ka, kb = -b[0][j], a[0][j]
                c = {i: ka * a[0].get(i, 0) + kb * b[0].get(i, 0) for i in a[0].keys() | b[0].keys()}
                y = {q: ka * a[1].get(q, 0) + kb * b[1].get(q, 0) for q in a[1].keys() | b[1].keys()}
                g = 0
                for v in (*c.values(), *y.values()):
                    g = gcd(g, v)
                g = g or 1
                new.append(({i: v // g for i, v in c.items() if v}, {q: v // g for q, v in y.items() if v},
                            a[2] | b[2]))
        # keep minimal supports only
        new.sort(key=lambda r: len(r[1]))
        kept: list = []
        for r in new:
            m = r[2]
            if not any(k[2] | m == m for k in kept):
                kept.append(r)
        if len(kept) > MAX_ROWS:
            return None
        rows = kept
    return [y for c, y, _ in rows if not c]
