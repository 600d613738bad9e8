"""Algorithms over an explored state space: bounds, dead and home markings, liveness, fairness, the CTL
model checker, the Model Checking Contest's global properties, and the verdicts they give.

May import cpn.statespace (and the layers under it); never the property language (cpn.properties), the
gate (cpn.gate), report or cli.
"""

from cpn.checks.bounds import Boundedness, PlaceBounds, boundedness
from cpn.checks.columns import TransitionIndex
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
from cpn.checks.verdict import Evidence, Status, Verdict

__all__ = [
    "Boundedness", "DeadMarkings", "Fairness", "HomeMarkings", "PlaceBounds", "SccSummary", "TransitionIndex",
    "boundedness", "dead_markings", "dead_transitions", "fairness", "home_markings", "live_transitions",
    "scc_summary",
    "Evidence", "Status", "Verdict",
]
