"""Strongly connected components of the occurrence graph: an iterative Tarjan on the CSR arrays.

Imports the standard library only. No recursion, so graphs of millions of states are fine.

References
----------
R. Tarjan, "Depth-first search and linear graph algorithms", SIAM J. Computing 1(2), 1972.
"""

from __future__ import annotations

from array import array
from dataclasses import dataclass


@dataclass
class SccDecomposition:
    """SCCs numbered 0.. in the order Tarjan completes them (a reverse topological order).

    `comp[v]` is the SCC of state v; `members[start[c]:start[c+1]]` are the states of SCC c;
    `terminal[c]` says no arc leaves SCC c; `nontrivial[c]` says SCC c contains a cycle (more than one
    state, or one state with a self-loop), i.e. an infinite occurrence sequence can stay in it.
    """

    comp: array
    members: array
    start: array
    terminal: bytearray
    nontrivial: bytearray

    @property
    def count(self) -> int:
        return len(self.start) - 1

    def nodes(self, c: int) -> array:
        return self.members[self.start[c]:self.start[c + 1]]

    def terminal_components(self) -> list[int]:
        return [c for c in range(self.count) if self.terminal[c]]


def _padded(offsets: array, n: int) -> array:
    """CSR offsets for n states where only the first len(offsets)-1 were expanded (no arcs after)."""
    if len(offsets) - 1 >= n:
        return offsets
    out = array("q", offsets)
    out.extend(array("q", [offsets[-1]]) * (n - (len(offsets) - 1)))
    return out


def strongly_connected_components(n: int, offsets: array, dst: array, skip_arc=None, keep_node=None,
                                  stop_at=None):
    """Tarjan's algorithm, iterative, over states 0..n-1 and the arcs `dst[offsets[v]:offsets[v+1]]`.

    Parameters
    ----------
    skip_arc : optional bytearray over arcs; arcs with a true entry are ignored.
    keep_node : optional bytearray over states; states with a false entry are ignored, as are arcs to them.
    stop_at : optional callable(nodes: list[int]) -> bool, called on each *nontrivial* SCC as soon as it
        is complete; when it returns true the search stops and that list is returned (the caller wants a
        witness, not the decomposition). If it never does, None is returned.

    Returns
    -------
    SccDecomposition, or (with stop_at) the first accepted nontrivial SCC's states or None.

    Examples
    --------
    >>> from array import array
    >>> d = strongly_connected_components(3, array("q", [0, 1, 2, 2]), array("i", [1, 0]))
    >>> d.count, list(d.comp), list(d.terminal)
    (2, [1, 1, 0], [1, 0])
    """
    offsets = _padded(offsets, n)
    index = array("i", [-1]) * n
    low = array("i", [0]) * n
    comp = array("i", [-1]) * n
    members = array("i")
    start = array("i", [0])
    terminal = bytearray()
    nontrivial = bytearray()
    exits = bytearray(n)  # state has an arc to an already completed (hence different) SCC
    loops = bytearray(n)  # state has a self-loop
    stack: list[int] = []
    counter = 0
    ncomp = 0
    for root in range(n):
        if index[root] != -1 or (keep_node is not None and not keep_node[root]):
            continue
        index[root] = low[root] = counter
        counter += 1
        stack.append(root)
        work = [root]
        ptr = [offsets[root]]
        while work:
            v = work[-1]
            i = ptr[-1]
            end = offsets[v + 1]
            lv = low[v]
            descended = False
            while i < end:
                w = dst[i]
                i += 1
                if skip_arc is not None and skip_arc[i - 1]:
                    continue
                iw = index[w]
                if iw == -1:
                    if keep_node is not None and not keep_node[w]:
                        continue
                    low[v] = lv
                    ptr[-1] = i
                    index[w] = low[w] = counter
                    counter += 1
                    stack.append(w)
                    work.append(w)
                    ptr.append(offsets[w])
                    descended = True
                    break
                if comp[w] == -1:
                    if iw < lv:
                        lv = iw
                    if w == v:
                        loops[v] = 1
                else:
                    exits[v] = 1
            if descended:
                continue
            low[v] = lv
            work.pop()
            ptr.pop()
            if lv == index[v]:
                first = len(members)
                term = 1
                loop = 0
                while True:
                    w = stack.pop()
                    comp[w] = ncomp
                    members.append(w)
                    if exits[w]:
                        term = 0
                    if loops[w]:
                        loop = 1
                    if w == v:
                        break
                size = len(members) - first
                nt = 1 if size > 1 or loop else 0
                if stop_at is not None and nt:
                    nodes = members[first:].tolist()
                    if stop_at(nodes):
                        return nodes
                start.append(len(members))
                terminal.append(term)
                nontrivial.append(nt)
                ncomp += 1
                if work:
                    exits[work[-1]] = 1
            elif work:
                u = work[-1]
                if lv < low[u]:
                    low[u] = lv
    if stop_at is not None:
        return None
    return SccDecomposition(comp, members, start, terminal, nontrivial)


def has_cycle(n: int, offsets: array, dst: array, skip_arc=None, keep_node=None, within=None) -> bool:
    """Whether the graph (less skipped arcs and dropped states) has a cycle; self-loops count.

    `within(nodes) -> bool` restricts which nontrivial SCCs count (default: any).
    """
    accept = within if within is not None else (lambda nodes: True)
    return strongly_connected_components(n, offsets, dst, skip_arc, keep_node, stop_at=accept) is not None


def scc_graph_arcs(dec: SccDecomposition, offsets: array, dst: array) -> tuple[int, int]:
    """Arcs of the SCC graph: (state-space arcs between distinct SCCs, distinct ordered SCC pairs)."""
    if dec.count <= 1:
        return 0, 0
    comp = dec.comp
    offsets = _padded(offsets, len(comp))
    members, start = dec.members, dec.start
    total = 0
    pairs = 0
    for c in range(dec.count):
        targets = set()
        for k in range(start[c], start[c + 1]):
            v = members[k]
            a, b = offsets[v], offsets[v + 1]
            if a == b:
                continue
            cs = list(map(comp.__getitem__, dst[a:b]))
            inside = cs.count(c)
            if inside != len(cs):
                total += len(cs) - inside
                targets.update(cs)
        targets.discard(c)
        pairs += len(targets)
    return total, pairs
