"""Properties decided by a sweep-line exploration (`cpn.statespace.sweep`), which keeps no graph.

Invariants, reachability, integer bounds of expressions are evaluated on every new state; dead markings,
place bounds and multiset bounds come from the exploration itself. Nothing that needs the whole graph
(dead and live transitions, home markings, livelocks, CTL) can be decided: such a property is `unknown`
with the reason. No trace is kept, so a violation names the marking without a path to it.
Imports `cpn.checks.*`, `cpn.statespace`, `cpn.lang` (types) and layer 0.
"""

from __future__ import annotations

from collections.abc import Callable

from cpn.checks.verdict import Verdict
from cpn.diagnostics import Span
from cpn.errors import ConfigurationError
from cpn.lang import types as T
from cpn.properties.kinds import (
    Bound,
    Check,
    DeadlockFree,
    DeadMarkings,
    Invariant,
    Reachable,
    judge_integer_limit,
    judge_multiset_limit,
)
from cpn.properties.predicates import PredicateError, PropertyLanguage
from cpn.properties.spec import TextOrigin
from cpn.values.multiset import Multiset

#: why a property that needs the whole graph is not decided
NOT_AVAILABLE: str = ("not available under the sweep-line method: it needs the whole state space ({what}), "
                      "which the sweep-line method does not keep; explore without sweep_line to decide it")
NO_TRACE: str = "no trace: the sweep-line method keeps no path to it"
MARKING_TEXT_CAP: int = 600

_NEEDS = {"dead_transitions": "every arc", "live_transitions": "its strongly connected components",
          "home": "its strongly connected components", "no_livelock": "its cycles", "ctl": "every arc"}


def progress_measure(lang: PropertyLanguage, text: str, origin: TextOrigin | None = None,
                     span: Span | None = None) -> Callable:
    """The compiled integer expression `text` as a function state -> int (ModelError if it is not one;
    spans in the scenario file, or in the text itself as the file '--progress' for the command line)."""
    if origin is None:
        origin = TextOrigin("--progress", text, tuple(range(len(text) + 1)))
        span = Span("--progress", 1, 1)
    compiled = lang.compile(text, origin, span, T.INT, "the progress measure")
    fn = compiled.fn

    def measure(state) -> int:
        try:
            return fn(None, state)
        except PredicateError as exc:
            raise ConfigurationError(f"the progress measure '{text}' cannot be evaluated in a reachable marking: "
                                     f"{exc}", hint="Write a measure that is defined in every reachable marking.") \
                from None

    return measure


def marking_text(engine, state, cap: int | None = MARKING_TEXT_CAP) -> str:
    """The non-empty places of a marking, `Page'place 1: 1`x; ...` (cut at `cap` characters)."""
    parts = []
    counts = engine.token_counts(state)
    for p, place in enumerate(engine.places):
        if counts[p]:
            parts.append(f"{place.name}: {engine.format_marking(state, p)}")
    text = "; ".join(parts) or "every place is empty"
    if engine.is_timed:
        text = f"@{engine.clock(state)} {text}"
    if cap is not None and len(text) > cap:
        text = text[:cap] + " ..."
    return text


