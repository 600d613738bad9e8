"""The multi-threaded native search (`--workers N` on a net whose every transition is in generated C).

N threads of this process, inside the C of `_threads.c` (cffi releases the GIL while the search runs),
search breadth-first level by level: each owns the states whose hash falls to it (a store of its own,
so the stores need no lock), keeps its own caches of the transitions' results, and sends the
successors another thread owns to it between two barriers. On a cache miss a thread runs the net's C
itself, in a context of its own over the one set of tables of markings, deltas and binding elements (one
numbering for all threads), which `_cnet.c` changes under a lock per table and reads without one. The
states are then numbered breadth-first (expanded ones first, by level, thread and order of storing;
then the unexpanded ones) into one ordinary `StateGraph`, the same arrays the one-process native search
fills: every analysis runs unchanged. The graph has the
states, arcs, dead markings and bounds of the one-process search (the numbering of states and the order
of arcs aside), and its parent pointers give shortest paths.

`cpn.statespace.chooser.why_not_threaded` says where the threads do not apply (a transition left to the
Python engine, no C compiler, ...); `run_threaded` returns (None, why) where the net's C met a binding it
cannot evaluate (a division by zero, a value outside its colour set, deep recursion: the one-process
search hands such a key to the Python engine, which the threads cannot call): the caller then runs the
process search.

While the threads run, this thread looks at the limits (seconds, memory), Ctrl-C and the progress hook
every `POLL_MS` milliseconds and asks them to stop; the states and arcs limits are looked at by the
threads themselves every few dozen states. A stopped search finishes the exchange of its level first (the
successors on their way are stored, unexpanded), so the partial graph is consistent, as in one process.
"""

from __future__ import annotations

import threading
import time
from array import array

from cpn.statespace import native
from cpn.statespace._memory import current_rss_mb, peak_rss_mb
from cpn.statespace.graph import StateGraph
from cpn.statespace.options import Backend, ExploreOptions, StopReason
from cpn.statespace.result import Exploration, Progress, observe
from cpn.statespace.store import PackedStore

#: how often (milliseconds) the calling thread looks at the limits, Ctrl-C and the progress hook
POLL_MS: int = 50

_RUNNING, _STOPPED, _FALLBACK, _NO_MEMORY = -9, 8, 7, 5
_STOPS = {native.ND_DONE: StopReason.COMPLETE, native.ND_MAX_STATES: StopReason.MAX_STATES,
          native.ND_MAX_ARCS: StopReason.MAX_ARCS}


