"""Layered (Sugiyama-style) graph layout, written for the drawings of this package.

Imports the standard library only. Nodes are put in layers (given, e.g. BFS depth, or the longest path
in the graph without its back edges), ordered within a layer by the barycentre of their neighbours to
reduce crossings, then given coordinates that keep each node near its neighbours in earlier layers.
It takes a few milliseconds for a few hundred nodes and needs no system tool.
"""

from __future__ import annotations

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
    index_of = {r: k for k, r in enumerate(depth)}
    nbrs = defaultdict(set)
    chains: dict = {}
    budget = 2 * len(nodes) if max_bends is None else max_bends
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
    rank = {n: i for r in depth for i, n in enumerate(rows[r])}

    def reorder(r: int, other: set) -> None:
        keyed = []
        for i, n in enumerate(rows[r]):
            ks = [rank[m] for m in nbrs[n] if level[m] in other]
            keyed.append((sum(ks) / len(ks) if ks else i, i, n))
        keyed.sort(key=lambda t: (t[0], t[1]))
        rows[r] = [n for _, _, n in keyed]
        for i, n in enumerate(rows[r]):
            rank[n] = i

    for _ in range(sweeps):
        for k, r in enumerate(depth[1:], 1):
            reorder(r, set(depth[:k]))
        for k in range(len(depth) - 2, -1, -1):
            reorder(depth[k], set(depth[k + 1:]))

    out = Layout(layer=dict(layer))
    y = margin
    placed: dict = {}
    where: dict = {}
    for r in depth:
        for row in _chunks(rows[r], size, gap_x, max_width):
            h = max(size[n][1] for n in row)
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
            for n, x in zip(row, xs):
                placed[n] = x + shift
                where[n] = (x + shift, y + h / 2)
            y += h + gap_y
    if where:
        left = min(where[n][0] - size[n][0] / 2 for n in where)
        for n, (x, yy) in where.items():
            where[n] = (x - left + margin, yy)
        out.pos = {n: where[n] for n in nodes}
        out.routes = {e: [where[d] for d in chain] for e, chain in chains.items()}
        out.width = max(where[n][0] + size[n][0] / 2 for n in where) + margin
        out.height = y - gap_y + margin
    return out


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
