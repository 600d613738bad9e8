"""Breadth-first generation of the occurrence graph: `Explorer(engine, options).run() -> Exploration`.

Uses the engine through its protocol only (`cpn.engine.Engine`, docs/internals.md). The driver, the
store (`graph.StateGraph`) and the trace builder (`trace`) are separate; the frontier is the tail
`states[expanded:]` of the store, which BFS fills in order. Which search runs (this loop, the native
one, threads, processes, Ray) is `cpn.statespace.chooser`'s choice; the result is a `result.Exploration`.
"""

from __future__ import annotations

import gc
import time
from array import array
from collections import deque
from collections.abc import Callable

from cpn.engine import Engine
from cpn.errors import EvaluationError
from cpn.statespace import chooser, native
from cpn.statespace._memory import current_rss_mb, peak_rss_mb
from cpn.statespace.graph import StateGraph
from cpn.statespace.native import HAND_OVER_BY
from cpn.statespace.options import Backend, ExploreOptions, StopReason
from cpn.statespace.result import Exploration, Progress
from cpn.statespace.store import new_store, pack
from cpn.statespace.trace import shortest_trace

# How many BFS levels without a new untimed marking, and how far past the clock at which the untimed
# markings stopped changing, before a timed search is declared to grow only because time grows.
TIME_GROWTH_LEVELS: int = 8
# The limits (time, memory) and the progress hook are looked at every this many expansions, and also
# whenever this many arcs were added since the last look: a net whose states have thousands of
# successors stores a million states in 512 expansions, far past a memory limit.
CHECK_EVERY: int = 512
CHECK_EVERY_ARCS: int = 1 << 16


def _observe(observe, g: StateGraph, observed: int) -> int:
    """Show an observing predicate the states stored from id `observed` on, in order; the next id to show."""
    if observe is None:
        return observed
    n = len(g.store)
    many = getattr(observe, "observe_many", None)  # a check's monitor takes the batch at once
    if many is not None:
        many(g.states[observed:n])
        return n
    for t in g.states[observed:n]:
        observe(t)
    return n


