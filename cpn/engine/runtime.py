"""Helpers that generated transition code calls: multiset items, inclusion, inhibition, constructors."""

from __future__ import annotations

from cpn.values.builtins import MLError, binop
from cpn.values.multiset import Multiset, TimedMultiset

ONCE = (0,)


def MS1(v):  # noqa: N802 - a name in generated code
    return Multiset.of(v)


def MSITEMS(m, delay):  # noqa: N802
    """(value, count, delay) triples of a multiset-valued expression."""
    if isinstance(m, TimedMultiset):
        return [(v, n, d + delay) for v, n, d in m.items]
    if isinstance(m, Multiset):
        return [(v, n, delay) for v, n in m.items()]
    return [(m, 1, delay)]


def ENOUGH(have: dict, need: dict) -> bool:  # noqa: N802
    get = have.get
    for v, n in need.items():
        if n and get(v, 0) < n:
            return False
    return True


def INHIBITED(have: dict, m) -> bool:  # noqa: N802
    """An inhibitor arc blocks when the place contains the inscription's multiset (or anything, if empty)."""
    items = MSITEMS(m, 0)
    need: dict = {}
    for v, n, _ in items:
        need[v] = need.get(v, 0) + n
    if not any(need.values()):
        return bool(have)
    return ENOUGH(have, need)


def IDX(cs, i):  # noqa: N802
    if not cs.contains(i):
        raise MLError(f"{cs.constructor}({i}) is outside colour set {cs.name}")
    return i


def BINOP(op, a, b):  # noqa: N802
    return binop(op, a, b)


RUNTIME = {"ONCE": ONCE, "MS1": MS1, "MSITEMS": MSITEMS, "ENOUGH": ENOUGH, "INHIBITED": INHIBITED,
           "IDX": IDX, "BINOP": BINOP, "MLError": MLError}
