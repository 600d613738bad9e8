"""Charts as SVG: bars and lines with axes, written directly (a plotting library is not needed for two
kinds of chart). `growth_chart` plots the states first reached at each BFS level; `scaling_chart` plots
states and seconds against a parameter of the model (the scaling tables of the benchmarks).

Imports the report's `svg` helpers only.
"""

from __future__ import annotations

import math

from cpn.report import svg as S

SERIES = ["#1d5fa8", "#d97706", "#1d7a3c", "#7c3aed"]


def nice_ticks(lo: float, hi: float, n: int = 5) -> list[float]:
    """Round tick values covering [lo, hi] (about n of them)."""
    if hi <= lo:
        hi = lo + 1
    raw = (hi - lo) / max(1, n)
    mag = 10 ** math.floor(math.log10(raw))
    step = next(m * mag for m in (1, 2, 2.5, 5, 10) if m * mag >= raw)
    start = math.floor(lo / step) * step
    ticks = []
    v = start
    while v <= hi + step * 1e-9:
        ticks.append(round(v, 10))
        v += step
    if ticks[-1] < hi:
        ticks.append(round(v, 10))
    return ticks


def log_ticks(lo: float, hi: float) -> list[float]:
    a = math.floor(math.log10(max(lo, 1e-12)))
    b = math.ceil(math.log10(max(hi, 1e-12)))
    return [10.0 ** k for k in range(a, max(b, a + 1) + 1)]


def _num(v: float) -> str:
    if v == 0:
        return "0"
    if abs(v) >= 1e6 or abs(v) < 1e-3:
        return f"{v:.0e}".replace("e+0", "e").replace("e-0", "e-")
    if v == int(v):
        return f"{int(v):,}"
    return f"{v:g}"


class _Axes:
    def __init__(self, x0, y0, w, h, xt, yt, log_y=False):
        self.x0, self.y0, self.w, self.h = x0, y0, w, h
        self.xlo, self.xhi = xt[0], xt[-1]
        self.ylo, self.yhi = yt[0], yt[-1]
        self.log_y = log_y
        self.xt, self.yt = xt, yt

    def x(self, v):
        return self.x0 + (v - self.xlo) / ((self.xhi - self.xlo) or 1) * self.w

    def y(self, v):
        if self.log_y:
            a, b, v = math.log10(self.ylo), math.log10(self.yhi), math.log10(max(v, self.ylo))
        else:
            a, b = self.ylo, self.yhi
        return self.y0 + self.h - (v - a) / ((b - a) or 1) * self.h

    def frame(self, x_label, y_label, x_ticks=None) -> list[str]:
        out = []
        for t in self.yt:
            yy = self.y(t)
            out.append(f'<line x1="{S.fmt(self.x0)}" y1="{S.fmt(yy)}" x2="{S.fmt(self.x0 + self.w)}" '
                       f'y2="{S.fmt(yy)}" stroke="#e4e7eb"/>')
            out.append(S.text(self.x0 - 6, yy + 4, _num(t), 11, "end", fill=S.MUTED))
        for t in (x_ticks if x_ticks is not None else self.xt):
            xx = self.x(t)
            out.append(f'<line x1="{S.fmt(xx)}" y1="{S.fmt(self.y0 + self.h)}" x2="{S.fmt(xx)}" '
                       f'y2="{S.fmt(self.y0 + self.h + 4)}" stroke="{S.MUTED}"/>')
            out.append(S.text(xx, self.y0 + self.h + 17, _num(t), 11, fill=S.MUTED))
        out.append(f'<path d="M{S.fmt(self.x0)},{S.fmt(self.y0)} V{S.fmt(self.y0 + self.h)} '
                   f'H{S.fmt(self.x0 + self.w)}" fill="none" stroke="{S.MUTED}"/>')
        out.append(S.text(self.x0 + self.w / 2, self.y0 + self.h + 36, x_label, 12, fill=S.INK))
        out.append(f'<text x="14" y="{S.fmt(self.y0 + self.h / 2)}" font-size="12" text-anchor="middle" '
                   f'transform="rotate(-90 14 {S.fmt(self.y0 + self.h / 2)})">{S.esc(y_label)}</text>')
        return out


def bar_chart(values: list[float], x_label: str, y_label: str, caption: str = "", width: float = 620,
              height: float = 260, tooltip=None) -> str:
    """Bars for values at x = 0, 1, 2, ...; tooltip(i, v) gives each bar's hover text."""
    top = 30 if caption else 12
    ax = _Axes(64, top, width - 84, height - top - 48, [0, max(1, len(values))],
               nice_ticks(0, max(values) if values else 1))
    step = max(1, math.ceil(len(values) / 12))
    body = ([S.text(10, 18, caption, 13, "start", weight="600")] if caption else [])
    body += ax.frame(x_label, y_label, x_ticks=[])
    bw = ax.w / max(1, len(values))
    for i, v in enumerate(values):
        x = ax.x0 + i * bw
        tip = tooltip(i, v) if tooltip else f"{_num(i)}: {_num(v)}"
        body.append(f'<rect class="bar" x="{S.fmt(x + bw * 0.12)}" y="{S.fmt(ax.y(v))}" width="{S.fmt(bw * 0.76)}" '
                    f'height="{S.fmt(ax.y0 + ax.h - ax.y(v))}" fill="{SERIES[0]}">{S.title(tip)}</rect>')
        if i % step == 0:
            body.append(S.text(x + bw / 2, ax.y0 + ax.h + 17, str(i), 11, fill=S.MUTED))
    return S.document(width, height, body, caption or y_label, cls="drawing chart")


