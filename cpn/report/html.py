"""The report as one self-contained HTML page: tables, the net, the state space, charts of traces.

Imports the report's model and drawings (`netdraw`, `graphdraw`, `msc`, `plot`). Everything is inline
(CSS, SVG, a small script that only adds conveniences): the page opens from a file, a CI artifact or a
mail without network access. `report_fragment` is the page's content (with its scoped style): the same
HTML is what Jupyter shows for a Report or a ReportTrace (`_repr_html_`).

A property gate adds its results with `verdicts=[Verdict(...)]`: the first violated property and its
trace go to the top of the page. `render_index` writes the page listing several runs.
"""

from __future__ import annotations

import os
from collections import Counter
from dataclasses import dataclass
from typing import TYPE_CHECKING

from cpn.engine.protocol import capability
from cpn.report import svg as S
from cpn.report.graphdraw import bfs_levels, draw_state_space, level_sizes, marking_text
from cpn.report.msc import draw_msc
from cpn.report.netdraw import draw_net
from cpn.report.plot import growth_chart
from cpn.report.reduction import reduction_text

if TYPE_CHECKING:  # a renderer of the report model, which shows itself in Jupyter with this page
    from cpn.report.model import Report

MAX_TRACE_CHARTS: int = 8  # dead markings whose trace is drawn (the first ones, by state number)
MAX_TABLE_ROWS: int = 50


@dataclass
class Verdict:
    """One property's result as the page shows it.

    status: 'holds', 'violated' or 'unknown'; detail: the reason or evidence in words; trace: a
    cpn.statespace.Trace of the report's exploration (a counterexample or a witness); cycle_from: for a
    lasso, the 1-based step where the repeated part starts; marked_step: the violating step (default:
    the last step of a violated property's trace; none for a lasso, whose cycle is marked); places: the
    place instances (names) the property reads, listed first, even when empty, in the marking shown after
    its trace; warnings: (code, text) pairs about a property that holds (W0702 vacuously, W0703 by the
    net's structure), shown under the table.
    """

    name: str
    status: str
    detail: str = ""
    trace: object = None
    cycle_from: int | None = None
    marked_step: int | None = None
    places: tuple = ()
    warnings: tuple = ()

    def resolved(self, engine) -> Verdict:
        """This verdict with `trace` as a Trace: evidence given as a path of states (`path`, `arcs`,
        and for a lasso `cycle`, `cycle_arcs`) is turned into steps, the cycle's start noted."""
        status = str(getattr(self.status, "value", self.status))  # a Status enum or its text
        if self.trace is None or hasattr(self.trace, "steps"):
            return Verdict(self.name, status, self.detail, self.trace, self.cycle_from, self.marked_step,
                           tuple(self.places), tuple(self.warnings))
        trace, cycle_from = evidence_trace(self.trace, engine)
        return Verdict(self.name, status, self.detail, trace,
                       self.cycle_from if self.cycle_from is not None else cycle_from, self.marked_step,
                       tuple(self.places), tuple(self.warnings))


def evidence_trace(evidence, engine=None) -> tuple:
    """(Trace, cycle_from) for a path of states from the initial state and an optional cycle.

    `evidence.path` are state ids starting at 0, `evidence.arcs[i]` the binding element of the step
    path[i] -> path[i+1]; a lasso's `cycle` lists the states its steps reach (`cycle_arcs` their binding
    elements) from path[-1] back to it. cycle_from is the 1-based step where the cycle starts, or None.
    """
    from cpn.statespace import Step, Trace

    path, arcs = list(evidence.path), list(evidence.arcs)
    pairs = list(zip(arcs, path, path[1:]))
    cycle = list(getattr(evidence, "cycle", ()) or ())
    cycle_from = None
    if cycle:
        cycle_from = len(pairs) + 1
        prev = path[-1]
        for be, s in zip(getattr(evidence, "cycle_arcs", ()), cycle):
            pairs.append((be, prev, s))
            prev = s
    fmt = engine.format_binding_element if engine is not None else str
    steps = tuple(Step(be, a, b, fmt(be)) for be, a, b in pairs)
    return Trace(pairs[-1][2] if pairs else (path[-1] if path else 0), steps), cycle_from


