"""The state space drawn as SVG: the full occurrence graph when it is small, else the SCC graph.

Imports `cpn.statespace` objects through the report and the `svg` and `layout` helpers. The full graph is
laid out by BFS level (level k holds the states first reached after k steps, so a shortest path runs
straight down); the SCC graph by the longest path in the (acyclic) component graph. The initial state
and dead markings are highlighted; every node has a tooltip with its marking.
"""

from __future__ import annotations

import math
from collections import defaultdict

from cpn.engine.protocol import capability
from cpn.report import svg as S
from cpn.report.layout import layered_layout

MAX_FULL_NODES: int = 300  # the full graph is drawn up to this many states (and MAX_FULL_ARCS arcs)
MAX_FULL_ARCS: int = 1500
MAX_SCC_NODES: int = 300
TOOLTIP_PLACES = 40


def bfs_levels(graph) -> list[int]:
    """The BFS level (distance from the initial state) of every state, from the BFS parent pointers."""
    parent = graph.parent
    level = [0] * graph.n_states
    for i in range(1, graph.n_states):
        level[i] = level[parent[i]] + 1  # a parent is always discovered before its child
    return level


def level_sizes(graph, levels: list[int] | None = None) -> list[int]:
    """How many states were first reached at each BFS level (the growth of the state space)."""
    sizes: list[int] = []
    for lv in bfs_levels(graph) if levels is None else levels:
        if lv == len(sizes):
            sizes.append(0)
        sizes[lv] += 1
    return sizes


def marking_text(engine, state, limit: int = TOOLTIP_PLACES) -> str:
    """One line per place instance with a non-empty marking (the tooltip of a state)."""
    lines = []
    for p, place in enumerate(engine.places):
        m = engine.format_marking(state, p)
        if m and m != "empty":
            lines.append(f"{place.name}: {S.clip(m, 120)}")
    if len(lines) > limit:
        lines = lines[:limit] + [f"… {len(lines) - limit} more places"]
    if getattr(engine, "is_timed", False) and not capability(engine, "time_condensation", False):
        lines.insert(0, f"model time {engine.clock(state)}")  # a condensed state's clock is shifted
    return "\n".join(lines) if lines else "(every place is empty)"


def choose(x) -> str:
    """'full', 'scc' or 'none': which drawing suits this exploration."""
    if x.n_states <= MAX_FULL_NODES and x.n_arcs <= MAX_FULL_ARCS:
        return "full"
    return "scc"


def draw_state_space(report, prefix: str = "ss") -> tuple[str, str]:
    """(kind, svg): the full graph ('full') or the SCC graph ('scc'); ('none', message) when too big."""
    x = report.exploration
    if choose(x) == "full":
        return "full", _full(report, prefix)
    dec = report.scc.decomposition
    if dec.count <= MAX_SCC_NODES:
        return "scc", _scc(report, prefix)
    return "none", (f"The state space has {x.n_states:,} states and its SCC graph {dec.count:,} nodes: too many "
                    f"to draw readably (the full graph is drawn up to {MAX_FULL_NODES} states, the SCC graph "
                    f"up to {MAX_SCC_NODES} components).")


def _edges_svg(edges: dict, pos: dict, radius: dict, layer: dict, prefix: str, label: dict,
               routes: dict) -> list[str]:
    out = []
    fade = ' stroke-opacity="0.6"' if len(edges) > 200 else ""  # dense graphs: let the nodes stand out
    for (u, v), n in edges.items():
        (x1, y1), (x2, y2) = pos[u], pos[v]
        tip = S.title(label.get((u, v), "")) if label.get((u, v)) else ""
        cls = f'class="edge" data-s="{u}" data-t="{v}"'
        if u == v:
            r = radius[u]
            d = (f"M{S.fmt(x1 + r * 0.7)},{S.fmt(y1 - r * 0.7)} C{S.fmt(x1 + r * 2.6)},{S.fmt(y1 - r * 2.6)} "
                 f"{S.fmt(x1 + r * 2.6)},{S.fmt(y1 + r * 2.6)} {S.fmt(x1 + r * 0.9)},{S.fmt(y1 + r * 0.5)}")
        elif routes.get((u, v)):  # through its bend points, between the nodes of the layers it crosses
            pts = routes[(u, v)]
            a = S.boundary_point(x1, y1, radius[u], 0, pts[0][0], pts[0][1], "circle")
            b = S.boundary_point(x2, y2, radius[v] + 1, 0, pts[-1][0], pts[-1][1], "circle")
            d = S.smooth_path([a, *pts, b])
        else:
            straight = layer[v] == layer[u] + 1
            dx, dy = x2 - x1, y2 - y1
            dist = max(1.0, math.hypot(dx, dy))
            bend = 0.0 if straight else min(60.0, 0.18 * dist + 12) * (1 if (layer[v] <= layer[u]) else -1)
            mx, my = (x1 + x2) / 2 - dy / dist * bend, (y1 + y2) / 2 + dx / dist * bend
            ax, ay = S.boundary_point(x1, y1, radius[u], 0, mx, my, "circle")
            bx, by = S.boundary_point(x2, y2, radius[v] + 1, 0, mx, my, "circle")
            d = (f"M{S.fmt(ax)},{S.fmt(ay)} L{S.fmt(bx)},{S.fmt(by)}" if straight else
                 f"M{S.fmt(ax)},{S.fmt(ay)} Q{S.fmt(mx)},{S.fmt(my)} {S.fmt(bx)},{S.fmt(by)}")
        width = 1.0 + min(2.0, math.log2(n)) if n > 1 else 1.0
        out.append(f'<path {cls} d="{d}" fill="none" stroke="#8a96a3" stroke-width="{S.fmt(width)}"{fade} '
                   f'marker-end="url(#{prefix}-arrow)">{tip}</path>')
    return out


