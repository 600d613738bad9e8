"""Fairness of transition instances (CPN Tools' TIsFairness), decided on the SCCs of the graph.

Imports `cpn.statespace` only (its cycle searches, `cpn.statespace.scc`). Where native code is available the whole
decision runs in C (`cpn.statespace.graphnative.fairness`, the same shortcuts and confined searches
without the walks); the Python code below is the fallback and the tests' reference. For a transition instance t and the infinite
occurrence sequences:
- impartial: t occurs infinitely often in every infinite occurrence sequence;
- fair: t occurs infinitely often in every infinite sequence in which it is enabled infinitely often;
- just: t occurs infinitely often in every infinite sequence in which it is, from some point on,
  continuously enabled.
On a finite graph an infinite sequence ends up cycling in a strongly connected set, so the witnesses
against each class are cycles that avoid t's arcs: any such cycle (not impartial), one through a state
where t is enabled (not fair), one whose states all enable t (not just). See docs/statespace.md.
"""

from __future__ import annotations

import enum
from array import array
from collections.abc import Callable
from itertools import compress

from cpn.statespace import Exploration, graphnative
from cpn.statespace.scc import SccDecomposition, first_cycle_component, has_cycle, walk_cycle

# cheap witness cycles before any search: walks per SCC, in the largest SCCs of at least some size
WALKS_PER_COMPONENT: int = 4
WALKED_COMPONENTS: int = 64
WALK_MIN_STATES: int = 16
# walks avoiding t from states enabling t, looking for a witness that t is not fair
TARGETED_WALKS: int = 64


class Fairness(enum.Enum):
    IMPARTIAL = "Impartial"
    FAIR = "Fair"
    JUST = "Just"
    NONE = "No Fairness"


def fairness(x: Exploration, dec: SccDecomposition, arc_transitions: array,
             progress: Callable[[int, int], None] | None = None, native: bool = True) -> dict[int, Fairness] | None:
    """Fairness class of each transition instance, or None when there is no infinite sequence.

    Every cycle lies in a nontrivial SCC of the graph. One pass over the states of those SCCs records,
    per transition instance t, the SCCs where t is enabled and those where t labels an arc inside the
    SCC; that settles most cases without a search:
    - t never enabled in a nontrivial SCC: no cycle passes through t's arcs, so every cycle avoids t
      and t is not impartial; no state of a cycle enables it, so t is fair;
    - an SCC with no arc of t inside is strongly connected in the graph less t: t is not impartial,
      and if t is enabled in that SCC, not fair either.
    A few walks per SCC find cycles; t labelling no arc of one is not impartial, and t enabled on one
    it does not label is not fair. What is left is decided by searches confined to the SCCs that
    matter and started from the states that matter (`has_cycle`, `first_cycle_component`):
    1. a cycle avoiding t (only when t labels an arc inside every nontrivial SCC and every walked
       cycle): none means impartial;
    2. a cycle avoiding t among the states where t is enabled: No Fairness;
    3. otherwise, unless already known not fair, a nontrivial SCC of the graph less t through a state
       enabling t, within the SCCs where t is enabled: Just, else Fair.
    `progress(done, total)` is called after each transition instance (once at the end with `native`).
    """
    nontrivial = dec.nontrivial
    if not any(nontrivial):
        return None
    g = x.graph
    n = g.n_states
    off, dst, comp = g.offsets, g.dst, dec.comp
    ntrans = len(x.engine.transitions)
    labels = arc_transitions
    if native:
        fast = graphnative.fairness(n, off, dst, labels, ntrans, comp, dec.members, dec.start, nontrivial)
        if fast is not None:
            if progress is not None:
                progress(ntrans, ntrans)
            return {t: Fairness(name) for t, name in enumerate(fast)}
    cyclic_components = [c for c in range(dec.count) if nontrivial[c]]
    enabled_in, inside = _components_of(dec, cyclic_components, off, dst, labels, ntrans)
    impartial_candidate = [len(inside[t]) == len(cyclic_components) for t in range(ntrans)]
    not_fair = [bool(enabled_in[t] - inside[t]) for t in range(ntrans)]
    not_just = [False] * ntrans
    _walk_witnesses(dec, cyclic_components, off, dst, labels, impartial_candidate, not_fair, not_just)

    result: dict[int, Fairness] = {}
    cyclic = None
    for t in range(ntrans):
        if not enabled_in[t]:
            result[t] = Fairness.FAIR
        elif impartial_candidate[t]:
            if cyclic is None:
                cyclic = bytearray(map(nontrivial.__getitem__, comp))
            # arcs between SCCs are followed (a cycle lies inside one SCC anyway, so they cannot make
            # one): testing `comp` on every arc made the search half as fast again on SwimmingPool-PT-01;
            # `cyclic` already confines it, as the states enabling t do below
            if not has_cycle(n, off, dst, labels, t, cyclic, compress(range(n), cyclic)):
                result[t] = Fairness.IMPARTIAL
        elif not_just[t]:
            result[t] = Fairness.NONE
    undecided = [t for t in range(ntrans) if t not in result]
    enabled_at = _enabled_states(dec, cyclic_components, off, labels, undecided, ntrans)
    keep = bytearray(n)
    walk_budget = max(64, sum(len(dec.nodes(c)) for c in cyclic_components))
    for t in range(ntrans):
        if t not in result:
            en = enabled_at[t]
            for v in en:
                keep[v] = 1
            try:
                if has_cycle(n, off, dst, labels, t, keep, en):
                    result[t] = Fairness.NONE
                elif (not_fair[t] or _walked_through_enabled(off, dst, comp, labels, t, en, keep, walk_budget)
                      or first_cycle_component(n, off, dst, lambda nodes: any(map(keep.__getitem__, nodes)),
                                               labels, t, roots=en, within=comp) is not None):
                    result[t] = Fairness.JUST
                else:
                    result[t] = Fairness.FAIR
            finally:
                for v in en:
                    keep[v] = 0
        if progress is not None:
            progress(t + 1, ntrans)
    return result