@dataclass
class IndexEntry:
    """One run on an index page: its title, the page it links to and its figures."""

    title: str
    href: str
    status: str  # 'holds' | 'violated' | 'unknown' | 'error' (the worst verdict of the run)
    states: int | None = None
    seconds: float | None = None
    detail: str = ""


class ReportTrace:
    """A trace of a report's exploration that displays itself as a chart in Jupyter."""

    def __init__(self, trace, report: Report, caption: str = "", marked_step: int | None = None,
                 cycle_from: int | None = None):
        self.trace, self.report = trace, report
        self.caption, self.marked_step, self.cycle_from = caption, marked_step, cycle_from

    def __len__(self) -> int:
        return len(self.trace)

    def svg(self, standalone: bool = False) -> str:
        """The message sequence chart alone (standalone: a complete .svg file)."""
        return draw_msc(self.trace, self.report.exploration, self.marked_step, self.caption, self.cycle_from,
                        standalone=standalone, prefix="msc-t")

    def _repr_html_(self) -> str:
        return _scoped(_trace_block(self.trace, self.report, self.caption, self.marked_step, self.cycle_from,
                                    "t", with_caption=True))


def dead_marking_traces(report: Report, limit: int = MAX_TRACE_CHARTS) -> list[ReportTrace]:
    """The shortest trace to each of the first `limit` dead markings, last step marked."""
    from cpn.statespace import shortest_trace

    x = report.exploration
    out = []
    for d in report.dead.states[:limit]:
        t = shortest_trace(x.graph, d, x.engine)
        out.append(ReportTrace(t, report, f"Shortest trace to dead marking {d + 1} ({len(t)} steps)",
                               marked_step=len(t) or None))
    return out


# ----------------------------------------------------------------------------------------------- page

def render_html(report: Report, verdicts: list | None = None, title: str | None = None,
                heading: str | None = None) -> str:
    """The whole page for one run (explore, or one scenario of a property check).

    title: the browser's title; heading: the page's headline (default: the model's file name).
    """
    title = title or f"{os.path.basename(report.model)} — cpn-verify report"
    return _page(title, report_fragment(report, verdicts, heading))


def report_fragment(report: Report, verdicts: list | None = None, heading: str | None = None) -> str:
    """The page's content with its scoped style and script (what Jupyter shows)."""
    return _scoped(_content(report, list(verdicts or []), heading))


def render_index(entries: list[IndexEntry], title: str = "cpn-verify check") -> str:
    """A page linking to one page per run, worst results first."""
    order = {"error": 0, "violated": 1, "unknown": 2, "holds": 3}
    timed = any(e.seconds is not None for e in entries)  # none: `check --no-timings`, no column
    rows = []
    for e in sorted(entries, key=lambda e: (order.get(e.status, 3), e.title)):
        secs = f'<td class="num">{"" if e.seconds is None else f"{e.seconds:.2f}"}</td>' if timed else ""
        rows.append(f'<tr><td><a href="{S.esc(e.href)}">{S.esc(e.title)}</a></td><td>{_pill(e.status)}</td>'
                    f'<td class="num">{"" if e.states is None else f"{e.states:,}"}</td>{secs}'
                    f'<td>{S.esc(e.detail)}</td></tr>')
    counts = Counter(e.status for e in entries)
    summary = ", ".join(f"{counts[k]} {k}" for k in ("error", "violated", "unknown", "holds") if counts[k])
    body = (f'<header><h1>{S.esc(title)}</h1><p class="sub">{len(entries)} runs: {S.esc(summary)}</p></header>'
            '<section><div class="tablewrap"><table><thead><tr><th>Run</th><th>Result</th><th>States</th>'
            f'{"<th>Seconds</th>" if timed else ""}<th>Detail</th></tr></thead><tbody>{"".join(rows)}</tbody></table>'
            '</div></section>')
    return _page(title, _scoped(body))


def write_pages(folder: str, runs: list[tuple[str, Report, list]], index_title: str = "cpn-verify check") -> str:
    """One page per run plus `index.html` linking them, in `folder`; returns the index's path.

    runs: (title, report, verdicts) per run (a scenario, or one row of its parameter table); the page of a
    run is named after its title. A run's result on the index is its worst verdict.
    """
    entries = []
    used: set = set()
    for title, report, verdicts in runs:
        stem = "".join(c if c.isalnum() or c in "-_." else "-" for c in title).strip("-") or "run"
        name, k = stem, 1
        while name in used or name == "index":
            k += 1
            name = f"{stem}-{k}"
        used.add(name)
        entries.append(write_run_page(folder, name, title, report, verdicts))
    return write_index(folder, entries, index_title)


