"""Boundedness: best integer bounds, best multiset bounds and token maxima, timestamps stripped.

Imports `cpn.checks._common` and `cpn.statespace` only. Every figure is computed over the distinct
markings each place takes (the engine interns them), not over states, so it costs little.
"""

from __future__ import annotations

from dataclasses import dataclass

from cpn.checks._common import place_representatives, untimed_multiset
from cpn.statespace import Exploration


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
    the explored part only.
    """
    engine = x.engine
    states = x.graph.states
    reps = place_representatives(engine, states)
    out = []
    count_tables = []
    for p, place in enumerate(engine.places):
        upper_ms: dict = {}
        lower_ms: dict | None = None
        counts: dict = {}
        hi_colour = 0
        for key, s in reps[p].items():
            ms = untimed_multiset(engine, p, engine.marking(s)[p])
            ms = {v: n for v, n in ms.items() if n}
            counts[key] = sum(ms.values())
            for v, n in ms.items():
                if n > upper_ms.get(v, 0):
                    upper_ms[v] = n
                if n > hi_colour:
                    hi_colour = n
            if lower_ms is None:
                lower_ms = dict(ms)
            else:
                lower_ms = {v: min(n, ms[v]) for v, n in lower_ms.items() if v in ms}
        lower_ms = lower_ms or {}
        count_tables.append(counts)
        fmt = getattr(engine, "format_multiset", None)
        out.append(PlaceBounds(
            place=place.name,
            upper=max(counts.values(), default=0),
            lower=min(counts.values(), default=0),
            upper_multiset=upper_ms,
            lower_multiset=lower_ms,
            upper_text=fmt(p, upper_ms) if fmt else _fmt(upper_ms),
            lower_text=fmt(p, lower_ms) if fmt else _fmt(lower_ms),
            max_of_one_colour=hi_colour,
        ))
    return Boundedness(
        places=out,
        max_tokens_per_marking=_max_tokens_per_marking(engine, states, reps, count_tables),
        max_tokens_in_place=max((b.upper for b in out), default=0),
        max_of_one_colour_in_place=max((b.max_of_one_colour for b in out), default=0),
    )


def _max_tokens_per_marking(engine, states, reps, count_tables) -> int:
    if not states:
        return 0
    from cpn.checks._common import has_place_columns

    if has_place_columns(engine, states):
        from operator import itemgetter

        columns = []
        for p, counts in enumerate(count_tables):
            if all(type(k) is int for k in counts):
                table = [0] * (max(counts, default=0) + 1)
                for k, n in counts.items():
                    table[k] = n
                columns.append(map(table.__getitem__, map(itemgetter(p), states)))
            else:
                columns.append(map(counts.__getitem__, map(itemgetter(p), states)))
        return max(map(sum, zip(*columns)), default=0)
    return max(sum(engine.token_counts(s)) for s in states)


def _fmt(ms: dict) -> str:
    if not ms:
        return "empty"
    return "++".join(f"{n}`{v!r}" for v, n in sorted(ms.items(), key=lambda kv: repr(kv[0])))
