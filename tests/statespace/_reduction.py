"""Cross-checks of a reduced state space against the full one (dead markings, visible projections)."""

from __future__ import annotations

import random

from cpn.statespace import ExploreOptions, Explorer


def canonical(engine, s) -> tuple:
    return tuple(frozenset(d.items()) for d in engine.marking(s))


def dead_set(x) -> set:
    e = x.engine
    return {canonical(e, x.graph.states[i]) for i in x.graph.dead_states()}


def projections(x, places) -> set:
    e = x.engine
    return {tuple(frozenset(e.marking(s)[p].items()) for p in places) for s in x.graph.states}


def compare(engine, max_states: int = 20000, seed: int = 0) -> dict | None:
    """Explore fully, then reduced for deadlocks and reduced for a random set of visible places; None
    when the full graph does not fit `max_states`. Raises AssertionError on a difference."""
    full = Explorer(engine, ExploreOptions(max_states=max_states)).run()
    if not full.complete:
        return None
    red = Explorer(engine, ExploreOptions(reduction="stubborn")).run()
    assert red.complete
    assert dead_set(red) == dead_set(full), "dead markings differ"
    n = len(engine.places)
    rng = random.Random(seed)
    visible = sorted(rng.sample(range(n), k=min(n, rng.randint(1, 2)))) if n else []
    vis = Explorer(engine, ExploreOptions(reduction="stubborn", visible_places=frozenset(visible))).run()
    assert vis.complete
    assert dead_set(vis) == dead_set(full), "dead markings differ (visibility on)"
    assert projections(vis, visible) == projections(full, visible), f"markings of places {visible} differ"
    return {"full": full.n_states, "deadlock": red.n_states, "visible": vis.n_states,
            "reduction": red.reduction}
