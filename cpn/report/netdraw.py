"""The net drawn as SVG: places, transitions, arcs with their inscriptions, each module instance as a
box nested in the box of the instance that contains it, place bounds and dead transition instances
marked.

Imports `cpn.net` (with `cpn.expr.pretty`) and the report's `svg` and `layout` helpers. A place bound to a
port, or fused with places of other instances, is drawn once, in the box of the instance that owns it
(the socket's instance, the first member of the fusion set); arcs from other instances cross the boxes.
An arc that would run through a node it does not join is routed around the nodes (`layout.Router`),
and inscriptions are put where they cover no node.
"""

from __future__ import annotations

import re
from dataclasses import dataclass, field

from cpn.expr import pretty
from cpn.report import svg as S
from cpn.report.layout import Router, boxes_overlap, layered_layout, pack_rows

PLACE_H = 40
TRANS_H = 34
LABEL_LINE = 16
PAD = 18
HEADER = 26
MAX_ROW_WIDTH = 1240  # child boxes wrap into rows no wider than this (a laptop screen)
INSCRIPTION_CHARS = 34
WRAP_CHARS = 20  # arc inscriptions are wrapped at about this many characters


_COMMENT = re.compile(r"\(\*.*?\*\)")


def _to_end_of_declaration(s: str) -> str:
    """`s` up to its first ';' or comment outside brackets and strings (the end of a multi-line
    expression's span may lie beyond the expression)."""
    depth = 0
    quoted = False
    for i, c in enumerate(s):
        if quoted:
            quoted = c != '"' or s[i - 1] == "\\"
        elif c == '"':
            quoted = True
        elif c == "(" and s.startswith("(*", i):
            return s[:i]
        elif c in "([{":
            depth += 1
        elif c in ")]}":
            depth -= 1
        elif c == ";" and depth <= 0:
            return s[:i]
    return s


@dataclass
class Unit:
    """One module (page) instance: its own place and transition instances and its child instances."""

    key: tuple  # (page name, instance number)
    label: str  # the instance's name ("Station1"), or the net's name for the top page
    module: str
    parent: tuple | None = None
    children: list = field(default_factory=list)
    places: list = field(default_factory=list)
    transitions: list = field(default_factory=list)
    binds: list = field(default_factory=list)  # "port = socket" of the instance


def instance_tree(net) -> tuple[dict, tuple]:
    """The module instances of `net` as Units keyed by (page, instance number), and the top's key.

    Follows the order in which the lowering numbers instances (depth first, counting per page), so the
    keys match `PlaceInstance.page/instance` and `TransitionInstance.page/instance`.
    """
    units: dict = {}
    cm = getattr(net, "checked", None)
    top_key = None
    if cm is not None and getattr(cm, "top", None) is not None:
        counter: dict = {}

        def walk(page, label, parent, depth, binds=()):
            counter[page.name] = counter.get(page.name, 0) + 1
            key = (page.name, counter[page.name])
            units[key] = Unit(key, label, page.name, parent, binds=list(binds))
            if parent is not None:
                units[parent].children.append(key)
            if depth > 64:
                return key
            for inst in page.instances:
                child = cm.modules.get(inst.module)
                if child is not None:
                    walk(child, inst.name, key, depth + 1, [f"{b[0]} = {b[2]}" for b in inst.binds])
            return key

        top_key = walk(cm.top, net.name, None, 0)
    for p in net.places:
        _unit_for(units, (p.page, p.instance), top_key, net).places.append(p.index)
    for t in net.transitions:
        _unit_for(units, (t.page, t.instance), top_key, net).transitions.append(t.index)
    if top_key is None:
        top_key = next(iter(units))
    return units, top_key


def _unit_for(units: dict, key: tuple, top_key, net) -> Unit:
    u = units.get(key)
    if u is None:  # not found by the walk (an imported net without the checked pages): a top-level box
        u = units[key] = Unit(key, f"{key[0]} {key[1]}", key[0], top_key)
        if top_key is not None:
            units[top_key].children.append(key)
    return u


def arc_inscription(net, a) -> str:
    """Arc instance a's inscription, with its delay on an input arc (`@+ k`, which the net keeps apart from
    the inscription: `ArcInstance.preemption`, its value in this instance)."""
    text = inscription(net, a.expr)
    return f"{text} @+ {a.preemption}" if getattr(a, "preemption", 0) else text