def write_run_page(folder: str, stem: str, title: str, report: Report, verdicts: list,
                   status: str | None = None) -> IndexEntry:
    """The page of one run, `folder/stem.html`; returns its entry for the index.

    status: the run's result on the index (default: its worst verdict; unknown for a partial search whose
    properties all hold).
    """
    os.makedirs(folder, exist_ok=True)
    name = f"{stem}.html"
    with open(os.path.join(folder, name), "w", encoding="utf-8") as fh:
        fh.write(render_html(report, verdicts, title=f"{title} — cpn-verify", heading=title))
    texts = [str(getattr(v.status, "value", v.status)) for v in verdicts or ()]
    if status is None:
        status = next((s for s in ("error", "violated", "unknown") if s in texts), "holds")
        if not report.exploration.complete and status == "holds":
            status = "unknown"
    failed = [v.name for v, t in zip(verdicts or (), texts) if t == "violated"]
    return IndexEntry(title, name, status, report.exploration.n_states, report.seconds if report.timings else None,
                      ("violated: " + ", ".join(failed)) if failed else "")


def write_index(folder: str, entries: list[IndexEntry], title: str = "cpn-verify check") -> str:
    """`folder/index.html` listing the runs' pages; returns its path."""
    os.makedirs(folder, exist_ok=True)
    path = os.path.join(folder, "index.html")
    with open(path, "w", encoding="utf-8") as fh:
        fh.write(render_index(entries, title))
    return path


def write_html(report: Report, path: str, verdicts: list | None = None) -> None:
    page = render_html(report, verdicts)
    with open(path, "w", encoding="utf-8") as fh:
        fh.write(page)


def _page(title: str, fragment: str) -> str:
    return ('<!DOCTYPE html>\n<html lang="en"><head><meta charset="utf-8">'
            '<meta name="viewport" content="width=device-width, initial-scale=1">'
            f'<title>{S.esc(title)}</title></head><body class="cpnv-page">{fragment}</body></html>\n')


def _scoped(inner: str) -> str:
    return f'<div class="cpnv"><style>{CSS}</style>{inner}<script>{SCRIPT}</script></div>'


def _pill(status: str) -> str:
    cls = {"holds": "ok", "violated": "bad", "error": "bad", "unknown": "warn", "full": "ok",
           "partial": "warn"}.get(status, "")
    return f'<span class="pill {cls}">{S.esc(status)}</span>'


def _section(ident: str, heading: str, inner: str, note: str = "") -> str:
    n = f'<p class="note">{note}</p>' if note else ""
    return f'<section id="{ident}"><h2>{S.esc(heading)}</h2>{n}{inner}</section>'


def _figure(svg: str, caption: str = "") -> str:
    cap = f"<figcaption>{caption}</figcaption>" if caption else ""
    return ('<figure class="drawing-box"><div class="tools"><button type="button" class="fit" '
            'title="fit the drawing to the width of the page">fit width</button></div>'
            f'<div class="scroll">{svg}</div>{cap}</figure>')


def _table(head: list[str], rows: list[list[str]], num_cols=()) -> str:
    th = "".join(f"<th>{S.esc(h)}</th>" for h in head)
    body = []
    for r in rows:
        body.append("<tr>" + "".join(f'<td{" class=num" if i in num_cols else ""}>{c}</td>'
                                     for i, c in enumerate(r)) + "</tr>")
    return f'<div class="tablewrap"><table><thead><tr>{th}</tr></thead><tbody>{"".join(body)}</tbody></table></div>'


