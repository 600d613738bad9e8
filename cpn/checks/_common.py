"""Helpers shared by the standard-report checks: place columns, transition of a binding element.

Imports `cpn.statespace` and the standard library only.
"""

from __future__ import annotations

from array import array
from operator import itemgetter


def is_timed_place(engine, p: int) -> bool:
    place = engine.places[p]
    timed = getattr(place, "timed", None)
    if timed is None:
        timed = getattr(getattr(place, "colour_set", None), "timed", False)
    return bool(timed) and bool(getattr(engine, "is_timed", False))


def has_place_columns(engine, states: list) -> bool:
    """Whether states are tuples whose item p is the intern id of place p's multiset (docs/internals.md)."""
    if not states:
        return False
    s0 = states[0]
    n = len(engine.places)
    return isinstance(s0, tuple) and len(s0) in (n, n + 1) and all(type(x) is int for x in s0[:n])


def place_representatives(engine, states: list) -> list[dict]:
    """Per place, {key: a state} with one state for every distinct marking the place takes.

    With the documented state layout the key is the place's intern id (computed at C speed with
    zip/itemgetter); otherwise it is a canonical form of the place's marking (slow path).
    """
    n = len(engine.places)
    if has_place_columns(engine, states):
        return [dict(zip(map(itemgetter(p), states), states)) for p in range(n)]
    out: list[dict] = [{} for _ in range(n)]
    for s in states:
        for p, ms in enumerate(engine.marking(s)):
            out[p].setdefault(frozenset(ms.items()), s)
    return out


def untimed_multiset(engine, p: int, ms: dict) -> dict:
    """The place's multiset with timestamps removed: {value: count}."""
    if not is_timed_place(engine, p):
        return dict(ms)
    out: dict = {}
    for key, n in ms.items():
        v = key[0]
        out[v] = out.get(v, 0) + n
    return out


class TransitionIndex:
    """Maps binding-element ids to transition-instance indices (cached)."""

    def __init__(self, engine):
        self.engine = engine
        self._by_obj = {id(t): i for i, t in enumerate(engine.transitions)}
        self._by_name = {t.name: i for i, t in enumerate(engine.transitions)}
        self._cache: dict[int, int] = {}

    def __call__(self, be: int) -> int:
        t = self._cache.get(be)
        if t is None:
            tr = self.engine.binding_element(be).transition
            if isinstance(tr, int):
                t = tr
            else:
                t = self._by_obj.get(id(tr))
                if t is None:
                    t = self._by_name[tr.name]
            self._cache[be] = t
        return t

    def arc_transitions(self, bes: array) -> array:
        """The transition instance of every arc, as an array parallel to `bes`."""
        distinct = sorted(set(bes))
        if not distinct:
            return array("i")
        table = [0] * (distinct[-1] + 1)
        for be in distinct:
            table[be] = self(be)
        n = len(self.engine.transitions)
        code = "B" if n <= 0xFF else "H" if n <= 0xFFFF else "i"
        return array(code, map(table.__getitem__, bes))