def inscription(net, expr) -> str:
    """An arc inscription as the modeller wrote it (from the source), else in canonical form."""
    if expr is None:
        return ""
    span = getattr(expr, "span", None)
    model = getattr(getattr(net, "checked", None), "model", None)
    if span is not None and model is not None and span.end_line and span.file == model.file:
        lines = model.source.split("\n")
        if 0 < span.line <= span.end_line <= len(lines):
            if span.line == span.end_line:
                s = lines[span.line - 1][span.col - 1: span.end_col]
            else:
                s = " ".join([lines[span.line - 1][span.col - 1:]] + lines[span.line: span.end_line - 1]
                             + [lines[span.end_line - 1][: span.end_col]])
            s = " ".join(_COMMENT.sub(" ", _to_end_of_declaration(s)).split())
            if s.startswith("arc "):  # no inscription written: the span is the arc's
                return ""
            if s:
                return s
    try:
        return pretty.expr(expr)
    except Exception:  # noqa: BLE001 - a construct the printer does not know: no inscription text
        return "…"


def wrap(label: str, width: int = WRAP_CHARS, max_lines: int = 2) -> list[str]:
    """An inscription broken at spaces into lines of about `width` characters (the rest clipped)."""
    if not label:
        return []
    lines: list[str] = []
    cur = ""
    for word in label.split(" "):
        if cur and len(cur) + 1 + len(word) > width:
            lines.append(cur)
            cur = word
        else:
            cur = f"{cur} {word}" if cur else word
    lines.append(cur)
    if len(lines) > max_lines:
        lines = lines[:max_lines - 1] + [S.clip(" ".join(lines[max_lines - 1:]), width)]
    return [S.clip(line, width + 6) for line in lines]


@dataclass
class _Node:
    kind: str  # 'place' | 'trans'
    index: int
    w: float
    h: float
    shape_h: float
    lines: list  # (text, css class, mono) shown under the shape
    shape_w: float = 0.0
    side: bool = False  # labels at the right of the shape (top-to-bottom layouts), else below it

    def side_size(self) -> tuple[float, float]:
        label_w = max([S.text_width(t, 12, m) for t, _, m in self.lines] + [0])
        return (self.shape_w + (label_w + 10 if self.lines else 0),
                max(self.shape_h, LABEL_LINE * len(self.lines) + 4))
    x: float = 0.0
    y: float = 0.0  # centre of the shape


def draw_net(net, bounds: dict | None = None, dead_transitions=(), occurrences: dict | None = None,
             max_row_width: float = MAX_ROW_WIDTH) -> str:
    """The SVG drawing of `net`.

    bounds: place instance name -> (upper, lower, upper multiset text); dead_transitions: names of
    transition instances that never occur; occurrences: transition instance name -> number of arcs
    of the state space it labels (shown in tooltips).
    """
    bounds = bounds or {}
    dead = set(dead_transitions)
    occurrences = occurrences or {}
    units, top = instance_tree(net)
    nodes = _net_nodes(net)
    collapsed = _collapsed(units, top, net, dead)
    sheet = _Sheet(net, units, top, nodes, collapsed, dead, max_row_width)
    width, height, items = sheet.measure(top, 0)
    routes, offset = _place_items(items, nodes)
    body: list[str] = [S.arrow_defs("na", {"line": S.LINE, "bad": S.BAD})]
    body += [_module_box(units, key, top, box, net, dead, bounds)
             for key, box in sorted(offset.items(), key=lambda kv: kv[1][4])
             if not (key == top and not units[key].children)]
    hidden = {("p", i) for k in collapsed for i in _all(units, k, "places")} | \
             {("t", i) for k in collapsed for i in _all(units, k, "transitions")}
    nodes = {n: node for n, node in nodes.items() if n not in hidden}
    titles = [(x + 10, y + 4, x + 10 + S.text_width(_box_title(units[key]), 13), y + 22)
              for key, (x, y, _w, _h, _depth, _lines) in offset.items()]  # inscriptions keep off them too
    arcs, right = _arcs(net, nodes, {e: [(x, y) for _, x, y in sorted(pts)] for e, pts in routes.items()},
                        titles)
    body += arcs
    for node in nodes.values():
        if node.kind == "place":
            body.append(_place(net.places[node.index], node, bounds))
        else:
            t = net.transitions[node.index]
            body.append(_transition(t, node, t.name in dead, occurrences.get(t.name)))
    right = max([right] + [_right_edge(node) for node in nodes.values()])  # labels may stick out of the boxes
    return S.document(max(width, right + 6) + 2, height + 2, body, f"the net {net.name}", cls="drawing net")


def _net_nodes(net) -> dict:
    """Every place and transition instance as a _Node sized for its shape and its label lines."""
    nodes: dict = {}
    for p in net.places:
        nodes[("p", p.index)] = _place_node(p)
    for t in net.transitions:
        nodes[("t", t.index)] = _transition_node(net, t)
    return nodes


