"""The state space: breadth-first generation of the occurrence graph, SCCs and shortest traces.

Uses the engine through its protocol (`cpn.engine.Engine`) only: never the net, the language, the checks, the
reports or the command line (tests/test_layering.py).
"""

from cpn.statespace.explore import Explorer
from cpn.statespace.graph import StateGraph
from cpn.statespace.options import Backend, ExploreOptions, StopReason
from cpn.statespace.result import Exploration, Progress
from cpn.statespace.scc import (
    SccDecomposition,
    first_cycle_component,
    has_cycle,
    strongly_connected_components,
)
from cpn.statespace.sweep import SweepExploration, SweepLine
from cpn.statespace.trace import Step, Trace, replay, shortest_trace

__all__ = [
    "Backend", "Exploration", "Explorer", "ExploreOptions", "Progress", "SccDecomposition", "StateGraph", "Step",
    "StopReason", "SweepExploration", "SweepLine", "Trace", "first_cycle_component", "has_cycle", "replay", "shortest_trace", "strongly_connected_components",
]