def _content(r: Report, verdicts: list, heading: str | None = None) -> str:
    x = r.exploration
    engine = x.engine
    verdicts = [v.resolved(engine) for v in verdicts]
    status = "full" if x.complete else "partial"
    parts = [_header(r, status, heading)]
    nav = []
    failed = [v for v in verdicts if v.status == "violated"]
    if verdicts:
        parts.append(_verdicts(r, verdicts, failed))
        nav.append(("verdicts", "Verdicts"))
    levels = bfs_levels(x.graph)
    if r.reduced or r.symmetric:
        # a graph reduced by stubborn sets keeps the dead markings only: no figure of the rest is shown;
        # a quotient by symmetry shows its sentence (what it preserves, the full counts) and the dead markings
        parts.append(_section("statistics", "Statistics", f"<p>{S.esc(reduction_text(x))}.</p>"))
        nav.append(("statistics", "Statistics"))
        parts.append(_dead_markings(r, dead_marking_traces(r), levels))
        nav.append(("dead", "Dead markings"))
        links = "".join(f'<a href="#{i}">{S.esc(t)}</a>' for i, t in nav)
        parts.insert(1, f'<nav aria-label="sections">{links}</nav>')
        return "".join(parts)
    occ = _occurrences(r)
    parts.append(_statistics(r))
    nav.append(("statistics", "Statistics"))
    dead_traces = dead_marking_traces(r)
    parts.append(_dead_markings(r, dead_traces, levels))
    nav.append(("dead", "Dead markings"))
    parts.append(_net(r, occ))
    nav.append(("net", "Net"))
    parts.append(_state_space(r, levels))
    nav.append(("statespace", "State space"))
    parts.append(_bounds(r))
    nav.append(("bounds", "Bounds"))
    parts.append(_transitions(r, engine, occ))
    nav.append(("transitions", "Transitions"))
    links = "".join(f'<a href="#{i}">{S.esc(t)}</a>' for i, t in nav)
    parts.insert(1, f'<nav aria-label="sections">{links}</nav>')
    return "".join(parts)


def _header(r: Report, status: str, heading: str | None = None) -> str:
    x = r.exploration
    dead = r.dead.count
    facts = [f"{x.n_states:,} states", f"{x.n_arcs:,} arcs"] + (
        ["reduced by stubborn sets"] if r.reduced else ["quotient by symmetry"] if r.symmetric
        else [f"{r.scc.nodes:,} SCCs"]) + [
             f"{dead:,} dead marking{'s' if dead != 1 else ''}"] + ([f"{r.seconds:.2f} s"] if r.timings else [])
    if heading:
        facts.insert(0, os.path.basename(r.model))
    opts = ", ".join(f"{k}={v}" for k, v in sorted((r.options.get("set") or {}).items()))
    tc = " · time condensation" if r.options.get("time_condensation") else ""
    return (f'<header><h1>{S.esc(heading or os.path.basename(r.model))} {_pill(status)}</h1>'
            f'<p class="sub">{S.esc(" · ".join(facts))}{S.esc(tc)}{" · " + S.esc(opts) if opts else ""}</p>'
            f'<p class="path">{S.esc(r.model)} · generated {S.esc(r.generated) + " " if r.timings else ""}'
            'by cpn-verify</p></header>')


def _verdicts(r: Report, verdicts: list, failed: list) -> str:
    rows = [[S.esc(v.name), _pill(v.status), S.esc(v.detail),
             str(len(v.trace)) if v.trace is not None else ""] for v in verdicts]
    inner = _table(["Property", "Verdict", "Detail", "Trace steps"], rows, num_cols=(3,))
    warned = [(v, code, text) for v in verdicts for code, text in v.warnings]
    if warned:
        inner += ('<p class="warnings"><strong>Warnings</strong></p><ul class="warnings">'
                  + "".join(f"<li><code>warning[{S.esc(code)}]</code> {S.esc(v.name)}: {S.esc(text)}</li>"
                            for v, code, text in warned) + "</ul>")
    if failed:
        v = failed[0]
        top = (f'<p class="headline">First violated property: <strong>{S.esc(v.name)}</strong>'
               + (f" — {S.esc(v.detail)}" if v.detail else "") + "</p>")
        if v.trace is not None:
            marked = v.marked_step if v.marked_step is not None else (
                None if v.cycle_from is not None else len(v.trace) or None)  # a lasso: the cycle is marked
            top += _trace_block(v.trace, r, f"Counterexample of {v.name} ({len(v.trace)} steps)", marked,
                                v.cycle_from, "v0", end=v)
        inner = top + inner
    for k, v in enumerate(verdicts):
        if v.trace is not None and v is not (failed[0] if failed else None):
            marked = v.marked_step if v.marked_step is not None else (
                len(v.trace) if v.status == "violated" and v.cycle_from is None else None)
            what = "counterexample" if v.status == "violated" else "trace"
            inner += _trace_block(v.trace, r, f"{v.name}: {what} ({len(v.trace)} steps)", marked, v.cycle_from,
                                  f"v{k + 1}", end=v)
    return _section("verdicts", "Verdicts", inner)


