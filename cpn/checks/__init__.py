"""The standard report's properties, computed from an exploration.

May import cpn.statespace (and the layers under it); never report or cli.
"""

from cpn.checks._common import TransitionIndex
from cpn.checks.bounds import Boundedness, PlaceBounds, boundedness
from cpn.checks.fairness import Fairness, fairness
from cpn.checks.gate import PropertyResult, RunResult, check, run_scenario
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
from cpn.checks.scenario import Scenario, load_scenario, loads_scenario
from cpn.checks.verdict import Evidence, Status, Verdict

__all__ = [
    "Boundedness", "DeadMarkings", "Fairness", "HomeMarkings", "PlaceBounds", "SccSummary", "TransitionIndex",
    "boundedness", "dead_markings", "dead_transitions", "fairness", "home_markings", "live_transitions",
    "scc_summary",
    "Evidence", "PropertyResult", "RunResult", "Scenario", "Status", "Verdict", "check", "load_scenario",
    "loads_scenario", "run_scenario",
]