class Explorer:
    """A breadth-first search over an engine's states, recording why it stopped.

    Parameters
    ----------
    engine : Engine
        The successor function (`cpn.engine.Engine`: `initial_state`, `successors`, ...).
    options : ExploreOptions, the limits.
    progress : optional callable receiving a `Progress` about every `options.progress_interval` s.

    Examples
    --------
    >>> import cpn
    >>> engine = cpn.loads("colset N = int with 0..3; var x : N; place P : N = 1`0;"
    ...                    " trans inc [x < 3]; arc P -> inc : x; arc inc -> P : x + 1;").engine()
    >>> x = Explorer(engine, ExploreOptions(max_states=100)).run()
    >>> x.n_states, x.n_arcs, x.stop_reason.value, x.graph.dead_states()
    (4, 3, 'complete', [3])
    """

    def __init__(self, engine: Engine, options: ExploreOptions | None = None,
                 progress: Callable[[Progress], None] | None = None):
        self.engine = engine
        self.options = options or ExploreOptions()
        self.progress = progress

    def run(self) -> Exploration:
        """Generate the occurrence graph breadth-first until it is complete or a limit stops it, in the
        search `cpn.statespace.chooser` chooses for the engine and the options."""
        opts = self.options
        parallel_note = None
        if opts.workers is not None or opts.ray is not None:
            partitioned, parallel_note = chooser.run_partitioned(self.engine, opts, self.progress)
            if partitioned is not None:
                return partitioned
        g = StateGraph()
        self._t0 = t0 = time.perf_counter()
        self._next_progress = t0 + opts.progress_interval
        self._deadline = t0 + opts.max_seconds if opts.max_seconds is not None else None
        self._watcher = _TimeGrowthWatcher(self.engine) if self.engine.is_timed else None
        # A model that reads the clock (intTime() in a guard, an inscription, a delay) can change its
        # behaviour at any later time: the markings modulo time say nothing about its future.
        self._reads_clock = self.engine.is_timed and self.engine.reads_clock
        stop, predicate_state = self._start(g)
        self._reduced = self._reduction(g)
        levels = 0
        self._backend = Backend.PYTHON
        self._notes = [parallel_note] if parallel_note else []
        self._backend_notes = []  # which search ran and why (`Exploration.backend_notes`)
        if stop is StopReason.COMPLETE:
            s0 = self._queue[0]
            backend, why = chooser.one_process(self.engine, opts, s0, self._reduced is not None)
            if backend is Backend.C:
                self._backend = Backend.C
                stop, predicate_state, levels = self._search_native(g, s0)
            else:
                if opts.backend is not Backend.PYTHON:
                    note = f"the Python back end searched this net: {why}"
                    (self._notes if chooser.needs_action(why) else self._backend_notes).append(note)
                stop, predicate_state, levels = self._search(g)
        return self._finish(g, stop, predicate_state, levels)

    def _reduction(self, g: StateGraph):
        """The reduced successor step asked for by the options, or None (full graph; a note says why
        when a reduction was asked for but does not apply)."""
        self._reduction_notes = []
        if self.options.reduction is None:
            return None
        if self.options.reduction == "symmetry":
            from cpn.statespace.symmetry import SymmetricSuccessors

            g.symmetry = SymmetricSuccessors(self.engine, self.options.symmetry)
            return g.symmetry
        if self.options.reduction != "stubborn":
            raise ValueError(f"unknown reduction {self.options.reduction!r} (known: 'stubborn', 'symmetry')")
        from cpn.engine.stubborn import StubbornSets
        from cpn.statespace.reduction import ReducedSuccessors

        sets = StubbornSets(self.engine.net, self.options.visible_places)
        if sets.refusal is not None:
            self._reduction_notes.append(f"stubborn sets were not applied: {sets.refusal}; every state was "
                                         "fully expanded")
            return None
        return ReducedSuccessors(self.engine, sets, g.store.index)

    def _search_native(self, g: StateGraph, s0) -> tuple[StopReason, int | None, int]:
        """The same search as `_search`, its loop in C (`cpn.statespace.native`)."""
        opts = self.options
        self._queue = None
        search = chooser.new_native_search(self.engine, g, s0, opts, self._backend_notes, self._level_hook(g))
        max_states = opts.max_states if opts.max_states is not None else 1 << 62
        max_arcs = opts.max_arcs if opts.max_arcs is not None else 1 << 62
        until = CHECK_EVERY
        # a predicate that only observes (may_stop False: a check's monitor) sees every new state in id
        # order, as the Python search shows it each state when it stores it, a batch at a time
        observe, observed = opts.stop_predicate, 1
        try:
            while True:
                # a stop at the arcs cap of this round is a look at the limits, as at `until`
                round_arcs = min(max_arcs, search.n_arcs + CHECK_EVERY_ARCS)
                stop = search.run(until, max_states, round_arcs)
                observed = _observe(observe, g, observed)
                if stop is StopReason.MAX_ARCS and round_arcs < max_arcs:
                    stop = None
                if stop is not None:
                    break
                n = len(g.store)
                stop = self._check_limits(n, search.n_arcs, n - search.head)
                if stop is not StopReason.COMPLETE:
                    break
                if search.head <= HAND_OVER_BY and search.round_trips > search.hand_over_rate() * search.head:
                    return self._hand_over(g, search)
                if search.head >= until:
                    until += CHECK_EVERY
        except native.HandOver as why:
            _observe(observe, g, observed)  # the states the native search stored before it stopped
            return self._hand_over(g, search, str(why))
        except EvaluationError as err:
            if not err.trace:
                err.trace = [step.text for step in shortest_trace(g, search.head, self.engine).steps]
            raise
        except KeyboardInterrupt:
            search.flush()
            _observe(observe, g, observed)
            stop = StopReason.INTERRUPTED
        g.store.finish()
        return stop, None, search.levels

    def _level_hook(self, g: StateGraph):
        """What the native search calls at each new BFS level of a timed net: the time-growth watch, as
        `_search` does it (None for an untimed net)."""
        watcher = self._watcher
        if watcher is None:
            return None
        timed_check = self.options.detect_time_growth and not self._reads_clock

        def on_level(start: int, end: int, fresh=None, clocks=None) -> StopReason | None:
            watcher.level(g.states, start, end, fresh, clocks)
            if timed_check and watcher.grows_only_by_time():
                return StopReason.TIME_GROWS
            return None
        return on_level

    def _hand_over(self, g: StateGraph, search, why: str | None = None) -> tuple[StopReason, int | None, int]:
        """Go on in Python from where the native search is: its caches are rarely reused on this net (or
        `why`: it cannot go on)."""
        head = search.head
        self._backend_notes.append(
            f"the native search handed over to the Python search after {head:,} states: " + (why or
            f"each state needed the engine {search.round_trips / head:.1f} times on average (transitions' "
            "results rarely recur)"))
        self._backend = Backend.PYTHON
        search.tg.engine_caches()
        self._queue = deque(g.states[head:])
        return self._search(g, head, search.level_end, search.levels)

    def _start(self, g: StateGraph) -> tuple[StopReason, int | None]:
        """Store the initial state; the search stops at once if it satisfies the stop predicate."""
        s0 = self.engine.initial_state()
        g.store = new_store(s0, packed=self.options.packed_states and self.options.pack_from <= 0)
        self._queue = deque([s0])
        g.parent.append(-1)
        g.parent_be.append(-1)
        if self._watcher is not None:
            self._watcher.level(g.states, 0, 1)
        pred = self.options.stop_predicate
        if pred is not None and pred(s0):
            return StopReason.PREDICATE, 0
        return StopReason.COMPLETE, None

    def _search(self, g: StateGraph, head: int = 0, level_end: int = 1,
                levels: int = 0) -> tuple[StopReason, int | None, int]:
        """Expand the states in BFS order: (why it stopped, the state satisfying the predicate, levels).
        It goes on from state `head` (its queue `self._queue`) when the native search hands over."""
        engine = self.engine
        opts = self.options
        store = g.store
        queue = self._queue
        offsets, dst, parent, parent_be = g.offsets, g.dst, g.parent, g.parent_be
        pred = opts.stop_predicate
        max_states = opts.max_states if opts.max_states is not None else 1 << 62
        max_arcs = opts.max_arcs if opts.max_arcs is not None else 1 << 62
        watcher = self._watcher
        timed_check = watcher is not None and opts.detect_time_growth and not self._reads_clock

        # --until-time: a state whose clock exceeds the bound gets a provisional negative number and is
        # stored after all the others when the search ends, so that the expanded states stay 0..expanded-1.
        until = opts.until_time if engine.is_timed else None
        clock_of = engine.clock if until is not None else None
        beyond = _Beyond()
        beyond_get = beyond.index.get

        stop = StopReason.COMPLETE
        predicate_state = None
        successors = engine.successors if self._reduced is None else self._reduced
        if opts.restricted:
            successors = _branching(successors, opts)
        add_successors = store.add_successors
        # the tuple store is filled inline (as fast as before the packed store); a packed one through
        # add_successors, one call per state, with the unexpanded states' tuples in `queue`
        tuples = store.kind == "tuples"
        if tuples:
            states, index = store.states, store.index
            index_get, states_append = index.get, states.append
        pop = queue.popleft
        push = queue.append
        parent_append = parent.append
        pbe_append = parent_be.append
        dst_append = dst.append
        bes_append = g.bes.append
        bes_extend = g.bes.extend
        off_append = offsets.append
        n_arcs = len(dst)
        next_check_arcs = n_arcs + CHECK_EVERY_ARCS
        n_states = len(store)
        # a reduction, branching options and the model-time bound keep the tuple store (they read its index)
        special = chooser.python_only(engine, opts, self._reduced is not None) is not None
        pack_from = opts.pack_from if opts.packed_states and tuples and not special else None
        succ: list | tuple = ()
        fresh: list | tuple = ()
        # The states are acyclic tuples of ints, yet each allocation burst makes the cyclic collector
        # walk every stored state again: switching it off cut MS(7) generation CPU time by about 25%.
        gc_was_enabled = gc.isenabled()
        gc.disable()
        try:
            while stop is StopReason.COMPLETE and head < n_states:
                if head == level_end:
                    levels += 1
                    if watcher is not None:
                        watcher.level(store.states, level_end, n_states)
                        if timed_check and watcher.grows_only_by_time():
                            stop = StopReason.TIME_GROWS
                            break
                    level_end = n_states
                if (not head & (CHECK_EVERY - 1) and head) or n_arcs >= next_check_arcs:
                    next_check_arcs = n_arcs + CHECK_EVERY_ARCS
                    stop = self._check_limits(n_states, n_arcs, n_states - head)
                    if stop is not StopReason.COMPLETE:
                        break
                    if pack_from is not None and n_states >= pack_from:
                        pack_from = None
                        g.store = store = pack(store)
                        if store.kind == "packed":
                            tuples = False
                            add_successors = store.add_successors
                            queue = deque(store.states[head:])
                            pop, push = queue.popleft, queue.append
                            bes_extend = g.bes.extend
                if n_states + len(beyond.states) >= max_states:
                    stop = StopReason.MAX_STATES
                    break
                if n_arcs >= max_arcs:
                    stop = StopReason.MAX_ARCS
                    break
                if tuples:
                    for be, t in successors(states[head]):
                        j = index_get(t)
                        if j is None and until is not None and clock_of(t) > until:
                            j = beyond_get(t)
                            if j is None:
                                j = beyond.add(t, head, be)
                                if pred is not None and pred(t):
                                    stop, predicate_state = StopReason.PREDICATE, j
                        elif j is None:
                            j = len(states)
                            index[t] = j
                            states_append(t)
                            parent_append(head)
                            pbe_append(be)
                            if pred is not None and pred(t):
                                stop, predicate_state = StopReason.PREDICATE, j
                        dst_append(j)
                        try:
                            bes_append(be)
                        except OverflowError:
                            g.bes = array("i", g.bes)  # binding-element ids outgrew 16 bits: widen once
                            bes_append, bes_extend = g.bes.append, g.bes.extend
                            bes_append(be)
                    n_states = len(states)
                    n_arcs = len(dst)
                else:
                    succ = ()
                    fresh = ()
                    succ = successors(queue[0])
                    if succ:
                        fresh = add_successors(succ, dst)
                        try:
                            bes_extend([be for be, _t in succ])
                        except OverflowError:
                            del g.bes[len(dst) - len(succ):]  # extend stopped part-way
                            g.bes = array("i", g.bes)  # binding-element ids outgrew 16 bits: widen once
                            bes_extend = g.bes.extend
                            bes_extend([be for be, _t in succ])
                        for k in fresh:
                            be, t = succ[k]
                            parent_append(head)
                            pbe_append(be)
                            push(t)
                            if pred is not None and pred(t):
                                stop, predicate_state = StopReason.PREDICATE, n_states
                            n_states += 1
                        n_arcs = len(dst)
                    pop()
                off_append(n_arcs)
                head += 1
        except EvaluationError as err:
            # An inscription or guard failed while expanding state `head`: say how it is reached.
            beyond.store(g)
            if not err.trace:
                err.trace = [step.text for step in shortest_trace(g, head, engine).steps]
            raise
        except KeyboardInterrupt:
            # A half-expanded state keeps no arcs: it is unexpanded. States it discovered stay.
            del dst[offsets[-1]:]
            del g.bes[offsets[-1]:]
            # States numbered by the store whose BFS parent was not yet recorded: they came from `head`.
            missing = len(g.store) - len(parent)
            for k in fresh[len(fresh) - missing:] if missing > 0 else ():
                parent.append(head)
                parent_be.append(succ[k][0])
            stop = StopReason.INTERRUPTED
        finally:
            self._queue = None
            store.finish()
            if gc_was_enabled:
                gc.enable()
        if predicate_state is not None and predicate_state < 0:
            predicate_state = len(g.store) - 1 - predicate_state
        if beyond.states and stop is StopReason.COMPLETE:
            stop = StopReason.UNTIL_TIME
        beyond.store(g)
        return stop, predicate_state, levels

    def _check_limits(self, n_states: int, n_arcs: int, queue: int) -> StopReason:
        """The time and memory limits, and the progress hook (looked at every CHECK_EVERY expansions)."""
        now = time.perf_counter()
        if self._deadline is not None and now >= self._deadline:
            return StopReason.MAX_SECONDS
        max_mem = self.options.max_memory_mb
        if max_mem is not None and current_rss_mb() >= max_mem:
            return StopReason.MAX_MEMORY
        if self.progress is not None and now >= self._next_progress:
            self._next_progress = now + self.options.progress_interval
            self.progress(Progress(n_states, n_arcs, queue, now - self._t0, current_rss_mb()))
        return StopReason.COMPLETE

    def _finish(self, g: StateGraph, stop: StopReason, predicate_state: int | None, levels: int) -> Exploration:
        """The last progress report and the result."""
        seconds = time.perf_counter() - self._t0
        watcher = self._watcher
        if watcher is not None:
            watcher.level(g.states, watcher.seen_upto, len(g.states))
        if self.progress is not None:
            self.progress(Progress(len(g.states), len(g.dst), len(g.states) - g.expanded, seconds,
                                   current_rss_mb()))
        notes = list(self._reduction_notes)
        asked_c = self.options.backend is Backend.C
        if self._reads_clock and self.options.detect_time_growth and stop is not StopReason.COMPLETE:
            engine = self.engine
            read = engine.clock_reads[min(engine.clock_reads)]
            notes.append(f"the time-growth watch does not apply to this model: {read.element} of transition "
                         f"'{read.transition}' reads the clock ({read.span}), so its behaviour may change at any "
                         "later time; bound the search with --max-states, --max-seconds or --max-memory")
        return Exploration(
            engine=self.engine, graph=g, options=self.options, stop_reason=stop, seconds=seconds,
            peak_memory_mb=peak_rss_mb(), predicate_state=predicate_state,
            untimed_states=watcher.untimed_count() if watcher is not None else None,
            time_growth=watcher.evidence() if stop is StopReason.TIME_GROWS else None,
            # what `--backend c` was refused is a note; what `auto` chose and why, a backend note
            levels=levels, notes=self._notes + (self._backend_notes if asked_c else []) + notes,
            backend=self._backend, backend_notes=[] if asked_c else list(self._backend_notes),
            reduction=self.options.reduction if self._reduced is not None else None,
            reduction_stats=None if self._reduced is None else g.symmetry.stats(g) if g.symmetry is not None else {
                "reduced_states": self._reduced.reduced, "fully_expanded_states": self._reduced.full_expansions,
                "visible_places": None if self.options.visible_places is None
                else sorted(self.options.visible_places)},
        )