def _statistics(r: Report) -> str:
    x = r.exploration
    status = "Full" if x.complete else f"Partial: stopped because {x.stop_reason.describe(x.options)}"
    ss = [["Nodes", f"{x.n_states:,}"], ["Arcs", f"{x.n_arcs:,}"], ["Seconds", f"{x.seconds:.3f}"],
          ["Status", S.esc(status)], ["BFS depth", f"{x.levels:,}"],
          ["Peak memory", f"{x.peak_memory_mb:,.0f} MiB"]]
    if not r.timings:
        ss = [row for row in ss if row[0] not in ("Seconds", "Peak memory")]
    if not x.complete:
        ss.append(["Unexpanded nodes", f"{x.unexpanded:,}"])
    if x.untimed_states is not None:
        ss.append(["Markings modulo time", f"{x.untimed_states:,}"])
    scc = [["Nodes", f"{r.scc.nodes:,}"], ["Arcs", f"{r.scc.arcs:,}"], ["Terminal", f"{r.scc.terminal:,}"],
           ["With a cycle", f"{r.scc.nontrivial:,}"]] + ([["Seconds", f"{r.scc.seconds:.3f}"]] if r.timings else [])
    home = ("unknown (partial)" if r.home.states is None else
            ("initial marking is a home marking" if r.home.initial_is_home else "initial marking is not a home "
             "marking") if r.timed else (f"{len(r.home.states):,} home markings"))
    other = [["Home markings", S.esc(home)], ["Dead markings", f"{r.dead.count:,}"],
             ["Dead transition instances", f"{len(r.dead_transitions):,}"],
             ["Live transition instances", "unknown (partial)" if r.live_transitions is None
              else f"{len(r.live_transitions):,}"],
             ["Tokens in one marking (max)", f"{r.bounds.max_tokens_per_marking:,}"]]
    cards = "".join(f'<div class="card"><h3>{h}</h3>{_kv(rows)}</div>'
                    for h, rows in (("State space", ss), ("SCC graph", scc), ("Properties", other)))
    notes = "".join(f'<p class="note warn">{S.esc(n)}</p>' for n in r.notes)
    return _section("statistics", "Statistics", f'<div class="cards">{cards}</div>{notes}')


def _kv(rows) -> str:
    return "<table class=kv>" + "".join(f"<tr><th>{k}</th><td>{v}</td></tr>" for k, v in rows) + "</table>"


def _dead_markings(r: Report, traces: list[ReportTrace], level: list[int]) -> str:
    x = r.exploration
    g, engine = x.graph, x.engine
    if not r.dead.states:
        text = "None." if x.complete else "None in the explored part (the state space is partial)."
        return _section("dead", "Dead markings", f"<p>{text}</p>")
    rows = []
    charted = {t.trace.target for t in traces}
    for d in r.dead.states[:MAX_TABLE_ROWS]:
        link = f'<a href="#trace-d{d + 1}">chart</a>' if d in charted else ""
        rows.append([f"{d + 1}", f"{level[d]}",
                     _marking_cell(marking_text(engine, g.states[d])), link])
    more = (f'<p class="note">{r.dead.count - MAX_TABLE_ROWS:,} more dead markings are not listed.</p>'
            if r.dead.count > MAX_TABLE_ROWS else "")
    inner = _table(["State", "Steps from initial", "Marking", "Trace"], rows, num_cols=(0, 1)) + more
    for t in traces:
        inner += _trace_block(t.trace, r, t.caption, t.marked_step, None, f"d{t.trace.target + 1}")
    if r.dead.count > len(traces):
        inner += (f'<p class="note">Charts are drawn for the first {len(traces)} dead markings of '
                  f'{r.dead.count:,}.</p>')
    note = ("Each chart is the shortest occurrence sequence from the initial marking; the last step, which "
            "reaches the dead marking, is marked.")
    return _section("dead", "Dead markings", inner, note)


