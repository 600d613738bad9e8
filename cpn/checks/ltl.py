"""LTL on the fly: the product of a Büchi automaton with the state space as it is built, an emptiness check
that stops at the first accepting cycle, and the counterexample as a lasso.

`check_ltl(system, formula, propositions)` decides whether every path of the system satisfies the
formula (`cpn.checks.buchi`'s tuples, ``("ap", i)`` being the state predicate `propositions[i]`). It
translates the negated formula into a generalised Büchi automaton and searches the product for an
accepting cycle with Couvreur's SCC-based algorithm ("On-the-fly verification of linear temporal logic",
FM 1999): one depth-first search that keeps a stack of SCC roots with the acceptance sets each has
met, and stops as soon as one root has met them all. Only the states the search reaches are generated.

Paths are infinite. A dead state (no enabled binding element) repeats forever: it gets a self-loop, the
stuttering extension of Spin and of the Model Checking Contest, so ``F p`` fails on a path that deadlocks
before p holds and ``G p`` holds on one that deadlocks with p true ever since.

The system is anything with `initial_state()` and `successors(state) -> [(label, state)]` (an engine, or
`Cache` around one so that several formulas share the states generated). Imports `cpn.checks.buchi`.

Examples
--------
>>> import cpn
>>> engine = cpn.loads("colset U = unit; place A : U = 1`(); place B : U;"
...                    " trans t; arc A -> t; arc t -> B;").engine()
>>> in_b = lambda s: engine.token_counts(s)[1] > 0
>>> check_ltl(engine, ("F", ("ap", 0)), [in_b]).holds, check_ltl(engine, ("G", ("ap", 0)), [in_b]).holds
(True, False)
"""

from __future__ import annotations

import time
from collections import deque
from collections.abc import Callable, Hashable
from dataclasses import dataclass, field

from cpn.checks.buchi import Automaton, translate


class Cache:
    """The successors of every state a search asked for, kept: formulas checked one after the other on
    the same system generate each state once. `expanded` counts the states whose successors were
    computed."""

    def __init__(self, system) -> None:
        self.system = system
        self.memo: dict = {}
        self._initial = None

    def initial_state(self):
        if self._initial is None:
            self._initial = self.system.initial_state()
        return self._initial

    def successors(self, state) -> list:
        got = self.memo.get(state)
        if got is None:
            got = self.memo[state] = list(self.system.successors(state))
        return got

    @property
    def expanded(self) -> int:
        return len(self.memo)


@dataclass
class LtlResult:
    """The verdict: `holds` True or False, or None when a limit stopped the search (`reason` says which).

    A violation comes with a lasso: `prefix` is the path (label, state) from the initial state (whose
    label is None) to the first state of the cycle, and `cycle` the steps (label, state) from there back
    to that state; a label None in the cycle is a dead state's stutter step. `product_states` counts the
    states of the product the search generated, `system_states` the distinct system states among them.
    """

    holds: bool | None
    prefix: list = field(default_factory=list)
    cycle: list = field(default_factory=list)
    product_states: int = 0
    system_states: int = 0
    automaton_states: int = 0
    reason: str = ""


class _Stop(Exception):
    pass


