"""The sweep-line method: explore in the order of a progress measure and forget the states behind it.

`SweepLine(engine, options, measure).run() -> SweepExploration`. A *progress measure* maps a state to an
integer. When no arc decreases it (the global clock of a timed net without time condensation never does),
a state whose progress is below the smallest progress still waiting to be expanded can never be reached
again, so it is deleted from memory: only the states of the current "sweep-line" are held. Every state is
then expanded exactly once and the counts of states and arcs equal the full search's.

An arc that decreases the measure is a *regress arc* (a user-declared measure may have them). It is
handled as in the generalised sweep-line method (Kristensen and Mailund, "A Generalised Sweep-Line Method
for Safety Properties", FME 2002): its target becomes a *persistent* state, never deleted, and a root of a
further sweep. Every reachable state is still expanded at least once, so dead markings, bounds and
invariants stay exact; but a state deleted in one sweep may be met again in a later one, so the counts
are then only upper bounds, and `exact` is False (the reports print no count as exact).

Nothing that needs the whole graph (SCCs, home markings, liveness, fairness, CTL, traces) is available.
Uses the engine through its protocol only, like `explore`.

References
----------
Christensen, Kristensen and Mailund, "A Sweep-Line Method for State Space Exploration", TACAS 2001.
Kristensen and Mailund, "A Generalised Sweep-Line Method for Safety Properties", FME 2002.
"""

from __future__ import annotations

import gc
import heapq
import time
from collections import deque
from collections.abc import Callable
from dataclasses import dataclass, field

from cpn.engine.protocol import capability
from cpn.errors import ConfigurationError
from cpn.statespace._memory import current_rss_mb, peak_rss_mb
from cpn.statespace.explore import CHECK_EVERY, _TimeGrowthWatcher
from cpn.statespace.options import ExploreOptions, StopReason
from cpn.statespace.result import Progress

#: the name of the default progress measure in reports
CLOCK_MEASURE: str = "the global clock"
#: the compiled engine's memo tables of transition results are emptied each time this many states have been
#: deleted behind the sweep-line: they outgrow the states themselves (MODBUS B, NS 10, 16 broadcasts:
#: 1.8 million entries for 16,597 states; emptied, the peak resident memory fell from 360 to 128 MiB)
FORGET_EVERY: int = 1024
#: the sweep's time-growth watch waits until the clock is this many times the clock at which the markings
#: modulo time stopped changing (see _SweepTimeGrowth)
TIME_GROWTH_FACTOR: int = 10


@dataclass
class SweepExploration:
    """The result of a sweep-line exploration: counts, dead markings and bounds, but no graph.

    `states` and `arcs` are the full search's counts when `exact` (no regress arc was met); otherwise
    they count the re-explorations too and are upper bounds. `peak_states` is the largest number of
    states held in memory at once (the sweep-line's states plus the persistent ones). `dead` lists every
    dead marking found, each once, in the order found.
    """

    engine: object
    options: ExploreOptions
    measure: str
    stop_reason: StopReason
    seconds: float
    peak_memory_mb: float
    states: int
    arcs: int
    unexpanded: int
    peak_states: int
    sweeps: int
    regress_arcs: int
    persistent: int
    dead: list
    bounds: list  # per place: [upper, lower] token counts
    multiset_upper: list  # per place: untimed multiset (value -> count), the best upper multiset bound
    multiset_lower: list
    regress_example: tuple | None = None  # (progress of the source, progress of the target)
    predicate_state: object = None
    time_growth: dict | None = None
    notes: list = field(default_factory=list)

    @property
    def complete(self) -> bool:
        return self.stop_reason is StopReason.COMPLETE

    @property
    def exact(self) -> bool:
        """The counts are those of the full state space: no arc decreased the progress measure."""
        return self.regress_arcs == 0

    # the names an `Exploration` gives the same figures (reports read either)
    method = "sweep-line"
    reduction = None
    graph = None

    @property
    def n_states(self) -> int:
        return self.states

    @property
    def n_arcs(self) -> int:
        return self.arcs

    def statistics(self) -> dict:
        """The sweep-line's own figures, for JSON reports."""
        return {"method": self.method, "progress_measure": self.measure, "exact": self.exact,
                "peak_states": self.peak_states, "sweeps": self.sweeps, "regress_arcs": self.regress_arcs,
                "persistent_states": self.persistent,
                "regress_example": list(self.regress_example) if self.regress_example else None}

    def integer_bounds(self) -> dict:
        """Best integer bounds per place instance (place name -> {"upper", "lower"})."""
        return {p.name: {"upper": b[0], "lower": b[1]} for p, b in zip(self.engine.places, self.bounds)}


