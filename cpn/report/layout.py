"""Layered (Sugiyama-style) graph layout, written for the drawings of this package.

Imports the standard library only. Nodes are put in layers (given, e.g. BFS depth, or the longest path
in the graph without its back edges), ordered within a layer by the barycentre of their neighbours to
reduce crossings, then given coordinates that keep each node near its neighbours in earlier layers.
It takes a few milliseconds for a few hundred nodes and needs no system tool.
"""

from __future__ import annotations

import math
from collections import defaultdict
from dataclasses import dataclass, field


@dataclass
class Layout:
    """Node centres in px, the layer of each node and the size of the whole drawing."""

    pos: dict = field(default_factory=dict)
    layer: dict = field(default_factory=dict)
    width: float = 0.0
    height: float = 0.0
    routes: dict = field(default_factory=dict)  # (u, v) -> bend points of an edge spanning layers


def back_edges(nodes: list, edges: list[tuple], roots: list | tuple = ()) -> set:
    """Edges (u, v) that close a cycle in a depth-first search started from `roots`, then the others.

    Removing them leaves an acyclic graph; the search order makes edges leaving the roots forward.
    """
    succ = defaultdict(list)
    for u, v in edges:
        succ[u].append(v)
    state: dict = {}  # 1 on the stack, 2 done
    back = set()
    for start in list(roots) + list(nodes):
        if start in state:
            continue
        state[start] = 1
        stack = [(start, iter(succ[start]))]
        while stack:
            u, it = stack[-1]
            for v in it:
                s = state.get(v)
                if s is None:
                    state[v] = 1
                    stack.append((v, iter(succ[v])))
                    break
                if s == 1:
                    back.add((u, v))
            else:
                state[u] = 2
                stack.pop()
    return back


def longest_path_layers(nodes: list, edges: list[tuple], roots: list | tuple = ()) -> dict:
    """Layer of each node: the length of the longest path reaching it once back edges are removed."""
    back = back_edges(nodes, edges, roots)
    succ = defaultdict(list)
    indeg = {n: 0 for n in nodes}
    for u, v in edges:
        if (u, v) in back or u == v:
            continue
        succ[u].append(v)
        indeg[v] += 1
    layer = {n: 0 for n in nodes}
    ready = [n for n in nodes if indeg[n] == 0]
    while ready:
        u = ready.pop()
        for v in succ[u]:
            layer[v] = max(layer[v], layer[u] + 1)
            indeg[v] -= 1
            if indeg[v] == 0:
                ready.append(v)
    return layer


def layered_layout(nodes: list, edges: list[tuple], size: dict, layer: dict | None = None,
                   roots: list | tuple = (), gap_x: float = 28, gap_y: float = 56, sweeps: int = 4,
                   margin: float = 10, direction: str = "TB", max_bends: int | None = None,
                   max_width: float | None = None) -> Layout:
    """Layered layout, top to bottom ("TB") or left to right ("LR"); `size[n]` is (width, height) in px.

    An edge that spans several layers gets a bend point in each layer it crosses, placed and ordered
    like a small node, so that it runs between the nodes rather than through them: `Layout.routes[(u, v)]`
    lists those points from u to v. `max_bends` bounds their number (default: twice the number of nodes);
    the longest edges past the bound get none. With `max_width` (top to bottom only), a layer wider than
    that is wrapped onto several rows, so the drawing stays that wide.
    """
    if direction == "LR":
        t = layered_layout(nodes, edges, {n: (h, w) for n, (w, h) in size.items()}, layer, roots, gap_y,
                           gap_x, sweeps, margin, max_bends=max_bends)
        return Layout({n: (y, x) for n, (x, y) in t.pos.items()}, t.layer, t.height, t.width,
                      {e: [(y, x) for x, y in pts] for e, pts in t.routes.items()})
    if layer is None:
        layer = longest_path_layers(nodes, edges, roots)
    level = dict(layer)
    size = dict(size)
    rows: dict[int, list] = defaultdict(list)
    for n in nodes:
        rows[level[n]].append(n)
    depth = sorted(rows)
    budget = 2 * len(nodes) if max_bends is None else max_bends
    nbrs, chains = _bend_chains(edges, level, size, rows, depth, budget)
    _order_rows(rows, depth, nbrs, level, sweeps)
    out = Layout(layer=dict(layer))
    where, y = _coordinates(rows, depth, nbrs, size, gap_x, gap_y, margin, max_width)
    if where:
        left = min(where[n][0] - size[n][0] / 2 for n in where)
        for n, (x, yy) in where.items():
            where[n] = (x - left + margin, yy)
        out.pos = {n: where[n] for n in nodes}
        out.routes = {e: [where[d] for d in chain] for e, chain in chains.items()}
        out.width = max(where[n][0] + size[n][0] / 2 for n in where) + margin
        out.height = y - gap_y + margin
    return out


