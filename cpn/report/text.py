"""The standard report as text, in CPN Tools' layout (OGNewSaveReport), with our honest additions:
the partial-search status and unexpanded states, time condensation, dead markings modulo time, and the
shortest trace to the first dead marking.

Imports `cpn.report.model` only.
"""

from __future__ import annotations

from cpn.report.model import Report

RULE = "-" * 72
NAME_WIDTH = 24  # CPN Tools wraps place and transition names of 24 or more characters


def _heading(title: str) -> list[str]:
    return ["", "", f" {title}", RULE, ""]


def _node_list(ids: list[int], total: int) -> str:
    """CPN Tools' None / All / [a,b] / N [a,b,c,d,e,...] form, with node numbers counted from 1."""
    if not ids:
        return "None"
    if len(ids) == total:
        return "All"
    shown = ",".join(str(i + 1) for i in ids[:5])
    if len(ids) <= 5:
        return f"[{shown}]"
    return f"{len(ids)} [{shown},...]"


def _name_list(names: list[str], total: int) -> list[str]:
    if not names:
        return ["     None"]
    if len(names) == total:
        return ["     All"]
    return [f"     {n}" for n in names]


def _row(name: str, *cols: str) -> list[str]:
    cells = "".join(c.ljust(11) for c in cols).rstrip()
    if len(name) < NAME_WIDTH:
        return [f"     {name.ljust(NAME_WIDTH)}{cells}"]
    return [f"     {name}", " " * (5 + NAME_WIDTH) + cells]


def _multiset(name: str, text: str) -> list[str]:
    parts = text.split("++")
    lines = [f"     {name}", " " * 25 + (parts[0] + ("++" if len(parts) > 1 else ""))]
    for i, p in enumerate(parts[1:], 1):
        lines.append(p + ("++" if i < len(parts) - 1 else ""))
    return lines


def render_text(r: Report) -> str:
    x = r.exploration
    g = x.graph
    out = ["CPN Tools state space report for:", r.model, f"Report generated: {r.generated}"]
    out.append(f"(cpn-verify; time condensation: {'on' if x.options.time_condensation else 'off'})"
               if r.timed else "(cpn-verify)")

    out += _heading("Statistics")
    status = "Full" if x.complete else (
        f"Partial (stopped because {x.stop_reason.describe(x.options)}; {x.unexpanded} unexpanded nodes)")
    out += ["  State Space", f"     Nodes:  {x.n_states}", f"     Arcs:   {x.n_arcs}",
            f"     Secs:   {int(x.seconds)}", f"     Status: {status}", ""]
    out += ["  Scc Graph", f"     Nodes:  {r.scc.nodes}", f"     Arcs:   {r.scc.arcs}",
            f"     Secs:   {int(r.scc.seconds)}"]
    if x.untimed_states is not None:
        out += ["", f"  Markings modulo time: {x.untimed_states}"]
    for note in r.notes:
        out += ["", f"  Note: {note}"]

    out += _heading("Boundedness Properties")
    if not x.complete:
        out += ["  (bounds of the explored part of a partial state space)", ""]
    out += ["  Best Integer Bounds", " " * (5 + NAME_WIDTH) + "Upper".ljust(11) + "Lower"]
    for b in r.bounds.places:
        out += _row(b.place, str(b.upper), str(b.lower))
    out += ["", "  Best Upper Multi-set Bounds"]
    for b in r.bounds.places:
        out += _multiset(b.place, b.upper_text)
    out += ["", "  Best Lower Multi-set Bounds"]
    for b in r.bounds.places:
        out += _multiset(b.place, b.lower_text)
    out += ["", "  Token maxima",
            f"     Tokens in one marking:          {r.bounds.max_tokens_per_marking}",
            f"     Tokens in one place:            {r.bounds.max_tokens_in_place}",
            f"     Tokens of one colour in a place: {r.bounds.max_of_one_colour_in_place}"]

    out += _heading("Home Properties")
    out += ["  Home Markings"]
    if r.home.states is None:
        out.append("     Unknown (the state space is partial)")
    elif r.timed:
        out.append("     Initial Marking is " + ("a home marking" if r.home.initial_is_home
                                                  else "not a home marking"))
    else:
        out.append("     " + _node_list(r.home.states, g.n_states))

    out += _heading("Liveness Properties")
    out += ["  Dead Markings", "     " + _node_list(r.dead.states, g.n_states)]
    if r.dead.untimed_count is not None:
        out.append(f"     {r.dead.untimed_count} after removing time stamps")
    if r.dead.unexpanded:
        out.append(f"     (plus {r.dead.unexpanded} unexpanded nodes, which are not dead markings)")
    if r.dead_trace is not None:
        out += ["", f"  Shortest trace to dead marking {r.dead_trace.target + 1} "
                f"({len(r.dead_trace)} steps)"]
        for k, step in enumerate(r.dead_trace.steps, 1):
            out.append(f"     {k}. {step.text}")
            for place, before, after in step.changes:
                out.append(f"          {place}: {before} -> {after}")
    ntrans = len(r.engine.transitions)
    out += ["", "  Dead Transition Instances"]
    out += (["     None seen in the explored part"] if not x.complete and not r.dead_transitions
            else _name_list(r.dead_transitions, ntrans))
    out += ["", "  Live Transition Instances"]
    out += (["     Unknown (the state space is partial)"] if r.live_transitions is None
            else _name_list(r.live_transitions, ntrans))

    out += _heading("Fairness Properties")
    if not r.fairness_known:
        out.append("     Unknown (the state space is partial)")
    elif r.fairness is None:
        out.append("     No infinite occurrence sequences.")
    else:
        for name, cls in r.fairness.items():
            out += _row(name, cls.value)
    return "\n".join(out) + "\n"
