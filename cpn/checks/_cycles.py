"""Cycle searches for fairness, confined to the strongly connected components of the graph.

Imports the standard library only. Every cycle of the occurrence graph lies inside one SCC, so the
searches start from given roots and go only where a cycle can be: the cycle search through the states
it is told to keep, Tarjan along arcs whose two ends are in the same SCC (`comp[v] == comp[w]`),
resetting only the states it touched. Apart from a memset of one byte per state, a search costs what
it visits, not the size of the whole graph, so one per transition instance does not cost graph x
transitions when each stays in a small region.
"""

from __future__ import annotations

from array import array


class ConfinedSearch:
    """Depth-first searches over the arcs that stay inside an SCC and do not carry a given label."""

    def __init__(self, n: int, offsets: array, dst: array, labels: array, comp: array):
        self.offsets, self.dst, self.labels, self.comp = offsets, dst, labels, comp
        self.index = array("i", [-1]) * n  # DFS number (-1: unvisited); reset after each search
        self.low = array("i", [0]) * n
        self.mark = bytearray(n)  # Tarjan: 1 once the state's SCC is complete; reset after each search

    def cycle_avoiding(self, avoid: int, roots, keep: bytearray) -> bool:
        """Whether some cycle reachable from `roots` through states whose `keep` entry is set avoids the
        arcs labelled `avoid`. Stops at the first arc back to the DFS stack.

        Arcs between SCCs are followed (a cycle lies inside one SCC anyway, so they cannot make one):
        testing `comp` on every arc made the search half as fast again on SwimmingPool-PT-01; `keep`
        already confines it (the states of the nontrivial SCCs, or those enabling a transition)."""
        off, dst, labels = self.offsets, self.dst, self.labels
        colour = bytearray(len(self.mark))  # 0 unseen, 1 on the DFS stack, 2 done; a memset per search
        for root in roots:
            if colour[root]:
                continue
            colour[root] = 1
            work = [root]
            ptr = [off[root]]
            while work:
                v = work[-1]
                i = ptr[-1]
                end = off[v + 1]
                while i < end:
                    if labels[i] == avoid:
                        i += 1
                        continue
                    w = dst[i]
                    i += 1
                    cw = colour[w]
                    if cw == 1:
                        return True
                    if cw == 0 and keep[w]:
                        ptr[-1] = i
                        colour[w] = 1
                        work.append(w)
                        ptr.append(off[w])
                        break
                else:
                    colour[v] = 2
                    work.pop()
                    ptr.pop()
        return False

    def component_through(self, avoid: int, roots, accept: bytearray) -> bool:
        """Whether the graph less the arcs labelled `avoid` has a nontrivial SCC (a self-loop counts)
        that holds a state with `accept` set, among the SCCs reachable from `roots` (Tarjan, iterative,
        stopping at the first such SCC)."""
        off, dst, labels, comp = self.offsets, self.dst, self.labels, self.comp
        index, low = self.index, self.low
        done = self.mark  # 1 once the state's SCC is complete
        touched = array("i")
        stack = array("i")
        counter = 0
        try:
            for root in roots:
                if index[root] != -1:
                    continue
                index[root] = low[root] = counter
                counter += 1
                touched.append(root)
                stack.append(root)
                work = array("i", [root])
                ptr = array("q", [off[root]])
                while work:
                    v = work[-1]
                    i = ptr[-1]
                    end = off[v + 1]
                    lv = low[v]
                    cv = comp[v]
                    descended = False
                    while i < end:
                        if labels[i] == avoid:
                            i += 1
                            continue
                        w = dst[i]
                        i += 1
                        if comp[w] != cv:
                            continue
                        iw = index[w]
                        if iw == -1:
                            low[v] = lv
                            ptr[-1] = i
                            index[w] = low[w] = counter
                            counter += 1
                            touched.append(w)
                            stack.append(w)
                            work.append(w)
                            ptr.append(off[w])
                            descended = True
                            break
                        if not done[w] and iw < lv:
                            lv = iw
                    if descended:
                        continue
                    low[v] = lv
                    work.pop()
                    ptr.pop()
                    if lv == index[v]:
                        size = 0
                        hit = False
                        while True:
                            w = stack.pop()
                            done[w] = 1
                            size += 1
                            if accept[w]:
                                hit = True
                            if w == v:
                                break
                        if hit:
                            if size > 1:
                                return True
                            a, b = off[v], off[v + 1]
                            if v in dst[a:b] and any(w == v and lab != avoid
                                                     for w, lab in zip(dst[a:b], labels[a:b])):
                                return True
                    elif work:
                        u = work[-1]
                        if lv < low[u]:
                            low[u] = lv
            return False
        finally:
            for v in touched:
                index[v] = -1
                done[v] = 0


def walk_cycle(offsets: array, dst: array, comp: array, start: int, choice: int, max_steps: int = 4096,
               labels: array | None = None, avoid: int = -1) -> list[int] | None:
    """The arcs (positions in `dst`) of a cycle inside the SCC of `start`, found by walking from it.

    Every state of a nontrivial SCC has an arc to a state of the same SCC, so a walk that always takes
    such an arc (the `choice`-th one, cyclically) revisits a state within |SCC| steps; the arcs from that
    state's first visit on form a cycle. `start` must lie in a nontrivial SCC. With `labels`, arcs
    labelled `avoid` are not taken, and the walk can get stuck. None when it gets stuck or revisits no
    state within `max_steps` steps (the walk is only a cheap source of witnesses).
    """
    c = comp[start]
    seen: dict[int, int] = {}
    path: list[int] = []
    v = start
    while v not in seen:
        if len(path) >= max_steps:
            return None
        seen[v] = len(path)
        a, b = offsets[v], offsets[v + 1]
        if labels is None:
            inside = [i for i in range(a, b) if comp[dst[i]] == c]
        else:
            inside = [i for i in range(a, b) if comp[dst[i]] == c and labels[i] != avoid]
            if not inside:
                return None
        i = inside[choice % len(inside)]
        path.append(i)
        v = dst[i]
    return path[seen[v]:]
