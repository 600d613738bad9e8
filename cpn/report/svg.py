"""Small helpers to write SVG as text: escaping, text width estimates, arrowheads and a shared style.

Imports the standard library only. The drawings (`netdraw`, `graphdraw`, `msc`, `plot`) write their
elements with these helpers; nothing here knows about nets or state spaces.
"""

from __future__ import annotations

import html
import math

FONT = "system-ui, -apple-system, 'Segoe UI', Roboto, 'DejaVu Sans', Arial, sans-serif"
MONO = "ui-monospace, 'DejaVu Sans Mono', Menlo, Consolas, monospace"

# Colours (also used by the page's CSS): readable on white, distinguishable for the common colour
# vision deficiencies (blue/orange/red with different lightness).
INK = "#1f2933"
MUTED = "#616e7c"
LINE = "#52606d"
PLACE_FILL = "#e8f1fb"
TRANS_FILL = "#fdf3e1"
BOX_STROKE = "#9aa5b1"
ACCENT = "#1d5fa8"
INITIAL = "#1d7a3c"
BAD = "#c0262d"
BAD_FILL = "#fde8e8"
WARN = "#b45309"


def esc(s) -> str:
    """Text escaped for SVG/HTML content and attribute values."""
    return html.escape(str(s), quote=True)


def text_width(s: str, size: float, mono: bool = False) -> float:
    """An estimate of the rendered width of `s` in px (monospace: exact for most fonts)."""
    if mono:
        return 0.61 * size * len(s)
    wide = sum(1 for c in s if c in "MWmw@%")
    narrow = sum(1 for c in s if c in "il.,:;'|!()[]{} ")
    return size * (0.56 * len(s) + 0.3 * wide - 0.27 * narrow)


def clip(s: str, n: int) -> str:
    """`s` cut to at most n characters, with an ellipsis when cut."""
    return s if len(s) <= n else s[: max(1, n - 1)] + "…"


def fmt(x: float) -> str:
    """A coordinate with at most one decimal."""
    r = round(x, 1)
    return str(int(r)) if r == int(r) else str(r)


def text(x: float, y: float, s: str, size: float = 12, anchor: str = "middle", cls: str = "",
         mono: bool = False, fill: str | None = None, weight: str | None = None, halo: bool = False) -> str:
    attrs = [f'x="{fmt(x)}"', f'y="{fmt(y)}"', f'font-size="{fmt(size)}"', f'text-anchor="{anchor}"']
    if mono:
        attrs.append(f'font-family="{esc(MONO)}"')
    if cls:
        attrs.append(f'class="{cls}"')
    if fill:
        attrs.append(f'fill="{fill}"')
    if weight:
        attrs.append(f'font-weight="{weight}"')
    if halo:
        attrs.append('stroke="#fff" stroke-width="3" stroke-linejoin="round" paint-order="stroke"')
    return f"<text {' '.join(attrs)}>{esc(s)}</text>"


def title(s: str) -> str:
    """A native tooltip (shown on hover without any script)."""
    return f"<title>{esc(s)}</title>"


def arrow_defs(prefix: str, colours: dict[str, str]) -> str:
    """<defs> with one arrowhead marker per colour, ids `{prefix}-{name}`."""
    out = ["<defs>"]
    for name, colour in colours.items():
        out.append(f'<marker id="{prefix}-{name}" viewBox="0 0 10 10" refX="9" refY="5" markerWidth="7" '
                   f'markerHeight="7" orient="auto-start-reverse"><path d="M0,0 L10,5 L0,10 z" '
                   f'fill="{colour}"/></marker>')
    out.append("</defs>")
    return "".join(out)


def document(width: float, height: float, body: list[str], label: str, cls: str = "drawing",
             standalone: bool = False) -> str:
    """An <svg> element of the given natural size, scalable through its viewBox."""
    w, h = max(1, math.ceil(width)), max(1, math.ceil(height))
    ns = ' xmlns="http://www.w3.org/2000/svg"' if standalone else ""
    head = (f'<svg{ns} class="{cls}" viewBox="0 0 {w} {h}" width="{w}" height="{h}" role="img" '
            f'aria-label="{esc(label)}" font-family="{esc(FONT)}" fill="{INK}">')
    return head + "".join(body) + "</svg>"