class SweepMonitor:
    """The sweep-line's stop predicate: evaluates the state properties on every new state."""

    def __init__(self, checks: list[Check], stop_at_first: bool):
        self.checks = [c for c in checks if isinstance(c, (Invariant, Reachable)) and c.on_the_fly]
        self.exprs = [c for c in checks if isinstance(c, Bound) and c.places is None]
        self.stop_at_first = stop_at_first
        self.only_witnesses = all(isinstance(c, Reachable) and c.on_the_fly for c in checks)
        self.state: dict[Check, object] = {}  # the first state that violates (or witnesses) each check
        self.extremes: dict[Check, list] = {}  # Bound over an expression: [hi, hi state, lo, lo state]

    def __call__(self, state) -> bool:
        violated = False
        for c in self.checks:
            if c.error is not None or c in self.state:
                continue
            try:
                v = bool(c.pred.fn(None, state))
            except PredicateError as exc:
                c.error = exc
                violated = True
                continue
            if v != isinstance(c, Invariant):
                self.state[c] = state
                violated = violated or isinstance(c, Invariant)
        for c in self.exprs:
            if c.error is not None:
                continue
            try:
                v = c.fn.fn(None, state)
            except PredicateError as exc:
                c.error = exc
                continue
            e = self.extremes.get(c)
            if e is None:
                self.extremes[c] = [v, state, v, state]
                continue
            if v > e[0]:
                e[0], e[1] = v, state
            if v < e[2]:
                e[2], e[3] = v, state
        if not self.stop_at_first:
            return False
        return violated or (self.only_witnesses and len(self.state) == len(self.checks))


def decide(check: Check, x, monitor: SweepMonitor, engine, stop_note: str | None = None) -> Verdict:
    """The verdict of one property on a sweep-line exploration `x` (`SweepExploration`)."""
    if check.error is not None:
        raise check.error
    if x.complete:
        reason = None
    else:
        why = stop_note or x.stop_reason.describe(x.options)
        reason = (f"the sweep-line search is partial: it stopped because {why}; {x.unexpanded:,} states were "
                  "not expanded")
    counted = (f"all {x.states:,} reachable markings" if x.exact
               else "every reachable marking (some more than once)")
    found = monitor.state.get(check)
    if isinstance(check, Invariant) and check.on_the_fly:
        if found is not None:
            return Verdict.violated(f"false in a reachable marking ({NO_TRACE}): {marking_text(engine, found)}")
        return Verdict.holds(f"true in {counted} (sweep-line)") if reason is None else Verdict.unknown(
            f"true in the {x.states:,} markings found; {reason}")
    if isinstance(check, Reachable) and check.on_the_fly:
        if found is not None:
            return Verdict.holds(f"witness ({NO_TRACE}): {marking_text(engine, found)}")
        return Verdict.violated(f"no reachable marking satisfies it ({counted}, sweep-line)") if reason is None \
            else Verdict.unknown(f"not found in the {x.states:,} markings found; {reason}")
    if isinstance(check, DeadlockFree):
        if x.dead:
            return Verdict.violated(f"a dead marking is reachable ({NO_TRACE}): {marking_text(engine, x.dead[0])}",
                                    count=len(x.dead))
        return Verdict.holds(f"none of {counted} is dead (sweep-line)") if reason is None else Verdict.unknown(
            f"no dead marking among the expanded markings; {reason}")
    if isinstance(check, DeadMarkings):
        return _dead_markings(check, x, engine, reason)
    if isinstance(check, Bound):
        return _bound(check, x, monitor, engine, reason)
    what = _NEEDS.get(check.spec.kind, "the graph")
    if isinstance(check, (Invariant, Reachable)):
        what = "the enabled binding elements of every marking"
    return Verdict.unknown(NOT_AVAILABLE.format(what=what))


def _dead_markings(check: DeadMarkings, x, engine, reason: str | None) -> Verdict:
    dead = x.dead
    f = check.spec.fields
    if check.pred is not None:
        for d in dead:
            if not check.pred.fn(None, d):
                return Verdict.violated(f"a dead marking does not satisfy the predicate ({NO_TRACE}): "
                                        f"{marking_text(engine, d)}")
    complete = reason is None
    if "count" in f and len(dead) != f["count"] and (complete or len(dead) > f["count"]):
        return Verdict.violated(f"{len(dead):,} dead markings, expected {f['count']:,}", count=len(dead))
    if "count_modulo_time" in f:
        n = len({engine.untimed(d) for d in dead})
        if n != f["count_modulo_time"] and (complete or n > f["count_modulo_time"]):
            return Verdict.violated(f"{n:,} dead markings modulo time, expected {f['count_modulo_time']:,}",
                                    count_modulo_time=n)
    if not complete:
        return Verdict.unknown(f"{len(dead):,} dead markings so far; {reason}")
    return Verdict.holds(f"{len(dead):,} dead marking{'s' if len(dead) != 1 else ''} (sweep-line)", count=len(dead))


