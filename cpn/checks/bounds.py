"""Boundedness: best integer bounds, best multiset bounds and token maxima, timestamps stripped.

Imports `cpn.checks.columns` and `cpn.statespace` only. Every figure is computed over the distinct
markings each place takes (the engine interns them), not over states, so it costs little.
"""

from __future__ import annotations

from dataclasses import dataclass, replace
from operator import itemgetter

from cpn.checks.columns import has_place_columns, place_markings, state_chunks
from cpn.statespace import Exploration, graphnative


@dataclass(frozen=True)
class PlaceBounds:
    place: str
    upper: int
    lower: int
    upper_multiset: dict
    lower_multiset: dict
    upper_text: str
    lower_text: str
    max_of_one_colour: int


@dataclass(frozen=True)
class Boundedness:
    places: list  # list[PlaceBounds], in the engine's place order
    max_tokens_per_marking: int
    max_tokens_in_place: int
    max_of_one_colour_in_place: int


def boundedness(x: Exploration) -> Boundedness:
    """Integer and multiset bounds of every place instance over all stored states.

    Upper multiset bound: for each colour, the largest multiplicity over all markings; lower: the
    smallest (0 for a colour missing from some marking). On a partial state space these are bounds of
    the explored part only. One pass over the distinct markings of each place (`place_markings`);
    only the tokens per marking need the states themselves (one C-speed pass over the columns of
    the places whose token count varies).
    """
    engine = x.engine
    states = x.graph.states
    markings = place_markings(engine, states, x.graph.store)
    out = []
    for p, place in enumerate(engine.places):
        upper_ms: dict = {}
        lower_ms: dict | None = None
        hi_colour = 0
        for _key, ms, _count in markings[p]:
            if 0 in ms.values():
                ms = {v: n for v, n in ms.items() if n}
            for v, n in ms.items():
                if n > upper_ms.get(v, 0):
                    upper_ms[v] = n
                    if n > hi_colour:
                        hi_colour = n
            if lower_ms is None:
                lower_ms = dict(ms)
            elif lower_ms:
                lower_ms = {v: (n if n < ms[v] else ms[v]) for v, n in lower_ms.items() if v in ms}
        lower_ms = lower_ms or {}
        counts = [c for _k, _ms, c in markings[p]]
        out.append(PlaceBounds(
            place=place.name,
            upper=max(counts, default=0),
            lower=min(counts, default=0),
            upper_multiset=upper_ms,
            lower_multiset=lower_ms,
            upper_text=engine.format_multiset(p, upper_ms),
            lower_text=engine.format_multiset(p, lower_ms),
            max_of_one_colour=hi_colour,
        ))
    sym = getattr(x.graph, "symmetry", None)
    if sym is not None and sym.moves_instances:
        # a quotient whose group moves module instances: place p of one instance has, in the full graph,
        # the markings that the same place of every instance has in the quotient
        for orbit in sym.place_orbits():
            hi, lo = max(out[p].upper for p in orbit), min(out[p].lower for p in orbit)
            for p in orbit:
                out[p] = replace(out[p], upper=hi, lower=lo)
    return Boundedness(
        places=out,
        max_tokens_per_marking=_max_tokens_per_marking(engine, states, markings, x.graph.store),
        max_tokens_in_place=max((b.upper for b in out), default=0),
        max_of_one_colour_in_place=max((b.max_of_one_colour for b in out), default=0),
    )


def _max_tokens_per_marking(engine, states, markings, store=None) -> int:
    """The most tokens in one state. A place whose markings all hold the same number of tokens adds
    that number to every state; only the others are read state by state (in C from a packed `store`)."""
    if not states:
        return 0
    constant = 0
    varying = []
    for p, row in enumerate(markings):
        counts = {c for _k, _ms, c in row}
        if len(counts) == 1:
            constant += counts.pop()
        else:
            varying.append(p)
    if not varying:
        return constant
    if has_place_columns(engine, states) and all(type(k) is int for p in varying for k, _ms, _c in markings[p]):
        tables = []
        for p in varying:
            table = [0] * (max(k for k, _ms, _c in markings[p]) + 1)
            for k, _ms, c in markings[p]:
                table[k] = c
            tables.append(table)
        fast = None if store is None else graphnative.max_sum(store, varying, tables)
        if fast is not None:
            return constant + fast
        tables = [(table.__getitem__, itemgetter(p)) for table, p in zip(tables, varying)]
        best = 0
        for chunk in state_chunks(states):
            columns = [map(count, map(get, chunk)) for count, get in tables]
            m = max(columns[0]) if len(columns) == 1 else max(map(sum, zip(*columns)))
            if m > best:
                best = m
        return constant + best
    return max(sum(engine.token_counts(s)) for s in states)
