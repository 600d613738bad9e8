"""The explorer's successor step under symmetry reduction, orbit counts and traces in the full graph.

`SymmetricSuccessors` wraps the engine's successor function: every successor is replaced by the canonical
representative of its orbit (`cpn.engine.symmetry.Canonicaliser`), so the explorer stores one state per
orbit and builds the quotient graph (an arc per enabled binding element of a representative, as in the
full graph). Because G maps the enabled binding elements of a marking onto those of its image, every state
of an orbit has as many successors as its representative: the full graph has sum |orbit(r)| states and sum
|orbit(r)| * outdegree(r) arcs over the representatives r, where |orbit(r)| = |G| / |stabiliser(r)|
(`full_counts`).

A path of the quotient graph is not a path of the full graph (each step lands on a representative, not on
the successor itself); `lifted_trace` rebuilds, step by step from the initial marking, a path of the full
graph through the same orbits: the same length, so still a shortest one, and it replays.
"""

from __future__ import annotations

from cpn.engine.symmetry import Canonicaliser
from cpn.statespace.trace import Step, Trace


class SymmetricSuccessors:
    """`successors(state)` of the quotient graph; records the orbit size of each state it expands."""

    def __init__(self, engine, scalars):
        self.engine = engine
        self.canon = Canonicaliser(engine, scalars)
        s0 = engine.initial_state()
        if any(self.canon.apply(s0, g) != s0 for g in self.canon.generators()):
            raise ValueError("the initial marking is not symmetric under "
                             + ", ".join(str(s) for s in scalars) + " (cpn.net.symmetry.symmetry_problems says where)")
        self.group_order = self.canon.group_order
        self.orbit: list[int] = []  # orbit size of state i, in expansion (= id) order
        self._pending: dict = {}  # canonical state -> stabiliser size, until expanded
        self._memo: dict = {}  # successor state -> its representative (bounded, see MEMO_MAX)

    def trace(self, graph, target: int, engine=None) -> Trace:
        """The trace to state `target` of the quotient `graph`, lifted to the full graph (`lifted_trace`):
        what `cpn.statespace.trace.shortest_trace` gives on a graph built with this step."""
        return lifted_trace(graph, target, engine)

    def initial(self, state):
        """The representative of the initial state's orbit (the initial state itself when it is
        symmetric, as `cpn.net.symmetry` requires)."""
        rep, stab = self.canon.canonical(state)
        self._pending[rep] = stab
        return rep

    def __call__(self, state):
        stab = self._pending.pop(state, None)
        if stab is None:
            stab = self.canon.canonical(state)[1]
        self.orbit.append(self.group_order // stab)
        out = []
        memo = self._memo
        pending = self._pending
        canonical = self.canon.canonical
        for be, t in self.engine.successors(state):
            rep = memo.get(t)
            if rep is None:
                rep, stab = canonical(t)
                if rep not in pending:
                    pending[rep] = stab
                if len(memo) >= MEMO_MAX:
                    memo.clear()
                memo[t] = rep
            out.append((be, rep))
        return out

    def full_counts(self, graph) -> tuple[int, int] | None:
        """(states, arcs) of the full graph, from the orbit sizes; None unless every state was expanded."""
        if graph.expanded != graph.n_states or len(self.orbit) != graph.n_states:
            return None
        off = graph.offsets
        states = sum(self.orbit)
        arcs = sum(k * (off[i + 1] - off[i]) for i, k in enumerate(self.orbit))
        return states, arcs

    def stats(self, graph) -> dict:
        """The figures of the reduction for the report: the group, the full graph's counts (None when
        the search was stopped), how many canonical forms and relabellings were computed."""
        full = self.full_counts(graph)
        return {"symmetry": [str(s) for s in self.canon.scalars], "group_order": self.group_order,
                "instances": [f"module '{f.module}' ({len(f.roots)} instances)" for f in self.canon.families],
                "full_states": None if full is None else full[0], "full_arcs": None if full is None else full[1],
                "canonical_forms": self.canon.canonicalised, "relabellings": self.canon.relabellings}

    def orbit_size(self, i: int, graph=None) -> int:
        """The number of states of the full graph in the orbit of state i."""
        if i < len(self.orbit):
            return self.orbit[i]
        return self.group_order // self.canon.canonical(graph.states[i])[1]

    def canonical(self, state):
        return self.canon.canonical(state)[0]

    @property
    def moves_instances(self) -> bool:
        """Whether the group moves module instances (`cpn.net.instance_symmetry`), not only values."""
        return bool(self.canon.families)

    def place_orbits(self) -> list[tuple[int, ...]]:
        """The orbits of the places that module instances move: the same place of every instance."""
        return [tuple(f.places[v][j] for v in f.places) for f in self.canon.families
                for j in range(len(next(iter(f.places.values()))))]

    def transition_orbits(self) -> list[tuple[int, ...]]:
        """The orbits of the transition instances of the module instances that the group moves."""
        return [tuple(f.transitions[v][j] for v in f.transitions) for f in self.canon.families
                for j in range(len(next(iter(f.transitions.values()))))]

    def close_transitions(self, occurring: set) -> set:
        """The transition instances that occur in the full graph, from those occurring in the quotient: a
        transition instance occurs when the same transition of another instance of its family does (the
        group maps its occurrence onto one of each instance)."""
        out = set(occurring)
        for orbit in self.transition_orbits():
            if any(t in occurring for t in orbit):
                out.update(orbit)
        return out


#: at most this many successor states are remembered with their representative (a state reached again
#: from another representative is not canonicalised twice); past it the memo starts again
MEMO_MAX: int = 1 << 16


def lift_path(graph, steps, engine=None) -> tuple[list, list[int]]:
    """A path of the full graph through the orbits of the quotient's path `steps` ((source, target,
    binding element) triples from the initial state): (its states, its binding elements). Each step takes
    the quotient's binding element when it leads into the orbit, else the first that does."""
    sym = graph.symmetry
    eng = engine if engine is not None else sym.engine
    state = eng.initial_state()
    states, bes = [state], []
    for _a, b, be0 in steps:
        want = graph.states[b]
        succ = eng.successors(state)
        chosen = next(((be, t) for be, t in succ if be == be0 and sym.canonical(t) == want), None)
        if chosen is None:
            chosen = next(((be, t) for be, t in succ if sym.canonical(t) == want), None)
        if chosen is None:
            raise RuntimeError(f"no successor of the lifted path reaches the orbit of state {b}")
        bes.append(chosen[0])
        state = chosen[1]
        states.append(state)
    return states, bes


def lifted_trace(graph, target: int, engine=None) -> Trace:
    """A shortest path of the full graph from the initial marking to a marking in the orbit of state
    `target` of the quotient graph (its steps name the quotient's states as source and target)."""
    path = []
    v = target
    while v > 0:
        path.append((graph.parent_be[v], graph.parent[v], v))
        v = graph.parent[v]
    path.reverse()
    states, bes = lift_path(graph, [(a, b, be) for be, a, b in path], engine)
    steps = []
    for k, (be, (_be0, a, b)) in enumerate(zip(bes, path)):
        if engine is None:
            steps.append(Step(be, a, b))
            continue
        changes = []
        for p, place in enumerate(engine.places):
            before, after = engine.format_marking(states[k], p), engine.format_marking(states[k + 1], p)
            if before != after:
                changes.append((place.name, before, after))
        steps.append(Step(be, a, b, engine.format_binding_element(be), tuple(changes)))
    return Trace(target, tuple(steps))


__all__ = ["MEMO_MAX", "SymmetricSuccessors", "lift_path", "lifted_trace"]
