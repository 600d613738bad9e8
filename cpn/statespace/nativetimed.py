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

import hashlib
import os
from array import array

from cpn._util.cbuild import note_built, noted_built, switched_off, why_unavailable
from cpn.engine.compiled import NEG_INF
from cpn.statespace.native import (
    GENERATE_AFTER,
    GENERATE_PER_LINE,
    LOOK_FOR_BUILT_AFTER,
    ND_CHECK,
    ND_DONE,
    ND_MAX_ARCS,
    ND_MAX_STATES,
    ND_NEED,
    ND_WIDE_BE,
    HandOver,
    NativeSearch,
    _Snapshot,
    library,
    library_built,
)
from cpn.statespace.options import Backend, StopReason

ND_LEVEL = 7
#: the search hands over to the Python search past this many returns to the engine per state (it expands
#: a state at most once, at about the cost of the Python search's step and more): where most states need
#: it, the C search only adds copying (the markings of timed places rarely recur, their timestamps move
#: with the clock; `python bench/modbus.py --native`: slower than the Python search where 70% and more
#: of the states need the engine)
HAND_OVER_RATE: float = 0.66
#: looked at from HAND_OVER_FROM to HAND_OVER_BY expanded states (a timed net's search often has few
#: states per level and returns to Python at each level, so it looks earlier than the explorer's 512)
HAND_OVER_FROM: int = 64
HAND_OVER_BY: int = 8192
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
        self._later = False  # `auto`: the net's C is made once the search is large enough (`_upgrade`)
        self._looked = False  # `auto`: whether the compile cache was looked at for the net's C (`_look_for_built`)
        self.options = options
        lib = None
        if options is not None and options.backend is not Backend.C and options.backend is not Backend.PYTHON \
                and not os.environ.get("CPN_NO_GENERATED") and switched_off() is None:
            self._later, self.generate_after = True, GENERATE_AFTER  # (a small search never makes it)
        elif options is not None:
            code, code_notes = timed_generated(self.tg, options)
            if code is not None:
                self.code = code
                # `--backend c` builds the net's C at once; `auto` once the search is large enough to repay
                # it (`native.GENERATE_AFTER`), the states so far expanded with the engine's help
                self.generate_after = 0 if options.backend is Backend.C else \
                    max(GENERATE_AFTER, GENERATE_PER_LINE * code.source.count("\n"))
                if self.generate_after == 0:
                    lib = self._timed_library()
                    code_notes = [] if lib is None else code_notes
                else:  # said once it is built (`_upgrade`)
                    code_notes = []
            self.notes.extend(code_notes)
        self.on_level = on_level
        self._fields = len(s0)
        self._attach(lib if lib is not None else library(timed=True), s0)

    def _level_summary(self, start: int, end: int) -> tuple:
        """For the time-growth watch, computed in C: the states start..end-1 whose untimed markings the C
        search had not met before, and (the smallest clock, the largest) of them all; (None, None) where
        it cannot say (the watch then looks at every state)."""
        lib, ffi, h = self.lib, self.ffi, self.timed_handle
        if self._watched < 0:
            return None, None
        self._watched, watched = -1, self._watched  # (for good if C cannot say: the watch looks itself)
        store = self.engine.store
        for p in self.tg.timed_places:
            have, total = self._views_sent[p], len(store.dicts[p])
            if have == total:
                continue
            index, views = self._view_ids[p], store.views[p]
            ids = array("i", [index.setdefault(frozenset(views[i].items()), len(index)) for i in range(have, total)])
            if lib.nt_put_views(h, p, have, total - have, ffi.from_buffer("int32_t[]", ids)) != 0:
                return None, None
            self._views_sent[p] = total
        lo, hi = ffi.new("int64_t *"), ffi.new("int64_t *")
        if watched < start:  # the states the watch was told of before (the initial state): met
            if lib.nt_level_fresh(h, watched, start, lo, hi) < 0:
                return None, None
        n = lib.nt_level_fresh(h, start, end, lo, hi)
        if n < 0:
            return None, None
        self._watched = end
        return ffi.unpack(lib.nt_fresh(h), n), (lo[0], hi[0])

    def _timed_library(self):
        """The library with the net's C, or None (then the code is dropped, with a note)."""
        lib = library(self.code, timed=True)
        if lib is not None:
            note_built(self._hint(), lib)
        else:
            self.notes.append(f"the C of the net's transitions could not be built ({why_unavailable()}): the "
                              "Python engine computes every transition's bindings")
            self.code = None
        return lib

    def _attach(self, lib, s0, old=None) -> None:
        """As `NativeSearch._attach`, and the timed search over it, its caches empty."""
        super()._attach(lib, s0, old)
        # what was copied to the C caches: per group the effects' (keys, time); the adds and the shifts
        self._sent = ([set() for _ in self.tg.groups], set(), set())
        tg = self.tg
        ffi, clib = self.ffi, self.lib
        handle = clib.nt_new(self.handle, int(tg.clock), int(tg.condensation), int(tg.priorities),
                             ffi.new("int32_t[]", [int(t) for t in tg.timed] or [0]), len(tg.timed_places),
                             ffi.new("int32_t[]", tg.timed_places or [0]))
        if handle == ffi.NULL:
            raise MemoryError("cannot allocate the native search")
        self.timed_handle = ffi.gc(handle, clib.nt_free)
        clib.nt_set_watch(self.timed_handle, 1 if self.on_level is not None else 0)
        # the ids of the untimed views of the timed places' markings, and how many of them C has
        if not hasattr(self, "_view_ids"):
            self._view_ids = {p: {} for p in tg.timed_places}
        self._views_sent = {p: 0 for p in tg.timed_places}
        self._watched = 0  # the states whose untimed markings C has met

    def _upgrade(self) -> None:
        """Go on with the net's C compiled in (the states so far copied; the caches are filled anew); under
        `auto`, the C is made first, and built once the search has more states than it has lines."""
        if self._later and (not self._make_code() or self.head < self.generate_after):
            return
        lib = self._timed_library()
        if lib is None:
            return
        self.notes.extend(f"the Python engine computes the bindings of transition '{self.tg.transition_name(t)}': "
                          f"{reason}" for t, reason in sorted(self.code.left.items()))
        old = _Snapshot(self)
        self._attach(lib, self.graph.states[0], old)
        self.round_trips = 0

    def _look_for_built(self) -> None:
        """`auto`, past LOOK_FOR_BUILT_AFTER states, once: where the compile cache records that a run built
        this net's C (`_hint`), the C is made now and the search goes on with it at once if its library is
        there; else nothing is made until the search is large enough to repay building it (`_upgrade`)."""
        self._looked = True
        if noted_built(self._hint()) and self._make_code() and library_built(self.code, timed=True):
            self.generate_after = self.head
            self._upgrade()

    def _hint(self) -> str:
        """A name of this net with its constants' values and the search's kind, under which the compile
        cache records that a run built the net's C (`cbuild.note_built`). Only a hint: the library's own key,
        a hash of the C made, is checked before it is used (`_look_for_built`)."""
        e = self.engine
        # the constants' values in the order of their declarations (uids are numbered per process)
        values = [repr(v) for _uid, v in sorted(e.ev.globals.items()) if not callable(v)]
        text = "\0".join([e.net.source_file, e.net.source, repr(values), repr(self.tg.condensation),
                          repr(self.tg.priorities)])
        return hashlib.sha256(text.encode()).hexdigest()[:24]

    def _make_code(self) -> bool:
        """`auto`: the net's C made at last (not built), and when to build it; False (with the notes) where
        there is none."""
        self._later = False
        self.code, code_notes = timed_generated(self.tg, self.options)
        if self.code is None:
            self.notes.extend(code_notes)
            return False
        self.generate_after = max(GENERATE_AFTER, GENERATE_PER_LINE * self.code.source.count("\n"))
        return True

    def _pending(self) -> bool:
        """Whether the net's C is to be built later in the search (`generate_after`)."""
        return self._later or (self.code is not None and self.gen is None)

    def hand_over_rate(self) -> float:
        return float("inf") if self._pending() else HAND_OVER_RATE

    def _run(self, until: int, max_states: int, max_arcs: int) -> StopReason | None:
        lib, h = self.lib, self.timed_handle
        while True:
            status = lib.nt_run(h, until, max_states, max_arcs)
            if status == ND_NEED:
                self.round_trips += 1
                head = self.head
                if HAND_OVER_FROM <= head <= HAND_OVER_BY and self.round_trips > HAND_OVER_RATE * head \
                        and not self._pending():
                    self.flush()
                    raise HandOver(f"each state needed the engine {self.round_trips / head:.1f} times on average "
                                   "(transitions' results rarely recur)")
                self._fill()
            elif status == ND_LEVEL:
                self.store.sync()  # the watch reads the states: the search may have widened their fields
                if self.gen is not None:  # and their markings, some of them made in C
                    self.code.to_python(self.engine, self.native_lib, self.gen)
                start, end = lib.nt_level_start(h), self.level_end
                stop = self.on_level(start, end, *self._level_summary(start, end))
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
                if status == ND_CHECK and self._pending():
                    if self.head >= self.generate_after:
                        self._upgrade()
                    elif self._later and not self._looked and self.head >= LOOK_FOR_BUILT_AFTER:
                        self._look_for_built()
                return {ND_CHECK: None, ND_DONE: StopReason.COMPLETE, ND_MAX_STATES: StopReason.MAX_STATES,
                        ND_MAX_ARCS: StopReason.MAX_ARCS}[status]

    def _fill(self) -> None:
        """The engine expands the state the C search misses values of; every value it used is cached."""
        lib, ffi = self.lib, self.ffi
        req = ffi.unpack(lib.nd_requests(self.handle), lib.nd_nrequests(self.handle))
        K = self._fields
        s = tuple(req[1:1 + K])
        missing = req[2 + K:2 + K + req[1 + K]]
        if self.head == getattr(self, "_last_fill", -1):
            self.flush()
            raise RuntimeError(f"the native search still misses values of state {self.head} once the engine "
                               "expanded it")
        self._last_fill = self.head
        if self.gen is not None:  # the engine gets the markings and binding elements made in C
            self.code.to_python(self.engine, self.native_lib, self.gen)
        try:
            x = self.tg.expand(s)
        except BaseException:
            self.flush()  # the graph up to the state being expanded, for an error's trace
            raise
        if x.time is not None and not 0 <= x.time < _U32:
            self.flush()
            raise HandOver(f"the model time {x.time} does not fit the native search's 32 bits")
        try:
            self._send(x, missing)
            if self.gen is not None:  # and C the engine's
                self.code.to_c(self.engine, self.native_lib, self.gen)
        except (OverflowError, TypeError) as exc:
            self.flush()
            raise HandOver(f"a value does not fit the native search's 32 bits ({exc})") from None

    def _send(self, x, missing) -> None:
        """Copy the values of expansion `x` the C caches do not hold yet (four calls): the ready lists of
        the groups `missing`, and the effects, adds and shifts not sent before."""
        lib, ffi, h = self.lib, self.ffi, self.timed_handle
        sent_effects, sent_adds, sent_shifts = self._sent
        buf = array("q")
        n = 0
        pairs_of, ids = self.tg.pairs, self.tg.ids
        for g in missing:
            key, pairs = x.keys[g], pairs_of(x.results[g])
            buf.extend((g, len(pairs), *ids(g, key)))
            for r, p in pairs:
                buf.append(_I64_MIN if r == NEG_INF else r)
                buf.append(p)
            n += 1
        if n:
            _check(lib.nt_put_readies(h, ffi.from_buffer("int64_t[]", buf), n))
        buf = array("i")
        n = 0
        for g, key, f, entries in x.effects:
            seen = sent_effects[g]
            if (key, f) in seen:
                continue
            seen.add((key, f))
            buf.extend((g, f if f < 1 << 31 else f - _U32, len(entries), *ids(g, key)))
            for entry in entries:
                buf.extend(entry)
            n += 1
        if n:
            _check(lib.nt_put_effects(h, ffi.from_buffer("int32_t[]", buf), n))
        for items, seen, put in ((x.adds, sent_adds, lib.nt_put_adds), (x.shifts, sent_shifts, lib.nt_put_shifts)):
            buf = array("I")
            n = 0
            for quad in items:
                if quad in seen:
                    continue
                seen.add(quad)
                buf.extend(quad)
                n += 1
            if n:
                _check(put(h, ffi.from_buffer("uint32_t[]", buf), n))

    def cache_bytes(self) -> int:
        return self.lib.nd_cache_bytes(self.handle) + self.lib.nt_cache_bytes(self.timed_handle)

    def uncached(self) -> int:
        """How many caches compute their results anew each time (`native.UNCACHED_AFTER`): of each group,
        its ready lists and its effects."""
        return self.lib.nt_uncached(self.timed_handle)


def timed_generated(tg, options) -> tuple[object | None, list[str]]:
    """The C of a timed net's transitions (a `NativeCode`, or None) and the notes saying what is left to
    Python (as `cpn.statespace.native.generated` for untimed nets)."""
    if options.backend is Backend.PYTHON or os.environ.get("CPN_NO_GENERATED"):
        return None, []
    off = switched_off()
    if off is not None:
        return None, [off]
    code, why = tg.native_code()
    if code is None:
        return None, [f"the Python engine computes every transition's bindings: {why}"]
    return code, [f"the Python engine computes the bindings of transition '{tg.transition_name(t)}': {reason}"
                  for t, reason in sorted(code.left.items())]


def _check(rc: int) -> None:
    if rc != 0:
        raise MemoryError("the native search's caches cannot grow any more")