def _bend_chains(edges: list, level: dict, size: dict, rows: dict, depth: list, budget: int) -> tuple[dict, dict]:
    """The neighbours of each node, with a chain of bend points for each edge that spans layers.

    The shortest edges get their bends first, while `budget` bends remain; each bend is added to
    `level`, `size` and `rows` like a small node. Returns the neighbours and (u, v) -> bend chain.
    """
    index_of = {r: k for k, r in enumerate(depth)}
    nbrs = defaultdict(set)
    chains: dict = {}
    by_span = sorted((e for e in dict.fromkeys(edges) if e[0] != e[1]),
                     key=lambda e: abs(index_of[level[e[0]]] - index_of[level[e[1]]]))
    for u, v in by_span:
        a, b = index_of[level[u]], index_of[level[v]]
        span = abs(a - b)
        if span <= 1 or span - 1 > budget:
            nbrs[u].add(v)
            nbrs[v].add(u)
            continue
        budget -= span - 1
        step = 1 if b > a else -1
        chain = []
        prev = u
        for k in range(a + step, b, step):
            d = ("__bend", len(chains), k)
            level[d] = depth[k]
            size[d] = (6.0, 6.0)
            rows[depth[k]].append(d)
            nbrs[prev].add(d)
            nbrs[d].add(prev)
            chain.append(d)
            prev = d
        nbrs[prev].add(v)
        nbrs[v].add(prev)
        chains[(u, v)] = chain
    return nbrs, chains


def _order_rows(rows: dict, depth: list, nbrs: dict, level: dict, sweeps: int) -> None:
    """Order each layer by the barycentre of its neighbours' ranks, sweeping down then up `sweeps` times."""
    rank = {n: i for r in depth for i, n in enumerate(rows[r])}
    for _ in range(sweeps):
        for k, r in enumerate(depth[1:], 1):
            _reorder(rows, r, set(depth[:k]), nbrs, level, rank)
        for k in range(len(depth) - 2, -1, -1):
            _reorder(rows, depth[k], set(depth[k + 1:]), nbrs, level, rank)


def _reorder(rows: dict, r: int, other: set, nbrs: dict, level: dict, rank: dict) -> None:
    """Sort layer `r` by the mean rank of each node's neighbours in the layers `other` (ties: as it was)."""
    keyed = []
    for i, n in enumerate(rows[r]):
        ks = [rank[m] for m in nbrs[n] if level[m] in other]
        keyed.append((sum(ks) / len(ks) if ks else i, i, n))
    keyed.sort(key=lambda t: (t[0], t[1]))
    rows[r] = [n for _, _, n in keyed]
    for i, n in enumerate(rows[r]):
        rank[n] = i


def _coordinates(rows: dict, depth: list, nbrs: dict, size: dict, gap_x: float, gap_y: float,
                 margin: float, max_width: float | None) -> tuple[dict, float]:
    """Node centres, layer by layer (a layer wider than max_width wrapped onto several rows), and the y
    below the last row."""
    y = margin
    placed: dict = {}
    where: dict = {}
    for r in depth:
        for row in _chunks(rows[r], size, gap_x, max_width):
            h = max(size[n][1] for n in row)
            for n, x in zip(row, _row_xs(row, nbrs, size, placed, gap_x, max_width)):
                placed[n] = x
                where[n] = (x, y + h / 2)
            y += h + gap_y
    return where, y