def _place_node(p) -> _Node:
    lines = [(p.colset_name, "cs", False)]
    if p.initial:
        lines.append((S.clip(_initial_text(p), INSCRIPTION_CHARS), "init", True))
    sw = max(76, S.text_width(p.place, 13) + 30)
    w = max([sw] + [S.text_width(t, 12, m) + 8 for t, _, m in lines])
    return _Node("place", p.index, w, PLACE_H + LABEL_LINE * len(lines), PLACE_H, lines, sw)


def _transition_node(net, t) -> _Node:
    lines = []
    for g in t.guards or []:
        lines.append((S.clip("[" + inscription(net, g) + "]", INSCRIPTION_CHARS), "guard", True))
    if t.delay is not None:
        lines.append((S.clip("@+" + inscription(net, t.delay), INSCRIPTION_CHARS), "guard", True))
    sw = max(80, S.text_width(t.transition, 13) + 26)
    w = max([sw] + [S.text_width(s, 12, m) + 8 for s, _, m in lines])
    return _Node("trans", t.index, w, TRANS_H + LABEL_LINE * len(lines), TRANS_H, lines, sw)


def _place_items(items: list, nodes: dict) -> tuple[dict, dict]:
    """Put the measured nodes at their absolute positions; returns the arcs' bends and the boxes.

    routes: edge -> [(bend number, x, y)]; offset: unit key -> (x, y, w, h, depth, summary lines).
    """
    routes: dict = {}
    offset: dict = {}
    for kind, k, x, y, extra in items:
        if kind == "bend":
            routes.setdefault(k[0], []).append((k[1], x, y))
        elif kind == "node":
            node = nodes[k]
            node.side = extra
            if extra:
                node.x, node.y = x - node.side_size()[0] / 2 + node.shape_w / 2, y
            else:
                node.x, node.y = x, y - node.h / 2 + node.shape_h / 2
        else:
            offset[k] = (x, y) + extra
    return routes, offset


def _module_box(units: dict, key, top, box: tuple, net, dead: set, bounds: dict) -> str:
    """The SVG box of one module instance: its frame and title, or the summary of a collapsed one."""
    x, y, w, h, depth, lines = box
    u = units[key]
    fill = "#fbfcfd" if depth % 2 == 0 else "#f3f5f7"
    tip = f"module instance {u.label} (module {u.module}, instance {key[1]})"
    extra = ""
    if lines is not None:  # a collapsed instance: its summary instead of its nodes
        tip += "\n" + "\n".join(_collapsed_tip(units, key, net, dead, bounds))
        extra = "".join(S.text(x + 10, y + HEADER + 12 + LABEL_LINE * k, t, 12, "start",
                               fill=S.BAD if bad else S.MUTED) for k, (t, bad) in enumerate(lines))
    return (f'<g class="module{" collapsed" if lines is not None else ""}">'
            f'<rect x="{S.fmt(x)}" y="{S.fmt(y)}" width="{S.fmt(w)}" '
            f'height="{S.fmt(h)}" rx="8" fill="{fill}" stroke="{S.BOX_STROKE}"'
            + (' stroke-dasharray="5 3"' if lines is not None else "") + "/>"
            + S.text(x + 10, y + 18, _box_title(u), 13, "start", weight="600", fill=S.MUTED)
            + extra + S.title(tip) + "</g>")


def _right_edge(node: _Node) -> float:
    """The right end of a node with its labels."""
    if node.side:
        return node.x + node.side_size()[0] - node.shape_w / 2
    return node.x + node.w / 2