def check_ltl(system, formula: tuple, propositions: list[Callable[[Hashable], bool]],
              max_states: int | None = None, deadline: float | None = None,
              weak_fairness: list[tuple[Callable, Callable]] | None = None,
              strong_fairness: list[tuple[Callable, Callable]] | None = None,
              step_propositions: list[Callable[[Hashable], bool]] | None = None,
              counterexample: bool = True) -> LtlResult:
    """Whether every infinite path of `system` from its initial state satisfies `formula` (see the module).

    `max_states` bounds the system states the search reaches (the product has up to that many times the
    automaton's states), `deadline` (a `time.monotonic()` value) the time;
    either stops the search with `holds` None. `weak_fairness` lists (enabled(state), occurs(label))
    pairs, one per transition under weak fairness: only the paths on which each such transition, if it
    is enabled in every state from some point on, occurs infinitely often count. A strongly connected
    part of the product then has a fair accepting cycle when its arcs meet every acceptance set and, for
    each pair, one of its arcs occurs or one of its states does not enable the transition; this is
    decided when the part is complete (not at its first accepting cycle). `step_propositions` are
    tests of a step's label (None for a dead state's stutter step): ``("ap", len(propositions) + j)``
    holds in a position of a path when the step that leaves it satisfies `step_propositions[j]`. `strong_fairness` lists such
    pairs for transitions under strong fairness: a transition enabled infinitely often occurs infinitely
    often. A complete part whose arcs meet every acceptance set is then searched for a fair sub-part: if a
    listed transition is enabled in one of its states but occurs on none of its arcs, the states that
    enable it are removed and the SCCs of the rest are searched in turn (the standard refinement for
    Streett conditions); a fair cycle lies in a sub-part where every listed transition that is enabled
    also occurs. With `counterexample` False a violation comes without its lasso (only the verdict).
    """
    aut = translate(("not", formula))
    search = _Search(system, aut, propositions, max_states, deadline, step_propositions or [])
    search.weak = list(weak_fairness or [])
    search.strong = list(strong_fairness or [])
    search.counterexample = counterexample
    try:
        found = search.run()
    except _Stop as stop:
        return LtlResult(None, product_states=len(search.index), system_states=len(search.masks),
                         automaton_states=len(aut), reason=str(stop))
    res = LtlResult(found is None, product_states=len(search.index), system_states=len(search.masks),
                    automaton_states=len(aut))
    if found is not None:
        res.prefix, res.cycle = _without_stutter(*found)
    return res


def _without_stutter(prefix: list, cycle: list) -> tuple[list, list]:
    """A dead state's repeated stutter steps (several automaton states over one system state) as one:
    the prefix ends at the dead state and the cycle is its one stutter step."""
    for k, (label, s) in enumerate(prefix[1:], 1):
        if label is None:
            return prefix[:k], [(None, s)]
    if cycle and all(label is None for label, _s in cycle):
        return prefix, [cycle[0]]
    return prefix, cycle


_DONE = -1  # the index of a product state whose SCC is finished


