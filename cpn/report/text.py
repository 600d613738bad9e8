"""The standard report as text, in CPN Tools' layout (OGNewSaveReport), with our honest additions:
the partial-search status and unexpanded states, time condensation, dead markings modulo time, and each
dead marking (up to a cap) with its marking and a shortest trace.

Long listings are cut (multi-set bounds of a counter place can have a million colours) and say how
many entries were left out; the JSON result keeps everything. Imports `cpn.report.model` and
`cpn.diagnostics` (display widths) only.
"""

from __future__ import annotations

from cpn.diagnostics import display_width, ljust_cells
from cpn.report.model import Report
from cpn.report.reduction import NOT_PRESERVED, SYM_NOT_PRESERVED
from cpn.report.words import noun

RULE = "-" * 72
NAME_WIDTH = 24  # CPN Tools wraps place and transition names of 24 or more characters
COLUMN_WIDTH = 11  # CPN Tools' column width; a wider number widens its column (two spaces at least)

# Default caps of the text listings (`render_text(max_listed=N)` sets them all to N; None: no cap).
MULTISET_TERMS: int = 20  # colours of one multi-set bound
TRACE_STEPS: int = 100  # steps of one trace
NAMES: int = 100  # transition instances in one list


def _heading(title: str) -> list[str]:
    return ["", "", f" {title}", RULE, ""]


def _node_list(ids, total: int) -> str:
    """CPN Tools' None / All / [a,b] / N [a,b,c,d,e,...] form, with node numbers counted from 1."""
    if not len(ids):
        return "None"
    if len(ids) == total:
        return "All"
    shown = ",".join(str(i + 1) for i in ids[:5])
    if len(ids) <= 5:
        return f"[{shown}]"
    return f"{len(ids)} [{shown},...]"


def _cut(n: int, cap: int | None) -> int:
    return n if cap is None else min(n, cap)


def _left_out(n: int, what: str, where: str = "the JSON result lists all") -> str:
    return f"... {n:,} more {what} not shown ({where}; --max-listed N shows more)"


def _name_list(names: list[str], total: int, cap: int | None) -> list[str]:
    if not names:
        return ["     None"]
    if len(names) == total:
        return ["     All"]
    k = _cut(len(names), cap)
    out = [f"     {n}" for n in names[:k]]
    if k < len(names):
        out.append("     " + _left_out(len(names) - k, "transition instances"))
    return out


def _widths(rows: list[tuple]) -> list[int]:
    """One width per column: CPN Tools' 11, or the widest cell plus two spaces (widths in terminal cells: a
    wide (CJK) character takes two)."""
    ncols = max((len(cols) for _name, cols in rows), default=0)
    return [max([COLUMN_WIDTH] + [display_width(cols[i]) + 2 for _n, cols in rows if i < len(cols)])
            for i in range(ncols)]


def _row(name: str, cols: tuple, widths: list[int]) -> list[str]:
    cells = "".join(ljust_cells(c, w) for c, w in zip(cols, widths)).rstrip()
    if display_width(name) < NAME_WIDTH:
        return [f"     {ljust_cells(name, NAME_WIDTH)}{cells}"]
    return [f"     {name}", " " * (5 + NAME_WIDTH) + cells]


def _table(rows: list[tuple], header: tuple | None = None) -> list[str]:
    widths = _widths(rows + ([("", header)] if header else []))
    out = []
    if header:
        out.append(" " * (5 + NAME_WIDTH) + "".join(ljust_cells(h, w) for h, w in zip(header, widths)).rstrip())
    for name, cols in rows:
        out += _row(name, cols, widths)
    return out


MULTISET_INDENT = 25  # the column where CPN Tools starts a multi-set bound, under the place's name


def _multiset(name: str, text: str, cap: int | None) -> list[str]:
    """A multi-set bound under its place, one colour a line, every line starting in the bound's column."""
    parts = text.split("++")
    k = _cut(len(parts), cap)
    pad = " " * MULTISET_INDENT
    lines = [f"     {name}"]
    for i, p in enumerate(parts[:k]):
        lines.append(pad + p + ("++" if i < len(parts) - 1 else ""))
    if k < len(parts):
        lines.append(pad + _left_out(len(parts) - k, noun(len(parts) - k, "colour")))
    return lines


def _short(text: str, cap: int | None) -> str:
    """A marking on one line, cut after `cap` colours."""
    parts = text.split("++")
    if cap is None or len(parts) <= cap:
        return text
    return "++".join(parts[:cap]) + f"++... ({len(parts) - cap:,} more {noun(len(parts) - cap, 'colour')})"


