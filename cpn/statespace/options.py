"""Exploration options and the reasons a search stops. Imports the standard library only."""

from __future__ import annotations

import enum
import os
from collections.abc import Callable
from dataclasses import dataclass

# The command line stops a search at this share of the memory the process may use (physical memory,
# or less where a container or `ulimit -v` says so). The rest is headroom for the report, which is
# built after the search stops: it added 10-17% to the peak on the unbounded nets measured
# (docs/statespace.md, "Limits").
DEFAULT_MEMORY_SHARE: float = 0.5


class Backend(enum.StrEnum):
    """The search: what `ExploreOptions.backend` asks for and what `Exploration.backend` says ran.

    The option is AUTO, PYTHON or C (the command line's and the scenario files' words "auto", "python",
    "c"); the result is PYTHON, C, or where `workers` or `ray` is set THREADS, WORKERS (processes) or RAY.
    `cpn.statespace.chooser` chooses one and says why not the others. The values are the words the reports
    print, so a member compares equal to its word (`Backend.C == "c"`).
    """

    AUTO = "auto"  # the native search where it can run, else Python (option only)
    PYTHON = "python"  # the breadth-first loop in Python (cpn.statespace.explore)
    C = "c"  # the native search (cpn.statespace.native, nativetimed)
    THREADS = "threads"  # the partitioned search in threads of this process (cpn.statespace.threads; result only)
    WORKERS = "workers"  # the partitioned search in processes (cpn.statespace.parallel; result only)
    RAY = "ray"  # the partitioned search on a Ray cluster (cpn.statespace.distributed; result only)

    @classmethod
    def option_words(cls) -> tuple[str, ...]:
        """The values `ExploreOptions.backend` takes: "auto", "python", "c"."""
        return (cls.AUTO.value, cls.PYTHON.value, cls.C.value)

    @classmethod
    def option(cls, value) -> Backend:
        """`value` (a member or its word) as an option; a ValueError naming the words for anything else."""
        if isinstance(value, str) and value in cls.option_words():
            return cls(value)
        raise ValueError(f"backend must be one of {', '.join(repr(w) for w in cls.option_words())}, "
                         f"got {value!r}")


class StopReason(enum.Enum):
    """Why an exploration ended. Only COMPLETE means every reachable state was expanded."""

    COMPLETE = "complete"
    MAX_STATES = "max_states"
    MAX_ARCS = "max_arcs"
    MAX_SECONDS = "max_seconds"
    MAX_MEMORY = "max_memory"
    PREDICATE = "predicate"
    INTERRUPTED = "interrupted"
    TIME_GROWS = "time_grows"
    UNTIL_TIME = "until_time"

    def describe(self, options: ExploreOptions | None = None) -> str:
        """One sentence saying why the search stopped, with the limit that stopped it."""
        o = options or ExploreOptions()
        if self is StopReason.COMPLETE:
            return "nothing left to explore"
        if self is StopReason.PREDICATE:
            return "a state satisfied the stop predicate"
        if self is StopReason.INTERRUPTED:
            return "interrupted by the user"
        if self is StopReason.TIME_GROWS:
            return "the state space grows only because time grows"
        if self is StopReason.UNTIL_TIME:
            return (f"the model-time bound until_time={o.until_time} was reached: the states whose clock "
                    "exceeds it were not expanded")
        limit = {StopReason.MAX_STATES: o.max_states, StopReason.MAX_ARCS: o.max_arcs,
                 StopReason.MAX_SECONDS: o.max_seconds, StopReason.MAX_MEMORY: o.max_memory_mb}[self]
        return f"{self.value.replace('max_memory', 'max_memory_mb')}={limit:g} was reached" if limit is not None else f"{self.value} was reached"


