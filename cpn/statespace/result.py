"""What an exploration gives: the `Exploration` (the graph, why the search stopped, what it cost, which
search ran) and the `Progress` snapshots on the way. Every search of this package (`explore`, `native`,
`threads`, `parallel`) returns an `Exploration`; the checks and the reports read it."""

from __future__ import annotations

from dataclasses import dataclass, field

from cpn.engine import Engine
from cpn.statespace.graph import StateGraph
from cpn.statespace.options import Backend, ExploreOptions, StopReason


@dataclass(frozen=True)
class Progress:
    """A snapshot for progress displays."""

    states: int
    arcs: int
    queue: int
    seconds: float
    memory_mb: float

    @property
    def states_per_second(self) -> float:
        return self.states / self.seconds if self.seconds > 0 else 0.0


@dataclass
class Exploration:
    """The result of one exploration: the graph, why it stopped and what it cost.

    `complete` says every reachable state was expanded; otherwise `stop_reason` says which limit
    stopped the search and `unexpanded` how many states wait in the queue.
    """

    engine: Engine
    graph: StateGraph
    options: ExploreOptions
    stop_reason: StopReason
    seconds: float
    peak_memory_mb: float
    predicate_state: int | None = None
    untimed_states: int | None = None
    time_growth: dict | None = None
    levels: int = 0
    notes: list = field(default_factory=list)
    #: notes on which search ran and why, that change no result and ask nothing of the user (the Python
    #: search of a timed net under `auto`, transitions whose bindings come from Python, a hand-over); the
    #: command line prints them with --verbose; a note that carries an action (no compiler, an unwritable
    #: compile cache, an incomplete installation) or answers `--backend c` is in `notes`
    backend_notes: list = field(default_factory=list)
    #: which search ran (`Backend`: its word is what the reports print): C (cpn.statespace.native), PYTHON,
    #: or the partitioned search: THREADS (cpn.statespace.threads), WORKERS (processes,
    #: cpn.statespace.parallel) or RAY (cpn.statespace.distributed); cpn.statespace.chooser chose it
    backend: Backend = Backend.PYTHON
    # the partial-order reduction that ran ("stubborn"), None for the full graph; its figures
    reduction: str | None = None
    reduction_stats: dict | None = None
    #: the partitioned search's figures (cpn.statespace.parallel): workers, successors and bytes sent between them
    partition: dict | None = None

    @property
    def restricted(self) -> bool:
        """Branching options left out some successors: this is a restricted state space."""
        return self.options.restricted

    @property
    def complete(self) -> bool:
        return self.stop_reason is StopReason.COMPLETE

    @property
    def n_states(self) -> int:
        return self.graph.n_states

    @property
    def n_arcs(self) -> int:
        return self.graph.n_arcs

    @property
    def unexpanded(self) -> int:
        return self.graph.n_states - self.graph.expanded


def observe(options: ExploreOptions, g: StateGraph, stop: StopReason) -> int | None:
    """Call the observing stop predicate on every state of an assembled graph but the initial one (the
    search asked it about that one), in breadth-first order as the one-process search does: the first
    state satisfying it (0: the initial state stopped the search), or None."""
    pred = options.stop_predicate
    if stop is StopReason.PREDICATE:
        return 0
    if pred is not None:
        for j, s in enumerate(g.states):
            if j and pred(s):
                return j
    return None
