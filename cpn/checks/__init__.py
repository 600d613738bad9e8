"""The standard report's properties, computed from an exploration.

May import cpn.statespace (and the layers under it); never report or cli.
"""

from cpn.checks._common import TransitionIndex
from cpn.checks.bounds import Boundedness, PlaceBounds, boundedness
from cpn.checks.fairness import Fairness, fairness
from cpn.checks.liveness import (
    DeadMarkings,
    HomeMarkings,
    SccSummary,
    dead_markings,
    dead_transitions,
    home_markings,
    live_transitions,
    scc_summary,
)

__all__ = [
    "Boundedness", "DeadMarkings", "Fairness", "HomeMarkings", "PlaceBounds", "SccSummary", "TransitionIndex",
    "boundedness", "dead_markings", "dead_transitions", "fairness", "home_markings", "live_transitions",
    "scc_summary",
]
