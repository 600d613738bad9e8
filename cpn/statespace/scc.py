"""Strongly connected components and cycles of the occurrence graph: an iterative Tarjan on the CSR
arrays, the search for a cycle, and a walk that finds one cheaply. The one Python implementation of
each: the liveness, home-marking, fairness, livelock and CTL checks (`cpn.checks`, `cpn.properties`)
all use these.

Imports the standard library and `cpn.statespace.graphnative` only. No recursion, so graphs of millions
of states are fine. The plain decomposition and the SCC graph's arcs run in C where native code is
available (`graphnative`, the same algorithm in the same order, so the same numbering); the Python code
here is the fallback and the tests' reference.

References
----------
R. Tarjan, "Depth-first search and linear graph algorithms", SIAM J. Computing 1(2), 1972.
"""

from __future__ import annotations

from array import array
from dataclasses import dataclass

from cpn.statespace import graphnative


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


def strongly_connected_components(n: int, offsets: array, dst: array, arc_labels=None, avoid: int = -1,
                                  keep_node=None, stop_at=None, native: bool = True, roots=None, within=None):
    """Tarjan's algorithm, iterative, over states 0..n-1 and the arcs `dst[offsets[v]:offsets[v+1]]`.

    Parameters
    ----------
    arc_labels, avoid : optional array over arcs (e.g. the transition of each arc) and a label; arcs
        whose label equals `avoid` are ignored.
    keep_node : optional bytearray over states; states with a false entry are ignored, as are arcs to them.
    stop_at : optional callable(nodes: list[int]) -> bool, called on each *nontrivial* SCC as soon as it
        is complete; when it returns true the search stops and that list is returned (the caller wants a
        witness, not the decomposition). If it never does, None is returned.
    roots : optional iterable of states: the search starts only from these (and sees only what they
        reach), instead of from every state.
    within : optional array over states (the SCC of each state in a decomposition of a larger graph): only
        arcs between two states with the same entry are followed. Every cycle lies inside one SCC, so a
        search for cycles of a subgraph loses none and goes only where one can be.

    Returns
    -------
    SccDecomposition, or (with stop_at) the first accepted nontrivial SCC's states or None.

    Without labels, kept states or stop_at, and with `native`, the decomposition is computed in C where
    that is available (`graphnative.scc`): the same SCCs, numbered the same way.

    Examples
    --------
    >>> from array import array
    >>> d = strongly_connected_components(3, array("q", [0, 1, 2, 2]), array("i", [1, 0]))
    >>> d.count, list(d.comp), list(d.terminal)
    (2, [0, 0, 1], [1, 1])
    """
    if native and arc_labels is None and keep_node is None and stop_at is None and roots is None \
            and within is None:
        fast = graphnative.scc(n, offsets, dst)
        if fast is not None:
            return SccDecomposition(*fast)
    offsets = _padded(offsets, n)
    index = array("i", [-1]) * n
    low = array("i", [0]) * n
    comp = array("i", [-1]) * n
    members = array("i")
    start = array("i", [0])
    terminal = bytearray()
    nontrivial = bytearray()
    exits = bytearray(n)  # state has an arc to an already completed (hence different) SCC
    stack = array("i")
    stack_append = stack.append
    counter = 0
    ncomp = 0
    filtered = arc_labels is not None
    # The depth-first search: descend along the first unvisited arc of the top frame, or, when the
    # frame has no arc left, pop it and, if it is the root of a component, close the component.
    # A DFS frame is a state and the position of its next arc (two ints in two lists). Frames that
    # held an iterator over a slice of dst ran no faster and cost about 200 bytes each, and the DFS
    # of a single large SCC is as deep as the SCC: on MS(8) that was 100 MB of peak memory.
    for root in range(n) if roots is None else roots:
        if index[root] != -1 or (keep_node is not None and not keep_node[root]):
            continue
        index[root] = low[root] = counter
        counter += 1
        stack_append(root)
        work = array("i", [root])
        ptr = array("q", [offsets[root]])
        while work:
            v = work[-1]
            i = ptr[-1]
            end = offsets[v + 1]
            lv = low[v]
            cv = within[v] if within is not None else 0
            descended = False
            while i < end:
                if filtered and arc_labels[i] == avoid:
                    i += 1
                    continue
                w = dst[i]
                i += 1
                if within is not None and within[w] != cv:
                    continue
                iw = index[w]
                if iw == -1:
                    if keep_node is not None and not keep_node[w]:
                        continue
                    low[v] = lv
                    ptr[-1] = i
                    index[w] = low[w] = counter
                    counter += 1
                    stack_append(w)
                    work.append(w)
                    ptr.append(offsets[w])
                    descended = True
                    break
                if comp[w] == -1:
                    if iw < lv:
                        lv = iw
                else:
                    exits[v] = 1
            if descended:
                continue
            low[v] = lv
            work.pop()
            ptr.pop()
            if lv == index[v]:
                # v is the root of a component: everything above it on the stack belongs to it
                first = len(members)
                term = _close_component(v, stack, comp, members, exits, ncomp)
                nt = 1 if len(members) - first > 1 or _self_loop(v, offsets, dst, arc_labels, avoid) else 0
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


