"""CTL on a finished occurrence graph: the labelling algorithm, with fairness, and its counterexamples.

Formulas are small trees (`Atom`, `Not`, `And`, `Or`, `EX`, `AX`, `EU`, `AU`, `EG`, `AF`, `EF`, `AG`); an
atom is a precomputed set of states (a bytearray). Paths are maximal (infinite, or ending in a dead
state). With fairness (sets of transition labels), path quantifiers range over *fair* paths: finite
maximal paths, and infinite paths that take an arc of every set infinitely often. `EG` is computed on the
SCC decomposition of the sub-graph where its argument holds (Clarke, Emerson and Sistla 1986; Emerson
and Lei 1986 for the fairness constraints), every operator in time linear in the size of the graph.
Imports `cpn.statespace` and the standard library only.
"""

from __future__ import annotations

import operator
import time
from array import array
from bisect import bisect_left
from collections import deque
from dataclasses import dataclass

from cpn.statespace import graphnative
from cpn.statespace.scc import strongly_connected_components


# ----------------------------------------------------------------------------- formulas
@dataclass(frozen=True)
class Atom:
    index: int
    text: str = ""


@dataclass(frozen=True)
class Not:
    arg: object


@dataclass(frozen=True)
class And:
    left: object
    right: object


@dataclass(frozen=True)
class Or:
    left: object
    right: object


@dataclass(frozen=True)
class Temporal:
    op: str  # EX AX EF AF EG AG EU AU, and EXB AXB (only arcs whose label `arcs` accepts)
    args: tuple
    arcs: object = None


class OutOfTime(Exception):
    """The deadline of a `Kripke` passed before the formula was labelled (the reason)."""


