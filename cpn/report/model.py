"""The standard report as data: `build_report(exploration, model=...) -> Report`.

Imports `cpn.checks` and `cpn.statespace` only. Renderers (text, json, graphs) read a Report and
return text; they compute nothing.
"""

from __future__ import annotations

import time
from contextlib import contextmanager
from dataclasses import dataclass, field

from cpn.checks import (
    Boundedness,
    DeadMarkings,
    Fairness,
    HomeMarkings,
    SccSummary,
    TransitionIndex,
    boundedness,
    dead_markings,
    dead_transitions,
    fairness,
    home_markings,
    live_transitions,
    scc_summary,
)
from cpn.engine.protocol import capability
from cpn.report.reduction import reduction_text
from cpn.statespace import Exploration, Trace, shortest_trace

# How many dead markings the report lists with their marking and a shortest trace (text and JSON).
DEAD_LISTED: int = 10


@dataclass(frozen=True)
class DeadMarking:
    """One listed dead marking: its state id (0-based), the non-empty places and a shortest trace."""

    state: int
    marking: dict  # place instance name -> marking text, non-empty places only, in the engine's order
    time: int | None  # the model time of the state (timed nets), else None
    trace: Trace


@dataclass
class Report:
    model: str
    options: dict
    exploration: Exploration
    scc: SccSummary
    bounds: Boundedness
    dead: DeadMarkings
    dead_transitions: list  # names; on a partial space: not seen so far
    live_transitions: list | None  # names, None when partial
    home: HomeMarkings
    fairness: dict | None  # name -> Fairness; None = no infinite occurrence sequences
    fairness_known: bool  # False on a partial space (not computed)
    dead_trace: Trace | None  # the trace to the first dead marking (= dead_listed[0].trace)
    seconds: float  # the whole report: generation plus analysis
    analysis_seconds: float
    generated: str = ""
    notes: list = field(default_factory=list)
    #: which search ran and why, where that changes no result and asks nothing of the user
    #: (`Exploration.backend_notes`): not in the text or HTML report; `--verbose` prints them
    backend_notes: list = field(default_factory=list)
    dead_listed: list = field(default_factory=list)  # list[DeadMarking], the first DEAD_LISTED ones
    dead_listed_cap: int | None = DEAD_LISTED
    # seconds of each part of the analysis, in the order computed (see REPORT_PARTS)
    part_seconds: dict = field(default_factory=dict)
    #: False: pages leave out what differs from run to run (seconds, peak memory, the date), as
    #: `check --no-timings` asks, so that a rerun writes them byte for byte
    timings: bool = True

    @property
    def engine(self):
        return self.exploration.engine

    @property
    def timed(self) -> bool:
        return self.engine.is_timed

    def _repr_html_(self) -> str:
        """Jupyter shows the report as the content of its HTML page (cpn.report.html)."""
        from cpn.report.html import report_fragment

        return report_fragment(self)

    @property
    def reduced(self) -> bool:
        """The state space is reduced (stubborn sets): only the dead markings are reported."""
        return self.exploration.reduction is not None and self.exploration.reduction != "symmetry"

    @property
    def symmetric(self) -> bool:
        """The state space is the quotient by a symmetry: some sections are not preserved."""
        return self.exploration.reduction == "symmetry"

    @property
    def moves_instances(self) -> bool:
        """The quotient's group moves module instances: live transitions and fairness are not preserved."""
        sym = self.exploration.graph.symmetry
        return sym is not None and sym.moves_instances

    @property
    def full_dead_count(self) -> int | None:
        """Under symmetry: the number of dead markings of the full state space (sum of the orbit sizes)."""
        sym = self.exploration.graph.symmetry
        if sym is None or not self.exploration.complete:
            return None
        return sum(sym.orbit_size(i, self.exploration.graph) for i in self.dead.states)


# the parts of the analysis, in the order build_report computes them (keys of Report.part_seconds)
REPORT_PARTS: tuple = ("transitions", "scc", "bounds", "dead_markings", "dead_transitions", "live_transitions",
                       "home_markings", "fairness", "trace")


def _choice_draw_notes(engine) -> list[str]:
    """A note naming the draws of the model explored as a choice of every value (cpn-verify's reading of
    `discrete` and `bernoulli`, beyond CPN Tools: docs/semantics.md, Bindings), if it has any."""
    net = capability(engine, "net")
    choices = getattr(getattr(net, "checked", None), "choice_draws", ()) if net is not None else ()
    if not choices:
        return []
    where = ", ".join(f"{call} at {span.file}:{span.line}:{span.col}" for call, span in choices[:3])
    return [f"random draws explored as a choice of every value (cpn-verify's reading; CPN Tools' state space "
            f"tool cannot analyse them): {where}{', ...' if len(choices) > 3 else ''}"]


