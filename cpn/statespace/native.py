"""The native search (`--backend c`): the breadth-first loop, the state store, the transitions' result
caches and the arcs in C (`_search.c`), the engine consulted only for what is not cached yet.

The engine gives its successor function as transition groups (`Engine.successor_groups`, LTSmin's
partitioned next-state function): a transition's enabled binding elements and their effects depend only
on the markings of the places it reads. The C search caches them per tuple of those place ids, and the
ids of written places per (place, delta, old id); on a miss it returns to Python, which asks the engine
and fills the cache, and the state is expanded once everything it needs is cached. So the graph is the
Python search's own: the same states in the same order, the same arcs, the same binding elements.

Where the engine can give it (`CompiledEngine.native_code`, `cpn.engine.ccodegen`), the transitions'
results and the written places' ids are computed by C generated from the net's inscriptions, compiled
into the same library: the search then returns to Python only for the transitions left to the Python
engine (each named with the reason in `notes`) and for what the C code cannot evaluate. Both keep
the same tables of markings, deltas and binding elements with the same ids (copied across before and
after every return to Python), so the graph is the same either way.

Where the native search cannot run, `cpn.statespace.chooser.why_not_native` says why in one line and the
explorer uses the Python loop.
"""

from __future__ import annotations

import gc
import os
from array import array

from cpn._util.cbuild import build, built, switched_off, why_unavailable
from cpn.engine.protocol import capability
from cpn.statespace.options import Backend, StopReason
from cpn.statespace.store import PackedStore

#: `auto` builds the net's C once the search has expanded this many states, or GENERATE_PER_LINE times the
#: lines of C if that is more (a large net's C takes seconds to compile), or once each state needs the
#: engine more than once on average (its results rarely recur: DP)
GENERATE_AFTER: int = 16_384
GENERATE_PER_LINE: int = 4
#: `auto` in a timed search makes the net's C (without building it) once the search has expanded this many
#: states, and goes on with it at once if its library is already built (a run before built it: the compile
#: cache), else at GENERATE_AFTER as above
LOOK_FOR_BUILT_AFTER: int = 4096
#: with the net's C, a transition whose cached results missed more than half of its first this many
#: lookups (its input places' markings rarely recur: DP) has them computed anew each time, not stored;
#: the same for the written places' new ids (0: every result is cached)
UNCACHED_AFTER: int = 4096

ND_DONE, ND_CHECK, ND_MAX_STATES, ND_MAX_ARCS, ND_NEED, _, ND_WIDE_BE = range(7)
_U32 = 1 << 32


def library(code=None, timed: bool = False):
    """The native search's library; with `code` (a `NativeCode`), the net's generated C compiled in, and
    the multi-threaded search (`_threads.c`, `cpn.statespace.threads`) with it; with `timed`, the search
    of timed nets and nets with priorities (`_timed.c`, `cpn.statespace.nativetimed`). The libraries and
    their units are the build manifest's (`cpn._native.manifest`)."""
    if code is None:
        return build("search-timed" if timed else "search")
    return build(_net_library(timed), code.source)


def library_built(code, timed: bool = False) -> bool:
    """Whether `library(code, timed)` is already built (then it only loads)."""
    return built(_net_library(timed), code.source)


def _net_library(timed: bool) -> str:
    """The manifest's library that takes a net's C."""
    return "search-timed-net" if timed else "search-net-threads"


def generated(engine, options) -> tuple[object | None, list[str]]:
    """The net's generated C (a `NativeCode`, or None) and the notes saying what is left to Python."""
    if options.backend is Backend.PYTHON or os.environ.get("CPN_NO_GENERATED"):
        return None, []
    off = switched_off()
    if off is not None:
        return None, [off]
    make = capability(engine, "native_code")  # an optional capability of the compiled engine
    if make is None:
        return None, ["the C back end has no code of this engine's transitions (the reference interpreter)"]
    code, why = make()
    if code is None:
        return None, [f"the Python engine computes every transition's bindings: {why}"]
    names = engine.transitions
    notes = [f"the Python engine computes the bindings of transition '{names[t].name}': {reason}"
             for t, reason in sorted(code.left.items())]
    return code, notes


#: the native search hands over to the Python search if, by the time it has expanded at most HAND_OVER_BY
#: states, it has returned to the engine more than HAND_OVER_RATE times per state (DP: about 3; MS: 0.2-0.5)
HAND_OVER_BY: int = 8192
HAND_OVER_RATE: float = 1.5

#: whether `auto` searches every timed net and net with priorities natively (`--backend c` always does);
#: False: only those whose transitions are all in the net's generated C (`chooser.why_not_timed_auto`):
#: with bindings from the Python engine, the native search of them measured 1.0 to 1.9 times the Python
#: search's time (`python bench/modbus.py --native`), wholly in C faster (`python bench/timed.py`,
#: docs/performance.md)
TIMED_AUTO: bool = False


