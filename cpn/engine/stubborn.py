"""Static stubborn sets of transition instances: the partial-order reduction of the state space.

`StubbornSets(net, visible_places)` chooses, in each state, a subset of the enabled transition
instances whose binding elements are the only ones the explorer follows (Valmari's strong stubborn sets,
built from the net's structure as for Petri nets in LoLA and TAPAAL, at the level of transition
instances of a coloured net). The construction reads only which places each transition instance
consumes from, produces to, inhibits on and resets (`cpn.arcs.ArcKind`); guards and inscriptions are
treated conservatively (any binding may consume or produce any colour on each of its arc's places).

Closure rules (a set T_s is stubborn in state s when it is closed under them and holds an enabled one):

- t enabled in T_s: every u that can disable t or that t can disable, or that does not commute with t:
  u consumes from a place t consumes from; u produces to a place that inhibits t; t produces to a
  place that inhibits u; u resets a place t consumes from, produces to or resets; t resets a place u
  consumes from or produces to. Firing is otherwise additive (M' = M - In(t,b) + Out(t,b)), so any
  other u and t commute (Valmari's D1) and u cannot disable t (D2: every enabled member is a key
  transition).
- t disabled in T_s: when a place p that t consumes from is empty and t's arc from p takes at least
  one token whatever the binding (`1`x`, `k`v` with k > 0, a sum with such a term), p is the scapegoat:
  every u that produces to p (only they can enable t). Otherwise every u that can help enable t: u
  produces to a place t consumes from (a consumed place only enables by gaining tokens), or u consumes
  from or resets a place that inhibits t (an inhibitor place only enables by losing tokens), so it holds
  whatever colour or guard disables t.

These preserve every reachable dead marking (Valmari 1990, "Stubborn sets for reduced state space
generation"; Theorem: D1 and D2 with a key transition in every non-dead state).

For invariants (safety) two more conditions are added (`visible_places` given):

- Visibility: a transition instance is visible when it can change a place the property reads (it
  consumes from, produces to or resets it). A stubborn set whose enabled members include a visible one
  is refused; when every candidate is refused the state is fully expanded (the ample-set condition C2
  of Clarke, Grumberg and Peled, "Model Checking", 1999, ch. 10).
- Ignoring: the cycle proviso of the explorer (`cpn.statespace.explore`): a state one of whose reduced
  successors is already stored is fully expanded. In a breadth-first search every cycle of the reduced
  graph has a state whose successor on the cycle was stored before it (the last-stored state of the
  cycle), so every cycle holds a fully expanded state, which implies condition C3 (ibid., and Bošnački
  and Holzmann's breadth-first proviso, SPIN 2005).

Timed nets and nets with priorities are not reduced (full expansion; `refusal` says why): a transition
that waits for a timestamp or a higher priority is disabled by the clock or by another transition's
enabling, which the structure above does not capture.

Examples
--------
>>> import cpn
>>> net = cpn.loads("colset U = unit; place A : U = 1`(); place B : U = 1`(); place C : U; place D : U;"
...                 " trans a; trans b; arc A -> a; arc a -> C; arc B -> b; arc b -> D;").net
>>> s = StubbornSets(net)
>>> sorted(s.choose(frozenset({0, 1})))  # independent: one of them is enough
[0]
"""

from __future__ import annotations

from collections.abc import Iterable

from cpn.expr import nodes as E


def takes_a_token(e) -> bool:
    """Whether an arc inscription is a multiset of at least one token for every binding."""
    if isinstance(e, E.ToMs):
        return True
    if isinstance(e, E.BinOp):
        if e.op == "`":
            return isinstance(e.left, E.Const) and type(e.left.value) is int and e.left.value > 0
        if e.op == "++":
            return takes_a_token(e.left) or takes_a_token(e.right)
    return False


# How many enabled transition instances are tried as seeds in a state (those with the fewest static
# conflicts first): every seed gives a stubborn set, more seeds may give a smaller one at the cost of a
# closure each (a net without independence pays them in every state).
MAX_SEEDS: int = 6