def default_measure(engine, options: ExploreOptions) -> Callable:
    """The global clock, for a timed net explored without time condensation; a ConfigurationError
    otherwise (no measure can be chosen for the user)."""
    if not getattr(engine, "is_timed", False):
        raise ConfigurationError(
            "the sweep-line method needs a progress measure, and this net is untimed (its clock is always 0)",
            hint="Give an integer expression over the marking that no occurrence decreases, e.g. "
                 "--progress \"ms_to_col (Top'Count 1)\" (or progress = \"...\" in the scenario's [explore]).")
    if options.time_condensation or capability(engine, "time_condensation", False):
        raise ConfigurationError(
            "the sweep-line method cannot use the clock under time condensation: the clock is set back to 0 "
            "in every state, so it measures no progress",
            hint="Explore without time condensation (the clock then never decreases), or give a progress "
                 "measure: --progress EXPR (progress = \"...\" in the scenario's [explore]).")
    return engine.clock


class SweepLine:
    """A sweep-line search over an engine's states.

    Parameters
    ----------
    engine : Engine
    options : ExploreOptions, the limits (`stop_predicate` is asked on every new state).
    measure : optional callable state -> int, the progress measure (default: the global clock,
        `default_measure`); `measure_text` names it in reports.
    progress : optional callable receiving a `Progress` about every `options.progress_interval` s.

    Examples
    --------
    >>> import cpn
    >>> engine = cpn.loads("colset N = int with 0..3; var x : N; place P : N = 1`0;"
    ...                    " trans inc [x < 3]; arc P -> inc : x; arc inc -> P : x + 1;").engine()
    >>> x = SweepLine(engine, measure=lambda s: max(engine.marking(s)[0])).run()
    >>> x.states, x.arcs, x.exact, x.peak_states, len(x.dead)
    (4, 3, True, 2, 1)
    """

    def __init__(self, engine, options: ExploreOptions | None = None, measure: Callable | None = None,
                 measure_text: str | None = None, progress: Callable | None = None):
        self.engine = engine
        self.options = options or ExploreOptions()
        self.by_clock = measure is None
        if measure is None:
            measure = default_measure(engine, self.options)
            measure_text = CLOCK_MEASURE
        self.measure = measure
        self.measure_text = measure_text or "the progress measure"
        self.progress = progress

    def run(self) -> SweepExploration:
        engine, opts = self.engine, self.options
        measure = self.measure
        t0 = time.perf_counter()
        next_progress = t0 + opts.progress_interval
        deadline = t0 + opts.max_seconds if opts.max_seconds is not None else None
        max_states = opts.max_states if opts.max_states is not None else 1 << 62
        max_arcs = opts.max_arcs if opts.max_arcs is not None else 1 << 62
        pred = opts.stop_predicate
        bounds = _Bounds(engine)
        observe = bounds.observe
        watcher = None
        if (self.by_clock and opts.detect_time_growth
                and not getattr(engine, "reads_clock", False)):
            watcher = _SweepTimeGrowth(engine)

        held: dict[int, set] = {}  # progress value -> the states held with it (the sweep-line)
        held_keys: list[int] = []  # heap of the keys of `held`
        pending: dict[int, deque] = {}  # progress value -> states waiting to be expanded
        heap: list[int] = []  # heap of the keys of `pending`
        persistent: set = set()  # targets of regress arcs: never deleted
        roots: list = []  # persistent states waiting for the next sweep
        dead: dict = {}
        n_states = n_arcs = n_held = peak = expanded = 0
        sweeps = 1
        regress = 0
        regress_example = None
        stop = StopReason.COMPLETE
        predicate_state = None

        s0 = engine.initial_state()
        v0 = measure(s0)
        held[v0] = {s0}
        held_keys.append(v0)
        pending[v0] = deque([s0])
        heap.append(v0)
        n_states = n_held = peak = 1
        observe(s0)
        if pred is not None and pred(s0):
            stop, predicate_state = StopReason.PREDICATE, s0
        forget = _memo_tables(engine)
        deleted = 0
        gc_was_enabled = gc.isenabled()
        gc.disable()  # states are acyclic tuples: see Explorer._search
        try:
            while stop is StopReason.COMPLETE:
                if not heap:
                    if not roots:
                        break
                    # a new sweep from the targets of the regress arcs (they stay persistent)
                    for k in held_keys:
                        n_held -= len(held.pop(k, ()))
                    held_keys = []
                    for r in roots:
                        v = measure(r)
                        q = pending.get(v)
                        if q is None:
                            q = pending[v] = deque()
                            heapq.heappush(heap, v)
                        q.append(r)
                    roots = []
                    sweeps += 1
                v = heap[0]
                q = pending[v]
                if not q:
                    heapq.heappop(heap)
                    del pending[v]
                    continue
                # forget the states behind the sweep-line: nothing can reach them again
                while held_keys and held_keys[0] < v:
                    k = heapq.heappop(held_keys)
                    gone = held.pop(k)
                    n_held -= len(gone)
                    deleted += len(gone)
                    if deleted >= FORGET_EVERY and forget is not None:
                        forget()
                        deleted = 0
                    if watcher is not None:
                        watcher.level(list(gone), 0, len(gone))
                        if watcher.grows_only_by_time():
                            stop = StopReason.TIME_GROWS
                if stop is not StopReason.COMPLETE:
                    break
                if n_states >= max_states:
                    stop = StopReason.MAX_STATES
                    break
                if n_arcs >= max_arcs:
                    stop = StopReason.MAX_ARCS
                    break
                if expanded and not expanded & (CHECK_EVERY - 1):
                    now = time.perf_counter()
                    if deadline is not None and now >= deadline:
                        stop = StopReason.MAX_SECONDS
                        break
                    if opts.max_memory_mb is not None and current_rss_mb() >= opts.max_memory_mb:
                        stop = StopReason.MAX_MEMORY
                        break
                    if self.progress is not None and now >= next_progress:
                        next_progress = now + opts.progress_interval
                        self.progress(Progress(n_states, n_arcs, sum(map(len, pending.values())) + len(roots),
                                               now - t0, current_rss_mb()))
                s = q[0]
                succ = engine.successors(s)
                q.popleft()
                expanded += 1
                if not succ:
                    dead[s] = None
                for _be, t in succ:
                    w = measure(t)
                    if w < v:
                        regress += 1
                        if regress_example is None:
                            regress_example = (v, w)
                        if t not in persistent:
                            persistent.add(t)
                            roots.append(t)
                            n_states += 1
                            observe(t)
                            if pred is not None and pred(t):
                                stop, predicate_state = StopReason.PREDICATE, t
                        continue
                    bucket = held.get(w)
                    if bucket is None:
                        bucket = held[w] = set()
                        heapq.heappush(held_keys, w)
                    elif t in bucket:
                        continue
                    if t in persistent:
                        continue
                    bucket.add(t)
                    pq = pending.get(w)
                    if pq is None:
                        pq = pending[w] = deque()
                        heapq.heappush(heap, w)
                    pq.append(t)
                    n_states += 1
                    n_held += 1
                    observe(t)
                    if pred is not None and pred(t):
                        stop, predicate_state = StopReason.PREDICATE, t
                n_arcs += len(succ)
                held_now = n_held + len(persistent)
                if held_now > peak:
                    peak = held_now
        except KeyboardInterrupt:
            stop = StopReason.INTERRUPTED
        finally:
            if gc_was_enabled:
                gc.enable()
        seconds = time.perf_counter() - t0
        unexpanded = sum(map(len, pending.values())) + len(roots)
        if self.progress is not None:
            self.progress(Progress(n_states, n_arcs, unexpanded, seconds, current_rss_mb()))
        notes = []
        if regress:
            notes.append(f"{regress:,} arc{'s' if regress != 1 else ''} decreased {self.measure_text} (first: "
                         f"from progress {regress_example[0]} to {regress_example[1]}); their targets were kept as "
                         f"persistent states and swept again ({sweeps} sweeps), so every state was explored "
                         "but some more than once: the counts of states and arcs are upper bounds, not exact")
        return SweepExploration(
            engine=engine, options=opts, measure=self.measure_text, stop_reason=stop, seconds=seconds,
            peak_memory_mb=peak_rss_mb(), states=n_states, arcs=n_arcs, unexpanded=unexpanded, peak_states=peak,
            sweeps=sweeps, regress_arcs=regress, persistent=len(persistent), dead=list(dead),
            bounds=bounds.counts, multiset_upper=bounds.upper, multiset_lower=bounds.lower,
            regress_example=regress_example, predicate_state=predicate_state,
            time_growth=watcher.evidence() if stop is StopReason.TIME_GROWS else None, notes=notes)