def run_threaded(engine, options: ExploreOptions, code, progress=None, stop_watch=None,
                 stopped_at_s0: bool = False):
    """The threaded search of `engine` with `options.workers` threads running `code` (the net's
    `NativeCode`, every transition in it: `cpn.statespace.chooser.why_not_threaded` found nothing against
    it): (Exploration, None), or (None, why) where it must be repeated another way. `stop_watch()` (optional) says whether
    Ctrl-C was pressed (the caller's handler); a KeyboardInterrupt stops the search the same way.
    `stopped_at_s0`: the (observing) stop predicate holds in the initial state, as the caller found when
    it asked it (once, whichever search then runs)."""
    t0 = time.perf_counter()
    s0 = engine.initial_state()
    n = options.workers or 1
    lib = native.library(code)
    ffi, clib = lib.ffi, lib.lib
    gen = clib.gen_new()
    if gen == ffi.NULL:
        raise MemoryError("cannot allocate the native transitions' tables")
    gen = ffi.gc(gen, clib.gen_free)
    code.to_c(engine, lib, gen)
    groups = engine.successor_groups().groups
    fields = [p for read, writes in groups for p in (*read, *writes)]
    big = 1 << 62
    h = clib.th_new(n, len(s0), len(groups),
                    ffi.new("int32_t[]", [len(r) for r, _ in groups] or [0]),
                    ffi.new("int32_t[]", [len(w) for _, w in groups] or [0]),
                    ffi.new("int32_t[]", fields or [0]), gen, ffi.new("uint32_t[]", list(s0)),
                    bytes(1 if v < 1 << 8 else 2 if v < 1 << 16 else 4 for v in s0),  # as narrow as s0 allows
                    1 if stopped_at_s0 else options.max_states if options.max_states is not None else big,
                    options.max_arcs if options.max_arcs is not None else big, native.UNCACHED_AFTER)
    if h == ffi.NULL:
        raise MemoryError("cannot allocate the threaded search")
    h = ffi.gc(h, clib.th_free)
    if clib.th_start(h) != 0:
        ffi.release(h)  # now, while `gen` (whose tables it shares) is alive: the order of collection is not known
        return None, "the threads could not be started"
    asked = None
    deadline = t0 + options.max_seconds if options.max_seconds is not None else None
    next_progress = t0 + options.progress_interval
    counts = ffi.new("int64_t[4]")
    status = _RUNNING
    while status == _RUNNING:
        try:
            if asked is not None:
                status = clib.th_wait(h, POLL_MS)
                continue
            now = time.perf_counter()
            if stop_watch is not None and stop_watch():
                asked = StopReason.INTERRUPTED
            elif deadline is not None and now >= deadline:
                asked = StopReason.MAX_SECONDS
            elif options.max_memory_mb is not None and current_rss_mb() >= options.max_memory_mb:
                asked = StopReason.MAX_MEMORY
            if asked is not None:
                clib.th_request_stop(h)
            if progress is not None and now >= next_progress:
                next_progress = now + options.progress_interval
                clib.th_progress(h, counts)
                progress(Progress(counts[0], counts[1], counts[0] - counts[2], now - t0, current_rss_mb()))
            status = clib.th_wait(h, POLL_MS)
        except KeyboardInterrupt:
            asked = StopReason.INTERRUPTED
            clib.th_request_stop(h)
        except BaseException:  # the progress hook failed: the threads stop before their tables go
            clib.th_request_stop(h)
            while clib.th_wait(h, POLL_MS) == _RUNNING:
                pass
            raise
    t_search = time.perf_counter()
    if status == _FALLBACK:
        return None, ("the net's C met a binding it cannot evaluate (a value outside its colour set, a "
                      "division by zero, deep recursion), which the threads cannot hand to the Python engine")
    if status == _NO_MEMORY:
        raise MemoryError("the threaded search cannot grow any more")
    stop = StopReason.PREDICATE if stopped_at_s0 else asked if status == _STOPPED else _STOPS[status]
    # the markings and binding elements the threads made go to the engine (Python) while the graph is
    # assembled (C, without the GIL) in another thread
    assembled: list = []

    def assemble():
        try:
            assembled.append(_assemble(lib, h, s0, n))
        except BaseException as exc:  # noqa: BLE001 (raised again in the calling thread)
            assembled.append(exc)

    worker = threading.Thread(target=assemble, daemon=True)
    worker.start()
    try:
        code.to_python(engine, lib, gen)
    finally:
        worker.join()
    if isinstance(assembled[0], BaseException):
        raise assembled[0]
    g, sizes = assembled[0]
    h = None
    t_assemble = time.perf_counter()
    predicate_state = observe(options, g, stop)
    if predicate_state is not None:
        stop = StopReason.PREDICATE
    seconds = time.perf_counter() - t0
    if progress is not None:
        progress(Progress(g.n_states, g.n_arcs, g.n_states - g.expanded, seconds, current_rss_mb()))
    note = (f"the search ran in {n} thread{'s' if n > 1 else ''} of this process, the states partitioned by "
            "a hash of each state")
    return Exploration(engine=engine, graph=g, options=options, stop_reason=stop, seconds=seconds,
                       peak_memory_mb=peak_rss_mb(), predicate_state=predicate_state, levels=sizes[4],
                       notes=[note], backend=Backend.THREADS,
                       partition={"workers": n, "threads": n, "worker_states": sizes[5:5 + n],
                                  "computed": sizes[5 + n:5 + 2 * n],
                                  "uncached": sizes[5 + 3 * n:5 + 4 * n],
                                  "cpu_seconds": {"expand": [round(us / 1e6, 3) for us in sizes[5 + 4 * n:5 + 5 * n]],
                                                  "receive": [round(us / 1e6, 3) for us in sizes[5 + 5 * n:5 + 6 * n]]},
                                  "barrier_seconds": [round(us / 1e6, 3) for us in sizes[5 + 2 * n:5 + 3 * n]],
                                  "seconds": {"search": round(t_search - t0, 3),
                                              "assemble": round(t_assemble - t_search, 3)}}), None


def _assemble(lib, h, s0: tuple, n: int) -> tuple[StateGraph, list[int]]:
    """The one graph of the threads' parts (see the module's docstring) and the search's figures."""
    ffi, clib = lib.ffi, lib.lib
    out = ffi.new("int64_t[]", 5 + 6 * n)
    clib.th_sizes(h, out)
    sizes = list(out)
    n_states, expanded, arcs, be_max = sizes[:4]
    widths = ffi.new("uint8_t[]", len(s0))
    if clib.th_widths(h, widths) != 0:
        raise MemoryError("the threaded search's graph cannot be assembled (no memory)")
    g = StateGraph()
    g.store = PackedStore(lib, s0, widths=list(widths))
    g.offsets = array("q", [0]) * (expanded + 1)  # (a repeat: a third of the time of array(bytes(n)))
    g.dst = array("i", [0]) * arcs
    be16 = be_max < 1 << 16
    g.bes = array("H" if be16 else "i", [0]) * arcs
    g.parent = array("i", [0]) * n_states
    g.parent_be = array("i", [0]) * n_states

    def buf(kind, a):
        return ffi.from_buffer(kind, a) if len(a) else ffi.NULL

    rc = clib.th_assemble(h, g.store.handle, buf("int64_t[]", g.offsets), buf("int32_t[]", g.dst),
                          buf("uint8_t[]", g.bes), 1 if be16 else 0,
                          buf("int32_t[]", g.parent), buf("int32_t[]", g.parent_be))
    if rc == -1:
        raise MemoryError("the threaded search's graph cannot be assembled (no memory)")
    if rc != 0 or len(g.store) != n_states:
        raise RuntimeError("the threaded search's parts do not make one graph (an arc was left open)")
    g.store.finish()
    return g, sizes


__all__ = ["POLL_MS", "run_threaded"]