def _components_of(dec: SccDecomposition, components: list[int], off: array, dst: array, labels: array,
                   ntrans: int) -> tuple[list[set], list[set]]:
    """Per transition instance t: the nontrivial SCCs where t is enabled, and those where one of its
    arcs joins two states of the SCC. One pass over the states of the nontrivial SCCs."""
    enabled_in: list[set] = [set() for _ in range(ntrans)]
    inside: list[set] = [set() for _ in range(ntrans)]
    comp = dec.comp
    comp_of = comp.__getitem__
    for c in components:
        nodes = dec.nodes(c)
        if len(nodes) == len(comp):
            # the whole graph is one SCC: every arc is inside it
            here = set(labels)
            for t in here:
                enabled_in[t].add(c)
                inside[t].add(c)
            continue
        here: set = set()
        within: set = set()
        c_eq = c.__eq__
        for v in nodes:
            a, b = off[v], off[v + 1]
            if b - a == 1:
                t = labels[a]
                here.add(t)
                if comp[dst[a]] == c:
                    within.add(t)
                continue
            ts = labels[a:b]
            here.update(ts)
            within.update(compress(ts, map(c_eq, map(comp_of, dst[a:b]))))
        for t in here:
            enabled_in[t].add(c)
        for t in within:
            inside[t].add(c)
    return enabled_in, inside


def _walk_witnesses(dec, components, off, dst, labels, impartial_candidate, not_fair, not_just) -> None:
    """Cheap witnesses from cycles found by walking (`walk_cycle`) in the larger nontrivial SCCs: a
    transition instance that labels no arc of such a cycle is not impartial; if it is enabled in one
    of the cycle's states it is not fair, and if it is enabled in all of them, not just."""
    ntrans = len(not_fair)
    everyone = set(range(ntrans))
    for c in sorted(components, key=lambda c: dec.start[c] - dec.start[c + 1])[:WALKED_COMPONENTS]:
        nodes = dec.nodes(c)
        if len(nodes) < WALK_MIN_STATES:
            break
        for k in range(WALKS_PER_COMPONENT):
            cycle = walk_cycle(off, dst, dec.comp, nodes[(k * len(nodes)) // WALKS_PER_COMPONENT], k)
            if cycle is None:
                continue
            on_cycle = set(map(labels.__getitem__, cycle))
            enabled_somewhere: set = set()
            enabled_everywhere = None
            for i in cycle:
                v = dst[i]
                here = set(labels[off[v]:off[v + 1]])
                enabled_somewhere |= here
                enabled_everywhere = here if enabled_everywhere is None else enabled_everywhere & here
            for t in everyone - on_cycle:
                impartial_candidate[t] = False
            for t in enabled_somewhere - on_cycle:
                not_fair[t] = True
            for t in (enabled_everywhere or set()) - on_cycle:
                not_just[t] = True


def _walked_through_enabled(off, dst, comp, labels, t: int, en: array, enabled: bytearray, budget: int) -> bool:
    """Whether a walk avoiding t's arcs from one of some states enabling t finds a cycle through a
    state enabling t (a witness that t is not fair). At most TARGETED_WALKS walks and `budget` steps
    in all, so that failing costs less than the search it tries to spare."""
    step = max(1, len(en) // TARGETED_WALKS)
    starts = en[::step][:TARGETED_WALKS]
    per_walk = max(16, budget // max(1, len(starts)))
    for k, v in enumerate(starts):
        cycle = walk_cycle(off, dst, comp, v, k, max_steps=per_walk, labels=labels, avoid=t)
        if cycle is not None and any(enabled[dst[i]] for i in cycle):
            return True
    return False


def _enabled_states(dec: SccDecomposition, components: list[int], off: array, labels: array, wanted: list[int],
                    ntrans: int) -> list[array]:
    """Per transition instance in `wanted`, the states of nontrivial SCCs where it is enabled (one pass
    over those states; empty arrays for the others)."""
    enabled_at = [array("i") for _ in range(ntrans)]
    if not wanted:
        return enabled_at
    wanted_set = set(wanted)
    appenders = [a.append for a in enabled_at]
    for c in components:
        for v in dec.nodes(c):
            a, b = off[v], off[v + 1]
            if b - a == 1:
                t = labels[a]
                if t in wanted_set:
                    appenders[t](v)
            else:
                for t in wanted_set.intersection(labels[a:b]):
                    appenders[t](v)
    return enabled_at