def _dead_markings(r: Report, marking_changes: bool, steps_cap: int | None, terms_cap: int | None) -> list[str]:
    out = []
    for d in r.dead_listed:
        out += ["", f"  Dead marking {d.state + 1}" + ("" if d.time is None else f" (model time {d.time})")]
        out += ([f"          {place}: {_short(text, terms_cap)}" for place, text in d.marking.items()]
                or ["          (every place is empty)"])
        n = len(d.trace)
        out.append(f"  {'A trace (shortest in the reduced graph)' if r.reduced else 'Shortest trace'} to dead marking "
                   f"{d.state + 1} ({n} {noun(n, 'step')})")
        k = _cut(n, steps_cap)
        for i, step in enumerate(d.trace.steps[:k], 1):
            out.append(f"     {i}. {step.text}")
            if marking_changes:
                for place, before, after in step.changes:
                    out.append(f"          {place}: {_short(before, terms_cap)} -> {_short(after, terms_cap)}")
        if k < n:
            out.append("     " + _left_out(n - k, noun(n - k, "step"), "the JSON result has the whole trace"))
    total = r.dead.count
    if total > len(r.dead_listed) and r.dead_listed:
        out += ["", f"  ({len(r.dead_listed)} of {total:,} dead markings listed with a trace; the JSON result "
                "lists the same ones, and the count)"]
    return out


def _full_counts(r: Report) -> list[str]:
    st = r.exploration.reduction_stats or {}
    if st.get("full_states") is None:
        return ["  Full State Space", "     Unknown (the quotient graph is partial)", ""]
    return ["  Full State Space (sums of the orbit sizes)", f"     Nodes:  {st['full_states']}",
            f"     Arcs:   {st['full_arcs']}", ""]


def _reduced(r: Report, marking_changes: bool, steps_cap: int | None, terms_cap: int | None) -> list[str]:
    """The sections of a report on a state space reduced by stubborn sets: the dead markings only."""
    out = []
    for title in ("Boundedness Properties", "Home Properties"):
        out += _heading(title) + [f"     {NOT_PRESERVED}"]
    out += _heading("Liveness Properties")
    out += ["  Dead Markings", "     " + _node_list(r.dead.states, r.exploration.graph.n_states)
            + " (node numbers of the reduced graph)"]
    if r.dead.unexpanded:
        out.append(f"     (plus {r.dead.unexpanded} unexpanded {noun(r.dead.unexpanded, 'node')}, "
                   f"which {noun(r.dead.unexpanded, 'is not a dead marking', 'are not dead markings')})")
    out += _dead_markings(r, marking_changes, steps_cap, terms_cap)
    out += ["", "  Dead Transition Instances", f"     {NOT_PRESERVED}"]
    out += ["", "  Live Transition Instances", f"     {NOT_PRESERVED}"]
    out += _heading("Fairness Properties") + [f"     {NOT_PRESERVED}"]
    return out


def render_text(r: Report, *, marking_changes: bool = True, max_listed: int | None | str = "default") -> str:
    """The report as text. `marking_changes`: show each trace step's marking changes. `max_listed`:
    one cap for every long listing (None: no cap); by default MULTISET_TERMS, TRACE_STEPS and NAMES.

    >>> import cpn
    >>> from cpn.report import build_report
    >>> from cpn.statespace import Explorer
    >>> m = cpn.loads("colset U = unit; place A : U = 1`(); trans t; arc A -> t;")
    >>> render_text(build_report(Explorer(m.engine()).run())).splitlines()[0]
    'CPN Tools state space report for:'
    """
    if max_listed == "default":
        terms_cap, steps_cap, names_cap = MULTISET_TERMS, TRACE_STEPS, NAMES
    else:
        terms_cap = steps_cap = names_cap = max_listed
    out = _statistics(r)
    if r.reduced:
        return "\n".join(out + _reduced(r, marking_changes, steps_cap, terms_cap)) + "\n"
    out += _boundedness(r, terms_cap) + _home(r) + _liveness(r, marking_changes, steps_cap, terms_cap, names_cap)
    out += _fairness(r)
    return "\n".join(out) + "\n"