class StubbornSets:
    """Chooses the enabled transition instances to follow in a state (see the module's docstring).

    `choose(enabled, empty)` returns the enabled members of a smallest stubborn set found, or None for a
    full expansion; it depends on the enabled set and the empty places only, so it is memoised by them.
    """

    def __init__(self, net, visible_places: Iterable[int] | None = None):
        n = len(net.transitions)
        self.n = n
        self.refusal: str | None = None
        if net.is_timed:
            self.refusal = "the net is timed (a timestamp or the clock can enable a transition instance)"
        elif any(t.priority is not None for t in net.transitions):
            self.refusal = "the net has priorities (a higher-priority enabling disables a transition instance)"
        consume, produce, inhibit, reset = ([set() for _ in range(n)] for _ in range(4))
        needs: list[set[int]] = [set() for _ in range(n)]  # consumed places whose arc takes a token
        for t in net.transitions:
            for a in t.arcs:
                if a.kind.consumes:
                    consume[t.index].add(a.place)
                    if a.expr is not None and takes_a_token(a.expr):
                        needs[t.index].add(a.place)
                if a.kind.produces:
                    produce[t.index].add(a.place)
                if a.kind.blocks:
                    inhibit[t.index].add(a.place)
                if a.kind.empties:
                    reset[t.index].add(a.place)
        by_place = {}
        for name, sets in (("consume", consume), ("produce", produce), ("inhibit", inhibit), ("reset", reset)):
            index: dict[int, set[int]] = {}
            for t, places in enumerate(sets):
                for p in places:
                    index.setdefault(p, set()).add(t)
            by_place[name] = index

        def of(kind: str, places: Iterable[int]) -> set[int]:
            out: set[int] = set()
            for p in places:
                out |= by_place[kind].get(p, set())
            return out

        # when t is an enabled member: what can disable it, what it can disable, what does not commute
        self.conflicts: list[tuple[int, ...]] = []
        # when t is a disabled member: what can enable it
        self.enablers: list[tuple[int, ...]] = []
        for t in range(n):
            c = (of("consume", consume[t]) | of("produce", inhibit[t]) | of("inhibit", produce[t])
                 | of("reset", consume[t] | produce[t] | reset[t]) | of("consume", reset[t])
                 | of("produce", reset[t]))
            c.discard(t)
            self.conflicts.append(tuple(sorted(c)))
            e = of("produce", consume[t]) | of("consume", inhibit[t]) | of("reset", inhibit[t])
            e.discard(t)
            self.enablers.append(tuple(sorted(e)))
        producers = by_place["produce"]
        # per transition: its scapegoat candidates, each with its producers (fewest first)
        self.scapegoats: list[tuple[tuple[int, tuple[int, ...]], ...]] = [
            tuple(sorted(((p, tuple(sorted(producers.get(p, set()) - {t}))) for p in needs[t]),
                         key=lambda pe: (len(pe[1]), pe[0]))) for t in range(n)]
        self.scapegoat_places = frozenset(p for ps in needs for p in ps)
        self.visible_places = None if visible_places is None else frozenset(visible_places)
        if self.visible_places is None:
            self.visible = frozenset()
        else:
            vp = self.visible_places
            self.visible = frozenset(t for t in range(n) if (consume[t] | produce[t] | reset[t]) & vp)
        self._memo: dict[tuple, frozenset | None] = {}
        self._weight = lambda t: (len(self.conflicts[t]), t)
        self._masks: tuple | None = None

    @property
    def preserves_invariants(self) -> bool:
        """Whether the visibility condition is on (for invariants over `visible_places`)."""
        return self.visible_places is not None

    def choose(self, enabled: frozenset, empty: frozenset = frozenset()) -> frozenset | None:
        """The enabled members of a smallest stubborn set found for a state whose enabled transition
        instances are `enabled` and whose empty places include `empty` (only those of
        `scapegoat_places` matter); None when the state must be fully expanded."""
        key = (enabled, empty)
        try:
            return self._memo[key]
        except KeyError:
            pass
        best = None
        if self.refusal is None and len(enabled) > 1:
            weight = self._weight
            for seed in sorted(enabled, key=weight)[:MAX_SEEDS]:
                found = self._closure(seed, enabled, empty, len(best) if best is not None else len(enabled))
                if found is not None and (best is None or len(found) < len(best)):
                    best = found
                    if len(best) == 1:
                        break
        if best is not None and len(best) == len(enabled):
            best = None
        self._memo[key] = best
        return best

    def _closure(self, seed: int, enabled: frozenset, empty: frozenset, bound: int) -> frozenset | None:
        """The enabled members of the closure of {seed}; None once it reaches `bound` enabled members or
        an enabled visible one. Sets of transition instances are bit masks here (one OR per member)."""
        masks = self._masks
        if masks is None:
            masks = self._masks = self._make_masks()
        conflict_mask, enabler_mask, scapegoat_masks, visible_mask = masks
        enabled_mask = 0
        for t in enabled:
            enabled_mask |= 1 << t
        members = todo = 1 << seed
        hits = 0
        n_hits = 0
        while todo:
            b = todo & -todo
            todo ^= b
            t = b.bit_length() - 1
            if b & enabled_mask:
                if b & visible_mask:
                    return None
                hits |= b
                n_hits += 1
                if n_hits >= bound:
                    return None
                more = conflict_mask[t]
            else:
                more = enabler_mask[t]
                if empty:
                    for p, producers in scapegoat_masks[t]:
                        if p in empty:
                            more = producers
                            break
            new = more & ~members
            if new:
                members |= new
                todo |= new
        return frozenset(t for t in enabled if hits >> t & 1)

    def _make_masks(self) -> tuple:
        def mask(ts) -> int:
            m = 0
            for t in ts:
                m |= 1 << t
            return m

        return ([mask(c) for c in self.conflicts], [mask(e) for e in self.enablers],
                [tuple((p, mask(ps)) for p, ps in sg) for sg in self.scapegoats], mask(self.visible))


__all__ = ["MAX_SEEDS", "StubbornSets", "takes_a_token"]