class Kripke:
    """The graph the formulas are evaluated on: n states, CSR successors, arc labels, predecessors."""

    def __init__(self, n: int, offsets, dst, labels, fairness: list[set] | None = None, predecessors=None,
                 full_scc=None):
        self.n = n
        self.offsets = offsets
        self.dst = dst
        self.labels = labels  # per arc: a label (transition or binding element), for fairness
        self.fairness = [set(f) for f in (fairness or [])]
        self.dead = bytearray(map(operator.eq, offsets[:n], offsets[1:n + 1]))
        self.pred_off, self.pred = predecessors if predecessors is not None else reverse_csr(n, offsets, dst)
        self.full_scc = full_scc
        self.arc_hints: dict = {}  # (u, v) -> arc index, for steps of explanations that need one arc
        self._fair = None
        #: a `time.monotonic()` value: `label` raises `OutOfTime` when it is passed before a temporal
        #: operator (each operator is one pass over the graph)
        self.deadline: float | None = None

    def successors(self, u: int):
        return self.dst[self.offsets[u]:self.offsets[u + 1]]

    def predecessors(self, v: int):
        return self.pred[self.pred_off[v]:self.pred_off[v + 1]]

    # ------------------------------------------------------------------ primitives
    def fair(self) -> bytearray:
        """States from which a fair maximal path starts (every state, without fairness)."""
        if self._fair is None:
            self._fair = self.eg(bytearray([1]) * self.n) if self.fairness else bytearray([1]) * self.n
        return self._fair

    def ex(self, phi: bytearray) -> bytearray:
        target = _and(phi, self.fair())
        fast = graphnative.ex(self.n, self.pred_off, self.pred, target)
        if fast is not None:
            return fast
        out = bytearray(self.n)
        for v in range(self.n):
            if target[v]:
                for u in self.predecessors(v):
                    out[u] = 1
        return out

    def exb(self, phi: bytearray, accept) -> bytearray:
        """States with an arc whose label `accept`s, to a (fair) phi-state."""
        target = _and(phi, self.fair())
        out = bytearray(self.n)
        offsets, dst, labels = self.offsets, self.dst, self.labels
        for u in range(self.n):
            for a in range(offsets[u], offsets[u + 1]):
                if target[dst[a]] and accept(labels[a]):
                    out[u] = 1
                    break
        return out

    def eu(self, phi: bytearray, psi: bytearray) -> bytearray:
        fast = graphnative.eu(self.n, self.pred_off, self.pred, phi, _and(psi, self.fair()))
        if fast is not None:
            return fast
        return self._backward(_and(psi, self.fair()), phi)

    def _backward(self, out: bytearray, phi: bytearray) -> bytearray:
        """`out` grown by every phi-state from which a path of phi-states reaches it (in place)."""
        queue = deque(v for v in range(self.n) if out[v])
        while queue:
            v = queue.popleft()
            for u in self.predecessors(v):
                if not out[u] and phi[u]:
                    out[u] = 1
                    queue.append(u)
        return out

    def eg_seeds(self, phi: bytearray) -> tuple[bytearray, object]:
        """phi-states where a fair path staying in phi can stay forever: dead phi-states and the states of
        fair nontrivial SCCs of the phi-sub-graph. Also returns the decomposition."""
        if self.full_scc is not None and 0 not in phi:
            dec = self.full_scc  # the sub-graph is the whole graph: its decomposition is already known
        else:
            dec = strongly_connected_components(self.n, self.offsets, self.dst, keep_node=phi)
        seeds = bytearray(self.n)
        ok = bytearray(dec.count)
        for c in range(dec.count):
            ok[c] = dec.nontrivial[c]
        if self.fairness:
            # one bit per fairness set: a label's mask says which sets it belongs to
            masks: dict = {}
            for k, f in enumerate(self.fairness):
                for lab in f:
                    masks[lab] = masks.get(lab, 0) | (1 << k)
            full = (1 << len(self.fairness)) - 1
            have = [0] * dec.count
            comp, offsets, dst, labels = dec.comp, self.offsets, self.dst, self.labels
            get = masks.get
            for u in range(self.n):
                cu = comp[u]
                if cu < 0 or not ok[cu] or have[cu] == full:
                    continue
                for a in range(offsets[u], offsets[u + 1]):
                    if comp[dst[a]] == cu:
                        have[cu] |= get(labels[a], 0)
            for c in range(dec.count):
                if ok[c] and have[c] != full:
                    ok[c] = 0
        comp = dec.comp
        for v in range(self.n):
            if phi[v] and (self.dead[v] or (comp[v] >= 0 and ok[comp[v]])):
                seeds[v] = 1
        return seeds, dec

    def eg(self, phi: bytearray) -> bytearray:
        if not self.fairness:
            fast = graphnative.eg(self.n, self.offsets, self.dst, self.pred_off, self.pred, self.dead, phi)
            if fast is not None:
                return fast
        seeds, _ = self.eg_seeds(phi)
        return self._backward(bytearray(seeds), phi)

    # ------------------------------------------------------------------ formulas
    def label(self, f, atoms: list[bytearray], memo: dict | None = None) -> bytearray:
        """The set of states satisfying formula f."""
        memo = {} if memo is None else memo
        got = memo.get(id(f))
        if got is not None:
            return got[1]
        out = self._label(f, atoms, memo)
        memo[id(f)] = (f, out)
        return out

    def _label(self, f, atoms, memo) -> bytearray:
        n = self.n
        if isinstance(f, Atom):
            return atoms[f.index]
        if isinstance(f, Not):
            return _not(self.label(f.arg, atoms, memo))
        if isinstance(f, And):
            return _and(self.label(f.left, atoms, memo), self.label(f.right, atoms, memo))
        if isinstance(f, Or):
            return _or(self.label(f.left, atoms, memo), self.label(f.right, atoms, memo))
        a = [self.label(x, atoms, memo) for x in f.args]
        if self.deadline is not None and time.monotonic() > self.deadline:
            raise OutOfTime(f"the time limit passed while labelling the {n:,} states with {f.op}")
        op = f.op
        if op == "EXB":
            return self.exb(a[0], f.arcs)
        if op == "AXB":
            return _not(self.exb(_not(a[0]), f.arcs))
        if op == "EX":
            return self.ex(a[0])
        if op == "AX":
            return _not(self.ex(_not(a[0])))
        if op == "EF":
            return self.eu(bytearray([1]) * n, a[0])
        if op == "AG":
            return _not(self.eu(bytearray([1]) * n, _not(a[0])))
        if op == "EG":
            return self.eg(a[0])
        if op == "AF":
            return _not(self.eg(_not(a[0])))
        if op == "EU":
            return self.eu(a[0], a[1])
        if op == "AU":
            npsi = _not(a[1])
            bad = _or(self.eu(npsi, _and(_not(a[0]), npsi)), self.eg(npsi))
            return _not(bad)
        raise ValueError(f"unknown CTL operator {op}")

    # ------------------------------------------------------------------ evidence
    def path_to(self, start: int, target: bytearray, within: bytearray | None = None) -> list[int] | None:
        """Shortest path (states) from start to a target state, through `within` states (BFS)."""
        if target[start]:
            return [start]
        parent = {start: -1}
        queue = deque([start])
        while queue:
            u = queue.popleft()
            for v in self.successors(u):
                if v in parent or (within is not None and not within[v] and not target[v]):
                    continue
                parent[v] = u
                if target[v]:
                    path = [v]
                    while parent[path[-1]] >= 0:
                        path.append(parent[path[-1]])
                    return path[::-1]
                queue.append(v)
        return None

    def lasso(self, start: int, phi: bytearray) -> tuple[list[int], list[int]] | None:
        """A fair maximal path from `start` staying in phi: (stem states, cycle states).

        The stem ends at a dead state (cycle empty) or at the first state of the cycle; the cycle lists
        the states after it, the last of which is the stem's last state again (a real cycle).
        """
        if not phi[start]:
            return None
        seeds, dec = self.eg_seeds(phi)
        good = self.eg(phi)
        if not good[start]:
            return None
        stem = self.path_to(start, seeds, within=good)
        if stem is None:
            return None
        s = stem[-1]
        if self.dead[s]:
            return stem, []
        c = dec.comp[s]
        inside = bytearray(self.n)
        for v in dec.nodes(c):
            inside[v] = 1
        cycle: list[int] = []
        self.last_cycle_arcs: list[int] = []
        cur = s
        for f in self.fairness:
            # reach an arc of f inside the SCC, take it
            src = bytearray(self.n)
            for u in dec.nodes(c):
                for a in range(self.offsets[u], self.offsets[u + 1]):
                    if self.labels[a] in f and inside[self.dst[a]]:
                        src[u] = 1
            seg = self.path_to(cur, src, within=inside)
            cycle.extend(seg[1:])
            self.last_cycle_arcs.extend([-1] * (len(seg) - 1))
            u = seg[-1]
            for a in range(self.offsets[u], self.offsets[u + 1]):
                if self.labels[a] in f and inside[self.dst[a]]:
                    cur = self.dst[a]
                    cycle.append(cur)
                    self.last_cycle_arcs.append(a)
                    break
        # back to s (at least one step)
        if not cycle or cycle[-1] != s:
            back = self._cycle_back(cur, s, inside) if cycle else self._cycle_back(s, s, inside)
            cycle.extend(back)
            self.last_cycle_arcs.extend([-1] * len(back))
        return stem, cycle

    def _cycle_back(self, frm: int, to: int, inside: bytearray) -> list[int]:
        """A path of at least one arc from frm to `to` inside the SCC, without frm itself."""
        parent: dict[int, int] = {}
        queue = deque()
        for v in self.successors(frm):
            if inside[v] and v not in parent:
                parent[v] = -1
                if v == to:
                    return [to]
                queue.append(v)
        while queue:
            u = queue.popleft()
            for v in self.successors(u):
                if inside[v] and v not in parent:
                    parent[v] = u
                    if v == to:
                        path = [v]
                        while parent[path[-1]] >= 0:
                            path.append(parent[path[-1]])
                        return path[::-1]
                    queue.append(v)
        raise AssertionError("a state of a nontrivial SCC has a path back to itself")

    def explain(self, f, atoms, start: int, value: bool, memo: dict) -> tuple[list[int], list[int]]:
        """Why f has truth value `value` in `start`: a path (states from start) and a cycle (maybe empty)."""
        if isinstance(f, Atom):
            return [start], []
        if isinstance(f, Not):
            return self.explain(f.arg, atoms, start, not value, memo)
        if isinstance(f, (And, Or)):
            # a false And, or a true Or, is explained by one part with that value; otherwise both parts have
            # the value and either explains it. Parts with a temporal operator explain more than atoms.
            parts = sorted([f.left, f.right], key=lambda p: not _temporal(p))
            for p in parts:
                if bool(self.label(p, atoms, memo)[start]) == value:
                    return self.explain(p, atoms, start, value, memo)
            return [start], []
        op = f.op
        a = [self.label(x, atoms, memo) for x in f.args]
        if (op == "AG" and not value) or (op == "EF" and value):
            target = _not(a[0]) if op == "AG" else a[0]
            target = _and(target, self.fair())
            path = self.path_to(start, target)
            if path is None:
                return [start], []
            rest, cyc = self.explain(f.args[0], atoms, path[-1], op != "AG", memo)
            return path[:-1] + rest, cyc
        if (op == "AF" and not value) or (op == "EG" and value):
            phi = _not(a[0]) if op == "AF" else a[0]
            got = self.lasso(start, phi)
            return got if got is not None else ([start], [])
        if (op == "EXB" and value) or (op == "AXB" and not value):
            target = _and(a[0] if op == "EXB" else _not(a[0]), self.fair())
            for x in range(self.offsets[start], self.offsets[start + 1]):
                if target[self.dst[x]] and f.arcs(self.labels[x]):
                    self.arc_hints[(start, self.dst[x])] = x  # this arc, not any arc between the two
                    return [start, self.dst[x]], []
            return [start], []
        if (op == "EX" and value) or (op == "AX" and not value):
            target = _and(a[0] if op == "EX" else _not(a[0]), self.fair())
            for v in self.successors(start):
                if target[v]:
                    return [start, v], []
            return [start], []
        if op == "EU" and value:
            path = self.path_to(start, _and(a[1], self.fair()), within=a[0])
            return (path, []) if path is not None else ([start], [])
        if op == "AU" and not value:
            npsi = _not(a[1])
            bad = _and(_not(a[0]), npsi)
            if self.eu(npsi, bad)[start]:
                path = self.path_to(start, _and(bad, self.fair()), within=npsi)
                if path is not None:
                    return path, []
            got = self.lasso(start, npsi)
            return got if got is not None else ([start], [])
        return [start], []