def _statistics(r: Report) -> list[str]:
    """The report's head and its Statistics section (state space, SCC graph, notes)."""
    x = r.exploration
    out = ["CPN Tools state space report for:", r.model, f"Report generated: {r.generated}"]
    out.append(f"(cpn-verify; time condensation: {'on' if x.options.time_condensation else 'off'})"
               if r.timed else "(cpn-verify)")

    out += _heading("Statistics")
    status = "Full" if x.complete else (
        f"Partial (stopped because {x.stop_reason.describe(x.options)}; {x.unexpanded} unexpanded "
        f"{noun(x.unexpanded, 'node')})")
    if x.restricted:
        status += f"; a restricted state space (branching options: {x.options.restriction()})"
    out += ["  State Space" + (" (reduced by stubborn sets)" if r.reduced else
                               " (quotient by symmetry: one node per orbit)" if r.symmetric else ""),
            f"     Nodes:  {x.n_states}", f"     Arcs:   {x.n_arcs}", f"     Secs:   {int(x.seconds)}",
            f"     Status: {status}", ""]
    if r.symmetric:
        out += _full_counts(r)
    out += (["  Scc Graph", f"     {NOT_PRESERVED}"] if r.reduced else
            ["  Scc Graph", f"     Nodes:  {r.scc.nodes}", f"     Arcs:   {r.scc.arcs}",
             f"     Secs:   {int(r.scc.seconds)}"])
    if x.untimed_states is not None:
        out += ["", f"  Markings modulo time: {x.untimed_states}"]
    for note in r.notes:
        out += ["", f"  Note: {note}"]
    return out


def _boundedness(r: Report, terms_cap) -> list[str]:
    """Boundedness Properties: integer and multi-set bounds, token maxima."""
    out = _heading("Boundedness Properties")
    if not r.exploration.complete:
        out += ["  (bounds of the explored part of a partial state space)", ""]
    out += ["  Best Integer Bounds"]
    out += _table([(b.place, (str(b.upper), str(b.lower))) for b in r.bounds.places], ("Upper", "Lower"))
    if r.symmetric:
        out += ["", "  Best Upper Multi-set Bounds", f"     {SYM_NOT_PRESERVED}",
                "", "  Best Lower Multi-set Bounds", f"     {SYM_NOT_PRESERVED}"]
    else:
        out += ["", "  Best Upper Multi-set Bounds"]
        for b in r.bounds.places:
            out += _multiset(b.place, b.upper_text, terms_cap)
        out += ["", "  Best Lower Multi-set Bounds"]
        for b in r.bounds.places:
            out += _multiset(b.place, b.lower_text, terms_cap)
    out += ["", "  Token maxima",
            f"     Tokens in one marking:          {r.bounds.max_tokens_per_marking}",
            f"     Tokens in one place:            {r.bounds.max_tokens_in_place}",
            f"     Tokens of one colour in a place: {r.bounds.max_of_one_colour_in_place}"]
    return out


def _home(r: Report) -> list[str]:
    """Home Properties."""
    out = _heading("Home Properties") + ["  Home Markings"]
    if r.symmetric:
        out.append(f"     {SYM_NOT_PRESERVED}")
    elif r.home.states is None:
        out.append("     Unknown (the state space is partial)")
    elif r.timed:
        out.append("     Initial Marking is " + ("a home marking" if r.home.initial_is_home
                                                  else "not a home marking"))
    else:
        out.append("     " + _node_list(r.home.states, r.exploration.graph.n_states))
    return out


def _liveness(r: Report, marking_changes: bool, steps_cap, terms_cap, names_cap) -> list[str]:
    """Liveness Properties: dead markings (with their traces), dead and live transition instances."""
    x = r.exploration
    out = _heading("Liveness Properties")
    out += ["  Dead Markings", "     " + _node_list(r.dead.states, x.graph.n_states)]
    if r.symmetric:
        full = r.full_dead_count
        out.append("     (orbits of the quotient graph" + ("" if full is None else
                   f"; {full} dead {noun(full, 'marking')} in the full state space") + ")")
    if r.dead.untimed_count is not None:
        out.append(f"     {r.dead.untimed_count} after removing time stamps")
    if r.dead.unexpanded:
        out.append(f"     (plus {r.dead.unexpanded} unexpanded {noun(r.dead.unexpanded, 'node')}, "
                   f"which {noun(r.dead.unexpanded, 'is not a dead marking', 'are not dead markings')})")
    out += _dead_markings(r, marking_changes, steps_cap, terms_cap)
    ntrans = len(r.engine.transitions)
    out += ["", "  Dead Transition Instances"]
    out += (["     None seen in the explored part"] if not x.complete and not r.dead_transitions
            else _name_list(r.dead_transitions, ntrans, names_cap))
    out += ["", "  Live Transition Instances"]
    out += ([f"     {SYM_NOT_PRESERVED}"] if r.moves_instances else
            ["     Unknown (the state space is partial)"] if r.live_transitions is None
            else _name_list(r.live_transitions, ntrans, names_cap))
    return out


def _fairness(r: Report) -> list[str]:
    """Fairness Properties."""
    out = _heading("Fairness Properties")
    if r.moves_instances:
        out.append(f"     {SYM_NOT_PRESERVED}")
    elif not r.fairness_known:
        out.append("     Unknown (the state space is partial)")
    elif r.fairness is None:
        out.append("     No infinite occurrence sequences.")
    else:
        out += _table([(name, (cls.value,)) for name, cls in r.fairness.items()])
    return out