def _row_xs(row: list, nbrs: dict, size: dict, placed: dict, gap_x: float, max_width: float | None) -> list:
    """The x of each node of a row: near the mean x of its neighbours already placed, without overlaps,
    the whole row shifted toward those wishes (and kept inside [0, max_width])."""
    want = []
    for n in row:
        xs = [placed[m] for m in nbrs[n] if m in placed]
        want.append(sum(xs) / len(xs) if xs else None)
    xs: list[float] = []
    for i, n in enumerate(row):
        pad = gap_x / 3 if i and _is_bend(n) and _is_bend(row[i - 1]) else gap_x  # bends pack closer
        lo = -1e18 if i == 0 else xs[-1] + (size[row[i - 1]][0] + size[n][0]) / 2 + pad
        xs.append(max(lo, want[i] if want[i] is not None else lo if i else 0.0))
    diffs = [w - x for w, x in zip(want, xs) if w is not None]
    shift = sum(diffs) / len(diffs) if diffs else 0.0
    if max_width is not None:  # keep the row inside [0, max_width]
        lo_x = xs[0] + shift - size[row[0]][0] / 2
        hi_x = xs[-1] + shift + size[row[-1]][0] / 2
        over = max(0.0, hi_x - max_width)
        shift -= over
        if lo_x - over < 0:
            shift -= lo_x - over
    return [x + shift for x in xs]


def _chunks(row: list, size: dict, gap: float, max_width: float | None) -> list[list]:
    """The row cut, in order, into pieces no wider than max_width (one piece without a limit)."""
    if max_width is None:
        return [row]
    out: list[list] = [[]]
    width = 0.0
    for n in row:
        w = size[n][0] + gap
        if out[-1] and width + w - gap > max_width:
            out.append([])
            width = 0.0
        out[-1].append(n)
        width += w
    return out


def _is_bend(n) -> bool:
    return type(n) is tuple and n[:1] == ("__bend",)


def pack_rows(sizes: list[tuple[float, float]], max_width: float, gap: float = 16) -> tuple[list, float, float]:
    """Top-left corners for boxes placed left to right in rows no wider than `max_width`.

    Returns (corners, total width, total height).
    """
    corners = []
    x = y = 0.0
    row_h = 0.0
    width = 0.0
    for w, h in sizes:
        if x > 0 and x + w > max_width:
            x = 0.0
            y += row_h + gap
            row_h = 0.0
        corners.append((x, y))
        x += w + gap
        row_h = max(row_h, h)
        width = max(width, x - gap)
    return corners, width, (y + row_h if sizes else 0.0)


# --------------------------------------------------------------------------------- routing around boxes

def segment_hits_box(a: tuple, b: tuple, box: tuple) -> bool:
    """Whether the segment a-b meets the box (x0, y0, x1, y1) (Liang-Barsky clipping)."""
    x0, y0, x1, y1 = box
    if max(a[0], b[0]) < x0 or min(a[0], b[0]) > x1 or max(a[1], b[1]) < y0 or min(a[1], b[1]) > y1:
        return False
    dx, dy = b[0] - a[0], b[1] - a[1]
    t0, t1 = 0.0, 1.0
    for p, q in ((-dx, a[0] - x0), (dx, x1 - a[0]), (-dy, a[1] - y0), (dy, y1 - a[1])):
        if p == 0:
            if q < 0:
                return False
            continue
        t = q / p
        if p < 0:
            if t > t1:
                return False
            t0 = max(t0, t)
        else:
            if t < t0:
                return False
            t1 = min(t1, t)
    return t0 <= t1


def boxes_overlap(a: tuple, b: tuple) -> bool:
    return a[0] < b[2] and b[0] < a[2] and a[1] < b[3] and b[1] < a[3]