def _memo_tables(engine) -> Callable | None:
    """A function that empties the engine's memo tables of transition results (their keys are markings of
    the places a transition reads, mostly behind the sweep-line once it has moved on), or None for an
    engine without them (`Engine.forget_memo`). Emptying them changes no result, only what is computed
    again."""
    return capability(engine, "forget_memo")


class _SweepTimeGrowth(_TimeGrowthWatcher):
    """`explore`'s time-growth watch, fed one clock value at a time as the sweep-line passes it. It is a
    heuristic, and a clock value is a much finer step than a breadth-first level (a sequential protocol
    has one state per clock value), so the sweep asks for more: the clock past TIME_GROWTH_FACTOR times
    the clock at which the markings modulo time stopped changing, and at least as many states met since
    then as before. (With `explore`'s test alone MODBUS A.1 and B.6 without condensation, which have quiet
    spells of 16 and 34 clock values before their last new states, were stopped before their end.)"""

    def __init__(self, engine):
        super().__init__(engine)
        self.states_seen = 0
        self.states_at_saturation = 0

    def level(self, states, start, end):
        before = len(self.untimed)
        super().level(states, start, end)
        self.states_seen += max(0, end - start)
        if len(self.untimed) > before:
            self.states_at_saturation = self.states_seen

    def grows_only_by_time(self) -> bool:
        return (super().grows_only_by_time()
                and self.last_min_clock > TIME_GROWTH_FACTOR * (self.clock_at_saturation + 1)
                and self.states_seen - self.states_at_saturation >= self.states_at_saturation)


