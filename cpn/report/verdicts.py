"""The report of one scenario run: its data (`run_report`, the JSON document) and its text and Markdown.

Traces are rendered as steps (time, binding element, binding, tokens removed and added per place
instance). Every renderer receives the JSON document, so reports re-read from disk (`--baseline`)
and fresh ones look the same. Imports `cpn.checks`, `cpn.statespace`, `cpn.values` and layer 0.
"""

from __future__ import annotations

import os

from cpn.checks.verdict import Evidence
from cpn.values.colours import format_multiset

SCHEMA = "cpn-verify/check-report/1"


# ----------------------------------------------------------------------------- traces
def trace_steps(engine, graph, evidence: Evidence | None) -> dict:
    """{"steps": [...], "cycle": [...]}: the evidence as printable, replayable steps."""
    if evidence is None:
        return {"steps": [], "cycle": []}
    steps = [_step(engine, graph, i + 1, u, v, be)
             for i, (u, v, be) in enumerate(zip(evidence.path, evidence.path[1:], evidence.arcs))]
    cycle = []
    prev = evidence.path[-1]
    n = len(steps)
    for i, (v, be) in enumerate(zip(evidence.cycle, evidence.cycle_arcs)):
        cycle.append(_step(engine, graph, n + i + 1, prev, v, be))
        prev = v
    return {"steps": steps, "cycle": cycle, "target": evidence.path[-1] + 1}


def _step(engine, graph, k: int, u: int, v: int, be: int) -> dict:
    su, sv = graph.states[u], graph.states[v]
    mu, mv = engine.marking(su), engine.marking(sv)
    consumed, produced = {}, {}
    for p, place in enumerate(engine.places):
        a, b = mu[p], mv[p]
        if a == b:
            continue
        minus = {x: n - b.get(x, 0) for x, n in a.items() if n > b.get(x, 0)}
        plus = {x: n - a.get(x, 0) for x, n in b.items() if n > a.get(x, 0)}
        timed = bool(getattr(place, "timed", False)) and bool(getattr(engine, "is_timed", False))
        if minus:
            consumed[place.name] = format_multiset(place.colour_set, minus.items(), timed=timed)
        if plus:
            produced[place.name] = format_multiset(place.colour_set, plus.items(), timed=timed)
    b = engine.binding_element(be)
    t = b.transition if isinstance(b.transition, int) else b.transition.index
    net = engine.net
    binding = {n: net.colsets[net.variables[n].data].format(x) if n in net.variables else repr(x)
               for n, x in b.binding.items()}
    return {"step": k, "time": engine.clock(sv), "binding_element": engine.format_binding_element(be),
            "transition": engine.transitions[t].name, "binding": binding, "consumed": consumed,
            "produced": produced, "from": u + 1, "to": v + 1}


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
        doc = {"name": r.spec.name, "kind": r.spec.kind, "line": r.spec.span.line, "column": r.spec.span.col,
               "verdict": v.status.value, "message": v.message}
        if r.spec.description:
            doc["description"] = r.spec.description
        if timings:
            doc["seconds"] = round(r.seconds, 4)
        if v.evidence is not None:
            doc["trace"] = trace_steps(result.engine, g, v.evidence)
        if v.details:
            doc["details"] = v.details
        props.append(doc)
    dead = g.dead_states()
    stats = {"states": x.n_states, "arcs": x.n_arcs, "complete": x.complete, "stop_reason": x.stop_reason.value,
             "unexpanded": x.unexpanded}
    if timings:
        stats["seconds"] = round(result.explore_seconds, 4)
        stats["check_seconds"] = round(result.check_seconds, 4)
    return {
        "schema": SCHEMA,
        "scenario": scen.name,
        "run": result.run.name,
        "file": scen.path,
        "model": scen.model,
        "parameters": result.run.params,
        "values": result.run.values,
        "options": {k: v for k, v in sorted(result.options.items())},
        "verdict": result.status.value,
        "statespace": stats,
        "dead_markings": {"count": len(dead)},
        "bounds": _integer_bounds(result),
        "properties": props,
    }


def _integer_bounds(result) -> dict:
    """Best integer bounds per place instance, from the distinct markings each place takes."""
    engine = result.engine
    states = result.exploration.graph.states
    out = {}
    if not states:
        return out
    columns = hasattr(engine, "place_view")
    for p, place in enumerate(engine.places):
        if columns:
            ids = {s[p]: s for s in states}
            sizes = [sum(engine.place_view(s, p).values()) for s in ids.values()]
        else:
            sizes = [sum(engine.marking(s)[p].values()) for s in states]
        out[place.name] = {"upper": max(sizes), "lower": min(sizes)}
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


def render_text(doc: dict) -> str:
    st = doc["statespace"]
    out = [f"Scenario {doc['run']}  ({os.path.relpath(doc['file'])})",
           f"  model       {os.path.relpath(doc['model'])}"]
    if doc["values"]:
        out.append("  values      " + ", ".join(f"{k}={v}" for k, v in doc["values"].items()))
    status = "complete" if st["complete"] else f"partial ({st['stop_reason']}, {st['unexpanded']:,} unexpanded)"
    secs = f", {st['seconds']:.2f} s" if "seconds" in st else ""
    out.append(f"  state space {st['states']:,} states, {st['arcs']:,} arcs, {status}{secs}")
    out.append(f"  verdict     {doc['verdict']}")
    out.append("")
    for p in doc["properties"]:
        out.append(f"  {p['verdict']:<9} {p['name']}  [{p['kind']}]")
        if p["message"]:
            out.append(f"            {p['message']}")
        if p["verdict"] != "holds" or "trace" in p:
            out.append(f"            at {_where(doc, p)}")
        if "trace" in p:
            label = "witness" if p["verdict"] == "holds" else "counterexample"
            n = len(p["trace"]["steps"])
            lasso = f", then a cycle of {len(p['trace']['cycle'])}" if p["trace"]["cycle"] else ""
            out.append(f"            {label}: {n} step{'s' if n != 1 else ''}{lasso}")
            out.extend(render_steps(p["trace"], indent="              "))
    return "\n".join(out) + "\n"


def render_markdown(doc: dict) -> str:
    st = doc["statespace"]
    out = [f"# Scenario `{doc['run']}`", "",
           f"- model: `{os.path.relpath(doc['model'])}`",
           f"- state space: {st['states']:,} states, {st['arcs']:,} arcs, "
           + ("complete" if st["complete"] else f"**partial** ({st['stop_reason']})"),
           f"- verdict: **{doc['verdict']}**", "",
           "| property | kind | verdict | detail |", "|---|---|---|---|"]
    for p in doc["properties"]:
        msg = p["message"].replace("|", "\\|")
        out.append(f"| {p['name']} | {p['kind']} | {p['verdict']} | {msg} |")
    for p in doc["properties"]:
        if "trace" in p and p["verdict"] != "holds":
            out += ["", f"## {p['name']}: counterexample", "", "```"]
            out += render_steps(p["trace"], indent="")
            out.append("```")
    return "\n".join(out) + "\n"