class Router:
    """Paths between points that keep `margin` px away from a set of boxes (the nodes of a drawing).

    `boxes` maps a key to (x0, y0, x1, y1). A path is a polyline through corners of the boxes grown by
    the margin: a shortest path (A*) in the graph of those corners in which two points are joined when
    the segment between them is clear and not longer than `reach` (the end is always tried), then
    straightened (a corner is skipped wherever the segment past it is clear). Segments are tested
    against the boxes of the grid cells they cover.
    """

    def __init__(self, boxes: dict, margin: float = 8.0, cell: float = 200.0, reach: float = 480.0):
        self.margin, self.cell, self.reach = margin, cell, reach
        self.keys = list(boxes)
        self.grown = [(x0 - margin, y0 - margin, x1 + margin, y1 + margin) for x0, y0, x1, y1 in boxes.values()]
        grid: dict = defaultdict(list)
        for i, b in enumerate(self.grown):
            for cx in range(int(b[0] // cell), int(b[2] // cell) + 1):
                for cy in range(int(b[1] // cell), int(b[3] // cell) + 1):
                    grid[(cx, cy)].append(i)
        self.grid = dict(grid)
        e = 0.5  # corners lie just outside the grown boxes
        self.corners = [p for x0, y0, x1, y1 in self.grown
                        for p in ((x0 - e, y0 - e), (x1 + e, y0 - e), (x1 + e, y1 + e), (x0 - e, y1 + e))
                        if not self._blocked(p, p, ())]

    def blocked(self, a: tuple, b: tuple, skip=(), shrink: float = 0.0) -> bool:
        """Whether the segment a-b meets a box (grown by the margin less `shrink`) whose key is not in
        `skip`."""
        skip_i = {i for i, k in enumerate(self.keys) if k in skip} if skip and not isinstance(skip, frozenset) else skip
        return self._blocked(a, b, skip_i, shrink)

    def _blocked(self, a: tuple, b: tuple, skip_i, shrink: float = 0.0) -> bool:
        lo_x, hi_x = (a[0], b[0]) if a[0] < b[0] else (b[0], a[0])
        lo_y, hi_y = (a[1], b[1]) if a[1] < b[1] else (b[1], a[1])
        c = self.cell
        grown, grid = self.grown, self.grid
        for cx in range(int(lo_x // c), int(hi_x // c) + 1):
            for cy in range(int(lo_y // c), int(hi_y // c) + 1):
                for i in grid.get((cx, cy), ()):
                    x0, y0, x1, y1 = grown[i]
                    if hi_x < x0 + shrink or lo_x > x1 - shrink or hi_y < y0 + shrink or lo_y > y1 - shrink:
                        continue
                    if i in skip_i:
                        continue
                    if segment_hits_box(a, b, (x0 + shrink, y0 + shrink, x1 - shrink, y1 - shrink)):
                        return True
        return False

    def path_blocked(self, points: list, skip=(), shrink: float = 0.0) -> bool:
        skip_i = frozenset(i for i, k in enumerate(self.keys) if k in skip)
        return any(self._blocked(a, b, skip_i, shrink) for a, b in zip(points, points[1:]))

    def route(self, a: tuple, b: tuple, skip=()) -> list | None:
        """The points of a clear path from a to b (both included), or None when there is none."""
        skip_i = frozenset(i for i, k in enumerate(self.keys) if k in skip)
        if not self._blocked(a, b, skip_i):
            return [a, b]
        found = self._search([a, *self.corners, b], skip_i)
        if found is None:
            return None
        out = [found[0]]  # straightened: from each point, on to the farthest one in sight
        i = 0
        while i < len(found) - 1:
            j = len(found) - 1
            while j > i + 1 and self._blocked(found[i], found[j], skip_i):
                j -= 1
            out.append(found[j])
            i = j
        return out

    def _search(self, pts: list, skip_i) -> list | None:
        import heapq

        goal = len(pts) - 1
        reach = self.reach
        near: dict = defaultdict(list)  # the points by grid cell of side `reach`
        for j in range(1, goal):
            near[(int(pts[j][0] // reach), int(pts[j][1] // reach))].append(j)

        def dist(i, j):
            return ((pts[i][0] - pts[j][0]) ** 2 + (pts[i][1] - pts[j][1]) ** 2) ** 0.5

        best = {0: 0.0}
        back: dict = {}
        heap = [(2 * dist(0, goal), 0.0, 0)]
        done: set = set()
        while heap:
            _f, g, i = heapq.heappop(heap)
            if i in done:
                continue
            if i == goal:
                out = [goal]
                while out[-1] != 0:
                    out.append(back[out[-1]])
                return [pts[k] for k in reversed(out)]
            done.add(i)
            cx, cy = int(pts[i][0] // reach), int(pts[i][1] // reach)
            for j in [goal, *(j for dx in (-1, 0, 1) for dy in (-1, 0, 1) for j in near.get((cx + dx, cy + dy), ()))]:
                if j in done:
                    continue
                ng = g + dist(i, j) + 4.0  # a little per corner: fewer corners among equal lengths
                if ng < best.get(j, math.inf) and not self._blocked(pts[i], pts[j], skip_i):
                    best[j] = ng
                    back[j] = i
                    heapq.heappush(heap, (ng + 2 * dist(j, goal), ng, j))  # weighted: fewer points tried
        return None