class _Bounds:
    """Integer and multiset bounds per place, updated with every new state. A place's marking is looked
    at once per distinct marking (by its id in the state tuple, where the engine interns them)."""

    def __init__(self, engine):
        self.engine = engine
        n = len(engine.places)
        self.counts: list = [[None, None] for _ in range(n)]
        self.upper: list = [None] * n
        self.lower: list = [None] * n
        self.seen: list = [set() for _ in range(n)]
        self.view = capability(engine, "place_view")
        self.timed = [bool(getattr(p, "timed", False)) for p in engine.places]

    def _views(self, s):
        view = self.view
        if view is not None:
            for p, seen in enumerate(self.seen):
                mid = s[p]
                if mid not in seen:
                    seen.add(mid)
                    yield p, view(s, p)
            return
        for p, ms in enumerate(self.engine.marking(s)):
            if self.timed[p]:
                flat: dict = {}
                for (value, _ts), k in ms.items():
                    flat[value] = flat.get(value, 0) + k
                ms = flat
            yield p, ms

    def observe(self, s) -> None:
        counts, upper, lower = self.counts, self.upper, self.lower
        for p, ms in self._views(s):
            n = sum(ms.values())
            c = counts[p]
            if c[0] is None or n > c[0]:
                c[0] = n
            if c[1] is None or n < c[1]:
                c[1] = n
            up = upper[p]
            if up is None:
                upper[p] = dict(ms)
                lower[p] = dict(ms)
                continue
            for value, k in ms.items():
                if up.get(value, 0) < k:
                    up[value] = k
            lo = lower[p]
            for value in [x for x, k in lo.items() if ms.get(x, 0) < k]:
                k = ms.get(value, 0)
                if k:
                    lo[value] = k
                else:
                    del lo[value]


__all__ = ["CLOCK_MEASURE", "SweepExploration", "SweepLine", "default_measure"]
