"""The report of one scenario run: its data (`run_report`, the JSON document) and its text and Markdown.

Traces are rendered as steps (time, binding element, binding, tokens removed and added per place
instance). Every renderer receives the JSON document, so reports re-read from disk (`--baseline`)
and fresh ones look the same. Imports `cpn.checks`, `cpn.engine` (to replay a trace without time
condensation, and the reference interpreter's arc evaluation), `cpn.values` and layer 0.
"""

from __future__ import annotations

import os
from collections import OrderedDict

from cpn.checks.verdict import Evidence
from cpn.engine.protocol import capability, has
from cpn.properties.vacuity import warning_code
from cpn.values.colours import format_multiset

SCHEMA = "cpn-verify/check-report/1"


# ----------------------------------------------------------------------------- traces
def trace_steps(engine, graph, evidence: Evidence | None, reads: tuple = ()) -> dict:
    """{"steps": [...], "cycle": [...], "target": n, "marking": {...}}: the evidence as printable,
    replayable steps, and the marking it leads to (where a lasso's cycle starts): "places" has every
    non-empty place and the places in `reads` (indices: those the property reads, listed in "reads")."""
    if evidence is None:
        return {"steps": [], "cycle": []}
    pairs = list(zip(evidence.path, evidence.path[1:], evidence.arcs))
    prev = evidence.path[-1]
    for v, be in zip(evidence.cycle, evidence.cycle_arcs):
        pairs.append((prev, v, be))
        prev = v
    states = [graph.states[evidence.path[0]]] + [graph.states[v] for _, v, _ in pairs]
    if getattr(graph, "symmetry", None) is not None:
        # a path of the quotient graph (symmetry reduction): the same orbits, in the full graph
        from cpn.statespace.symmetry import lift_path

        states, bes = lift_path(graph, pairs, engine)
        pairs = [(u, v, be) for (u, v, _), be in zip(pairs, bes)]
    shown, texts = engine, None
    if capability(engine, "time_condensation", False):
        # condensed states keep timestamps relative to their clock: replay the trace on the same net
        # without condensation to print the model time and the absolute timestamps
        replayed = _replay_absolute(engine, [be for _, _, be in pairs])
        if replayed is not None:
            shown, states, texts = replayed
    arcs = _ArcTokens(engine)
    out = []
    after = shown.marking(states[0])  # each state's marking read once: it ends one step and begins the next
    for i, (u, v, be) in enumerate(pairs):
        text = texts[i] if texts is not None else engine.format_binding_element(be)
        time = shown.clock(states[i + 1])
        before, after = after, shown.marking(states[i + 1])
        out.append(_step(shown, before, after, time, i + 1, u, v, text, arcs(engine.binding_element(be), time)))
    n = len(evidence.path) - 1
    return {"steps": out[:n], "cycle": out[n:], "target": evidence.path[-1] + 1,
            "marking": end_marking(shown, states[n], evidence.path[-1], reads)}


def end_marking(engine, state, sid: int, reads: tuple = ()) -> dict:
    """{"state": 1-based id, "reads": [place names], "places": {name: multiset}} of one marking: every
    non-empty place, and each place of `reads` (indices) even when empty; time stamps when timed."""
    places = {}
    for p, place in enumerate(engine.places):
        text = engine.format_marking(state, p)
        if p in reads or (text and text != "empty"):
            places[place.name] = text or "empty"
    doc = {"state": sid + 1, "reads": [engine.places[p].name for p in reads], "places": places}
    if getattr(engine, "is_timed", False):
        doc["time"] = engine.clock(state)
    return doc


#: engines built to print traces, per net and kind, reused by every trace of the net last reported on (the
#: traces of one run, and of runs that share their net: `cpn.model.caching`): replaying a trace only reads an
#: engine (what it interns grows, its successor function is the same). One net: an engine holds its memo
#: tables, some 30,000 objects for a MODBUS net, which every full collection of the garbage collector walks
_PRINTING_ENGINES: OrderedDict = OrderedDict()
PRINTING_NETS: int = 1


