"""Which search explores a net, and why not the others: the one place that chooses among the Python
breadth-first loop (`explore`), the native search (`native`, `nativetimed`), the threads of one process
(`threads`), worker processes (`parallel`) and a Ray cluster (`distributed`).

The option and the result are one enum, `Backend` (`cpn.statespace.options`): `ExploreOptions.backend`
is AUTO, PYTHON or C, `Exploration.backend` says which of PYTHON, C, THREADS, WORKERS or RAY ran. Each
`why_not_*` gives the reason a search cannot run these options in one line (None: it can); the explorer
keeps the reason as a note where it chose another search.

- `workers` or `ray` set: `run_partitioned` tries the threads (every transition in the net's generated
  C, `why_not_threaded`), else processes or Ray (`why_not_partitioned`); where neither applies, the
  explorer searches in one process with the note.
- One process: `one_process` gives C where `python_only` and `why_not_native` find nothing against it,
  else PYTHON with the reason; `new_native_search` picks the native search of the net's kind (transition
  groups, or the groups of a timed net or a net with priorities).
"""

from __future__ import annotations

import os

from cpn.engine.protocol import capability, has
from cpn.statespace import native, parallel, threads
from cpn.statespace.nativetimed import TimedNativeSearch
from cpn.statespace.options import Backend, ExploreOptions

_U32 = 1 << 32


def _small_ints(s0) -> bool:
    return isinstance(s0, tuple) and bool(s0) and all(type(v) is int and 0 <= v < _U32 for v in s0)


def python_only(engine, options: ExploreOptions, reduced: bool) -> str | None:
    """Why only the Python search can run these options (reductions, branching options and the model-time
    bound are steps of the Python search), or None. `reduced`: a reduction applies to this net."""
    if reduced:
        return "the native search does not reduce the graph (--reduction)"
    if options.restricted:
        return "the native search has no branching options"
    if options.until_time is not None and engine.is_timed:
        return "the native search has no model-time bound (--until-time)"
    return None


def why_not_native(engine, options: ExploreOptions, s0) -> str | None:
    """Why the native search cannot run this exploration (None if it can)."""
    if options.backend is Backend.PYTHON:
        return "the Python back end was asked for"
    if not options.packed_states:
        return "the states are to be kept as tuples (packed_states=False)"
    if options.stop_predicate is not None and getattr(options.stop_predicate, "may_stop", True):
        return "a stop predicate that may end the search is a Python function of each new state"
    # optional capabilities of an engine (the Engine protocol's other members are required)
    groups = capability(engine, "successor_groups")
    timed = None
    if groups is None or groups() is None:
        timed = capability(engine, "timed_groups")
        if timed is None or timed() is None:
            if getattr(engine, "reads_clock", False):
                read = engine.clock_reads[min(engine.clock_reads)]
                return (f"{read.element} of transition '{read.transition}' reads the model clock, and the "
                        "native search examines transitions at the clock and the occurrence time only")
            return "this engine gives no transition groups (the reference interpreter)"
    if timed is not None and options.backend is not Backend.C and not native.TIMED_AUTO:
        why = why_not_timed_auto(timed())
        if why is not None:
            return why
    if not _small_ints(s0):
        return "the states are not tuples of small non-negative integers"
    if native.library(timed=timed is not None) is None:
        return f"no native code: {native.why_unavailable()}"
    return None


def why_not_timed_auto(tg) -> str | None:
    """Why `auto` leaves a timed net or a net with priorities (its groups `tg`) to the Python search, or
    None: it searches it natively where the net's generated C computes every transition (measured faster
    than the Python search; with transitions whose bindings come from the engine, slower: docs/performance.md)."""
    if native.switched_off() is not None or os.environ.get("CPN_NO_GENERATED"):
        why = "the net's C is switched off"
    else:
        left, why = tg.native_left()  # (one instance of each module's transition: the whole C comes later)
        if left:
            t, reason = min(left.items())
            why = f"transition '{tg.transition_name(t)}' is left to the Python engine: {reason}"
        elif left is not None:
            return None
    return ("timed nets and nets with priorities are searched natively by `auto` only where the net's "
            "generated C computes every transition (else the native search is slower than the Python one, "
            f"docs/performance.md), otherwise with --backend c: {why}")


def needs_action(why: str) -> bool:
    """Whether `why`, a reason `why_not_native` gave, asks something of the user: native code could not be
    built for a reason they can change (no compiler, the compiler failed, an unwritable compile cache, an
    incomplete installation), not because they switched it off or the net has no C."""
    return why.startswith("no native code: ") and native.switched_off() is None


