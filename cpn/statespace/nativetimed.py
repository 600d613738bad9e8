"""The native search of timed nets and of nets with priorities (`_timed.c`, driving `_search.c`'s search).

The engine gives their successor function as transition groups whose binding elements are selected over
all transitions at once (`Engine.timed_groups`, `cpn.engine.timedgroups`): per group, its binding elements'
ready times and priorities per tuple of read place ids, and their effects per (read ids, occurrence time).
The C search caches both, the written places' new ids and, under time condensation, the shifted markings'
ids; it computes the occurrence time and selects by priority itself. A state with a value not cached yet
goes back to Python once: the engine expands it in its own order (so the markings and binding elements
it interns get the Python search's ids) and every value it used is cached. So the graph is the Python
search's own: the same states in the same order, the same arcs, the same binding elements.

The time-growth watch of a timed search (`cpn.statespace.explore`) looks at every new BFS level: the C
search stops at each one for it (`on_level`). A value that does not fit the C search's 32 bits (a model
time past 2^32 - 1) hands the search over to Python (`HandOver`) with the states found so far.
"""

from __future__ import annotations

from array import array

from cpn.engine.compiled import NEG_INF
from cpn.statespace.native import (
    ND_CHECK,
    ND_DONE,
    ND_MAX_ARCS,
    ND_MAX_STATES,
    ND_NEED,
    ND_WIDE_BE,
    HandOver,
    NativeSearch,
    generated,
    library,
)
from cpn.statespace.options import StopReason

ND_LEVEL = 7
_U32 = 1 << 32
_I64_MIN = -(1 << 63)


class TimedNativeSearch(NativeSearch):
    """A native search over `TimedGroups` (see the module's docstring); `on_level(start, end)` is called
    at each new BFS level (the states start..end-1) and may return a StopReason to stop there."""

    def __init__(self, engine, graph, s0, options=None, notes: list[str] | None = None, on_level=None):
        self.engine = engine
        self.graph = graph
        self.notes = notes if notes is not None else []
        self.tg = engine.timed_groups()
        self.round_trips = 0
        self.code, self.gen = None, None
        self.generate_after = 1 << 62
        if options is not None:
            _, code_notes = generated(engine, options)
            self.notes.extend(code_notes)
        self.on_level = on_level
        self._attach(library(timed=True), s0)
        tg = self.tg
        ffi, lib = self.ffi, self.lib
        handle = lib.nt_new(self.handle, int(tg.clock), int(tg.condensation), int(tg.priorities),
                            ffi.new("int32_t[]", [int(t) for t in tg.timed] or [0]), len(tg.timed_places),
                            ffi.new("int32_t[]", tg.timed_places or [0]))
        if handle == ffi.NULL:
            raise MemoryError("cannot allocate the native search")
        self.timed_handle = ffi.gc(handle, lib.nt_free)
        lib.nt_set_watch(self.timed_handle, 1 if on_level is not None else 0)

    def _run(self, until: int, max_states: int, max_arcs: int) -> StopReason | None:
        lib, h = self.lib, self.timed_handle
        while True:
            status = lib.nt_run(h, until, max_states, max_arcs)
            if status == ND_NEED:
                self.round_trips += 1
                self._fill()
            elif status == ND_LEVEL:
                stop = self.on_level(lib.nt_level_start(h), self.level_end)
                if stop is not None:
                    self.flush()
                    return stop
            elif status == ND_WIDE_BE:
                self.flush()
                g = self.graph
                g.bes = array("i", g.bes)  # binding-element ids outgrew 16 bits: widen once
                lib.nd_set_be32(self.handle)
            elif status < 0:
                self.flush()
                raise MemoryError("the native search cannot grow any more")
            else:
                self.flush()
                return {ND_CHECK: None, ND_DONE: StopReason.COMPLETE, ND_MAX_STATES: StopReason.MAX_STATES,
                        ND_MAX_ARCS: StopReason.MAX_ARCS}[status]

    def _fill(self) -> None:
        """The engine expands the state the C search misses values of; every value it used is cached."""
        lib, ffi, h = self.lib, self.ffi, self.timed_handle
        req = ffi.unpack(lib.nd_requests(self.handle), lib.nd_nrequests(self.handle))
        s = tuple(req[1:])
        if self.head == getattr(self, "_last_fill", -1):
            self.flush()
            raise RuntimeError(f"the native search still misses values of state {self.head} once the engine "
                               "expanded it")
        self._last_fill = self.head
        try:
            x = self.tg.expand(s)
        except BaseException:
            self.flush()  # the graph up to the state being expanded, for an error's trace
            raise
        if x.time is not None and not 0 <= x.time < _U32:
            self.flush()
            raise HandOver(f"the model time {x.time} does not fit the native search's 32 bits")
        try:
            for g, key, pairs in x.ready:
                flat = array("q")
                for r, p in pairs:
                    flat.append(_I64_MIN if r == NEG_INF else r)
                    flat.append(p)
                _check(lib.nt_put_ready(h, g, _u32(ffi, key), len(pairs), ffi.from_buffer("int64_t[]", flat or
                                                                                          array("q", [0]))))
            for g, key, f, entries in x.effects:
                flat = array("i", [v for entry in entries for v in entry])
                if min(flat) < -1:
                    raise HandOver("a negative id cannot be stored by the native search")
                _check(lib.nt_put_effect(h, g, _u32(ffi, (*key, f)), len(entries), ffi.from_buffer("int32_t[]", flat)))
            for p, did, old, nid in x.adds:
                _check(lib.nd_put_add(self.handle, p, did, old, _fit(nid)))
            for p, old, f, nid in x.shifts:
                _check(lib.nt_put_shift(h, p, old, f, _fit(nid)))
        except (OverflowError, TypeError) as exc:
            self.flush()
            raise HandOver(f"a value does not fit the native search's 32 bits ({exc})") from None

    def cache_bytes(self) -> int:
        return self.lib.nd_cache_bytes(self.handle) + self.lib.nt_cache_bytes(self.timed_handle)


def _u32(ffi, values):
    return ffi.from_buffer("uint32_t[]", array("I", values or (0,)))


def _fit(v: int) -> int:
    if not 0 <= v < _U32:
        raise OverflowError(f"id {v}")
    return v


def _check(rc: int) -> None:
    if rc != 0:
        raise MemoryError("the native search's caches cannot grow any more")