def build_report(x: Exploration, model: str = "<unsaved net>", options: dict | None = None,
                 trace_to_dead: bool = True, dead_listed: int | None = DEAD_LISTED, progress=None) -> Report:
    """Compute every section of the standard report from an exploration.

    The first `dead_listed` dead markings (all of them for None) are listed with their marking and a
    shortest trace (with `trace_to_dead`; without it, none is listed).

    `progress(part, done, total)`, when given, is called as each part (a name of REPORT_PARTS) starts
    (done 0), as fairness advances (done transition instances out of total) and when a part ends
    (done == total); it must not raise. The checks compute; only the caller displays.

    Examples
    --------
    >>> import cpn
    >>> from cpn.statespace import Explorer
    >>> m = cpn.loads("colset N = int with 0..3; var x : N; place P : N = 1`0;"
    ...               " trans inc [x < 3]; arc P -> inc : x; arc inc -> P : x + 1;")
    >>> r = build_report(Explorer(m.engine()).run(), "counter")
    >>> r.dead.count, r.dead_transitions, r.bounds.places[0].upper_text
    (1, [], '1`0++1`1++1`2++1`3')
    """
    t0 = time.perf_counter()
    clock = _PartClock(t0, progress)
    engine = x.engine
    names = [t.name for t in engine.transitions]
    with clock.part("transitions"):
        tindex = TransitionIndex(engine)
        arc_t = tindex.arc_transitions(x.graph.bes)
    with clock.part("scc"):
        scc = scc_summary(x)
    with clock.part("bounds"):
        bounds = boundedness(x)
    with clock.part("dead_markings"):
        dead = dead_markings(x)
    with clock.part("dead_transitions"):
        dead_t = [names[t] for t in dead_transitions(x, tindex)]
    with clock.part("live_transitions"):
        live = live_transitions(x, scc, arc_t)
        live_names = None if live is None else [names[t] for t in live]
    with clock.part("home_markings"):
        home = home_markings(x, scc)
    with clock.part("fairness"):
        fair = _fairness(x, scc, arc_t, names, progress)
    with clock.part("trace"):
        listed = []
        if trace_to_dead:
            chosen = dead.states if dead_listed is None else dead.states[:dead_listed]
            listed = [dead_marking(x, i) for i in chosen]
        trace = listed[0].trace if listed else None
    analysis = time.perf_counter() - t0
    return Report(
        model=model, options=dict(options or {}), exploration=x, scc=scc, bounds=bounds, dead=dead,
        dead_transitions=dead_t, live_transitions=live_names, home=home, fairness=fair,
        fairness_known=x.complete, dead_trace=trace, seconds=x.seconds + analysis,
        analysis_seconds=analysis, generated=time.strftime("%a %b %d %H:%M:%S %Y"), notes=_notes(x),
        backend_notes=list(getattr(x, "backend_notes", ())),
        dead_listed=listed, dead_listed_cap=dead_listed, part_seconds=clock.seconds,
    )


class _PartClock:
    """Times the parts of the analysis one after the other, and tells `progress` as each starts and ends."""

    def __init__(self, t0: float, progress) -> None:
        self.seconds: dict[str, float] = {}
        self._last = t0
        self._progress = progress

    @contextmanager
    def part(self, name: str):
        if self._progress is not None:
            self._progress(name, 0, 1)
        yield
        now = time.perf_counter()
        self.seconds[name] = now - self._last
        self._last = now
        if self._progress is not None:
            self._progress(name, 1, 1)


def _fairness(x: Exploration, scc, arc_t, names: list, progress) -> dict | None:
    """Each transition instance's fairness class by name; None on a partial space, under a symmetry that
    moves module instances, or without infinite occurrence sequences."""
    moves = x.graph.symmetry is not None and x.graph.symmetry.moves_instances
    if not x.complete or moves:
        return None
    step = None if progress is None else (lambda k, total: progress("fairness", k, total))
    f = fairness(x, scc.decomposition, arc_t, progress=step)
    return None if f is None else {names[t]: cls for t, cls in f.items()}


def _notes(x: Exploration) -> list[str]:
    """The report's notes: the reduction, the search's own notes, random draws and a growth of time only."""
    notes = list(x.notes) + _choice_draw_notes(x.engine)
    if x.reduction is not None:
        notes.insert(0, reduction_text(x))
    if x.time_growth is not None:
        notes.append(
            "the state space grows only because time grows: after "
            f"{x.time_growth['untimed_markings']} distinct markings modulo time, "
            f"{x.time_growth['levels_without_new_untimed_marking']} more BFS levels found nothing but later "
            f"clocks (now {x.time_growth['frontier_min_clock']}). Run again with --time-condensation "
            "(CPN Tools' CreationTime reduction) to get a finite state space."
        )
    return notes


def dead_marking(x: Exploration, state: int) -> DeadMarking:
    """State `state` with its non-empty places and a shortest trace from the initial state."""
    engine = x.engine
    s = x.graph.states[state]
    marking = {}
    for p, place in enumerate(engine.places):
        text = engine.format_marking(s, p)
        if text != "empty":
            marking[place.name] = text
    return DeadMarking(state, marking, engine.clock(s) if engine.is_timed else None,
                       shortest_trace(x.graph, state, engine))


__all__ = ["DEAD_LISTED", "REPORT_PARTS", "DeadMarking", "Fairness", "Report", "build_report", "dead_marking"]
