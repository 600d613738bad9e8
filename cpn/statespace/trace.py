"""Shortest traces from the initial state, rebuilt from BFS parent pointers, and their replay.

Imports `cpn.statespace.graph` and the standard library only.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from itertools import compress
from operator import ne

from cpn.statespace.graph import StateGraph


@dataclass(frozen=True)
class Step:
    """One occurrence: binding element `be` leads from state `source` to state `target`."""

    be: int
    source: int
    target: int
    text: str = ""
    changes: tuple = ()  # (place name, marking before, marking after) for every place that changed


@dataclass(frozen=True)
class Trace:
    """A path from the initial state (state 0) to `target`; shortest when built from a BFS."""

    target: int
    steps: tuple = field(default_factory=tuple)

    def __len__(self) -> int:
        return len(self.steps)

    def to_json(self) -> list[dict]:
        return [{"binding_element": s.text, "from": s.source + 1, "to": s.target + 1,
                 "changes": [{"place": p, "before": a, "after": b} for p, a, b in s.changes]}
                for s in self.steps]


def shortest_trace(graph: StateGraph, target: int, engine=None) -> Trace:
    """The BFS-tree path to `target`; with an engine, each step carries its text and marking changes.
    On a quotient graph (symmetry reduction) the path is lifted to the full graph by the graph's successor
    step (`symmetry.SymmetricSuccessors.trace`)."""
    if graph.symmetry is not None:
        return graph.symmetry.trace(graph, target, engine)
    path = []
    v = target
    parent, parent_be = graph.parent, graph.parent_be
    while v > 0:
        path.append((parent_be[v], parent[v], v))
        v = parent[v]
    path.reverse()
    if engine is None:
        return Trace(target, tuple(Step(be, a, b) for be, a, b in path))
    steps = []
    places = engine.places
    states = graph.states
    sb = states[0] if path else None
    for be, a, b in path:
        # each state is read (a packed store decodes it) once: a step starts where the previous ended
        sa, sb = sb, states[b]
        # the places whose item differs (one pass in C), then any place beyond the state's items
        common = min(len(places), len(sa))
        differing = [*compress(range(common), map(ne, sa, sb)), *range(common, len(places))]
        changes = []
        for p in differing:
            before, after = engine.format_marking(sa, p), engine.format_marking(sb, p)
            if before != after:
                changes.append((places[p].name, before, after))
        steps.append(Step(be, a, b, engine.format_binding_element(be), tuple(changes)))
    return Trace(target, tuple(steps))


def replay(engine, graph: StateGraph, trace: Trace) -> bool:
    """Fire the trace's binding elements again from the initial state; True if it reaches its target.

    Each step must be an enabled binding element of the engine at the current state, and lead to the
    state the graph recorded.
    """
    state = engine.initial_state()
    if graph.states[0] != state:
        return False
    canonical = graph.symmetry.canonical if graph.symmetry is not None else None
    for step in trace.steps:
        nxt = [t for be, t in engine.successors(state) if be == step.be]
        want = graph.states[step.target]
        if canonical is not None:  # a lifted trace reaches the orbit of the quotient's state
            lifted = [t for t in nxt if canonical(t) == want]
            if not lifted:
                return False
            state = lifted[0]
            continue
        if want not in nxt:
            return False
        state = want
    if canonical is not None:
        return canonical(state) == graph.states[trace.target]
    return state == graph.states[trace.target]