def _bend_budget(n_nodes: int, n_edges: int) -> int:
    """Bend points for edges that span BFS levels: they keep a sparse graph's long arcs clear of the
    nodes, but would make a dense graph (more than two arcs per state) far too wide: none there."""
    return n_nodes if n_edges <= 2 * n_nodes else 0


def _node_svg(prefix: str, ident: str, x: float, y: float, r: float, label: str, tip: str, kind: str) -> str:
    fill, stroke, sw = {"dead": (S.BAD, S.BAD, 1.5), "initial": ("#fff", S.INITIAL, 3.0),
                        "unexpanded": ("#fff", S.MUTED, 1.2)}.get(kind, ("#fff", S.ACCENT, 1.4))
    colour = "#fff" if kind == "dead" else S.INK
    dash = ' stroke-dasharray="3 2"' if kind == "unexpanded" else ""
    size = 11 if len(label) <= 3 else 9
    return (f'<g class="node {kind}" id="{prefix}-{ident}" data-node="{ident}">{S.title(tip)}'
            f'<circle cx="{S.fmt(x)}" cy="{S.fmt(y)}" r="{S.fmt(r)}" fill="{fill}" stroke="{stroke}" '
            f'stroke-width="{sw}"{dash}/>' + S.text(x, y + size * 0.36, label, size, fill=colour) + "</g>")


def _full(report, prefix: str) -> str:
    x = report.exploration
    g, engine = x.graph, x.engine
    level = bfs_levels(g)
    n = g.n_states
    edges: dict = defaultdict(int)
    labels: dict = defaultdict(list)
    for i in range(g.expanded):
        for be, j in g.out_arcs(i):
            edges[(i, j)] += 1
            if len(labels[(i, j)]) < 6:
                labels[(i, j)].append(engine.format_binding_element(be))
    label = {k: "\n".join(v) + (f"\n… {edges[k] - len(v)} more" if edges[k] > len(v) else "")
             for k, v in labels.items()}
    nodes = list(range(n))
    r = 13.0
    lay = layered_layout(nodes, list(edges), {i: (2 * r, 2 * r) for i in nodes},
                         layer={i: level[i] for i in nodes}, gap_x=16, gap_y=46, margin=30,
                         max_bends=_bend_budget(len(nodes), len(edges)))
    dead = set(report.dead.states)
    body = [S.arrow_defs(prefix, {"arrow": "#8a96a3"})]
    body += _edges_svg(edges, lay.pos, {i: r for i in nodes}, lay.layer, prefix, label, lay.routes)
    for i in nodes:
        kind = ("dead" if i in dead else "initial" if i == 0 else "unexpanded" if not g.is_expanded(i)
                else "state")
        what = {"dead": " (dead marking)", "initial": " (initial marking)",
                "unexpanded": " (not expanded: a limit stopped the search)"}.get(kind, "")
        tip = f"state {i + 1}{what}, BFS level {level[i]}\n" + marking_text(engine, g.states[i])
        px, py = lay.pos[i]
        body.append(_node_svg(prefix, f"s{i + 1}", px, py, r, str(i + 1), tip, kind))
    return S.document(lay.width, lay.height, body, f"the state space: {n} states", cls="drawing statespace")


def _scc(report, prefix: str) -> str:
    x = report.exploration
    g, engine = x.graph, x.engine
    dec = report.scc.decomposition
    comp = dec.comp
    edges: dict = defaultdict(int)
    for i in range(g.expanded):
        a = comp[i]
        for _be, j in g.out_arcs(i):
            b = comp[j]
            if a != b:
                edges[(a, b)] += 1
    nodes = list(range(dec.count - 1, -1, -1))  # Tarjan's order reversed: a topological order
    size = {c: len(dec.nodes(c)) for c in nodes}
    biggest = max(size.values()) if size else 1
    radius = {c: 12 + 16 * math.sqrt(size[c] / biggest) for c in nodes}
    lay = layered_layout(nodes, list(edges), {c: (2 * radius[c], 2 * radius[c]) for c in nodes},
                         roots=[comp[0]], gap_x=18, gap_y=46, margin=30,
                         max_bends=_bend_budget(len(nodes), len(edges)))
    dead = set(report.dead.states)
    body = [S.arrow_defs(prefix, {"arrow": "#8a96a3"})]
    label = {k: f"{n} arcs" for k, n in edges.items()}
    body += _edges_svg(edges, lay.pos, radius, lay.layer, prefix, label, lay.routes)
    for c in nodes:
        members = dec.nodes(c)
        has_dead = any(s in dead for s in members)
        kind = "dead" if has_dead else "initial" if comp[0] == c else "state"
        shown = ", ".join(str(s + 1) for s in list(members)[:12]) + (", …" if len(members) > 12 else "")
        tip = (f"SCC {c + 1}: {len(members)} states ({shown})"
               + (", terminal" if dec.terminal[c] else "") + (", contains a cycle" if dec.nontrivial[c] else "")
               + (", contains the initial state" if comp[0] == c else "")
               + (", a dead marking" if has_dead else ""))
        if len(members) == 1:
            tip += "\n" + marking_text(engine, g.states[members[0]])
        px, py = lay.pos[c]
        body.append(_node_svg(prefix, f"c{c + 1}", px, py, radius[c], str(len(members)), tip, kind))
    return S.document(lay.width, lay.height, body, f"the SCC graph: {dec.count} components",
                      cls="drawing sccgraph")
