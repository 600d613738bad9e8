"""The JSON result of `explore`: a stable schema (docs/statespace.md); keys are added, never renamed.

Imports `cpn.report.model`, `cpn.report.graphs` (its export limit), `cpn.engine.protocol` and `cpn.values`
only.
"""

from __future__ import annotations

from cpn.engine.protocol import capability
from cpn.report.graphs import MAX_EXPORT_STATES
from cpn.report.model import Report
from cpn.report.reduction import NOT_PRESERVED, REDUCED_SECTIONS
from cpn.values import colours as C

SCHEMA_VERSION: int = 1
EXAMPLES: int = 10


def to_json(r: Report, graph: bool = False, max_export_states: int | None = None) -> dict:
    """The report as a JSON-ready dict (the schema of docs/statespace.md); with `graph`, also the state
    space itself (`graph_json`) under the key "graph", for up to `max_export_states` states.

    >>> import cpn
    >>> from cpn.report import build_report
    >>> from cpn.statespace import Explorer
    >>> m = cpn.loads("colset U = unit; place A : U = 1`(); trans t; arc A -> t;")
    >>> d = to_json(build_report(Explorer(m.engine()).run()))
    >>> d["statespace"]["states"], d["dead_markings"]["count"], d["dead_transitions"]
    (2, 1, [])
    """
    x = r.exploration
    out = {
        "schema": SCHEMA_VERSION,
        "model": r.model,
        "options": r.options,
        "statespace": _statespace(r),
        "scc": {
            "nodes": r.scc.nodes,
            "arcs": r.scc.arcs,
            "terminal": r.scc.terminal,
            "nontrivial": r.scc.nontrivial,
            "arcs_distinct_pairs": r.scc.arc_pairs,
            "seconds": round(r.scc.seconds, 3),
        },
        "bounds": {b.place: {"upper": b.upper, "lower": b.lower} for b in r.bounds.places},
        "multiset_bounds": _multiset_bounds(r),
        "dead_markings": _dead_markings(r),
        "dead_transitions": r.dead_transitions,
        "live_transitions": r.live_transitions,
        "home_markings": _home_markings(r),
        "fairness": (None if r.fairness is None
                     else {name: cls.value for name, cls in r.fairness.items()}),
        "infinite_occurrence_sequences": (None if not r.fairness_known else any(r.scc.decomposition.nontrivial)),
        "tokens": {
            "max_per_marking": r.bounds.max_tokens_per_marking,
            "max_in_place": r.bounds.max_tokens_in_place,
            "max_of_one_colour_in_place": r.bounds.max_of_one_colour_in_place,
        },
        "report_seconds": round(r.seconds, 3),
        "report_part_seconds": {part: round(sec, 3) for part, sec in r.part_seconds.items()},
        "notes": r.notes,
        "backend_notes": r.backend_notes,
        "reduction": None if not r.reduced else {
            "name": x.reduction, **(x.reduction_stats or {}),
            "preserves": ["dead_markings"] + (["invariants_over_visible_places"]
                                              if (x.reduction_stats or {}).get("visible_places") is not None else []),
            "not_preserved": list(REDUCED_SECTIONS), "why": NOT_PRESERVED},
    }
    if graph:
        out["graph"] = graph_json(r, max_export_states)
    if r.symmetric:
        _symmetry_quotient(out, r)
    if r.reduced:
        # a reduced graph says nothing about these: null, never the reduced graph's figures
        for key in ("scc", "bounds", "multiset_bounds", "dead_transitions", "live_transitions", "home_markings",
                    "fairness", "infinite_occurrence_sequences", "tokens"):
            out[key] = None
        out["statespace"]["reduced"] = True
    return out