def printing_engine(net, time_condensation: bool = False, reference: bool = False):
    """The engine of `net` of that kind that prints traces, built once while the net is among the last
    `PRINTING_NETS` reported on."""
    from cpn.engine import compile_net

    key = (id(net), time_condensation, reference)
    kept = _PRINTING_ENGINES.get(key)
    if kept is not None and kept[0] is net:
        _PRINTING_ENGINES.move_to_end(key)
        return kept[1]
    engine = compile_net(net, time_condensation=time_condensation, reference=reference)
    _PRINTING_ENGINES[key] = (net, engine)  # the net is held, so its id is not reused while kept
    while len({k[0] for k in _PRINTING_ENGINES}) > PRINTING_NETS:
        _PRINTING_ENGINES.popitem(last=False)
    return engine


def _replay_absolute(engine, bes: list[int]):
    """(uncondensed engine, its states along the trace, binding element texts) or None if it diverges."""
    twin = getattr(engine, "uncondensed", None)  # the compiled engine's, without compiling it again
    plain = twin() if twin is not None else printing_engine(engine.net, reference=bool(capability(engine, "reference",
                                                                                                   False)))
    # the twin numbers binding elements as the engine does (it shares its table): compared by number
    same = twin is not None
    state = plain.initial_state()
    states, texts = [state], []
    for be in bes:
        want = engine.format_binding_element(be)
        nxt = next((t for b, t in plain.successors(state)
                    if (b == be if same else plain.format_binding_element(b) == want)), None)
        if nxt is None:
            return None
        state = nxt
        states.append(state)
        texts.append(want)
    return plain, states, texts


class _ArcTokens:
    """The tokens a binding element takes from and puts on each untimed place, from the transition's arc
    inscriptions (so a token that a double arc takes and puts back shows as both). Evaluated with the
    reference interpreter's arc evaluation; None when an inscription cannot be evaluated here."""

    def __init__(self, engine):
        self.ref = printing_engine(engine.net, reference=True)

    def __call__(self, b, clock) -> dict | None:
        ref = self.ref
        t = ref.transitions[b.transition if isinstance(b.transition, int) else b.transition.index]
        try:
            env = ref.binding_env(t, b.binding)
            ref.ev.time = clock
            out: dict[int, tuple[dict, dict]] = {}
            for a in t.arcs:
                if not (a.kind.consumes or a.kind.produces) or a.expr is None or ref.places[a.place].timed:
                    continue
                take, put = out.setdefault(a.place, ({}, {}))
                for v, n, _ in ref.arc_tokens(a.expr, env, t):
                    if a.kind.consumes:
                        take[v] = take.get(v, 0) + n
                    if a.kind.produces:
                        put[v] = put.get(v, 0) + n
            resets = {a.place for a in t.arcs if a.kind.empties}
        except Exception:  # noqa: BLE001 - printing falls back to the change of the marking
            return None
        return {p: d for p, d in out.items() if p not in resets}


def _step(engine, mu: list, mv: list, time, k: int, u: int, v: int, text: str, tokens: dict | None = None) -> dict:
    """Step k, from state u (marking mu) to state v (marking mv, at `time`)."""
    consumed, produced = {}, {}
    for p, place in enumerate(engine.places):
        a, b = mu[p], mv[p]
        if tokens is not None and p in tokens:
            take, put = tokens[p]
            if take:
                consumed[place.name] = format_multiset(place.colour_set, take.items())
            if put:
                produced[place.name] = format_multiset(place.colour_set, put.items())
            continue
        if a == b:
            continue
        minus = {x: n - b.get(x, 0) for x, n in a.items() if n > b.get(x, 0)}
        plus = {x: n - a.get(x, 0) for x, n in b.items() if n > a.get(x, 0)}
        timed = bool(getattr(place, "timed", False)) and bool(getattr(engine, "is_timed", False))
        if minus:
            consumed[place.name] = format_multiset(place.colour_set, minus.items(), timed=timed)
        if plus:
            produced[place.name] = format_multiset(place.colour_set, plus.items(), timed=timed)
    tname, _, rest = text.partition(": ")
    binding = {}
    for item in _split_binding(rest):
        name, _, value = item.partition("=")
        binding[name] = value
    return {"step": k, "time": time, "binding_element": text, "transition": tname,
            "binding": binding, "consumed": consumed, "produced": produced, "from": u + 1, "to": v + 1}