def _marking_cell(text: str, shown: int = 6) -> str:
    """A marking in a table cell: the first places, the rest folded away when there are many."""
    lines = text.split("\n")
    head = f'<span class="mono">{S.esc(chr(10).join(lines[:shown]))}</span>'
    if len(lines) <= shown + 2:
        return f'<span class="mono">{S.esc(text)}</span>'
    rest = f'<span class="mono">{S.esc(chr(10).join(lines[shown:]))}</span>'
    return f"{head}<details><summary>{len(lines) - shown} more places</summary>{rest}</details>"


def _trace_block(trace, r: Report, caption: str, marked: int | None, cycle_from: int | None, ident: str,
                 with_caption: bool = False, end: Verdict | None = None) -> str:
    """A trace's chart and its steps; with `end` (the verdict whose trace it is), then the marking the
    trace leads to."""
    after = _end_marking(trace, r, end) if end is not None else ""
    if not len(trace):
        return (f'<div class="trace" id="trace-{ident}"><h3>{S.esc(caption)}</h3>'
                f"<p>The initial marking itself: no step is needed.</p>{after}</div>")
    svg = draw_msc(trace, r.exploration, marked, caption if with_caption else "", cycle_from,
                   prefix=f"msc-{ident}")
    steps = "".join(f"<li><span class=mono>{S.esc(s.text)}</span>"
                    + (" <em>(the cycle starts here)</em>" if k == cycle_from else "") + "</li>"
                    for k, s in enumerate(trace.steps, 1))
    head = "" if with_caption else f"<h3>{S.esc(caption)}</h3>"
    return (f'<div class="trace" id="trace-{ident}">{head}{_figure(svg)}{after}'
            f'<details><summary>Steps as binding elements</summary><ol>{steps}</ol></details></div>')


MARKING_ROWS: int = 8  # places of the marking after a trace shown before the rest is folded away


def _end_marking(trace, r: Report, v: Verdict) -> str:
    """The marking a verdict's trace leads to, as a table: the places the property reads first (marked,
    even when empty), then the other marked places; model time and absolute time stamps, the trace
    being fired again without time condensation when the search used it."""
    from cpn.report.verdicts import _replay_absolute, end_marking

    x = r.exploration
    engine, state = x.engine, x.graph.states[trace.target]
    if capability(engine, "time_condensation", False) and len(trace):
        replayed = _replay_absolute(engine, [s.be for s in trace.steps])
        if replayed is not None:
            engine, state = replayed[0], replayed[1][-1]
    names = [p.name for p in engine.places]
    reads = tuple(names.index(p) for p in v.places if p in names)
    m = end_marking(engine, state, trace.target, reads)
    what = {"violated": "Violating marking", "error": "The marking where the property failed"}.get(
        str(v.status), "Marking reached")
    at = f" at time {m['time']}" if "time" in m else ""
    first = [p for p in m["reads"] if p in m["places"]]
    order = first + [p for p in m["places"] if p not in first]
    if not order:
        return f'<div class="end-marking"><h4>{S.esc(what)} {m["state"]}{S.esc(at)}</h4><p>Every place is empty.</p></div>'

    def row(p):
        tag = ' <span class="pill">read by the property</span>' if p in first else ""
        return (f'<tr{" class=read" if p in first else ""}><td>{S.esc(p)}{tag}</td>'
                f'<td><span class="mono">{S.esc(m["places"][p])}</span></td></tr>')

    head = "".join(row(p) for p in order[:MARKING_ROWS])
    rest = "".join(row(p) for p in order[MARKING_ROWS:])
    table = f"<table><tbody>{head}</tbody></table>"
    if rest:
        table += (f"<details><summary>{len(order) - MARKING_ROWS} more marked places</summary>"
                  f"<table><tbody>{rest}</tbody></table></details>")
    return f'<div class="end-marking"><h4>{S.esc(what)} {m["state"]}{S.esc(at)}</h4>{table}</div>'



def _net(r: Report, occ: dict) -> str:
    engine = r.engine
    bounds = {b.place: (b.upper, b.lower, b.upper_text) for b in r.bounds.places}
    svg = draw_net(engine.net, bounds, r.dead_transitions, occ)
    note = ("Each module instance is a box inside the instance that contains it. The blue badge on a place "
            "is its integer bound (lower..upper) over the state space; transition instances that never occur "
            "are red and dashed. Hover for details.")
    return _section("net", "The net", _figure(svg), note)