def graph_json(r: Report, max_states: int | None = None) -> dict:
    """The state space as the drawings have it: every state (`node` from 1, its non-empty places as text,
    its clock on a timed model without time condensation, else null, whether it is dead or expanded, its
    SCC) and every arc (`from`, `to`, `binding_element`). Above `max_states` states (None: the drawings'
    limit, MAX_EXPORT_STATES; 0: no limit) the graph is skipped: `skipped` true, the number of states,
    the limit and a note saying how to raise it.

    >>> import cpn
    >>> from cpn.report import build_report
    >>> from cpn.statespace import Explorer
    >>> m = cpn.loads("colset U = unit; place A : U = 1`(); trans t; arc A -> t;")
    >>> g = graph_json(build_report(Explorer(m.engine()).run()))
    >>> [s["marking"] for s in g["states"]], g["arcs"]
    ([{"Top'A 1": '1`()'}, {}], [{'from': 1, 'to': 2, 'binding_element': "Top't 1: {}"}])
    """
    x = r.exploration
    g = x.graph
    limit = MAX_EXPORT_STATES if max_states is None else max_states
    if limit and x.n_states > limit:
        return {"skipped": True, "states": x.n_states, "limit": limit,
                "note": f"the state space has {x.n_states:,} states, above the limit of {limit:,} for exports; "
                        f"raise it with --max-export-states {x.n_states} (0: no limit)"}
    engine = x.engine
    timed = bool(getattr(engine, "is_timed", False)) and not capability(engine, "time_condensation", False)
    dead = set(r.dead.states)
    dec = getattr(r.scc, "decomposition", None) if r.scc is not None else None
    states = []
    for i, s in enumerate(g.states):
        marking = {}
        for p, place in enumerate(engine.places):
            text = engine.format_marking(s, p)
            if text != "empty":
                marking[place.name] = text
        states.append({"node": i + 1, "marking": marking, "time": engine.clock(s) if timed else None,
                       "dead": i in dead, "expanded": g.is_expanded(i),
                       "scc": dec.comp[i] + 1 if dec is not None else None})
    arcs = [{"from": i + 1, "to": j + 1, "binding_element": engine.format_binding_element(be)}
            for i in range(g.expanded) for be, j in g.out_arcs(i)]
    return {"skipped": False, "states": states, "arcs": arcs}


def _statespace(r: Report) -> dict:
    """The search's figures, how it stopped and the options that shaped the graph."""
    x = r.exploration
    return {
        "states": x.n_states,
        "arcs": x.n_arcs,
        "complete": x.complete,
        "stop_reason": x.stop_reason.value,
        "stop_message": x.stop_reason.describe(x.options),
        "unexpanded": x.unexpanded,
        "restricted": x.restricted,
        "restriction": x.options.restriction(),
        "seconds": round(x.seconds, 3),
        "peak_memory_mb": round(x.peak_memory_mb, 1),
        "timed": r.timed,
        "time_condensation": bool(x.options.time_condensation),
        "untimed_states": x.untimed_states,
        "time_growth": x.time_growth,
        "reads_clock": bool(getattr(r.engine, "reads_clock", False)),
        "levels": x.levels,
    }


def _dead_markings(r: Report) -> dict:
    """The dead markings: count, example nodes, a shortest trace and the listed ones with their traces."""
    return {
        "count": r.dead.count,
        "examples": [i + 1 for i in r.dead.states[:EXAMPLES]],
        "untimed_count": r.dead.untimed_count,
        "unexpanded": r.dead.unexpanded,
        "trace": r.dead_trace.to_json() if r.dead_trace is not None else None,
        "listed_cap": r.dead_listed_cap,
        "listed": [{"node": d.state + 1, "marking": d.marking, "time": d.time, "trace": d.trace.to_json()}
                   for d in r.dead_listed],
    }


def _home_markings(r: Report) -> dict:
    """The home markings (null figures when they are unknown)."""
    home = r.home
    return {
        "count": None if home.states is None else len(home.states),
        "examples": None if home.states is None else [i + 1 for i in home.states[:EXAMPLES]],
        "initial_is_home": home.initial_is_home,
        "all": None if home.states is None else len(home.states) == r.exploration.graph.n_states,
    }