def _split_binding(text: str) -> list[str]:
    """The `var=value` items of ``{a=1, f=(1,3)}`` (commas inside brackets and strings kept)."""
    body = text.strip()
    if body.startswith("{") and body.endswith("}"):
        body = body[1:-1]
    items, depth, start, quoted = [], 0, 0, False
    for i, c in enumerate(body):
        if c == '"':
            quoted = not quoted
        elif quoted:
            continue
        elif c in "([{":
            depth += 1
        elif c in ")]}":
            depth -= 1
        elif c == "," and depth == 0:
            items.append(body[start:i].strip())
            start = i + 1
    if body[start:].strip():
        items.append(body[start:].strip())
    return items


def render_steps(trace: dict, indent: str = "    ") -> list[str]:
    out = []
    steps, cycle = trace.get("steps", []), trace.get("cycle", [])
    if not steps and not cycle:
        out.append(f"{indent}(the initial marking)")
    for s in steps:
        out.extend(_render_step(s, indent))
    if cycle:
        out.append(f"{indent}then forever, the cycle back to marking {cycle[-1]['to']}:")
        for s in cycle:
            out.extend(_render_step(s, indent + "  "))
    if trace.get("marking"):
        out.extend(render_marking(trace["marking"], indent, bool(cycle)))
    return out


MARKING_PLACES: int = 20  # places of a marking printed after a trace (the ones the property reads first)


def render_marking(m: dict, indent: str = "    ", lasso: bool = False) -> list[str]:
    """The marking at the end of a trace: the places the property reads first (even when empty), then the
    other marked places, at most MARKING_PLACES in all, and how many more are marked."""
    what = ("violating marking" if m.get("violating") else "the marking where the property failed"
            if "violating" in m else "marking reached")
    at = f" at time {m['time']}" if "time" in m else ""
    where = " (where the cycle starts)" if lasso else ""
    reads = [p for p in m.get("reads", []) if p in m["places"]]
    if not m["places"]:
        return [f"{indent}{what} {m['state']}{at}{where}: every place is empty"]
    shown = reads + [p for p in m["places"] if p not in reads][:max(0, MARKING_PLACES - len(reads))]
    said = f", the property reads {', '.join(reads)}" if reads else ""
    out = [f"{indent}{what} {m['state']}{at}{where}{said}:"]
    width = max(len(p) for p in shown)
    out += [f"{indent}       {p:<{width}}  {m['places'][p]}" for p in shown]
    others = len(m["places"]) - len(shown)
    if others:
        out.append(f"{indent}       (and {others} more marked place{'s' if others != 1 else ''}: all in the JSON "
                   "report)")
    return out


def _render_step(s: dict, indent: str) -> list[str]:
    lines = [f"{indent}{s['step']:>3}. @{s['time']}  {s['binding_element']}"]
    places = sorted(set(s["consumed"]) | set(s["produced"]))
    width = max((len(p) for p in places), default=0)
    for p in places:
        if p in s["consumed"]:
            lines.append(f"{indent}       {p:<{width}}  - {s['consumed'][p]}")
        if p in s["produced"]:
            lines.append(f"{indent}       {p:<{width}}  + {s['produced'][p]}")
    return lines