def boundary_point(cx: float, cy: float, hw: float, hh: float, tx: float, ty: float, shape: str) -> tuple:
    """Where the segment from the centre (cx, cy) toward (tx, ty) leaves a node's outline.

    `shape` is 'ellipse' (half axes hw, hh), 'circle' (radius hw) or 'rect' (half sizes hw, hh).
    """
    dx, dy = tx - cx, ty - cy
    if dx == 0 and dy == 0:
        return cx, cy
    if shape == "rect":
        sx = hw / abs(dx) if dx else math.inf
        sy = hh / abs(dy) if dy else math.inf
        s = min(sx, sy)
    elif shape == "circle":
        s = hw / math.hypot(dx, dy)
    else:
        s = 1.0 / math.sqrt((dx / hw) ** 2 + (dy / hh) ** 2)
    return cx + dx * s, cy + dy * s


def smooth_path(points: list[tuple[float, float]]) -> str:
    """Path data for a smooth curve through the points (Catmull-Rom as cubic Béziers)."""
    pts = list(points)
    d = [f"M{fmt(pts[0][0])},{fmt(pts[0][1])}"]
    for i in range(len(pts) - 1):
        p0 = pts[i - 1] if i else pts[i]
        p1, p2 = pts[i], pts[i + 1]
        p3 = pts[i + 2] if i + 2 < len(pts) else p2
        c1 = (p1[0] + (p2[0] - p0[0]) / 6, p1[1] + (p2[1] - p0[1]) / 6)
        c2 = (p2[0] - (p3[0] - p1[0]) / 6, p2[1] - (p3[1] - p1[1]) / 6)
        d.append(f"C{fmt(c1[0])},{fmt(c1[1])} {fmt(c2[0])},{fmt(c2[1])} {fmt(p2[0])},{fmt(p2[1])}")
    return " ".join(d)


def rounded_path(points: list[tuple[float, float]], radius: float = 8.0) -> str:
    """Path data for a polyline whose corners are rounded (each by at most `radius`, and at most half of
    the segments that meet there), so the curve stays within `radius` of the corner."""
    pts = list(points)
    d = [f"M{fmt(pts[0][0])},{fmt(pts[0][1])}"]
    for i in range(1, len(pts) - 1):
        (x0, y0), (x1, y1), (x2, y2) = pts[i - 1], pts[i], pts[i + 1]
        l1, l2 = math.hypot(x1 - x0, y1 - y0), math.hypot(x2 - x1, y2 - y1)
        r = min(radius, l1 / 2, l2 / 2)
        if r < 0.5:
            d.append(f"L{fmt(x1)},{fmt(y1)}")
            continue
        ax, ay = x1 - (x1 - x0) * r / l1, y1 - (y1 - y0) * r / l1
        bx, by = x1 + (x2 - x1) * r / l2, y1 + (y2 - y1) * r / l2
        d.append(f"L{fmt(ax)},{fmt(ay)} Q{fmt(x1)},{fmt(y1)} {fmt(bx)},{fmt(by)}")
    d.append(f"L{fmt(pts[-1][0])},{fmt(pts[-1][1])}")
    return " ".join(d)


def path_points(d: str, samples: int = 12) -> list[tuple[float, float]]:
    """The points of path data made of absolute M, L, Q and C commands, curves sampled `samples` times."""
    import re

    tokens = re.findall(r"[MLQC]|-?\d+(?:\.\d+)?(?:e-?\d+)?", d)
    out: list[tuple[float, float]] = []
    cmd, i = "M", 0
    while i < len(tokens):
        if tokens[i] in "MLQC":
            cmd = tokens[i]
            i += 1
            continue
        n = {"M": 2, "L": 2, "Q": 4, "C": 6}[cmd]
        v = [float(t) for t in tokens[i:i + n]]
        i += n
        if cmd in "ML" or not out:
            out.append((v[-2], v[-1]))
            continue
        p0 = out[-1]
        ctrl = [(v[k], v[k + 1]) for k in range(0, n, 2)]
        for k in range(1, samples + 1):
            s = k / samples
            ps = [p0, *ctrl]
            while len(ps) > 1:  # de Casteljau
                ps = [(a[0] + (b[0] - a[0]) * s, a[1] + (b[1] - a[1]) * s) for a, b in zip(ps, ps[1:])]
            out.append(ps[0])
    return out