def _occurrences(r: Report) -> dict:
    """Transition instance name -> number of arcs of the state space it labels."""
    engine = r.engine
    names = [t.name for t in engine.transitions]
    counts: Counter = Counter()
    for be, n in Counter(r.exploration.graph.bes).items():
        counts[names[engine.binding_element(be).transition]] += n
    return counts


def _state_space(r: Report, levels: list[int]) -> str:
    x = r.exploration
    kind, drawing = draw_state_space(r)
    if kind == "full":
        note = ("The full state space, one row per BFS level. The initial marking has a green ring, dead markings "
                "are red; hover a node for its marking, an arc for its binding elements.")
        inner = _figure(drawing)
    elif kind == "scc":
        note = (f"The state space has {x.n_states:,} states: drawn is its SCC graph (a node per strongly connected "
                "component, labelled with its number of states). The component of the initial marking has a "
                "green ring; red components contain a dead marking.")
        inner = _figure(drawing)
    else:
        note, inner = drawing, ""
    inner += _figure(growth_chart(level_sizes(x.graph, levels)))
    return _section("statespace", "The state space", inner, note)


def _bounds(r: Report) -> str:
    rows = [[S.esc(b.place), str(b.upper), str(b.lower), f'<span class="mono">{S.esc(b.upper_text)}</span>',
             f'<span class="mono">{S.esc(b.lower_text)}</span>'] for b in r.bounds.places]
    note = "" if r.exploration.complete else "Bounds of the explored part of a partial state space."
    return _section("bounds", "Bounds", _table(["Place instance", "Upper", "Lower", "Upper multi-set",
                                                "Lower multi-set"], rows, num_cols=(1, 2)), note)


def _transitions(r: Report, engine, occ: dict) -> str:
    dead = set(r.dead_transitions)
    live = set(r.live_transitions or ())
    rows = []
    for t in engine.transitions:
        if t.name in dead:
            st = '<span class="pill bad">dead</span>'
        elif t.name in live:
            st = '<span class="pill ok">live</span>'
        else:
            st = "unknown" if r.live_transitions is None else "neither"
        fair = "" if not r.fairness else S.esc(r.fairness[t.name].value) if t.name in r.fairness else ""
        rows.append([S.esc(t.name), st, fair, f"{occ.get(t.name, 0):,}"])
    return _section("transitions", "Transition instances",
                    _table(["Transition instance", "Liveness", "Fairness", "Arcs"], rows, num_cols=(3,)))