def _symmetry_quotient(out: dict, r: Report) -> None:
    """A graph of orbits: the reduction's figures, the full counts, and null for the sections it loses."""
    from cpn.properties.symmetry import INSTANCE_NOT_PRESERVED, NOT_PRESERVED_SECTIONS, PRESERVED
    from cpn.properties.symmetry import NOT_PRESERVED as SYM_NOT_PRESERVED

    st = r.exploration.reduction_stats or {}
    moved = r.moves_instances
    lost = list(NOT_PRESERVED_SECTIONS) + (list(INSTANCE_NOT_PRESERVED) if moved else [])
    out["reduction"] = {"name": "symmetry", **st,
                        "preserves": [p for p in PRESERVED if not (moved and p in INSTANCE_NOT_PRESERVED)],
                        "not_preserved": lost, "why": SYM_NOT_PRESERVED}
    for key in lost:
        out[key] = None
    out["statespace"].update(quotient=True, full_states=st.get("full_states"), full_arcs=st.get("full_arcs"))
    out["dead_markings"]["full_count"] = r.full_dead_count


def _multiset_bounds(r: Report) -> dict:
    """Each place's multi-set bounds as CPN ML text (`upper`, `lower`) and as terms (`upper_terms`,
    `lower_terms`): one {"colour": CPN ML text, "value": the colour as JSON, "count": n} per colour, in the
    text's order."""
    sets = {p.name: p.colour_set for p in r.engine.places}
    out = {}
    for b in r.bounds.places:
        cs = sets.get(b.place)
        out[b.place] = {"upper": b.upper_text, "lower": b.lower_text,
                        "upper_terms": multiset_terms(cs, b.upper_multiset),
                        "lower_terms": multiset_terms(cs, b.lower_multiset)}
    return out


def multiset_terms(cs, ms: dict) -> list[dict]:
    """The terms of an untimed multiset (value -> count) of colour set `cs`, in CPN ML order.

    >>> from cpn.values.colours import IntCS, ProductCS, EnumCS
    >>> pend = ProductCS("PEND", [EnumCS("K", ["req", "resp"]), IntCS("NO", 0, 9)])
    >>> multiset_terms(pend, {(1, 3): 2, (0, 7): 1})
    [{'colour': '(req,7)', 'value': ['req', 7], 'count': 1}, {'colour': '(resp,3)', 'value': ['resp', 3], 'count': 2}]
    """
    items = [(v, n) for v, n in ms.items() if n]
    if not isinstance(cs, C.ColourSet):  # an engine that gives no colour sets (a test's toy engine)
        return [{"colour": repr(v), "value": _plain(v), "count": n} for v, n in sorted(items, key=repr)]
    items.sort(key=lambda it: cs.sort_key(it[0]))
    return [{"colour": cs.format(v), "value": json_value(cs, v), "count": n} for v, n in items]


def json_value(cs, v):
    """A colour as a JSON value: numbers, booleans and strings as they are, unit as null, an enumeration's or
    a union's constant by its name, an index by its number, products and lists as arrays, records as objects
    by label, a union's constructor with an argument as {constructor: argument}."""
    while isinstance(cs, (C.AliasCS, C.SubsetCS)):
        cs = cs.base
    if isinstance(cs, C.UnitCS):
        return None
    if isinstance(cs, C.EnumCS):
        return cs.format(v)
    if isinstance(cs, C.ProductCS):
        return [json_value(c, x) for c, x in zip(cs.components, v)]
    if isinstance(cs, C.RecordCS):
        return {label: json_value(c, x) for (label, c), x in zip(cs.fields, v)}
    if isinstance(cs, C.ListCS):
        return [json_value(cs.elem, x) for x in v]
    if isinstance(cs, C.UnionCS):
        if isinstance(v, tuple):
            name, arg = cs.constructors[v[0]]
            return {name: json_value(arg, v[1])}
        return cs.constructors[v][0]
    return _plain(v)


def _plain(v):
    if v is None or isinstance(v, (bool, int, float, str)):
        return v
    if isinstance(v, tuple):
        return [_plain(x) for x in v]
    return str(v)