def _temporal(f) -> bool:
    if isinstance(f, Temporal):
        return True
    if isinstance(f, Not):
        return _temporal(f.arg)
    if isinstance(f, (And, Or)):
        return _temporal(f.left) or _temporal(f.right)
    return False


def reverse_csr(n: int, offsets, dst) -> tuple[array, array]:
    """Predecessors in CSR form: (pred_off, pred), the sources of the arcs into v being
    pred[pred_off[v]:pred_off[v+1]], in the order of the arcs: a counting sort in native code
    (`cpn.statespace.graphnative`), else a sort of the arc indices by destination."""
    got = graphnative.reverse(n, offsets, dst)
    if got is not None:
        return got
    m = len(dst)
    src = array("i")
    for u in range(n):
        k = offsets[u + 1] - offsets[u]
        if k:
            src.extend(array("i", [u]) * k)
    order = sorted(range(m), key=dst.__getitem__)
    pred = array("i", map(src.__getitem__, order))
    ends = array("i", map(dst.__getitem__, order))
    pred_off = array("q", (bisect_left(ends, v) for v in range(n + 1)))
    return pred_off, pred


def _not(a: bytearray) -> bytearray:
    return a.translate(_NOT)


_NOT = bytes([1, 0] + [0] * 254)


# 0/1 bytes combine as big integers: one C operation instead of a Python loop per state
def _and(a: bytearray, b: bytearray) -> bytearray:
    return bytearray((int.from_bytes(a, "little") & int.from_bytes(b, "little")).to_bytes(len(a), "little"))


def _or(a: bytearray, b: bytearray) -> bytearray:
    return bytearray((int.from_bytes(a, "little") | int.from_bytes(b, "little")).to_bytes(len(a), "little"))