@dataclass
class _Sheet:
    """What the layout of the module instances' boxes needs: the net, its instance tree and its nodes."""

    net: object
    units: dict
    top: tuple
    nodes: dict
    collapsed: dict
    dead: set
    max_row_width: float

    def measure(self, key, depth) -> tuple[float, float, list]:
        """Lay out unit `key`; returns its size and the (kind, key, x, y) items relative to its corner."""
        u = self.units[key]
        if key in self.collapsed:
            return self._summary_box(key, depth)
        own = [("p", i) for i in u.places] + [("t", i) for i in u.transitions]
        edges = self._edges(u, set(own))
        # Nodes without an arc inside this instance (sockets and fused places used by the instances
        # below) go in a row above the rest, close to the boxes that use them.
        linked = {n for e in edges for n in e}
        row = [n for n in own if n not in linked] if u.children else []
        flow = [n for n in own if n not in row]
        lay, side = self._flow_layout(u, flow, edges, depth)
        pos, bends, lw, lh = self._arrange(row, lay, side, depth)
        kids = [self.measure(c, depth + 1) for c in u.children]
        corners, kw, kh = pack_rows([(w, h) for w, h, _ in kids], max(lw, self.max_row_width - 2 * PAD * depth))
        header = HEADER if key != self.top or u.children else 0
        inner_w = max(lw, kw, S.text_width(_box_title(u), 13) + 10)
        w = inner_w + 2 * PAD
        h = header + lh + (PAD if lh and kids else 0) + kh + PAD + (0 if header else PAD)
        items = [("box", key, 0.0, 0.0, (w, h, depth, None))]
        dx = PAD + (inner_w - lw) / 2
        for n, (x, y, sd) in pos.items():
            items.append(("node", n, dx + x, header + (PAD if not header else 0) + y, sd))
        for b, (x, y) in bends.items():
            items.append(("bend", b, dx + x, header + (PAD if not header else 0) + y, None))
        ky = header + (PAD if not header else 0) + lh + (PAD if lh and kids else 0)
        for (cx, cy), (_cw, _ch, citems) in zip(corners, kids):
            for kind, k, x, y, extra in citems:
                items.append((kind, k, PAD + cx + x, ky + cy + y, extra))
        return w, h, items

    def _summary_box(self, key, depth) -> tuple[float, float, list]:
        """The size and item of a collapsed instance: one box with its summary lines."""
        lines = _summary(self.units, key, self.collapsed[key], self.net, self.dead)
        w = max([220.0, S.text_width(_box_title(self.units[key]), 13) + 20]
                + [S.text_width(t, 12) + 20 for t, _ in lines])
        h = HEADER + LABEL_LINE * len(lines) + 10
        return w, h, [("box", key, 0.0, 0.0, (w, h, depth, lines))]

    def _edges(self, u: Unit, own_set: set) -> list:
        """The arcs between the unit's own nodes, as (source, target) node keys."""
        edges = []
        for i in u.transitions:
            for a in self.net.transitions[i].arcs:
                pk = ("p", a.place)
                if pk not in own_set:
                    continue
                edges.append((("t", i), pk) if a.kind == "out" else (pk, ("t", i)))
        return edges

    def _flow_layout(self, u: Unit, flow: list, edges: list, depth):
        """The layered layout of the unit's linked nodes, left to right, or top to bottom when too wide.

        Returns the layout (None without nodes) and whether the labels go at the right of the nodes.
        """
        if not flow:
            return None, False
        net, nodes = self.net, self.nodes
        roots = [("p", i) for i in u.places if net.places[i].initial]
        # the gap between layers leaves room for the widest (wrapped) inscription of the unit's arcs
        widest = max([S.text_width(line, 12, True) for i in u.transitions for a in net.transitions[i].arcs
                      for line in wrap(arc_inscription(net, a))] + [0])
        gap = min(190.0, max(84.0, widest + 36))
        lay = layered_layout(flow, edges, {n: (nodes[n].w, nodes[n].h) for n in flow}, roots=roots,
                             gap_x=gap, gap_y=30, margin=0, direction="LR")
        if lay.width <= self.max_row_width - 2 * PAD * (depth + 1):
            return lay, False
        # a long chain: top to bottom instead, with each node's labels at its right
        lay = layered_layout(flow, edges, {n: nodes[n].side_size() for n in flow}, roots=roots,
                             gap_x=150, gap_y=58, margin=0, direction="TB",
                             max_width=self.max_row_width - 2 * PAD * (depth + 1))
        return lay, True

    def _arrange(self, row: list, lay, side: bool, depth) -> tuple[dict, dict, float, float]:
        """The unlinked row above the laid-out flow: node centres, arc bends, and the size of both."""
        nodes = self.nodes
        pos: dict = {}
        lw = lh = 0.0
        if row:
            corners, lw, lh = pack_rows([(nodes[n].w, nodes[n].h) for n in row],
                                        self.max_row_width - 2 * PAD * depth, gap=48)
            for n, (cx, cy) in zip(row, corners):
                pos[n] = (cx + nodes[n].w / 2, cy + nodes[n].h / 2, False)
        bends: dict = {}
        if lay:
            top_y = lh + (PAD if row else 0)
            for n, (x, y) in lay.pos.items():
                pos[n] = (x, top_y + y, side)
            for e, pts in lay.routes.items():
                for i, (x, y) in enumerate(pts):
                    bends[(e, i)] = (x, top_y + y)
            lw, lh = max(lw, lay.width), top_y + lay.height
        if row and lay:  # centre the row over the flow
            shift = (lw - max(pos[n][0] + nodes[n].w / 2 for n in row)) / 2
            for n in row:
                x, y, sd = pos[n]
                pos[n] = (x + shift, y, sd)
        return pos, bends, lw, lh


FULL_INSTANCES = 3  # of a module with more instances, at most this many are drawn in full


def _all(units: dict, key, what: str) -> list:
    """The place or transition indices of unit `key` and of every instance below it."""
    u = units[key]
    out = list(getattr(u, what))
    for c in u.children:
        out += _all(units, c, what)
    return out