CSS = """
.cpnv{--ink:#1f2933;--muted:#616e7c;--line:#d5dbe1;--accent:#1d5fa8;--ok:#1d7a3c;--bad:#c0262d;--warn:#b45309;
 color:var(--ink);font:15px/1.5 system-ui,-apple-system,'Segoe UI',Roboto,'DejaVu Sans',Arial,sans-serif;
 max-width:1320px;margin:0 auto;padding:16px 20px 40px;box-sizing:border-box}
body.cpnv-page{margin:0;background:#fff}
.cpnv *{box-sizing:border-box}
.cpnv h1{font-size:24px;margin:4px 0 2px;overflow-wrap:anywhere}
.cpnv h2{font-size:19px;margin:28px 0 8px;padding-bottom:4px;border-bottom:1px solid var(--line)}
.cpnv h3{font-size:15px;margin:14px 0 6px}
.cpnv .sub{margin:0;font-size:16px}
.cpnv .path{margin:2px 0 0;color:var(--muted);font-size:13px;overflow-wrap:anywhere}
.cpnv nav{position:sticky;top:0;z-index:2;background:#fff;border-bottom:1px solid var(--line);padding:6px 0;
 margin:10px 0 0;display:flex;flex-wrap:wrap;gap:4px 14px;font-size:14px}
.cpnv a{color:var(--accent)}
.cpnv .pill{display:inline-block;font-size:12px;font-weight:600;padding:1px 9px;border-radius:10px;
 vertical-align:middle;background:#e4e7eb;color:var(--ink)}
.cpnv .pill.ok{background:#dcf2e3;color:var(--ok)} .cpnv .pill.bad{background:#fde8e8;color:var(--bad)}
.cpnv .pill.warn{background:#fdf0dc;color:var(--warn)}
.cpnv .cards{display:grid;grid-template-columns:repeat(auto-fit,minmax(260px,1fr));gap:12px}
.cpnv .card{border:1px solid var(--line);border-radius:8px;padding:8px 12px}
.cpnv .card h3{margin:2px 0 4px}
.cpnv table{border-collapse:collapse;font-size:14px}
.cpnv .tablewrap{overflow-x:auto;max-width:100%}
.cpnv .tablewrap table{min-width:50%}
.cpnv th,.cpnv td{text-align:left;padding:4px 10px;border-bottom:1px solid var(--line);vertical-align:top}
.cpnv thead th{background:#f5f7fa;font-weight:600}
.cpnv td.num{text-align:right;font-variant-numeric:tabular-nums}
.cpnv table.kv th{font-weight:normal;color:var(--muted);padding-left:0}
.cpnv .mono{font-family:ui-monospace,'DejaVu Sans Mono',Menlo,Consolas,monospace;font-size:13px;
 white-space:pre-wrap;overflow-wrap:anywhere}
.cpnv .note{color:var(--muted);margin:4px 0 8px;font-size:14px}
.cpnv .note.warn{color:var(--warn)}
.cpnv figure{margin:8px 0 14px;border:1px solid var(--line);border-radius:8px;position:relative}
.cpnv .scroll{overflow:auto;max-height:85vh;padding:4px}
.cpnv .scroll>svg{display:block;max-width:none}
.cpnv .scroll>svg.statespace,.cpnv .scroll>svg.sccgraph{margin:0 auto}
.cpnv figure.fitted .scroll>svg{width:100%;height:auto}
.cpnv figcaption{font-size:13px;color:var(--muted);padding:4px 8px}
.cpnv .tools{position:absolute;right:6px;top:6px;z-index:1}
.cpnv .tools button{font:12px system-ui,sans-serif;border:1px solid var(--line);background:#fff;border-radius:5px;
 padding:2px 8px;cursor:pointer;color:var(--ink)}
.cpnv .trace{margin-top:10px}
.cpnv .end-marking h4{font-size:14px;margin:6px 0 4px}
.cpnv .end-marking tr.read td{font-weight:600}
.cpnv section,.cpnv .trace{scroll-margin-top:44px}
.cpnv .headline{font-size:16px;margin:6px 0;padding:8px 12px;border-left:4px solid var(--bad);background:#fdf3f3}
.cpnv details{margin:0 0 8px;font-size:14px}
.cpnv svg .node{cursor:default}
.cpnv svg .node:hover circle{stroke-width:3.5}
.cpnv svg .edge.hl{stroke:#1d5fa8;stroke-width:2.5;stroke-opacity:1}
.cpnv svg .place:hover ellipse,.cpnv svg .transition:hover rect{stroke-width:2.6}
@media (max-width:600px){.cpnv{padding:10px 10px 30px;font-size:14px}.cpnv h1{font-size:20px}
 .cpnv th,.cpnv td{padding:3px 6px}}
"""

# Conveniences only (the page is complete without script): "fit width" toggles, and hovering a state
# highlights the arcs that enter and leave it.
SCRIPT = """
(function(){
  var root = document.currentScript && document.currentScript.parentElement;
  if (!root) return;
  root.querySelectorAll('figure.drawing-box').forEach(function(fig){
    var b = fig.querySelector('button.fit');
    if (!b) return;
    b.addEventListener('click', function(){
      var on = fig.classList.toggle('fitted');
      b.textContent = on ? 'actual size' : 'fit width';
    });
  });
  root.querySelectorAll('svg.statespace, svg.sccgraph').forEach(function(svg){
    function mark(node, on){
      var id = node.getAttribute('data-node').slice(1);
      svg.querySelectorAll('.edge').forEach(function(e){
        if (e.getAttribute('data-s') === String(Number(id) - 1) || e.getAttribute('data-t') === String(Number(id) - 1))
          e.classList.toggle('hl', on);
      });
    }
    svg.querySelectorAll('.node').forEach(function(n){
      n.addEventListener('mouseenter', function(){ mark(n, true); });
      n.addEventListener('mouseleave', function(){ mark(n, false); });
    });
  });
})();
"""