# ----------------------------------------------------------------------------- the report document
def run_report(result, timings: bool = True) -> dict:
    """The JSON document of one run (keys are a contract: add, never rename)."""
    x = result.exploration
    g = x.graph
    scen = result.scenario
    props = []
    for r in result.results:
        v = r.verdict
        at = v.at or r.spec.span  # an error is placed at the text that raised
        doc = {"name": r.spec.name, "kind": r.spec.kind, "line": at.line, "column": at.col,
               "verdict": v.status.value, "message": v.message}
        if r.spec.expect != "holds":
            doc["expect"] = r.spec.expect
        doc["gate"] = r.gate_status.value  # the verdict as the gate counts it (see 'expect')
        if r.spec.description:
            doc["description"] = r.spec.description
        if timings:
            doc["seconds"] = round(r.seconds, 4)
        if v.evidence is not None:
            doc["trace"] = trace_steps(result.engine, g, v.evidence, getattr(r, "reads", ()))
            if v.status.value != "holds":
                doc["trace"]["marking"]["violating"] = v.status.value == "violated"
        if v.details:
            doc["details"] = v.details
        if getattr(r, "warnings", None):  # it holds vacuously, or by the net's structure alone
            doc["warnings"] = list(r.warnings)
            doc["warning_codes"] = [warning_code(w) for w in r.warnings]
        props.append(doc)
    sweep = getattr(x, "method", None) == "sweep-line"  # no graph: its own dead markings and bounds
    dead = x.dead if sweep else g.dead_states()
    stats = {"states": x.n_states, "arcs": x.n_arcs, "complete": x.complete, "stop_reason": x.stop_reason.value,
             "unexpanded": x.unexpanded, **(x.statistics() if sweep else {})}
    if x.reduction is not None:
        # the counts are the reduced graph's; bounds are not preserved by the reduction
        stats["reduction"] = x.reduction
    if x.reduction == "symmetry":
        st = x.reduction_stats or {}
        stats.update(symmetry=st.get("symmetry"), full_states=st.get("full_states"), full_arcs=st.get("full_arcs"))
    if timings:
        stats["seconds"] = round(result.explore_seconds, 4)
        stats["check_seconds"] = round(result.check_seconds, 4)
    return {
        "schema": SCHEMA,
        "scenario": scen.name,
        "run": result.run.name,
        "file": scen.path,
        "model": _portable(scen.model),
        "parameters": result.run.params,
        "values": result.run.values,
        "options": {k: v for k, v in sorted(result.options.items())},
        "verdict": result.status.value,
        "statespace": stats,
        "dead_markings": {"count": len(dead)},
        "bounds": x.integer_bounds() if sweep else _integer_bounds(result) if x.reduction in (None, "symmetry") else None,
        "properties": props,
    }


def _integer_bounds(result) -> dict:
    """Best integer bounds per place instance, from the distinct markings each place takes."""
    engine = result.engine
    states = result.exploration.graph.states
    out = {}
    if not states:
        return out
    columns = has(engine, "place_view")
    if columns:
        states = list(states)  # (a store decodes a state each time it is read: once, not once per place)
    for p, place in enumerate(engine.places):
        if columns:
            ids = {s[p]: s for s in states}
            sizes = [sum(engine.place_view(s, p).values()) for s in ids.values()]
        else:
            sizes = [sum(engine.marking(s)[p].values()) for s in states]
        out[place.name] = {"upper": max(sizes), "lower": min(sizes)}
    sym = result.exploration.graph.symmetry
    if sym is not None and sym.moves_instances:
        # the same place of every module instance the symmetry permutes has the bounds of all of them
        names = [p.name for p in engine.places]
        for orbit in sym.place_orbits():
            hi = max(out[names[p]]["upper"] for p in orbit)
            lo = min(out[names[p]]["lower"] for p in orbit)
            for p in orbit:
                out[names[p]] = {"upper": hi, "lower": lo}
    return out


def report_name(run_name: str) -> str:
    """A file name for a run: 'MS[N=2,K=3]' -> 'MS-N=2,K=3'."""
    safe = "".join(c if c.isalnum() or c in "_.=,+-" else "-" for c in run_name).strip("-")
    while "--" in safe:
        safe = safe.replace("--", "-")
    return safe or "scenario"


# ----------------------------------------------------------------------------- text and Markdown
def _where(doc: dict, p: dict) -> str:
    return f"{os.path.relpath(doc['file'])}:{p['line']}:{p['column']}"


def _reduced_words(st: dict) -> str:
    """' (reduced by stubborn sets)', or for symmetry the quotient and the full graph's counts."""
    if not st.get("reduction"):
        return ""
    if st["reduction"] != "symmetry":
        return f" (reduced by {st['reduction']} sets)"
    full = (f"; {st['full_states']:,} states, {st['full_arcs']:,} arcs in the full graph"
            if st.get("full_states") is not None else "")
    return f" (one per orbit under the symmetry {', '.join(st.get('symmetry') or [])}{full})"


