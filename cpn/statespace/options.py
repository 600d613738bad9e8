"""Exploration options and the reasons a search stops. Imports the standard library only."""

from __future__ import annotations

import enum
from collections.abc import Callable
from dataclasses import dataclass


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
        limit = {StopReason.MAX_STATES: o.max_states, StopReason.MAX_ARCS: o.max_arcs,
                 StopReason.MAX_SECONDS: o.max_seconds, StopReason.MAX_MEMORY: o.max_memory_mb}[self]
        return f"{self.value.replace('max_memory', 'max_memory_mb')}={limit:g} was reached" if limit is not None else f"{self.value} was reached"


@dataclass(frozen=True)
class ExploreOptions:
    """Limits of one exploration. None means no limit.

    `stop_predicate(state) -> bool` is evaluated on every newly stored state (and the initial
    state); the search stops at the first state for which it is true. `time_condensation` is only
    recorded here (the engine applies it when built); `detect_time_growth` lets the explorer stop
    a timed search whose untimed markings no longer change while the clock keeps growing.
    """

    max_states: int | None = None
    max_arcs: int | None = None
    max_seconds: float | None = None
    max_memory_mb: float | None = None
    stop_predicate: Callable[[tuple], bool] | None = None
    time_condensation: bool = False
    detect_time_growth: bool = True
    progress_interval: float = 0.5