def line_chart(xs: list[float], series: list[tuple[str, list[float]]], x_label: str, y_label: str,
               caption: str = "", log_y: bool = False, width: float = 420, height: float = 260,
               standalone: bool = False) -> str:
    """Lines with point markers, one per (name, ys) in `series`, over the same xs."""
    top = 30 if caption else 12
    ys = [v for _, vs in series for v in vs if v is not None]
    lo, hi = (min(ys), max(ys)) if ys else (0, 1)
    yt = log_ticks(max(lo, 1e-9), hi) if log_y else nice_ticks(min(0, lo), hi)
    xt = nice_ticks(min(xs), max(xs)) if xs else [0, 1]
    legend_h = 18 * len(series) if len(series) > 1 else 0
    ax = _Axes(64, top + legend_h, width - 84, height - top - legend_h - 48, xt, yt, log_y)
    # the data's own x values as ticks when they are whole numbers far enough apart to be read
    gaps = [ax.x(b) - ax.x(a) for a, b in zip(sorted(xs), sorted(xs)[1:])]
    readable = all(float(x).is_integer() for x in xs) and len(xs) <= 16 and min(gaps, default=99) >= 22
    xt_shown = list(xs) if xs and readable else xt
    body = ([S.text(10, 18, caption, 13, "start", weight="600")] if caption else [])
    body += ax.frame(x_label, y_label + (" (log scale)" if log_y else ""), x_ticks=xt_shown)
    for k, (name, vs) in enumerate(series):
        colour = SERIES[k % len(SERIES)]
        pts = [(ax.x(x), ax.y(v), x, v) for x, v in zip(xs, vs) if v is not None]
        if pts:
            d = " ".join(("M" if i == 0 else "L") + f"{S.fmt(px)},{S.fmt(py)}" for i, (px, py, _, _) in enumerate(pts))
            body.append(f'<path d="{d}" fill="none" stroke="{colour}" stroke-width="2"/>')
        for px, py, x, v in pts:
            body.append(f'<circle cx="{S.fmt(px)}" cy="{S.fmt(py)}" r="3.5" fill="{colour}">'
                        f'{S.title(f"{name}: {_num(v)} at {x_label} = {_num(x)}")}</circle>')
        if legend_h:
            ly = top + 4 + 18 * k
            body.append(f'<rect x="{S.fmt(ax.x0)}" y="{ly}" width="14" height="4" fill="{colour}"/>'
                        + S.text(ax.x0 + 20, ly + 6, name, 12, "start"))
    return S.document(width, height, body, caption or y_label, cls="drawing chart", standalone=standalone)


def growth_chart(level_sizes: list[int]) -> str:
    """States first reached at each BFS level (the breadth of the search level by level)."""
    total = sum(level_sizes)
    return bar_chart(level_sizes, "BFS level (steps from the initial marking)", "new states",
                     caption=f"State-space growth: {total:,} states over {len(level_sizes)} BFS levels",
                     tooltip=lambda i, v: f"level {i}: {v:,} new states")


def scaling_chart(rows: list[dict], param: str = "N", standalone: bool = False,
                  states: tuple = ("states",), seconds: tuple = ("seconds",)) -> str:
    """States and seconds against a parameter: rows like {"N": 3, "states": 837, "seconds": 0.1}.

    Two panels side by side (states on a log scale), one line per column named in `states` and in
    `seconds` (e.g. a run with and one without broadcasts); rows missing a figure leave a gap. With
    standalone=True the result is a complete SVG file, e.g. for an image next to a benchmark table.
    """
    rows = sorted(rows, key=lambda r: r[param])
    xs = [r[param] for r in rows]
    left = line_chart(xs, [(c, [r.get(c) for r in rows]) for c in states], param, "states",
                      caption="States", log_y=True)
    right = line_chart(xs, [(c, [r.get(c) for r in rows]) for c in seconds], param, "seconds",
                       caption="Seconds")
    body = [f'<g>{left}</g>', f'<g transform="translate(430,0)">{right}</g>']
    return S.document(850, 260, body, f"states and seconds against {param}", cls="drawing chart",
                      standalone=standalone)


def markdown_table(text: str, after: str = "") -> list[dict]:
    """The first Markdown table of `text` after the line containing `after`, as rows of numbers.

    Cells are read as numbers where they are ("1 177", "0.71"); a column heading that repeats an earlier
    one gets the earlier one's prefix ("with a broadcast: states" then "arcs" gives "with a broadcast:
    arcs"). Cells that are not numbers are kept as text.
    """
    lines = text.split("\n")
    start = next((k for k, line in enumerate(lines) if after in line), 0) if after else 0
    k = next((j for j in range(start, len(lines)) if lines[j].lstrip().startswith("|")), None)
    if k is None:
        return []
    head = [c.strip() for c in lines[k].strip().strip("|").split("|")]
    prefix = ""
    names = []
    for h in head:
        if ": " in h:
            prefix = h.split(": ")[0] + ": "
        names.append(h if ": " in h or h not in names else prefix + h)
    rows = []
    for line in lines[k + 2:]:
        if not line.lstrip().startswith("|"):
            break
        cells = [c.strip() for c in line.strip().strip("|").split("|")]
        rows.append({n: _number(c) for n, c in zip(names, cells)})
    return rows


def _number(cell: str):
    t = cell.replace(" ", "").replace("\u202f", "").replace(",", "")
    try:
        return int(t)
    except ValueError:
        try:
            return float(t)
        except ValueError:
            return cell