def property_warnings(p: dict) -> list[tuple[str, str]]:
    """(code, text) of each warning of a property of a report: W0702 it holds vacuously, W0703 it follows
    from the net's structure (a report written before the codes were kept gets them from the text)."""
    texts = p.get("warnings") or []
    codes = p.get("warning_codes") or [warning_code(w) for w in texts]
    return list(zip(codes, texts))


def render_text(doc: dict) -> str:
    st = doc["statespace"]
    out = [f"Scenario {doc['run']}  ({os.path.relpath(doc['file'])})",
           f"  model       {os.path.relpath(doc['model'])}"]
    if doc["values"]:
        out.append("  values      " + ", ".join(f"{k}={v}" for k, v in doc["values"].items()))
    status = "complete" if st["complete"] else f"partial ({st['stop_reason']}, {st['unexpanded']:,} unexpanded)"
    secs = f", {st['seconds']:.2f} s" if "seconds" in st else ""
    reduced = _reduced_words(st)
    reduced += _sweep_text(st)
    out.append(f"  state space {st['states']:,} states, {st['arcs']:,} arcs{reduced}, {status}{secs}")
    out.append(f"  verdict     {doc['verdict']}")
    out.append("")
    for p in doc["properties"]:
        out.append(f"  {label(p):<9} {p['name']}  [{p['kind']}]")
        if p["message"]:
            out.append(f"            {p['message']}")
        for code, w in property_warnings(p):
            out.append(f"            warning[{code}]: {w}")
        if p["verdict"] != "holds" or "trace" in p:
            out.append(f"            at {_where(doc, p)}")
        if "trace" in p:
            what = "witness" if p["verdict"] == "holds" else "counterexample"
            n = len(p["trace"]["steps"])
            lasso = f", then a cycle of {len(p['trace']['cycle'])}" if p["trace"]["cycle"] else ""
            out.append(f"            {what}: {n} step{'s' if n != 1 else ''}{lasso}")
            out.extend(render_steps(p["trace"], indent="              "))
    return "\n".join(out) + "\n"


def _sweep_text(st: dict) -> str:
    """How a sweep-line search counted (its states are not kept: no traces)."""
    if st.get("method") != "sweep-line":
        return ""
    exact = "exact counts" if st["exact"] else "upper bounds: some states were explored more than once"
    return f" (sweep-line, {exact}; at most {st['peak_states']:,} states held at once)"


def label(p: dict) -> str:
    """A property's verdict as printed: 'violated (expected)' when its scenario expects the violation,
    'holds (expected violated)' when it expects one that did not happen."""
    if p.get("expect", "holds") == "holds":
        return p["verdict"]
    return f"{p['verdict']} (expected)" if p["verdict"] == p["expect"] else f"{p['verdict']} (expected {p['expect']})"


def render_markdown(doc: dict) -> str:
    st = doc["statespace"]
    out = [f"# Scenario `{doc['run']}`", "",
           f"- model: `{os.path.relpath(doc['model'])}`",
           f"- state space: {st['states']:,} states, {st['arcs']:,} arcs"
           + _reduced_words(st) + _sweep_text(st) + ", "
           + ("complete" if st["complete"] else f"**partial** ({st['stop_reason']})"),
           f"- verdict: **{doc['verdict']}**", "",
           "| property | kind | verdict | detail |", "|---|---|---|---|"]
    for p in doc["properties"]:
        msg = p["message"].replace("|", "\\|")
        out.append(f"| {p['name']} | {p['kind']} | {label(p)} | {msg} |")
    warned = [(p, code, w) for p in doc["properties"] for code, w in property_warnings(p)]
    if warned:
        out += ["", "## Warnings", ""]
        out += [f"- {p['name']} (`{_where(doc, p)}`): warning[{code}]: {w}" for p, code, w in warned]
    for p in doc["properties"]:
        if "trace" in p and p["verdict"] != "holds":
            out += ["", f"## {p['name']}: counterexample", "", "```"]
            out += render_steps(p["trace"], indent="")
            out.append("```")
    return "\n".join(out) + "\n"


def _portable(path: str) -> str:
    """A model path as reports keep it: relative to the working directory (the same in every clone of a
    repository), absolute only where no relative path exists."""
    try:
        return os.path.relpath(path)
    except ValueError:  # another drive
        return path