def one_process(engine, options: ExploreOptions, s0, reduced: bool) -> tuple[Backend, str | None]:
    """The search of one process for these options: (C, None), or (PYTHON, why not C)."""
    why = python_only(engine, options, reduced) or why_not_native(engine, options, s0)
    return (Backend.C, None) if why is None else (Backend.PYTHON, why)


def new_native_search(engine, graph, s0, options=None, notes: list[str] | None = None, on_level=None):
    """The native search for this engine: over its transition groups (`native.NativeSearch`), or over the
    groups of a timed net or a net with priorities (`nativetimed.TimedNativeSearch`, which calls
    `on_level(start, end)` at each new BFS level)."""
    if engine.successor_groups() is not None:
        return native.NativeSearch(engine, graph, s0, options, notes)
    return TimedNativeSearch(engine, graph, s0, options, notes, on_level)


def why_not_threaded(engine, options: ExploreOptions, s0) -> tuple[str | None, object]:
    """(why the threads cannot search this net with these options or None, the net's `NativeCode`)."""
    if options.ray is not None:
        return "the workers run on a Ray cluster (--ray)", None
    if not options.threads:
        return "processes were asked for (threads=False)", None
    if options.backend is Backend.PYTHON:
        return "the Python back end was asked for", None
    off = native.switched_off()
    if off is not None:
        return off, None
    if not options.packed_states:
        return "the states are to be kept as tuples (packed_states=False)", None
    groups = capability(engine, "successor_groups")  # an optional capability of the compiled engine
    if groups is None or groups() is None:
        return "this engine gives no transition groups (priorities, or the reference interpreter)", None
    if not _small_ints(s0):
        return "the states are not tuples of small non-negative integers", None
    code, notes = native.generated(engine, options)
    if code is None:
        return (notes[0] if notes else "the net's transitions have no C"), None
    if code.left:
        return notes[0] + (f" (and {len(notes) - 1} more)" if len(notes) > 1 else ""), None
    if native.library(code) is None:
        return f"the net's C could not be built ({native.why_unavailable()})", None
    return None, code


def why_not_partitioned(engine, options: ExploreOptions) -> str | None:
    """Why these options need the one-process search (None if the partitioned search can run them)."""
    from cpn.engine.transfer import transfer_for

    if engine.is_timed:
        return ("timed nets are searched in one process: the time-growth watch and the model-time bound "
                "look at every state of a level in order")
    if options.reduction is not None:
        return ("stubborn sets (--reduction) are computed in one process" if options.reduction == "stubborn"
                else "the quotient by symmetry (--symmetry) is computed in one process")
    if options.restricted:
        return "branching options restrict the search in one process"
    if options.stop_predicate is not None and getattr(options.stop_predicate, "may_stop", True):
        return "a stop predicate ends the search at the first state satisfying it in breadth-first order"
    if transfer_for(engine) is None or not has(engine, "net"):
        return "this engine cannot send its states to other processes (the reference interpreter)"
    return None


def run_partitioned(engine, options: ExploreOptions, progress=None):
    """The partitioned search of `engine` with `options.workers` threads or processes (or on the Ray
    cluster `options.ray`): (Exploration, None), or (None, why) where it does not apply or gave up (the
    caller then searches in one process)."""
    why = why_not_partitioned(engine, options)
    if why is not None:
        return None, f"the search ran in one process: {why}"
    n = options.workers
    if n is not None and n < 1:
        raise ValueError(f"workers must be at least 1, got {n}")
    # the stop predicate (an observing one: why_not_partitioned) is asked about the initial state once,
    # whichever search runs
    pred = options.stop_predicate
    at_s0 = pred is not None and bool(pred(engine.initial_state()))
    why_not, code = why_not_threaded(engine, options, engine.initial_state())
    if why_not is None:
        with parallel.CtrlC() as ctrl_c:
            threaded, why_not = threads.run_threaded(engine, options, code, progress, lambda: ctrl_c.hit, at_s0)
        if threaded is not None:
            return threaded, None
    if options.ray is not None:
        from cpn.statespace.distributed import RayWorkers

        def transport(blob: bytes, cond: bool):
            return RayWorkers(n, blob, cond, options.ray)
    else:
        def transport(blob: bytes, cond: bool):
            return parallel.LocalWorkers(n or 1, blob, cond)
    return parallel.run_partitioned(engine, options, progress, transport, at_s0,
                                    None if options.ray is not None else why_not)


__all__ = ["needs_action", "new_native_search", "one_process", "python_only", "run_partitioned",
           "why_not_native", "why_not_partitioned", "why_not_threaded"]
