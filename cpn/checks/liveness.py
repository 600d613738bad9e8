"""Home, liveness and dead-marking properties from the SCC decomposition (CPN Tools' definitions).

Imports `cpn.checks.columns` and `cpn.statespace` only. Properties that need the whole graph (home
markings, live transitions) are None on a partial state space: an unexpanded state has no arcs yet
and would look like a terminal SCC.
"""

from __future__ import annotations

from array import array
from dataclasses import dataclass
from itertools import compress

from cpn.checks.columns import TransitionIndex
from cpn.statespace import Exploration, SccDecomposition, graphnative
from cpn.statespace.scc import scc_graph_arcs, strongly_connected_components

DEAD_EXAMPLES: int = 10


@dataclass(frozen=True)
class SccSummary:
    decomposition: SccDecomposition
    nodes: int
    arcs: int  # state-space arcs whose ends lie in different SCCs (CPN Tools' count, docs/statespace.md)
    arc_pairs: int  # distinct ordered pairs of different SCCs joined by at least one arc
    terminal: int
    nontrivial: int
    seconds: float


def scc_summary(x: Exploration) -> SccSummary:
    import time

    t0 = time.perf_counter()
    g = x.graph
    dec = strongly_connected_components(g.n_states, g.offsets, g.dst)
    between, pairs = scc_graph_arcs(dec, g.offsets, g.dst)
    return SccSummary(dec, dec.count, between, pairs, sum(dec.terminal), sum(dec.nontrivial),
                      time.perf_counter() - t0)


@dataclass(frozen=True)
class DeadMarkings:
    count: int
    states: list  # all dead state ids (0-based), increasing
    untimed_count: int | None  # distinct dead markings once timestamps are removed (timed nets)
    unexpanded: int  # states never expanded: not dead, not known


def dead_markings(x: Exploration) -> DeadMarkings:
    g = x.graph
    dead = graphnative.dead_states(g.offsets)
    if dead is None:
        dead = g.dead_states()
    untimed = None
    if x.engine.is_timed:
        untimed = len({x.engine.untimed(g.states[i]) for i in dead})
    return DeadMarkings(len(dead), dead, untimed, x.unexpanded)


def dead_transitions(x: Exploration, tindex: TransitionIndex | None = None) -> list[int]:
    """Transition instances (indices) that label no arc; on a partial space: none seen so far."""
    tindex = tindex or TransitionIndex(x.engine)
    seen = {tindex(be) for be in tindex.distinct(x.graph.bes)}
    sym = getattr(x.graph, "symmetry", None)
    if sym is not None and sym.moves_instances:
        seen = sym.close_transitions(seen)
    return [t for t in range(len(x.engine.transitions)) if t not in seen]


def _moves_instances(x: Exploration) -> bool:
    sym = getattr(x.graph, "symmetry", None)
    return sym is not None and sym.moves_instances


def live_transitions(x: Exploration, scc: SccSummary, arc_transitions, native: bool = True) -> list[int] | None:
    """Transition instances that label an arc inside every terminal SCC (None if partial, or on a quotient
    whose group moves module instances: not preserved there, `cpn.properties.symmetry`)."""
    if not x.complete or _moves_instances(x):
        return None
    g = x.graph
    dec = scc.decomposition
    ntrans = len(x.engine.transitions)
    if native:
        fast = graphnative.live(g.offsets, arc_transitions, ntrans, dec.comp, dec.members, dec.start,
                                dec.terminal)
        if fast is not None:
            return [t for t in range(ntrans) if fast[t]]
    live = set(range(ntrans))
    off = g.offsets
    for c in dec.terminal_components():
        if not live:
            break
        inside: set = set()
        nodes = dec.nodes(c)
        if len(nodes) == g.n_states:
            inside = set(arc_transitions)
        else:
            for v in nodes:
                a, b = off[v], off[v + 1]
                if a != b:
                    inside.update(arc_transitions[a:b])
                    if len(inside) == ntrans:
                        break
        live &= inside
    return sorted(live)


@dataclass(frozen=True)
class HomeMarkings:
    """Home markings: the states of the unique terminal SCC (empty if there are several).

    `initial_is_home` is CPN Tools' timed-net test: from every state a state equal to the initial one
    modulo time is reachable (each terminal SCC holds such a state).
    """

    states: object  # sorted state ids (a range or an array('i')); None on a partial state space
    initial_is_home: bool | None


def home_markings(x: Exploration, scc: SccSummary) -> HomeMarkings:
    if not x.complete:
        return HomeMarkings(None, None)
    dec = scc.decomposition
    terms = dec.terminal_components()
    homes: object = []
    if len(terms) == 1:
        nodes = dec.nodes(terms[0])
        n = x.graph.n_states
        # A range or an int array, not a list: a list of 531,441 ids costs 19 MB (MS(8)). A large SCC's
        # states are picked from its column in increasing order rather than sorted.
        if len(nodes) == n:
            homes = range(n)
        elif 8 * len(nodes) >= n:
            homes = array("i", compress(range(n), map(terms[0].__eq__, dec.comp)))
        else:
            homes = array("i", sorted(nodes))
    engine = x.engine
    states = x.graph.states
    if engine.is_timed:
        u0 = engine.untimed(states[0])
        initial = all(any(engine.untimed(states[v]) == u0 for v in dec.nodes(c)) for c in terms)
    else:
        initial = len(terms) == 1 and dec.comp[0] == terms[0]
    return HomeMarkings(homes, initial)
