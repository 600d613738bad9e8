"""A plain BFS over an engine, to a canonical form of the graph (for comparing engines)."""

from __future__ import annotations

from collections import Counter


def canon(engine, s):
    return tuple(frozenset(d.items()) for d in engine.marking(s)), engine.clock(s)


def graph(engine, limit: int = 200) -> dict:
    """Canonical marking -> Counter of (transition, binding, successor) for the first `limit` states."""
    s0 = engine.initial_state()
    seen = {canon(engine, s0)}
    queue = [s0]
    out = {}
    i = 0
    while i < len(queue) and i < limit:
        s = queue[i]
        i += 1
        succ: Counter = Counter()
        for be, t in engine.successors(s):
            b = engine.binding_element(be)
            ct = canon(engine, t)
            succ[(b.transition, tuple(sorted(b.binding.items())), ct)] += 1
            if ct not in seen:
                seen.add(ct)
                queue.append(t)
        out[canon(engine, s)] = succ
    return out


def counts(engine, limit: int = 10**7) -> tuple[int, int, int]:
    s0 = engine.initial_state()
    seen = {s0}
    queue = [s0]
    arcs = dead = 0
    i = 0
    while i < len(queue) and i < limit:
        s = queue[i]
        i += 1
        succ = engine.successors(s)
        arcs += len(succ)
        dead += not succ
        for _, t in succ:
            if t not in seen:
                seen.add(t)
                queue.append(t)
    return len(queue), arcs, dead


def same_exploration(a, b) -> None:
    """Two explorations (`cpn.statespace.Exploration`) of the same net found the very same graph: the
    same states (their markings and clocks) under the same ids, the same arcs in the same order, the same
    binding elements, BFS parents and levels, and stopped for the same reason."""
    ga, gb = a.graph, b.graph
    assert a.stop_reason is b.stop_reason and a.levels == b.levels
    assert a.predicate_state == b.predicate_state
    assert len(ga.states) == len(gb.states)
    assert [a.engine.marking(s) for s in ga.states] == [b.engine.marking(s) for s in gb.states]
    assert [a.engine.clock(s) for s in ga.states] == [b.engine.clock(s) for s in gb.states]
    assert list(ga.offsets) == list(gb.offsets)
    assert list(ga.dst) == list(gb.dst)
    assert list(ga.bes) == list(gb.bes)
    assert [a.engine.format_binding_element(be) for be in sorted(set(ga.bes))] == \
        [b.engine.format_binding_element(be) for be in sorted(set(gb.bes))]
    assert list(ga.parent) == list(gb.parent) and list(ga.parent_be) == list(gb.parent_be)