def _collapsed(units: dict, top, net, dead: set) -> dict:
    """Instances drawn as a summary box: key -> the key of the instance of the same module drawn in full.

    Of a module with more than FULL_INSTANCES instances, the first is drawn in full, then the next ones
    in which some transition occurs, up to FULL_INSTANCES; the others are summarised (a protocol with 16
    slaves would otherwise be 16 copies of one drawing).
    """
    by_module: dict = {}
    order: list = []

    def walk(k):
        order.append(k)
        for c in units[k].children:
            walk(c)

    walk(top)
    for k in order:
        if k != top:
            by_module.setdefault(units[k].module, []).append(k)
    out: dict = {}
    for keys in by_module.values():
        if len(keys) <= FULL_INSTANCES:
            continue
        full = [keys[0]]
        for k in keys[1:]:
            if len(full) < FULL_INSTANCES and any(net.transitions[t].name not in dead
                                                  for t in _all(units, k, "transitions")):
                full.append(k)
        for k in keys:
            if k not in full and not any(a in out for a in _ancestors(units, k)):
                out[k] = keys[0]
    return out


def _ancestors(units: dict, key) -> list:
    out = []
    k = units[key].parent
    while k is not None:
        out.append(k)
        k = units[k].parent
    return out


def _summary(units: dict, key, like, net, dead: set) -> list[tuple[str, bool]]:
    """The lines of a collapsed instance's box: (text, is a warning)."""
    ts = _all(units, key, "transitions")
    n_dead = sum(1 for t in ts if net.transitions[t].name in dead)
    n_p = len(_all(units, key, "places"))
    lines = [(f"drawn like {units[like].label}: {_count(n_p, 'place')}, {_count(len(ts), 'transition')}", False)]
    if units[key].binds:
        lines.append((S.clip("ports: " + ", ".join(units[key].binds), 60), False))
    lines.append((f"{n_dead} of {_count(len(ts), 'transition')} dead" if n_dead else "no dead transition",
                  bool(n_dead)))
    return lines


def _count(n: int, noun: str) -> str:
    return f"{n} {noun}" + ("" if n == 1 else "s")


def _collapsed_tip(units: dict, key, net, dead: set, bounds: dict) -> list[str]:
    out = []
    for t in _all(units, key, "transitions"):
        name = net.transitions[t].name
        if name in dead:
            out.append(f"dead: {name}")
    for p in _all(units, key, "places"):
        b = bounds.get(net.places[p].name)
        if b is not None:
            out.append(f"{net.places[p].name}: bounds {b[1]}..{b[0]}")
    return out


def _box_title(u: Unit) -> str:
    return u.label if u.parent is None or u.label == u.module else f"{u.label} : {u.module}"


def _initial_text(p) -> str:
    parts = []
    for key, n in p.initial.items():
        v, delay = (key if p.timed else (key, 0))
        try:
            s = p.colour_set.format(v)
        except Exception:  # noqa: BLE001
            s = repr(v)
        parts.append(f"{n}`{s}" + (f"@{delay}" if delay else ""))
    return "++".join(parts)


def _label_origin(node: _Node) -> tuple[float, float, str]:
    """Where a node's first label line goes: under the shape, or at its right in a side layout."""
    if node.side:
        return node.x + node.shape_w / 2 + 6, node.y - LABEL_LINE * (len(node.lines) - 1) / 2 + 4, "start"
    return node.x, node.y + node.shape_h / 2 + 13, "middle"


def _place(p, node: _Node, bounds: dict) -> str:
    x, y, rx, ry = node.x, node.y, node.shape_w / 2, node.shape_h / 2
    b = bounds.get(p.name)
    tip = [f"place {p.name} : {p.colset_name}"]
    if p.aliases:
        tip.append("also: " + ", ".join(p.aliases))
    if p.initial:
        tip.append("initial marking: " + _initial_text(p))
    if b is not None:
        tip.append(f"integer bounds: upper {b[0]}, lower {b[1]}")
        tip.append(f"upper multi-set bound: {b[2]}")
    out = [f'<g class="place" data-name="{S.esc(p.name)}">', S.title("\n".join(tip)),
           f'<ellipse cx="{S.fmt(x)}" cy="{S.fmt(y)}" rx="{S.fmt(rx)}" ry="{S.fmt(ry)}" '
           f'fill="{S.PLACE_FILL}" stroke="{S.ACCENT}" stroke-width="1.6"/>',
           S.text(x, y + 4.5, p.place, 13, weight="600")]
    lx, ly, anchor = _label_origin(node)
    for s, cls, mono in node.lines:
        out.append(S.text(lx, ly, s, 12, anchor, cls=cls, mono=mono,
                          fill=S.INITIAL if cls == "init" else S.MUTED))
        ly += LABEL_LINE
    if b is not None:
        label = str(b[0]) if b[0] == b[1] else f"{b[1]}..{b[0]}"
        bw = S.text_width(label, 11) + 10
        bx, by = x + rx - bw + 6, y - ry - 8
        out.append(f'<g class="bound"><rect x="{S.fmt(bx)}" y="{S.fmt(by)}" width="{S.fmt(bw)}" height="16" '
                   f'rx="8" fill="{S.ACCENT}"/>' + S.text(bx + bw / 2, by + 12, label, 11, fill="#fff")
                   + "</g>")
    out.append("</g>")
    return "".join(out)


