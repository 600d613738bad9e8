"""The net drawing: no arc runs through a node it does not join, and no inscription covers a node.

Read back from the SVG: a node's box is its shape (ellipse, rectangle) with its text (name, colour set,
initial marking, guard, delay), an arc is its path (curves sampled), an inscription the box of its text.
"""

import pathlib
import re
import xml.etree.ElementTree as ET

import pytest

import cpn
from cpn.report import svg as S
from cpn.report.layout import Router, segment_hits_box
from cpn.report.netdraw import draw_net

ROOT = pathlib.Path(__file__).resolve().parents[2]
NS = "{http://www.w3.org/2000/svg}"


def _root(svg: str):
    return ET.fromstring(svg.replace("<svg ", '<svg xmlns="http://www.w3.org/2000/svg" ', 1))


def _text_box(t) -> tuple:
    x, y, size = float(t.get("x")), float(t.get("y")), float(t.get("font-size"))
    w = S.text_width(t.text or "", size, "font-family" in t.attrib)
    anchor = t.get("text-anchor")
    x0 = x - w / 2 if anchor == "middle" else x - w if anchor == "end" else x
    return (x0, y - 0.75 * size, x0 + w, y + 0.2 * size)


def _union(boxes):
    return (min(b[0] for b in boxes), min(b[1] for b in boxes), max(b[2] for b in boxes), max(b[3] for b in boxes))


def _nodes(root) -> dict:
    out = {}
    for g in root.iter(f"{NS}g"):
        cls = (g.get("class") or "").split()
        if "place" not in cls and "transition" not in cls:
            continue
        boxes = []
        for e in g:
            if e.tag == f"{NS}ellipse":
                cx, cy, rx, ry = (float(e.get(k)) for k in ("cx", "cy", "rx", "ry"))
                boxes.append((cx - rx, cy - ry, cx + rx, cy + ry))
            elif e.tag == f"{NS}rect":
                x, y, w, h = (float(e.get(k)) for k in ("x", "y", "width", "height"))
                boxes.append((x, y, x + w, y + h))
            elif e.tag == f"{NS}text":
                boxes.append(_text_box(e))
        out[g.get("data-name")] = _union(boxes)
    return out


def _points(d: str) -> list:
    """Absolute M/L/Q/C path data as points, curves sampled (written here, apart from the drawing's code)."""
    tokens = re.findall(r"[MLQC]|-?[\d.]+", d)
    pts, cmd, i = [], None, 0
    while i < len(tokens):
        if tokens[i] in "MLQC":
            cmd, i = tokens[i], i + 1
            continue
        n = {"M": 2, "L": 2, "Q": 4, "C": 6}[cmd]
        v = [float(t) for t in tokens[i:i + n]]
        i += n
        if cmd in "ML":
            pts.append((v[0], v[1]))
            continue
        p0, ctrl = pts[-1], [(v[k], v[k + 1]) for k in range(0, n, 2)]
        for k in range(1, 21):
            s = k / 20
            if cmd == "Q":
                (x1, y1), (x2, y2) = ctrl
                pts.append(((1 - s) ** 2 * p0[0] + 2 * (1 - s) * s * x1 + s * s * x2,
                            (1 - s) ** 2 * p0[1] + 2 * (1 - s) * s * y1 + s * s * y2))
            else:
                (x1, y1), (x2, y2), (x3, y3) = ctrl
                r = 1 - s
                pts.append((r ** 3 * p0[0] + 3 * r * r * s * x1 + 3 * r * s * s * x2 + s ** 3 * x3,
                            r ** 3 * p0[1] + 3 * r * r * s * y1 + 3 * r * s * s * y2 + s ** 3 * y3))
    return pts


def _arcs(root) -> list:
    out = []
    for g in root.iter(f"{NS}g"):
        if g.get("class") != "arc":
            continue
        m = re.match(r"\w+ arc (.+?) – (.+? \d+)", g.find(f"{NS}title").text)
        out.append((m.group(1), m.group(2), _points(g.find(f"{NS}path").get("d")),
                    [_text_box(t) for t in g.findall(f"{NS}text")]))
    return out


def _overlap(a, b) -> bool:
    return a[0] < b[2] and b[0] < a[2] and a[1] < b[3] and b[1] < a[3]


def crossings(svg: str) -> list:
    """(what, place, transition, node): arcs through, and inscriptions over, nodes other than the arc's ends."""
    root = _root(svg)
    nodes = _nodes(root)
    found = []
    for place, trans, pts, labels in _arcs(root):
        assert place in nodes and trans in nodes
        for name, (x0, y0, x1, y1) in nodes.items():
            if name in (place, trans):
                continue
            box = (x0 + 1, y0 + 1, x1 - 1, y1 - 1)  # touching is not crossing
            if any(segment_hits_box(a, b, box) for a, b in zip(pts, pts[1:])):
                found.append(("arc", place, trans, name))
            if any(_overlap(lb, box) for lb in labels):
                found.append(("inscription", place, trans, name))
    return found


@pytest.mark.parametrize("path", ["models/examples/broadcast.cpnet", "models/examples/stations.cpnet",
                                  "models/examples/timer_cancel.cpnet", "tests/report/nets/minibus.cpnet",
                                  "bench/nets/ms_sym.cpnet", "models/modbus/modbus_a.cpnet"])
def test_no_arc_or_inscription_crosses_a_node_it_does_not_join(path):
    net = cpn.load(str(ROOT / path)).net
    svg = draw_net(net)
    assert crossings(svg) == []
    assert len(_arcs(_root(svg))) > 0


def test_the_modbus_slave_receives_around_its_discard_transition():
    # arcs from the top page's places to the slaves' transitions ran straight through other transitions
    # (Slave1'Discard among them), their inscriptions over the guards
    net = cpn.load(str(ROOT / "models/modbus/modbus.cpnet")).net
    svg = draw_net(net)
    assert crossings(svg) == []
    into_slave = [a for a in _arcs(_root(svg)) if a[0] == "Modbus'b2s 1" and a[1].startswith("Slave'")]
    assert {a[1] for a in into_slave} >= {"Slave'Discard 1", "Slave'AcceptUnicast 1"}


def test_router_paths_keep_off_every_box_but_may_start_inside_their_own():
    boxes = {"a": (0, 0, 40, 20), "wall": (100, -200, 120, 200), "b": (200, 0, 240, 20)}
    r = Router(boxes, margin=8)
    path = r.route((20, 10), (220, 10), skip={"a", "b"})
    assert path[0] == (20, 10) and path[-1] == (220, 10) and len(path) > 2
    assert not any(segment_hits_box(p, q, (92, -208, 128, 208)) for p, q in zip(path, path[1:]))
    assert r.route((20, 10), (20, 300), skip={"a"}) == [(20, 10), (20, 300)]  # nothing in the way