@dataclass(frozen=True)
class ExploreOptions:
    """Limits of one exploration. None means no limit.

    `stop_predicate(state) -> bool` is evaluated on every newly stored state (and the initial
    state); the search stops at the first state for which it is true. `until_time` bounds model time: a
    state whose clock exceeds it is stored but never expanded (the timed state space up to that time).
    Branching options (CPN Tools' state space tool has them): `branching_predicate(be) -> bool`, on
    binding element ids (`engine.binding_element(be)` gives the transition and the binding), keeps only the
    binding elements for which it is true; `max_successors` keeps at most that many arcs per state (the
    first ones, in the engine's fixed order). Either makes the result a restricted state space, and
    `branching_text` says how it was restricted in the report. `time_condensation` is only
    recorded here (the engine applies it when built); `detect_time_growth` lets the explorer stop
    a timed search whose untimed markings no longer change while the clock keeps growing.
    `reduction` and `visible_places` select a partial-order reduction (see the fields).
    `packed_states` keeps the states as packed records in native memory where that can be built
    (`cpn.statespace.store`); the Python search packs them once it has `pack_from` states (0: from the
    start), since packing from Python costs time (6-26% on DP and MS) that only large searches repay in
    memory (about half). The graph is the same either way. `backend` (a `Backend` or its word) is "auto"
    (the native search, `cpn.statespace.native`, where it can run, else Python, with a note saying why),
    "c" (the same, the note printed as a warning) or "python"; the graph is the same with either, and
    `cpn.statespace.chooser` makes the choice.
    """

    max_states: int | None = None
    max_arcs: int | None = None
    max_seconds: float | None = None
    max_memory_mb: float | None = None
    stop_predicate: Callable[[tuple], bool] | None = None
    time_condensation: bool = False
    detect_time_growth: bool = True
    until_time: int | None = None
    branching_predicate: Callable[[int], bool] | None = None
    max_successors: int | None = None
    branching_text: str | None = None

    @property
    def restricted(self) -> bool:
        """True if branching options restrict which successors are explored."""
        return self.branching_predicate is not None or self.max_successors is not None

    def restriction(self) -> str | None:
        """The branching options in words, for reports (None if there are none)."""
        if not self.restricted:
            return None
        parts = []
        if self.branching_predicate is not None:
            parts.append(self.branching_text or "only the binding elements satisfying the branching predicate")
        if self.max_successors is not None:
            parts.append(f"at most {self.max_successors} successor{'s' if self.max_successors != 1 else ''} "
                         "per state")
        return "; ".join(parts)
    progress_interval: float = 0.5
    # "stubborn": follow only the binding elements of a stubborn set in each state (cpn.engine.stubborn),
    # which preserves the dead markings; with `visible_places` (place indices a property reads) also
    # the invariants over those places (visibility condition and cycle proviso)
    reduction: str | None = None
    visible_places: frozenset | None = None
    # "symmetry": the symmetric colour sets (`cpn.net.symmetry.Scalar`), checked beforehand with
    # `cpn.net.symmetry.symmetry_problems`; the graph is the quotient (one state per orbit)
    symmetry: tuple = ()
    packed_states: bool = True
    pack_from: int = 1_000_000
    backend: Backend = Backend.AUTO
    # the partitioned search (cpn.statespace.parallel): `workers` processes (None: this process alone), on
    # the Ray cluster at `ray` ("auto": a local Ray instance) when that is set
    workers: int | None = None
    ray: str | None = None
    # `workers` are threads of this process (cpn.statespace.threads) where the net is wholly in generated C
    # and the options allow; False: always processes
    threads: bool = True

    def __post_init__(self):
        object.__setattr__(self, "backend", Backend.option(self.backend))


def machine_memory_mb() -> float | None:
    """The memory this process may use, in MiB: the smallest of physical memory, the memory limit of
    its control group (cgroup v2 `memory.max` or v1 `memory.limit_in_bytes`) and `RLIMIT_AS`.
    None where none of them can be read."""
    limits = []
    try:
        limits.append(os.sysconf("SC_PHYS_PAGES") * os.sysconf("SC_PAGE_SIZE"))
    except (AttributeError, ValueError, OSError):
        pass
    limits += _cgroup_limits()
    try:
        import resource

        soft, _hard = resource.getrlimit(resource.RLIMIT_AS)
        if soft != resource.RLIM_INFINITY and soft > 0:
            limits.append(soft)
    except (ImportError, ValueError, OSError):
        pass
    return min(limits) / 1048576 if limits else None


def _cgroup_limits() -> list[int]:
    """Memory limits of this process's control group, v2 and v1 (a file that says 'max' or a huge
    number means no limit)."""
    files = ["/sys/fs/cgroup/memory.max", "/sys/fs/cgroup/memory/memory.limit_in_bytes"]
    try:
        with open("/proc/self/cgroup", encoding="ascii") as fh:
            for line in fh:
                _id, controllers, path = line.rstrip("\n").split(":", 2)
                if path in ("", "/"):
                    continue
                if controllers == "":
                    files.append(f"/sys/fs/cgroup{path}/memory.max")
                elif "memory" in controllers.split(","):
                    files.append(f"/sys/fs/cgroup/memory{path}/memory.limit_in_bytes")
    except (OSError, ValueError):
        pass
    out = []
    for name in files:
        try:
            with open(name, encoding="ascii") as fh:
                text = fh.read().strip()
        except OSError:
            continue
        if text.isdigit() and 0 < int(text) < 1 << 60:
            out.append(int(text))
    return out


def default_max_memory_mb() -> float | None:
    """DEFAULT_MEMORY_SHARE of `machine_memory_mb()`, rounded down to a whole MiB (None if unknown)."""
    total = machine_memory_mb()
    return None if total is None else float(int(total * DEFAULT_MEMORY_SHARE))