class _TimeGrowthWatcher:
    """Follows, level by level, the distinct untimed markings and the clock of a timed search.

    The search is declared to grow only because time grows when no new untimed marking has appeared
    for TIME_GROWTH_LEVELS levels and every state of the newest level has a clock beyond twice the
    largest clock seen when the last new untimed marking appeared (so at least one more full period of
    the protocol's timing was explored without anything but time changing).
    """

    def __init__(self, engine: Engine):
        self.untimed_of = engine.untimed
        self.clock_of = engine.clock
        self.untimed: set = set()
        # the states whose untimed markings the native timed search met first, not in `untimed` yet
        self.first: array = array("q")
        self.states = None
        self.seen_upto = 0
        self.quiet_levels = 0
        self.max_clock = 0
        self.clock_at_saturation = 0
        self.last_min_clock = 0

    def level(self, states, start, end, fresh=None, clocks=None):
        """The states start..end-1 of a new level; where the search gives them (the native timed search),
        `fresh`: those of them whose untimed markings it met first, and `clocks`: the level's smallest and
        largest clock."""
        if start >= end:
            return
        before = self.untimed_count()
        add = self.untimed.add
        untimed_of, clock_of = self.untimed_of, self.clock_of
        if fresh is not None:  # their untimed markings computed if the Python search takes over (`untimed_count`)
            self.first.extend(fresh)
            self.states = states
            lo, hi = clocks[0], max(self.max_clock, clocks[1])
        else:
            self.materialize()
            lo = None
            hi = self.max_clock
            for i in range(start, end):
                s = states[i]
                add(untimed_of(s))
                c = clock_of(s)
                if lo is None or c < lo:
                    lo = c
                if c > hi:
                    hi = c
        self.seen_upto = end
        self.max_clock = hi
        self.last_min_clock = lo
        if self.untimed_count() > before:
            self.quiet_levels = 0
            self.clock_at_saturation = hi
        else:
            self.quiet_levels += 1

    def untimed_count(self) -> int:
        """The number of distinct untimed markings seen (`first`: each one met first by the native search)."""
        return len(self.untimed) + len(self.first)

    def materialize(self) -> None:
        """The untimed markings of the states in `first` into `untimed` (the Python search goes on)."""
        if self.first:
            add, untimed_of, states = self.untimed.add, self.untimed_of, self.states
            for i in self.first:
                add(untimed_of(states[i]))
            self.first = array("q")

    def grows_only_by_time(self) -> bool:
        return (self.quiet_levels >= TIME_GROWTH_LEVELS
                and self.last_min_clock > 2 * self.clock_at_saturation + 1)

    def evidence(self) -> dict:
        return {
            "untimed_markings": self.untimed_count(),
            "levels_without_new_untimed_marking": self.quiet_levels,
            "clock_when_untimed_markings_stopped_growing": self.clock_at_saturation,
            "frontier_min_clock": self.last_min_clock,
        }