def _transition(t, node: _Node, is_dead: bool, occ) -> str:
    x, y, w, h = node.x, node.y, node.shape_w, node.shape_h
    tip = [f"transition {t.name}"]
    if t.guards:
        tip.append("guard: " + " andalso ".join(f"[{pretty.expr(g)}]" for g in t.guards))
    if is_dead:
        tip.append("dead: it never occurs in the state space")
    elif occ is not None:
        tip.append(f"labels {occ:,} arcs of the state space")
    fill, stroke, dash = (S.BAD_FILL, S.BAD, ' stroke-dasharray="5 3"') if is_dead else (S.TRANS_FILL, S.WARN, "")
    out = [f'<g class="transition{" dead" if is_dead else ""}" data-name="{S.esc(t.name)}">',
           S.title("\n".join(tip)),
           f'<rect x="{S.fmt(x - w / 2)}" y="{S.fmt(y - h / 2)}" width="{S.fmt(w)}" height="{S.fmt(h)}" '
           f'rx="3" fill="{fill}" stroke="{stroke}" stroke-width="1.6"{dash}/>',
           S.text(x, y + 4.5, t.transition, 13, weight="600")]
    lx, ly, anchor = _label_origin(node)
    for s, cls, mono in node.lines:
        out.append(S.text(lx, ly, s, 12, anchor, cls=cls, mono=mono, fill=S.MUTED))
        ly += LABEL_LINE
    if is_dead:
        out.append(f'<g class="dead-tag"><rect x="{S.fmt(x + w / 2 - 30)}" y="{S.fmt(y - h / 2 - 9)}" '
                   f'width="36" height="16" rx="8" fill="{S.BAD}"/>'
                   + S.text(x + w / 2 - 12, y - h / 2 + 3, "dead", 11, fill="#fff") + "</g>")
    out.append("</g>")
    return "".join(out)


ROUTE_MARGIN = 8.0  # px an arc routed around other nodes keeps from them
CLEARANCE = 2.0  # px an arc drawn as laid out must keep from other nodes, else it is routed around them


def _node_box(node: _Node) -> tuple:
    """The box a node takes with its labels (under the shape, or at its right), and room for a badge
    (a place's bound, a transition's "dead") above it."""
    if node.side:
        w, h = node.side_size()
        x0 = node.x - node.shape_w / 2
        return (x0, node.y - h / 2 - 9, x0 + w, node.y + h / 2)
    top = node.y - node.shape_h / 2
    return (node.x - node.w / 2, top - 9, node.x + node.w / 2, top + node.h)


@dataclass
class _Drawn:
    """One arc's geometry: its path data, its points (curves sampled), where its inscription goes."""

    a: object
    transition: int
    d: str
    points: list
    start: tuple
    end: tuple
    label: tuple | None  # the laid-out place of the inscription: (x, y, steep)


