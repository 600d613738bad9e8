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
