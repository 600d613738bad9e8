"""The report of a sweep-line exploration (`cpn.statespace.sweep.SweepExploration`): text in the layout
of CPN Tools' standard report, and JSON with the keys of `explore --json` (docs/statespace.md).

A sweep-line search keeps no graph: the sections that need one (SCC graph, home and liveness properties,
fairness, traces) say so instead of giving a figure. Imports `cpn.statespace` and the standard library.
"""

from __future__ import annotations

import time

from cpn.report.json import multiset_terms
from cpn.statespace.sweep import SweepExploration

#: the sections of the standard report a sweep-line search cannot give, and why
NOT_AVAILABLE: dict = {
    "scc": "the SCC graph needs the whole state space, which the sweep-line method does not keep",
    "home_markings": "home markings need the SCC graph of the whole state space",
    "live_transitions": "liveness needs the SCC graph of the whole state space",
    "dead_transitions": "dead transition instances need every arc of the whole state space",
    "fairness": "fairness needs the SCC graph of the whole state space",
    "traces": "the sweep-line method keeps no path from the initial marking",
}
EXAMPLES: int = 10


def _dead_texts(x: SweepExploration, limit: int | None) -> list[str]:
    engine = x.engine
    out = []
    for s in x.dead[:limit]:
        counts = engine.token_counts(s)
        parts = [f"{p.name}: {engine.format_marking(s, i)}" for i, p in enumerate(engine.places) if counts[i]]
        head = f"@{engine.clock(s)} " if engine.is_timed else ""
        out.append(head + ("; ".join(parts) or "every place is empty"))
    return out


def render_sweep_text(x: SweepExploration, model: str, max_listed: int | None = EXAMPLES) -> str:
    """The standard report's sections that a sweep-line search can fill, and why the others are empty."""
    engine = x.engine
    lines = ["CPN Tools state space report for:", model,
             f"Report generated: {time.strftime('%a %b %d %H:%M:%S %Y')}",
             f"(cpn-verify; sweep-line method, progress measure: {x.measure}; time condensation: "
             f"{'on' if x.options.time_condensation else 'off'})", "", "",
             " Statistics", "-" * 72, "", "  State Space (sweep-line)"]
    exact = "" if x.exact else "  (an upper bound: some states were explored more than once)"
    lines += [f"     Nodes:  {x.states}{exact}", f"     Arcs:   {x.arcs}{exact}", f"     Secs:   {int(x.seconds)}",
              f"     Status: {'Full' if x.complete else 'Partial'}",
              f"     Peak nodes held in memory: {x.peak_states}",
              f"     Peak memory: {x.peak_memory_mb:.0f} MiB (the process)",
              f"     Sweeps: {x.sweeps}; regress arcs: {x.regress_arcs}; persistent nodes: {x.persistent}"]
    if not x.complete:
        lines.append(f"     Stopped because {x.stop_reason.describe(x.options)}; {x.unexpanded:,} nodes not expanded")
    lines += ["", f"  Scc Graph: not available ({NOT_AVAILABLE['scc']})"]
    for note in x.notes:
        lines += ["", f"  Note: {note}"]
    lines += ["", "", " Boundedness Properties", "-" * 72, "", "  Best Integer Bounds",
              f"     {'':<28}{'Upper':<11}Lower"]
    names = [p.name for p in engine.places]
    width = max([28] + [len(n) + 2 for n in names])
    for name, (hi, lo) in zip(names, x.bounds):
        lines.append(f"     {name:<{width}}{hi!s:<11}{lo}")
    for title, bounds in (("Best Upper Multi-set Bounds", x.multiset_upper),
                          ("Best Lower Multi-set Bounds", x.multiset_lower)):
        lines += ["", f"  {title}"]
        for p, (name, ms) in enumerate(zip(names, bounds)):
            lines.append(f"     {name}")
            lines.append(f"                         {engine.format_multiset(p, ms or {}) or 'empty'}")
    lines += ["", "", " Home Properties", "-" * 72, "", f"  Home Markings: not available "
              f"({NOT_AVAILABLE['home_markings']})", "", "", " Liveness Properties", "-" * 72, "",
              f"  Dead Markings: {len(x.dead)}" + ("" if x.complete else " (so far: the search is partial)")]
    shown = _dead_texts(x, max_listed)
    for i, text in enumerate(shown, 1):
        lines.append(f"     {i}. {text}")
    if len(shown) < len(x.dead):
        lines.append(f"     ... {len(x.dead) - len(shown):,} more (the JSON result lists all)")
    if x.dead:
        lines.append(f"     (no trace: {NOT_AVAILABLE['traces']})")
    lines += ["", f"  Dead Transition Instances: not available ({NOT_AVAILABLE['dead_transitions']})",
              "", f"  Live Transition Instances: not available ({NOT_AVAILABLE['live_transitions']})",
              "", "", " Fairness Properties", "-" * 72, "", f"  not available ({NOT_AVAILABLE['fairness']})", ""]
    return "\n".join(lines) + "\n"


def sweep_to_json(x: SweepExploration, model: str, options: dict | None = None) -> dict:
    """The JSON result: the keys of `explore --json`; those a sweep-line search cannot fill are null and
    `not_available` says why."""
    engine = x.engine
    return {
        "schema": 1,
        "model": model,
        "options": options or {},
        "statespace": {
            "states": x.states, "arcs": x.arcs, "complete": x.complete, "stop_reason": x.stop_reason.value,
            "stop_message": x.stop_reason.describe(x.options), "unexpanded": x.unexpanded,
            "seconds": round(x.seconds, 3), "peak_memory_mb": round(x.peak_memory_mb, 1),
            "timed": bool(engine.is_timed), "time_condensation": bool(x.options.time_condensation),
            "time_growth": x.time_growth, **x.statistics(),
        },
        "scc": None,
        "bounds": x.integer_bounds(),
        "multiset_bounds": {p.name: {"upper": engine.format_multiset(i, x.multiset_upper[i] or {}),
                                     "lower": engine.format_multiset(i, x.multiset_lower[i] or {}),
                                     "upper_terms": multiset_terms(p.colour_set, x.multiset_upper[i] or {}),
                                     "lower_terms": multiset_terms(p.colour_set, x.multiset_lower[i] or {})}
                            for i, p in enumerate(engine.places)},
        "dead_markings": {"count": len(x.dead), "markings": _dead_texts(x, None), "trace": None},
        "dead_transitions": None,
        "live_transitions": None,
        "home_markings": None,
        "fairness": None,
        "not_available": dict(NOT_AVAILABLE),
        "notes": list(x.notes),
    }


__all__ = ["NOT_AVAILABLE", "render_sweep_text", "sweep_to_json"]