class HandOver(Exception):  # noqa: N818 - a request, not an error
    """The native search cannot go on with this net: the Python search goes on from its head."""


class _Snapshot:
    """What a search being replaced leaves to its successor: its store and where it stands."""

    def __init__(self, search):
        self.lib, self.ffi, self.store = search.lib, search.ffi, search.store
        self.handle = search.handle  # kept alive while the states are copied
        self.head, self.level_end, self.levels, self.n_arcs = (search.head, search.level_end, search.levels,
                                                               search.n_arcs)


class NativeSearch:
    """One native breadth-first search filling a `StateGraph` (see the module's docstring)."""

    def __init__(self, engine, graph, s0, options=None, notes: list[str] | None = None):
        self.engine = engine
        self.graph = graph
        self.notes = notes if notes is not None else []
        self.tg = engine.successor_groups()
        self.tg.caller_caches()
        self.round_trips = 0  # returns to Python for what the caches miss
        self.code, self._code_notes = generated(engine, options) if options is not None else (None, [])
        self.gen = None
        if self.code is None:
            self.notes.extend(self._code_notes)
        # `--backend c` builds the net's C at once; `auto` once the search is large enough to repay it
        self.generate_after = 0 if options is not None and options.backend is Backend.C else \
            max(GENERATE_AFTER, GENERATE_PER_LINE * (self.code.source.count("\n") if self.code else 0))
        if self.code is not None and self.generate_after == 0:
            lib = self._generated_library()
            if lib is not None:
                self._attach(lib, s0)
                return
        self._attach(library(), s0)

    def _generated_library(self):
        """The library with the net's C, or None (then the code is dropped, with a note)."""
        lib = library(self.code)
        if lib is None:
            self.notes.append(f"the C of the net's transitions could not be built ({why_unavailable()}): the "
                              "Python engine computes every transition's bindings")
            self.code = None
        else:
            self.notes.extend(self._code_notes)
        return lib

    def _attach(self, lib, s0, old=None) -> None:
        """Set up the store and the search in library `lib`; with `old` (the search so far, in another
        library), its states are copied over in their order and the search goes on from its head."""
        self.native_lib = lib
        self.ffi, self.lib = ffi, clib = lib.ffi, lib.lib
        # a field starts as narrow as the initial state allows; the search widens it when a value needs it
        store = PackedStore(lib, s0, widths=old.store.widths if old is not None else None)
        if old is not None:
            n = len(old.store)
            if n > 1:  # the records are laid out alike (the same widths): copy them as they are
                arena = old.lib.cs_arena(old.store.handle)
                W = old.lib.cs_width(old.store.handle)
                src = ffi.cast("uint8_t *", int(old.ffi.cast("uintptr_t", arena))) + W
                ids, fresh = ffi.new("int32_t[]", n), ffi.new("int32_t[]", n)
                if clib.cs_add_many(store.handle, src, n - 1, ids, fresh) != n - 1:
                    raise RuntimeError("the native search's states could not be copied")
        self.graph.store = self.store = store
        groups = self.tg.groups
        fields = [p for read, writes in groups for p in (*read, *writes)]
        handle = clib.nd_new(store.handle, len(s0), len(groups),
                             ffi.new("int32_t[]", [len(r) for r, _ in groups] or [0]),
                             ffi.new("int32_t[]", [len(w) for _, w in groups] or [0]),
                             ffi.new("int32_t[]", fields or [0]))
        if handle == ffi.NULL:
            raise MemoryError("cannot allocate the native search")
        self.handle = ffi.gc(handle, clib.nd_free)
        if old is not None:
            clib.nd_resume(self.handle, old.head, old.level_end, old.levels, old.n_arcs,
                           1 if self.graph.bes.itemsize == 4 else 0)
        self.gen = None
        if lib is not None and self.code is not None and hasattr(clib, "gen_new"):
            gen = clib.gen_new()
            if gen == ffi.NULL:
                raise MemoryError("cannot allocate the native transitions' tables")
            self.gen = ffi.gc(gen, clib.gen_free)
            self.code.to_c(self.engine, lib, self.gen)
            clib.nd_set_gen(self.handle, self.gen)
            clib.nd_set_uncache_after(self.handle, UNCACHED_AFTER)

    def _upgrade(self) -> None:
        """Go on with the net's C compiled in (the states so far copied; the caches are filled anew)."""
        lib = self._generated_library()
        if lib is None:
            return
        old = _Snapshot(self)
        self._attach(lib, self.graph.states[0], old)
        self.round_trips = 0

    def hand_over_rate(self) -> float:
        """Returns to the engine per state past which the explorer hands over to the Python search."""
        return HAND_OVER_RATE

    @property
    def head(self) -> int:
        return self.lib.nd_head(self.handle)

    @property
    def level_end(self) -> int:
        return self.lib.nd_level_end(self.handle)

    @property
    def levels(self) -> int:
        return self.lib.nd_levels(self.handle)

    @property
    def n_arcs(self) -> int:
        return self.lib.nd_total_arcs(self.handle)

    def run(self, until: int, max_states: int, max_arcs: int) -> StopReason | None:
        """Expand states up to state `until` (None: there, the caller looks at its limits) or to a stop."""
        gc_was_enabled = gc.isenabled()
        gc.disable()  # the engine's tables grow by many small dicts, none of them in a cycle
        try:
            return self._run(until, max_states, max_arcs)
        finally:
            if gc_was_enabled:
                gc.enable()

    def _run(self, until: int, max_states: int, max_arcs: int) -> StopReason | None:
        lib, h = self.lib, self.handle
        while True:
            status = lib.nd_run(h, until, max_states, max_arcs)
            if status == ND_NEED:
                self.round_trips += 1
                self._fill()
            elif status == ND_WIDE_BE:
                self.flush()
                g = self.graph
                g.bes = array("i", g.bes)  # binding-element ids outgrew 16 bits: widen once
                lib.nd_set_be32(h)
            elif status < 0:
                self.flush()
                raise MemoryError("the native search cannot grow any more")
            else:
                self.flush()
                if status == ND_CHECK and self.code is not None and self.gen is None \
                        and (self.head >= self.generate_after or self.round_trips > self.head):
                    self._upgrade()
                return {ND_CHECK: None, ND_DONE: StopReason.COMPLETE, ND_MAX_STATES: StopReason.MAX_STATES,
                        ND_MAX_ARCS: StopReason.MAX_ARCS}[status]

    def _fill(self) -> None:
        """Ask the engine for what the state being expanded misses: transitions' results for markings of
        their input places not seen before, then the ids of written places."""
        lib, h, ffi, tg = self.lib, self.handle, self.ffi, self.tg
        req = ffi.unpack(lib.nd_requests(h), lib.nd_nrequests(h))
        i = 0
        if self.gen is not None:
            self.code.to_python(self.engine, self.native_lib, self.gen)
        try:
            while i < len(req):
                if req[i] == 0:
                    k = req[i + 1]
                    nr = len(tg.groups[k][0])
                    key = req[i + 2:i + 2 + nr]
                    i += 2 + nr
                    flat = tg.results(k, tuple(key))
                    width = 1 + nr + len(tg.groups[k][1])
                    try:
                        buf = array("i", flat or (0,))
                    except OverflowError:
                        raise OverflowError("an id does not fit the native search's 32 bits") from None
                    if flat and min(buf) < 0:
                        raise OverflowError("a negative id cannot be stored by the native search")
                    if lib.nd_put_group(h, k, ffi.from_buffer("uint32_t[]", array("I", key or (0,))),
                                        len(flat) // width, ffi.from_buffer("int32_t[]", buf)) != 0:
                        raise MemoryError("the native search's caches cannot grow any more")
                else:
                    p, did, old = req[i + 1:i + 4]
                    i += 4
                    nid = tg.add(p, old, did)
                    if not 0 <= nid < _U32:
                        raise OverflowError(f"place id {nid} does not fit the native search's 32 bits")
                    if lib.nd_put_add(h, p, did, old, nid) != 0:
                        raise MemoryError("the native search's caches cannot grow any more")
        except BaseException:
            self.flush()  # the graph up to the state being expanded, for an error's trace
            raise
        if self.gen is not None:
            self.code.to_c(self.engine, self.native_lib, self.gen)

    def flush(self) -> None:
        """Move the arcs, offsets and BFS parents of the states expanded since the last flush to the graph."""
        lib, h, ffi, g = self.lib, self.handle, self.ffi, self.graph
        self.store.sync()  # the search may have widened the records' fields
        if self.gen is not None:  # the engine gets the markings and binding elements made in C
            self.code.to_python(self.engine, self.native_lib, self.gen)
        n = lib.nd_narcs(h)
        if n:
            g.dst.frombytes(ffi.buffer(lib.nd_dst(h), 4 * n))
            g.bes.frombytes(ffi.buffer(lib.nd_bes(h), g.bes.itemsize * n))
        m = lib.nd_noff(h)
        if m:
            g.offsets.frombytes(ffi.buffer(lib.nd_offsets(h), 8 * m))
        k = lib.nd_nnew(h)
        if k:
            g.parent.frombytes(ffi.buffer(lib.nd_parent(h), 4 * k))
            g.parent_be.frombytes(ffi.buffer(lib.nd_parent_be(h), 4 * k))
        lib.nd_clear_batch(h)

    def cache_bytes(self) -> int:
        return self.lib.nd_cache_bytes(self.handle)

    def uncached(self) -> int:
        """How many caches compute their results anew each time (UNCACHED_AFTER)."""
        return self.lib.nd_uncached(self.handle)