def _branching(successors, opts: ExploreOptions):
    """`successors` restricted by the branching options (the predicate is asked once per binding element)."""
    pred = opts.branching_predicate
    cap = opts.max_successors
    verdict: dict[int, bool] = {}

    def keep(be: int) -> bool:
        v = verdict.get(be)
        if v is None:
            v = verdict[be] = bool(pred(be))
        return v

    def restricted(state):
        succ = successors(state)
        if pred is not None:
            succ = [(be, t) for be, t in succ if keep(be)]
        if cap is not None:
            succ = succ[:cap]
        return succ

    return restricted


class _Beyond:
    """The states past the model-time bound, numbered -1, -2, ... while the search runs."""

    def __init__(self):
        self.index: dict = {}
        self.states: list = []
        self.parent: list[int] = []
        self.parent_be: list[int] = []

    def add(self, state, parent: int, be: int) -> int:
        j = -1 - len(self.states)
        self.index[state] = j
        self.states.append(state)
        self.parent.append(parent)
        self.parent_be.append(be)
        return j

    def store(self, g: StateGraph) -> None:
        """Append the states to the graph after all the others and renumber the arcs that reach them."""
        if not self.states:
            return
        store = g.store  # the tuple store: the explorer keeps it when a model-time bound is set
        base = len(store.states)
        for k, s in enumerate(self.states):
            store.index[s] = base + k
        store.states.extend(self.states)
        g.parent.extend(array("i", self.parent))
        g.parent_be.extend(array("i", self.parent_be))
        dst = g.dst
        for i, d in enumerate(dst):
            if d < 0:
                dst[i] = base - 1 - d
        self.states, self.index, self.parent, self.parent_be = [], {}, [], []