def _arcs(net, nodes: dict, routes: dict, titles: list = ()) -> tuple[list[str], float]:
    """The arcs as SVG, and the rightmost x any inscription reaches.

    routes: (from node, to node) -> bend points of a laid-out edge that spans several layers; titles:
    boxes of the module boxes' titles. An arc drawn as laid out that would cross another node (its shape
    or its labels) is routed around the nodes instead (layout.Router), and each inscription goes to the
    first place along its arc where it covers no node, no title and no other inscription, inside the
    drawing."""
    pairs: dict = {}
    for t in net.transitions:
        for a in t.arcs:
            pairs.setdefault((a.place, t.index), []).append(a)
    boxes = {n: _node_box(node) for n, node in nodes.items()}
    router = Router(boxes, ROUTE_MARGIN)
    drawn: list[_Drawn] = []
    for (p, ti), arcs in pairs.items():
        if ("p", p) not in nodes or ("t", ti) not in nodes:  # an end inside a collapsed instance
            continue
        pn, tn = nodes[("p", p)], nodes[("t", ti)]
        place, trans = net.places[p], net.transitions[ti]
        # An arc between module instances is bent so that it does not run through the nodes lined up
        # between them (the same transition of the next instance, typically).
        cross = (place.page, place.instance) != (trans.page, trans.instance)
        dist = ((pn.x - tn.x) ** 2 + (pn.y - tn.y) ** 2) ** 0.5
        base = min(120.0, 0.12 * dist + 16) if cross else 0.0
        keys = [(("t", ti), ("p", p)) if a.kind == "out" else (("p", p), ("t", ti)) for a in arcs]
        skip = {("p", p), ("t", ti)}
        laid = []
        for k, a in enumerate(arcs):
            bend = base + (k - (len(arcs) - 1) / 2) * 34
            # an arc alone in its direction between the two nodes follows the layout's bend points
            route = routes.get(keys[k]) if keys.count(keys[k]) == 1 and not cross else None
            laid.append(_laid_out(a, pn, tn, bend, route))
        around = [k for k, g in enumerate(laid)
                  if router.path_blocked(g.points, skip, shrink=ROUTE_MARGIN - CLEARANCE)]
        detour = router.route((pn.x, pn.y), (tn.x, tn.y), skip) if around else None
        for j, k in enumerate(around):
            if detour:
                spacing = min(8.0, 2 * (ROUTE_MARGIN - 3) / max(1, len(around) - 1))
                laid[k] = _routed(arcs[k], pn, tn, detour, (j - (len(around) - 1) / 2) * spacing)
        drawn += laid
    out = []
    right = 0.0
    taken: list = []
    node_boxes = list(boxes.values()) + list(titles)
    for g in drawn:
        svg, r = _arc_svg(net, g, node_boxes, taken)
        out.append(svg)
        right = max(right, r)
    return out, right


def _laid_out(a, pn: _Node, tn: _Node, bend: float, route: list | None) -> _Drawn:
    """The arc as the layout draws it: straight, bent by `bend` px, or through the layout's bend points."""
    (px, py), (tx, ty) = (pn.x, pn.y), (tn.x, tn.y)
    dx, dy = tx - px, ty - py
    dist = max(1.0, (dx * dx + dy * dy) ** 0.5)
    nx, ny = -dy / dist, dx / dist  # unit normal
    mx, my = (px + tx) / 2 + nx * bend, (py + ty) / 2 + ny * bend  # control point
    ax, ay = S.boundary_point(px, py, pn.shape_w / 2, pn.shape_h / 2, mx, my, "ellipse")
    bx, by = S.boundary_point(tx, ty, tn.shape_w / 2, tn.shape_h / 2, mx, my, "rect")
    if a.kind == "out":
        (ax, ay), (bx, by) = (bx, by), (ax, ay)
    d = (f"M{S.fmt(ax)},{S.fmt(ay)} L{S.fmt(bx)},{S.fmt(by)}" if bend == 0 else
         f"M{S.fmt(ax)},{S.fmt(ay)} Q{S.fmt(mx)},{S.fmt(my)} {S.fmt(bx)},{S.fmt(by)}")
    lx = (ax + bx) / 2 + (nx * bend / 2 if bend else 0)
    ly = (ay + by) / 2 + (ny * bend / 2 if bend else 0)
    label = (lx, ly, abs(by - ay) > 1.5 * abs(bx - ax))
    if route:  # through the bend points the layout left between the nodes of the layers it crosses
        (sn, ss), (en, es) = ((tn, "rect"), (pn, "ellipse")) if a.kind == "out" else ((pn, "ellipse"), (tn, "rect"))
        ax, ay = S.boundary_point(sn.x, sn.y, sn.shape_w / 2, sn.shape_h / 2, route[0][0], route[0][1], ss)
        bx, by = S.boundary_point(en.x, en.y, en.shape_w / 2, en.shape_h / 2, route[-1][0], route[-1][1], es)
        pts = [(ax, ay), *route, (bx, by)]
        d = S.smooth_path(pts)
        m = len(pts) // 2
        (x0, y0), (x1, y1) = pts[m - 1], pts[m + 1] if m + 1 < len(pts) else pts[m]
        label = (pts[m][0], pts[m][1], abs(y1 - y0) > 1.5 * abs(x1 - x0))
    return _Drawn(a, tn.index, d, S.path_points(d), (ax, ay), (bx, by), label)


def _routed(a, pn: _Node, tn: _Node, detour: list, offset: float) -> _Drawn:
    """The arc along `detour` (place centre to transition centre, around the other nodes), its corners
    shifted `offset` px sideways (arcs between the same two nodes side by side), rounded."""
    (px, py), (tx, ty) = detour[0], detour[-1]
    inner = list(detour[1:-1]) or [((px + tx) / 2, (py + ty) / 2)]
    if offset:
        dist = max(1.0, ((tx - px) ** 2 + (ty - py) ** 2) ** 0.5)
        nx, ny = -(ty - py) / dist, (tx - px) / dist
        inner = [(x + nx * offset, y + ny * offset) for x, y in inner]
    elif not detour[1:-1]:
        inner = []
    first, last = inner[0] if inner else (tx, ty), inner[-1] if inner else (px, py)
    ax, ay = S.boundary_point(px, py, pn.shape_w / 2, pn.shape_h / 2, first[0], first[1], "ellipse")
    bx, by = S.boundary_point(tx, ty, tn.shape_w / 2, tn.shape_h / 2, last[0], last[1], "rect")
    pts = [(ax, ay), *inner, (bx, by)]
    if a.kind == "out":
        pts.reverse()
    d = S.rounded_path(pts, ROUTE_MARGIN - 2)
    return _Drawn(a, tn.index, d, S.path_points(d), pts[0], pts[-1], None)


