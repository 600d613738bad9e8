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
        return {
            StopReason.COMPLETE: "nothing left to explore",
            StopReason.MAX_STATES: f"max_states={o.max_states} was reached",
            StopReason.MAX_ARCS: f"max_arcs={o.max_arcs} was reached",
            StopReason.MAX_SECONDS: f"max_seconds={o.max_seconds:g} was reached",
            StopReason.MAX_MEMORY: f"max_memory_mb={o.max_memory_mb:g} was reached",
            StopReason.PREDICATE: "a state satisfied the stop predicate",
            StopReason.INTERRUPTED: "interrupted by the user",
            StopReason.TIME_GROWS: "the state space grows only because time grows",
        }[self]


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