class _Search:
    def __init__(self, system, aut: Automaton, propositions, max_states, deadline, step_props) -> None:
        self.system = system
        self.aut = aut
        self.props = propositions
        self.step_props = step_props
        self.step_masks: dict = {}  # label -> bitmask of its true step propositions
        self.max_states = max_states
        self.deadline = deadline
        self.masks: dict = {}  # system state -> bitmask of its true propositions
        self.index: dict = {}  # product state -> depth-first number, or _DONE
        self.weak: list = []  # (enabled(state), occurs(label)) per transition under weak fairness
        self.strong: list = []  # the same under strong fairness
        self.counterexample = True  # False: a violation is reported without building its lasso

    def mask(self, s) -> int:
        m = self.masks.get(s)
        if m is None:
            m = 0
            for i, p in enumerate(self.props):
                if p(s):
                    m |= 1 << i
            self.masks[s] = m
        return m

    def step_mask(self, label) -> int:
        m = self.step_masks.get(label)
        if m is None:
            m = 0
            for i, p in enumerate(self.step_props, len(self.props)):
                if label is not None and p(label):
                    m |= 1 << i
            self.step_masks[label] = m
        return m

    def steps(self, s) -> list:
        """The system's steps from s, a dead state stuttering."""
        out = self.system.successors(s)
        return out if out else [(None, s)]

    def successors(self, v: tuple) -> list:
        """(label, product state, acceptance sets) after product state v = (system state, automaton
        state): the automaton reads the present system state and the step that leaves it, the system
        moves."""
        s, q = v
        base = self.mask(s)
        by_mask: dict = {}
        out = []
        for label, t in self.steps(s):
            m = base | self.step_mask(label) if self.step_props else base
            moves = by_mask.get(m)
            if moves is None:
                moves = by_mask[m] = {}
                for acc, r in self.aut.moves(q, m):
                    moves[r] = moves.get(r, 0) | acc  # one edge per target, with every set some edge to it meets
            out.extend((label, (t, r), acc) for r, acc in moves.items())
        return out

    def run(self):
        """None when the product has no accepting cycle, else the lasso (prefix, cycle)."""
        aut = self.aut
        full = aut.full
        index = self.index
        roots: list[list] = []  # [depth-first number, sets met inside its SCC, sets of the arc into it]
        live: list = []  # states of the SCCs not yet finished, in depth-first order
        todo: list = []  # the depth-first path: [product state, its successors, next position, label in]
        fair = bool(self.weak or self.strong)  # then an accepting SCC is judged when it is complete

        def push(v, label, acc) -> None:
            index[v] = len(index)
            if self.max_states is not None and len(self.masks) > self.max_states:
                raise _Stop(f"the search reached more than {self.max_states:,} markings")
            if self.deadline is not None and len(index) % 256 == 0 and time.monotonic() > self.deadline:
                raise _Stop("the time limit was reached")
            roots.append([index[v], 0, acc])
            live.append(v)
            todo.append([v, self.successors(v), 0, label])

        push((self.system.initial_state(), aut.initial), None, 0)
        while todo:
            top = todo[-1]
            v, succ, k = top[0], top[1], top[2]
            if k == len(succ):
                todo.pop()
                if roots[-1][0] == index[v]:
                    if fair and roots[-1][1] == full:
                        scc = {w for w in live if index[w] >= index[v]}
                        part = self._fair_part(scc)
                        if part is not None:
                            todo.append(top)
                            return self.lasso(todo, index[v], scc, part)
                    roots.pop()
                    while True:
                        w = live.pop()
                        index[w] = _DONE
                        if w == v:
                            break
                continue
            top[2] = k + 1
            label, w, acc = succ[k]
            iw = index.get(w)
            if iw is None:
                push(w, label, acc)
                continue
            if iw == _DONE:
                continue
            met = acc
            while roots[-1][0] > iw:
                r = roots.pop()
                met |= r[1] | r[2]
            roots[-1][1] |= met
            if roots[-1][1] == full and not fair:
                root = roots[-1][0]
                scc = {w for w in live if index[w] >= root}
                return self.lasso(todo, root, scc, scc)
        return None

    def _fair_part(self, scc: set) -> set | None:
        """A part of the finished SCC `scc` (itself, or an SCC of it after the refinement) whose arcs meet
        every acceptance set, every weak pair (one of its arcs occurs, or one of its states does not enable
        the transition) and every strong pair (one of its arcs occurs, or none of its states enables the
        transition); None when there is none."""
        work = [scc]
        while work:
            part = work.pop()
            met, labels = 0, []
            for v in part:
                for label, w, acc in self.successors(v):
                    if w in part:
                        met |= acc
                        labels.append(label)
            if not labels or met != self.aut.full:
                continue  # a single state without a self-loop has no cycle
            if any(not any(map(occurs, labels)) and all(enabled(v[0]) for v in part)
                   for enabled, occurs in self.weak):
                continue  # so do all its sub-parts: the transition is enabled in each of their states
            ignored = [enabled for enabled, occurs in self.strong if not any(map(occurs, labels))]
            drop = {v for v in part if any(enabled(v[0]) for enabled in ignored)}
            if not drop:
                return part
            work.extend(self._components(part - drop))
        return None

    def _components(self, states: set) -> list[set]:
        """The SCCs of the product restricted to `states` (Tarjan's algorithm, iterative)."""
        index: dict = {}
        low: dict = {}
        stack: list = []
        on: set = set()
        out: list = []
        for s0 in states:
            if s0 in index:
                continue
            work = [(s0, iter([w for _l, w, _a in self.successors(s0) if w in states]))]
            index[s0] = low[s0] = len(index)
            stack.append(s0)
            on.add(s0)
            while work:
                v, it = work[-1]
                for w in it:
                    if w not in index:
                        index[w] = low[w] = len(index)
                        stack.append(w)
                        on.add(w)
                        work.append((w, iter([x for _l, x, _a in self.successors(w) if x in states])))
                        break
                    if w in on:
                        low[v] = min(low[v], index[w])
                else:
                    work.pop()
                    if work:
                        u = work[-1][0]
                        low[u] = min(low[u], low[v])
                    if low[v] == index[v]:
                        comp = set()
                        while True:
                            w = stack.pop()
                            on.discard(w)
                            comp.add(w)
                            if w == v:
                                break
                        out.append(comp)
        return out

    def lasso(self, todo: list, root: int, scc: set, inside: set):
        if not self.counterexample:
            return [], []
        return self._lasso(todo, root, scc, inside)

    def _lasso(self, todo: list, root: int, scc: set, inside: set):
        """The counterexample when `inside`, a part of the SCC `scc` of the root with depth-first number
        `root`, has a fair accepting cycle: the depth-first path to the root, a path in the SCC to a state
        of the part, then a cycle in the part through an arc of every acceptance set and fair to every
        weak and strong pair."""
        index, aut = self.index, self.aut
        prefix = []
        for v, _succ, _k, label in todo:
            prefix.append((label, v))
            if index[v] == root:
                break
        if prefix[-1][1] not in inside:
            prefix.extend((label, w) for label, w, _acc in
                          self._path(prefix[-1][1], scc, lambda label, w, acc: w in inside))
        start = prefix[-1][1]
        cycle: list = []
        cur = start
        need = aut.full
        while need:
            k = (need & -need).bit_length() - 1
            seg = self._path(cur, inside, lambda label, w, acc, k=k: acc >> k & 1)
            for _label, _v, acc in seg:
                need &= ~acc
            cycle.extend(seg)
            cur = seg[-1][1]
        for enabled, occurs in self.weak:
            # the transition occurs on the cycle, or the cycle passes a state where it is not enabled
            if any(occurs(label) or not enabled(v[0]) for label, v, _acc in cycle):
                continue
            seg = self._path(cur, inside, lambda label, w, acc, e=enabled, o=occurs: o(label) or not e(w[0]))
            cycle.extend(seg)
            cur = seg[-1][1]
        for _enabled, occurs in self.strong:
            # in a fair part a transition that is enabled somewhere occurs on some arc: the cycle takes one
            if any(occurs(label) for label, _v, _acc in cycle) or \
                    not any(occurs(label) for v in inside for label, w, _a in self.successors(v) if w in inside):
                continue
            seg = self._path(cur, inside, lambda label, w, acc, o=occurs: o(label))
            cycle.extend(seg)
            cur = seg[-1][1]
        if cur != start or not cycle:
            cycle.extend(self._path(cur, inside, None, start))
        prefix, cycle = self._shortest_prefix(prefix, cycle)
        return ([(label, v[0]) for label, v in prefix], [(label, v[0]) for label, v, _acc in cycle])

    def _shortest_prefix(self, prefix: list, cycle: list) -> tuple[list, list]:
        """The lasso with the shortest prefix to the cycle found through the product states the search
        generated: a breadth-first search of them from the initial product state to the nearest product
        state of the cycle, which is then entered there (rotated to start and end at that state). No new
        state is generated (the search may have left unvisited a shorter way through states it never
        reached). The cycle itself is the one found (not the shortest accepting cycle); it keeps every arc,
        so it meets the same acceptance sets and fairness."""
        states = [prefix[-1][1]] + [w for _label, w, _acc in cycle[:-1]]
        at = {}
        for k, v in enumerate(states):
            at.setdefault(v, k)
        v0 = prefix[0][1]
        generated = self.index
        parent: dict = {v0: None}
        queue = deque([v0])
        hit = v0 if v0 in at else None
        while queue and hit is None:
            u = queue.popleft()
            for label, w, _acc in self.successors(u):
                if w in parent or w not in generated:
                    continue
                parent[w] = (u, label)
                if w in at:
                    hit = w
                    break
                queue.append(w)
        if hit is None:
            return prefix, cycle
        path = []
        v = hit
        while parent[v] is not None:
            u, label = parent[v]
            path.append((label, v))
            v = u
        path.append((None, v0))
        path.reverse()
        if len(path) >= len(prefix):
            return prefix, cycle  # the search's own prefix is already a shortest one
        k = at[hit]
        return path, cycle[k:] + cycle[:k]

    def _path(self, frm, inside: set, arc_goal, to=None) -> list:
        """The shortest steps (label, product state, sets) from frm inside the SCC, ending with an arc
        that `arc_goal(label, target, sets)` accepts, or at state `to` (at least one step)."""
        parent: dict = {}
        queue = deque([frm])
        seen = {frm}
        while queue:
            u = queue.popleft()
            for label, w, acc in self.successors(u):
                if w not in inside:
                    continue
                if (arc_goal is not None and arc_goal(label, w, acc)) or (to is not None and w == to):
                    out = [(label, w, acc)]
                    while u != frm:
                        u, step = parent[u]
                        out.append(step)
                    return out[::-1]
                if w not in seen:
                    seen.add(w)
                    parent[w] = (u, (label, w, acc))
                    queue.append(w)
        raise AssertionError("a state of an accepting SCC reaches every state and arc of it")


__all__ = ["Cache", "LtlResult", "check_ltl"]
