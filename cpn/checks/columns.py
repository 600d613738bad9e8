"""Helpers shared by the standard-report checks: place columns, transition of a binding element.

Uses the engine through its protocol (`cpn.engine.Engine`), and the compiled engine's intern tables
where it has them (`_intern_tables`, a fast path).
"""

from __future__ import annotations

from array import array
from itertools import islice
from operator import itemgetter

from cpn.engine import Engine
from cpn.engine.protocol import capability
from cpn.statespace import graphnative


def is_timed_place(engine: Engine, p: int) -> bool:
    return engine.is_timed and engine.places[p].timed


def has_place_columns(engine, states: list) -> bool:
    """Whether states are tuples whose item p is the intern id of place p's multiset (docs/internals.md)."""
    if not states:
        return False
    s0 = states[0]
    n = len(engine.places)
    return isinstance(s0, tuple) and len(s0) in (n, n + 1) and all(type(x) is int for x in s0[:n])


def place_markings(engine, states: list, store=None) -> list[list[tuple[object, dict, int]]]:
    """Per place, every distinct marking it takes over `states`: (key, untimed multiset, tokens).

    With the compiled engine's state layout (docs/internals.md: item p of a state is the intern id of
    place p's multiset) the key is that id: the distinct ids come from one C-speed pass per place
    column (`set(map(itemgetter(p), states))`) and each id's untimed multiset and token count are read
    from the engine's intern tables, so the work per distinct marking is one place's, not a whole
    state's. Otherwise (the reference engine) the key is a canonical form of the place's marking and
    every state's marking is read once. The multisets are the engine's own: do not mutate them.
    """
    n = len(engine.places)
    tables = _intern_tables(engine)
    if tables is not None and has_place_columns(engine, states):
        views, counts = tables
        # a packed store's records are read in C, without decoding a state
        ids = None if store is None else graphnative.place_columns(store, [len(v) for v in views])
        if ids is None:
            seen: list[set] = [set() for _ in range(n)]
            adders = [s.update for s in seen]
            getters = [itemgetter(p) for p in range(n)]
            for chunk in state_chunks(states):
                for add, get in zip(adders, getters):
                    add(map(get, chunk))
            ids = [sorted(s) for s in seen]
        out = []
        for p in range(n):
            vp, cp = views[p], counts[p]
            out.append([(i, vp[i], cp[i]) for i in ids[p]])
        return out
    seen: list[dict] = [{} for _ in range(n)]
    for s in states:
        for p, ms in enumerate(engine.marking(s)):
            key = frozenset(ms.items())
            if key not in seen[p]:
                um = untimed_multiset(engine, p, ms)
                seen[p][key] = (key, um, sum(um.values()))
    return [list(d.values()) for d in seen]


# states per chunk when reading place columns: a chunk's tuples stay in the processor's cache while every
# column is read from them (Peterson-PT-2, 102 places x 20,754 states: 0.28-0.29 s against 0.72-1.12 s
# for each column over all states, on a loaded machine)
CHUNK_STATES: int = 1024


def state_chunks(states: list):
    """The states in consecutive lists of CHUNK_STATES. A sequence that is not a list (a packed store's
    states) is iterated, which decodes its records a few thousand at a time; its slices decode them one
    by one (IBM319-PT-none: 0.066 s against 0.005 s for 2,482 states of 253 places, under cProfile)."""
    if isinstance(states, list):
        for k in range(0, len(states), CHUNK_STATES):
            yield states[k:k + CHUNK_STATES]
        return
    it = iter(states)
    while chunk := list(islice(it, CHUNK_STATES)):
        yield chunk


def _intern_tables(engine):
    """The compiled engine's per-place intern tables (untimed multisets, token counts), or None."""
    store = capability(engine, "store")
    views = getattr(store, "views", None)
    counts = getattr(store, "counts", None)
    if views is None or counts is None or len(views) != len(engine.places):
        return None
    return views, counts


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
        self._distinct: tuple | None = None  # (the bes array, its length, its distinct values)

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

    def distinct(self, bes: array) -> list[int]:
        """The distinct binding elements of an array of arcs, increasing (kept for the last array)."""
        known = self._distinct
        if known is not None and known[0] is bes and known[1] == len(bes):
            return known[2]
        distinct = graphnative.distinct_ids(bes)
        if distinct is None:
            distinct = sorted(set(bes))
        self._distinct = (bes, len(bes), distinct)
        return distinct

    def arc_transitions(self, bes: array) -> array:
        """The transition instance of every arc, as an array parallel to `bes`."""
        distinct = self.distinct(bes)
        if not distinct:
            return array("i")
        table = [0] * (distinct[-1] + 1)
        for be in distinct:
            table[be] = self(be)
        n = len(self.engine.transitions)
        code = "B" if n <= 0xFF else "H" if n <= 0xFFFF else "i"
        fast = graphnative.map_ids(bes, table, code)
        return fast if fast is not None else array(code, map(table.__getitem__, bes))