def _bound(check: Bound, x, monitor: SweepMonitor, engine, reason: str | None) -> Verdict:
    complete = reason is None
    rows = []
    if check.places is None:
        e = monitor.extremes.get(check)
        if e is None:
            return Verdict.unknown(f"no marking was evaluated; {reason}")
        rows.append((check.spec.fields.get("expr"), e[0], e[2], None))
    else:
        for p in check.places:
            hi, lo = x.bounds[p]
            rows.append((engine.places[p].name, hi, lo, p))
    problems, unknowns, holds = [], [], []
    into = {"holds": holds, "violated": problems, "unknown": unknowns}
    for name, hi, lo, p in rows:
        for key, want in check.limits.items():
            outcome, text = judge_integer_limit(key, want, hi, lo, complete)
            into[outcome].append(f"{name}: {text}")
        if p is None:
            continue
        for key, want in check.multiset_limits.items():
            upper = key in ("upper_multiset_equals", "at_most_multiset")
            got = Multiset((x.multiset_upper if upper else x.multiset_lower)[p] or {})
            broken = not got <= want if upper else not want <= got
            outcome, text = judge_multiset_limit(key, engine.format_multiset(p, dict(want.items())),
                                                 engine.format_multiset(p, dict(got.items())), broken, got == want,
                                                 complete)
            into[outcome].append(f"{name}: {text}")
    if problems:
        return Verdict.violated("; ".join(problems) + f" ({NO_TRACE})")
    if unknowns:
        return Verdict.unknown("; ".join(unknowns) + f"; {reason}")
    return Verdict.holds("; ".join(holds) + " (sweep-line)")


def sweep_run(scenario, engine, lang: PropertyLanguage, checks: list[Check], opts: dict, progress=None):
    """Explore one run with the sweep-line method and decide its properties: (exploration, [(check,
    verdict, seconds)], seconds of exploration, seconds of deciding)."""
    import time

    from cpn.checks.verdict import Status
    from cpn.statespace import ExploreOptions
    from cpn.statespace.sweep import SweepLine

    measure = text = None
    if opts.get("progress"):
        text = opts["progress"]
        # the scenario's own text has its place in the file; one from the command line has none
        own = scenario.explore.get("progress") == text
        origin, span = scenario.explore_texts.get("progress", (None, None)) if own else (None, None)
        measure = progress_measure(lang, text, origin, span)
    monitor = SweepMonitor(checks, bool(opts.get("stop_at_first_violation", False)))
    options = ExploreOptions(max_states=opts.get("max_states"), max_arcs=opts.get("max_arcs"),
                             max_seconds=opts.get("max_seconds"), max_memory_mb=opts.get("max_memory_mb"),
                             stop_predicate=monitor, time_condensation=bool(opts.get("time_condensation", False)),
                             detect_time_growth=bool(opts.get("detect_time_growth", True)))
    t0 = time.perf_counter()
    x = SweepLine(engine, options, measure, text, progress=progress).run()
    explore_seconds = time.perf_counter() - t0
    note = "stop_at_first_violation is set and a violation (or witness) was found" \
        if x.stop_reason.value == "predicate" else None
    results = []
    t1 = time.perf_counter()
    for c in checks:
        t = time.perf_counter()
        try:
            verdict = decide(c, x, monitor, engine, note)
        except PredicateError as exc:
            verdict = Verdict(Status.ERROR, str(exc), at=exc.span)
        results.append((c, verdict, time.perf_counter() - t))
    return x, results, explore_seconds, time.perf_counter() - t1


__all__ = ["NOT_AVAILABLE", "SweepMonitor", "decide", "marking_text", "progress_measure", "sweep_run"]
