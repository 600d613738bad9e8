"""The one verdict type of every property: holds, violated with evidence, unknown with the reason.

Evidence is a path of the occurrence graph from the initial state (a shortest one, from BFS parent
pointers, where the property asks for a marking) and, for properties about infinite behaviour, a cycle
that returns to the path's last state (a lasso). Imports `cpn.statespace` and the standard library only.
"""

from __future__ import annotations

import enum
from dataclasses import dataclass, field

from cpn.diagnostics import Span
from cpn.statespace.graph import StateGraph


class Status(enum.Enum):
    HOLDS = "holds"
    VIOLATED = "violated"
    UNKNOWN = "unknown"
    ERROR = "error"  # the property text raised an ML exception in some marking


@dataclass(frozen=True)
class Evidence:
    """A path of states from state 0 (`path[0] == 0`) and, for a lasso, the states of its cycle.

    `arcs[i]` is the binding element of the step path[i] -> path[i+1]; `cycle_arcs[i]` that of the i-th
    step of the cycle, which starts at path[-1] and ends there again (cycle[-1] == path[-1]).
    """

    path: tuple
    arcs: tuple
    cycle: tuple = ()
    cycle_arcs: tuple = ()

    def __repr__(self) -> str:
        steps = len(self.path) - 1
        cycle = f", then a cycle of {len(self.cycle)}" if self.cycle else ""
        return f"Evidence({steps} step{'s' if steps != 1 else ''} to state {self.target}{cycle})"

    @property
    def is_lasso(self) -> bool:
        return bool(self.cycle)

    @property
    def target(self) -> int:
        return self.path[-1]


@dataclass
class Verdict:
    status: Status
    message: str
    evidence: Evidence | None = None
    details: dict = field(default_factory=dict)
    at: Span | None = None  # an error's position in the scenario: the text that raised (else the property's)

    @classmethod
    def holds(cls, message: str = "", evidence: Evidence | None = None, **details) -> Verdict:
        return cls(Status.HOLDS, message, evidence, details)

    @classmethod
    def violated(cls, message: str, evidence: Evidence | None = None, **details) -> Verdict:
        return cls(Status.VIOLATED, message, evidence, details)

    @classmethod
    def unknown(cls, reason: str, evidence: Evidence | None = None, **details) -> Verdict:
        return cls(Status.UNKNOWN, reason, evidence, details)


def _arc_between(graph: StateGraph, u: int, v: int) -> int:
    """The binding element of the first arc u -> v (the engine's order makes it deterministic)."""
    off, dst, bes = graph.offsets, graph.dst, graph.bes
    for a in range(off[u], off[u + 1]):
        if dst[a] == v:
            return bes[a]
    raise ValueError(f"no arc from state {u} to state {v}")


def path_evidence(graph: StateGraph, path: list[int], cycle: list[int] | None = None,
                  cycle_arcs: list[int] | None = None, arc_hints: dict | None = None) -> Evidence:
    """Evidence for an explicit path of states (path[0] must be 0: the initial state); `arc_hints` maps
    a step (u, v) to the arc index it must take."""
    assert path and path[0] == 0
    ev = evidence_to(graph, 0, then=path, cycle=cycle, cycle_arcs=cycle_arcs)
    if arc_hints:
        arcs = tuple(graph.bes[arc_hints[(u, v)]] if (u, v) in arc_hints else be
                     for u, v, be in zip(ev.path, ev.path[1:], ev.arcs))
        ev = Evidence(ev.path, arcs, ev.cycle, ev.cycle_arcs)
    return ev


def bfs_path(graph: StateGraph, target: int) -> list[int]:
    """The BFS-tree path of states 0 .. target (a shortest path)."""
    path = [target]
    parent = graph.parent
    while path[-1] > 0:
        path.append(parent[path[-1]])
    return path[::-1]


def evidence_to(graph: StateGraph, target: int, then: list[int] | None = None,
                cycle: list[int] | None = None, cycle_arcs: list[int] | None = None) -> Evidence:
    """Evidence: the shortest path to `target`, followed by the states `then` (a path from target, given
    with target first) and a cycle (states after its start, ending at its start). `cycle_arcs` may give,
    per cycle step, the arc index to take (-1: the first arc between the two states)."""
    path = bfs_path(graph, target)
    if then:
        assert then[0] == target
        path += list(then[1:])
    arcs = [graph.parent_be[v] if graph.parent[v] == u else _arc_between(graph, u, v)
            for u, v in zip(path, path[1:])]
    cyc = list(cycle or [])
    carcs = []
    prev = path[-1]
    for i, v in enumerate(cyc):
        a = cycle_arcs[i] if cycle_arcs is not None else -1
        carcs.append(graph.bes[a] if a >= 0 else _arc_between(graph, prev, v))
        prev = v
    return Evidence(tuple(path), tuple(arcs), tuple(cyc), tuple(carcs))