def _label_boxes(lines: list[str], x: float, top: float, anchor: str) -> tuple:
    w = max(S.text_width(line, 12, True) for line in lines)
    x0 = x - w / 2 if anchor == "middle" else x - w if anchor == "end" else x
    return (x0, top, x0 + w, top + 14 * len(lines) - 1)


def _label_candidates(g: _Drawn, n: int):
    """Where an inscription of n lines may go: (x, top of its first line, anchor), the laid-out place
    first, then beside the arc at points along it (the middle first)."""
    if g.label is not None:
        lx, ly, steep = g.label
        yield (lx + 7, ly + 4 - 7 * (n - 1) - 10, "start") if steep else (lx, ly - 4 - 14 * (n - 1) - 10, "middle")
    pts = g.points
    lengths = [((b[0] - a[0]) ** 2 + (b[1] - a[1]) ** 2) ** 0.5 for a, b in zip(pts, pts[1:])]
    total = sum(lengths)
    for f in (0.5, 0.38, 0.62, 0.26, 0.74, 0.15, 0.85):
        at, i = f * total, 0
        while i < len(lengths) - 1 and at > lengths[i]:
            at -= lengths[i]
            i += 1
        (x0, y0), (x1, y1) = pts[i], pts[i + 1]
        s = at / lengths[i] if lengths[i] else 0.0
        x, y = x0 + (x1 - x0) * s, y0 + (y1 - y0) * s
        if abs(y1 - y0) > 1.5 * abs(x1 - x0):  # steep: at its side
            yield (x + 7, y - 7 * n, "start")
            yield (x - 7, y - 7 * n, "end")
        else:
            yield (x, y - 3 - 14 * n, "middle")
            yield (x, y + 3, "middle")


def _arc_svg(net, g: _Drawn, node_boxes: list, taken: list) -> tuple[str, float]:
    """One arc as SVG with its inscription, and the rightmost x it reaches; `taken` collects the boxes
    of the inscriptions placed so far."""
    a = g.a
    bx, by = g.end
    label = arc_inscription(net, a)
    dash = ""
    m_end = 'marker-end="url(#na-line)"'
    m_start = ""
    if a.kind == "both":
        m_start = 'marker-start="url(#na-line)"'
    elif a.kind == "inhibitor":
        m_end = ""
        dash = ' stroke-dasharray="2 3"'
        label = ("inhibitor " + label).strip()
    elif a.kind == "reset":
        dash = ' stroke-dasharray="7 3"'
        label = ("reset " + label).strip()
    tip = f"{a.kind} arc {net.places[a.place].name} – {net.transitions[g.transition].name}" + (f": {label}" if label else "")
    out = [f'<g class="arc">{S.title(tip)}<path d="{g.d}" fill="none" stroke="{S.LINE}" stroke-width="1.4"'
           f'{dash} {m_start} {m_end}/>']
    if a.kind == "inhibitor":
        out.append(f'<circle cx="{S.fmt(bx)}" cy="{S.fmt(by)}" r="4" fill="#fff" stroke="{S.LINE}"/>')
    right = max(x for x, _ in g.points)
    if label:
        lines = wrap(label)
        choice = first_free = None
        for x, top, anchor in _label_candidates(g, len(lines)):
            box = _label_boxes(lines, x, top, anchor)
            if box[0] < 1 or box[1] < 1 or any(boxes_overlap(box, b) for b in node_boxes):
                continue
            if first_free is None:
                first_free = (x, top, anchor, box)
            if not any(boxes_overlap(box, b) for b in taken):
                choice = (x, top, anchor, box)
                break
        choice = choice or first_free
        if choice is None:
            x, top, anchor = next(_label_candidates(g, len(lines)))
            choice = (x, top, anchor, _label_boxes(lines, x, top, anchor))
        x, top, anchor, box = choice
        taken.append(box)
        for k, line in enumerate(lines):
            out.append(S.text(x, top + 10 + 14 * k, line, 12, anchor, mono=True, halo=True, cls="inscription"))
        right = max(right, box[2])
    out.append("</g>")
    return "".join(out), right