def _close_component(v: int, stack: array, comp: array, members: array, exits: bytearray, c: int) -> int:
    """Pop component c (the states above and including its root v) off Tarjan's stack into `members`;
    return 1 if it is terminal (no state of it has an arc to another component), else 0."""
    term = 1
    while True:
        w = stack.pop()
        comp[w] = c
        members.append(w)
        if exits[w]:
            term = 0
        if w == v:
            return term


def _self_loop(v: int, offsets: array, dst: array, arc_labels, avoid: int) -> bool:
    """Whether state v has an arc to itself (not labelled `avoid`)."""
    a, b = offsets[v], offsets[v + 1]
    if v not in dst[a:b]:
        return False
    if arc_labels is None:
        return True
    return any(w == v and lab != avoid for w, lab in zip(dst[a:b], arc_labels[a:b]))


def has_cycle(n: int, offsets: array, dst: array, arc_labels=None, avoid: int = -1, keep_node=None,
              roots=None) -> bool:
    """Whether the graph, less the arcs labelled `avoid` and the states not kept, has a cycle (with
    `roots`, one that these states reach).

    A depth-first search that stops at the first arc back to a state on its stack (a self-loop counts);
    unlike a full SCC decomposition it usually ends after a few steps when a cycle exists. Apart from a
    memset of one byte per state it costs what it visits, so that one search per transition instance
    confined to a small region (`keep_node`, `roots`) does not cost graph x transitions.

    >>> from array import array
    >>> off, dst = array("q", [0, 1, 2, 3]), array("i", [1, 2, 1])  # 0 -> 1 -> 2 -> 1
    >>> has_cycle(3, off, dst), has_cycle(3, off, dst, array("b", [0, 1, 0]), avoid=1)
    (True, False)
    """
    offsets = _padded(offsets, n)
    colour = bytearray(n)  # 0 unseen, 1 on the DFS stack, 2 done
    labels = arc_labels
    for root in range(n) if roots is None else roots:
        if colour[root] or (keep_node is not None and not keep_node[root]):
            continue
        colour[root] = 1
        work = [root]
        ptr = [offsets[root]]
        while work:
            v = work[-1]
            i = ptr[-1]
            end = offsets[v + 1]
            while i < end:
                if labels is not None and labels[i] == avoid:
                    i += 1
                    continue
                w = dst[i]
                i += 1
                cw = colour[w]
                if cw == 1:
                    return True
                if cw == 0 and (keep_node is None or keep_node[w]):
                    ptr[-1] = i
                    colour[w] = 1
                    work.append(w)
                    ptr.append(offsets[w])
                    break
            else:
                colour[v] = 2
                work.pop()
                ptr.pop()
    return False


def first_cycle_component(n: int, offsets: array, dst: array, accept, arc_labels=None, avoid: int = -1,
                          keep_node=None, roots=None, within=None) -> list[int] | None:
    """The states of the first nontrivial SCC (less avoided arcs and dropped states; with `roots` and
    `within`, as `strongly_connected_components` reads them) that `accept`s, or None."""
    return strongly_connected_components(n, offsets, dst, arc_labels, avoid, keep_node, stop_at=accept, roots=roots,
                                         within=within)


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


def scc_graph_arcs(dec: SccDecomposition, offsets: array, dst: array, native: bool = True) -> tuple[int, int]:
    """Arcs of the SCC graph: (state-space arcs between distinct SCCs, distinct ordered SCC pairs).

    CPN Tools' report counts the first: LimitProtocol (CPN book ch. 7) has 37,312 such arcs, published
    as its SCC graph's arcs, and 20,154 distinct pairs.
    """
    if dec.count <= 1:
        return 0, 0
    if native:
        fast = graphnative.scc_arcs(offsets, dst, dec.comp, dec.members, dec.start)
        if fast is not None:
            return fast
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
