"""A trace drawn as a message sequence chart (SVG).

Imports `cpn.checks.columns`, the report's `netdraw.instance_tree` and `svg` helpers. One lifeline per
module instance that takes part (for a net with a single instance: one per transition instance); each
step of the trace is an event on the lifeline of its transition's instance; a token produced by a step
of one instance and consumed by a later step of another instance is an arrow between the two events.
Tokens are followed place by place, first in first out among equal values; a token that was in the
initial marking has no sender and draws no arrow. A token taken by a step that puts no token anywhere
(a lost or discarded frame) ends in a cross; a token still in its place at the end of the trace, in a
place that another instance takes tokens from, is an open dashed arrow toward that instance (the one
that could take it next, when one can). For timed nets the vertical axis shows model time.
"""

from __future__ import annotations

import weakref
from collections import Counter, defaultdict, deque
from dataclasses import dataclass, field

from cpn.checks.columns import untimed_multiset
from cpn.engine.protocol import capability
from cpn.report import svg as S
from cpn.report.netdraw import instance_tree

ROW = 36  # px per step
TIME_GAP = 20  # extra px when model time advances
COLUMN = 172
HEAD = 58
LEFT = 86
MESSAGE_CHARS = 34  # longer token values are cut (the tooltip has them whole)


@dataclass
class Event:
    step: int  # 1-based
    line: int  # lifeline index
    label: str  # the transition's name
    text: str  # the binding element
    time: int | None
    changes: tuple = ()


@dataclass
class Message:
    src: int  # step producing the token (1-based)
    dst: int | None  # step consuming it; None: still in its place at the end of the trace
    src_line: int
    dst_line: int
    label: str  # "Place: value"
    fate: str = "delivered"  # 'delivered', 'lost' (taken by a step that puts no token anywhere), 'pending'


@dataclass
class Chart:
    lifelines: list = field(default_factory=list)  # (label, sublabel)
    events: list = field(default_factory=list)
    messages: list = field(default_factory=list)
    timed: bool = False
    by: str = "module instance"  # or "transition instance"


def _lifeline_keys(net) -> tuple[dict, list, str]:
    """Transition index -> lifeline key, the keys in drawing order with labels, and what a lifeline is."""
    units, top = instance_tree(net)
    with_trans = [k for k, u in units.items() if u.transitions]
    if len(with_trans) >= 2:
        order = []

        def walk(k):
            order.append(k)
            for c in units[k].children:
                walk(c)

        walk(top)
        order += [k for k in units if k not in order]
        of = {t: key for key, u in units.items() for t in u.transitions}
        labels = [(k, units[k].label, "" if units[k].parent is None else units[k].module) for k in order]
        return of, labels, "module instance"
    of = {t.index: ("t", t.index) for t in net.transitions}
    labels = [(("t", t.index), t.transition, f"instance {t.instance}" if t.instance > 1 else "")
              for t in net.transitions]
    return of, labels, "transition instance"


def build_chart(trace, exploration) -> Chart:
    """The events and messages of `trace` (a cpn.statespace.Trace of this exploration)."""
    engine = exploration.engine
    g = exploration.graph
    net = engine.net
    of, keyed, by = _lifeline_keys(net)
    timed = bool(getattr(engine, "is_timed", False))
    times = _step_times(trace, exploration) if timed else None
    events = []
    messages = []
    producers: dict = defaultdict(deque)  # (place, value) -> deque of (step, line key)
    used: set = set()
    for k, step in enumerate(trace.steps, 1):
        be = engine.binding_element(step.be)
        t = net.transitions[be.transition]
        key = of[be.transition]
        used.add(key)
        sa, sb = g.states[step.source], g.states[step.target]
        ma, mb = engine.marking(sa), engine.marking(sb)
        taken, put = [], []
        for p in range(len(net.places)):
            if ma[p] == mb[p]:
                continue
            before, after = untimed_multiset(engine, p, ma[p]), untimed_multiset(engine, p, mb[p])
            taken += [(p, v) for v, n in before.items() for _ in range(n - after.get(v, 0))]
            put += [(p, v) for v, n in after.items() for _ in range(n - before.get(v, 0))]
        for p, v in taken:
            q = producers[(p, v)]
            if q:
                src, skey = q.popleft()
                if skey != key:  # taken by a step that puts nothing back anywhere: lost on the way
                    messages.append((src, k, skey, key, f"{net.places[p].place}: {_value(net, p, v)}",
                                     "delivered" if put else "lost"))
                    used.add(skey)
        for p, v in put:
            producers[(p, v)].append((k, key))
        events.append((k, key, t.transition, step.text or engine.format_binding_element(step.be),
                       times[k - 1] if times else None, step.changes))
    if trace.steps:
        messages += _pending(producers, engine, g.states[trace.steps[-1].target], of, len(trace.steps))
        used.update(m[3] for m in messages)
    shown = [(key, a, b) for key, a, b in keyed if key in used]
    index = {key: i for i, (key, _a, _b) in enumerate(shown)}
    chart = Chart([(a, b) for _k, a, b in shown], timed=bool(times), by=by)
    chart.events = [Event(k, index[key], lab, text, time, ch) for k, key, lab, text, time, ch in events]
    chart.messages = [Message(s, d, index[a], index[b], lab, fate) for s, d, a, b, lab, fate in messages]
    return chart


def _pending(producers: dict, engine, last, of: dict, n_steps: int) -> list:
    """Messages for the tokens still in their places at the end of the trace, in places that another
    lifeline takes tokens from: toward the lifeline of a binding element that could take the token next
    (enabled at the last marking), else toward the first other lifeline with an arc that takes from the
    place."""
    net = engine.net
    takers: dict = defaultdict(list)  # place -> lifeline keys of the transitions that take its tokens
    for t in net.transitions:
        for a in t.arcs:
            if a.kind.takes and of[t.index] not in takers[a.place]:
                takers[a.place].append(of[t.index])
    left = [(p, v, src, skey) for (p, v), q in producers.items() for src, skey in q
            if any(key != skey for key in takers[p])]
    if not left:
        return []
    next_taker: dict = {}  # (place, value) -> lifeline keys of enabled binding elements that take it
    try:
        m = engine.marking(last)
        places = {p for p, _v, _s, _k in left}
        for be, succ in engine.successors(last):
            key = of[engine.binding_element(be).transition]
            ms = engine.marking(succ)
            for p in places:
                if ms[p] == m[p]:
                    continue
                before, after = untimed_multiset(engine, p, m[p]), untimed_multiset(engine, p, ms[p])
                for v, n in before.items():
                    if n > after.get(v, 0):
                        next_taker.setdefault((p, v), []).append(key)
    except Exception:  # noqa: BLE001 - the successors cannot be computed here: the net's arcs decide
        next_taker = {}
    out = []
    for p, v, src, skey in sorted(left, key=lambda item: item[2]):
        keys = [k for k in next_taker.get((p, v), ()) if k != skey] or [k for k in takers[p] if k != skey]
        out.append((src, None, skey, keys[0], f"{net.places[p].place}: {_value(net, p, v)}", "pending"))
    return out


_PLAIN: weakref.WeakKeyDictionary = weakref.WeakKeyDictionary()  # engine -> the same net without condensation


def _step_times(trace, exploration) -> list | None:
    """The model time at which each step occurs; None when it cannot be known.

    With time condensation the stored states carry shifted clocks, so the trace is fired again on an
    engine of the same net without condensation, matching each binding element by its transition and
    binding.
    """
    engine = exploration.engine
    g = exploration.graph
    if not capability(engine, "time_condensation", False):
        return [engine.clock(g.states[s.target]) for s in trace.steps]
    try:
        plain = _PLAIN.get(engine)
        if plain is None:  # compiled once per engine: the charts of one page share it
            plain = _PLAIN[engine] = type(engine)(engine.net, time_condensation=False)
        state = plain.initial_state()
        times = []
        for step in trace.steps:
            want = engine.binding_element(step.be)
            state = next(succ for be, succ in plain.successors(state) if plain.binding_element(be) == want)
            times.append(plain.clock(state))
        return times
    except Exception:  # noqa: BLE001 - no time axis rather than no chart
        return None


def _value(net, p: int, v) -> str:
    try:
        return net.places[p].colour_set.format(v)
    except Exception:  # noqa: BLE001 - a value the colour set cannot print: its Python form
        return repr(v)


def draw_msc(trace, exploration, marked_step: int | None = None, caption: str = "",
             cycle_from: int | None = None, standalone: bool = False, prefix: str = "msc") -> str:
    """The chart of `trace` as SVG.

    marked_step: the 1-based step to mark as the violating one (default: none); cycle_from: for a lasso,
    the 1-based step where the repeated part starts; standalone: a complete SVG file (with xmlns).
    """
    chart = build_chart(trace, exploration)
    return render_chart(chart, marked_step, caption, cycle_from, standalone, prefix)


def render_chart(chart: Chart, marked_step: int | None = None, caption: str = "",
                 cycle_from: int | None = None, standalone: bool = False, prefix: str = "msc") -> str:
    n_lines = max(1, len(chart.lifelines))
    col = max([COLUMN] + [S.text_width(a, 13) + 34 for a, _ in chart.lifelines])
    width = LEFT + col * n_lines + 40
    if caption:  # the title is bold 14 px: the chart is at least as wide
        width = max(width, 1.1 * S.text_width(caption, 14) + 24)
    xs = [LEFT + col * i + col / 2 for i in range(n_lines)]
    top = HEAD + (22 if caption else 0)
    ys, time_marks, y = _rows(chart, top)
    pending = Counter(m.dst_line for m in chart.messages if m.dst is None)
    pending_y = y - ROW + 22  # where the arrows of tokens still in their places end, below the last step
    height = y + 30 + 9 * max(0, max(pending.values(), default=0) - 1)
    body = [S.arrow_defs(prefix, {"msg": S.ACCENT}),
            f'<defs><marker id="{prefix}-open" viewBox="0 0 10 10" refX="9" refY="5" markerWidth="8" '
            f'markerHeight="8" orient="auto"><path d="M1,1 L9,5 L1,9" fill="none" stroke="{S.ACCENT}" '
            'stroke-width="1.5"/></marker></defs>']
    if standalone:
        body.append(f'<rect width="{S.fmt(width)}" height="{S.fmt(height)}" fill="#fff"/>')
    if caption:
        body.append(S.text(10, 20, caption, 14, "start", weight="600"))
    body.append(S.text(12, top - 14, "time" if chart.timed else "step", 12, "start", fill=S.MUTED))
    body += [_lifeline(label, sub, xs[i], col, top, height) for i, (label, sub) in enumerate(chart.lifelines)]
    for ty, t in time_marks:
        body.append(f'<line class="time" x1="{LEFT - 6}" y1="{S.fmt(ty)}" x2="{S.fmt(width - 10)}" '
                    f'y2="{S.fmt(ty)}" stroke="#d5dbe1"/>'
                    + S.text(12, ty + 4, f"t = {t}", 12, "start", fill=S.MUTED, weight="600"))
    widths = {ev.step: max(60, S.text_width(ev.label, 13) + 22) for ev in chart.events}  # bold 12 px
    taken: set = set()  # (step, side) where a message label already sits
    open_ends: dict = defaultdict(int)  # lifeline -> pending messages that end on it so far
    for m in chart.messages:
        body.append(_message(m, xs, ys, widths, taken, open_ends, pending_y, prefix))
    for ev in chart.events:
        body += _event(ev, xs[ev.line], ys[ev.step], widths[ev.step], ev.step == marked_step)
    if marked_step is not None and marked_step in ys:
        y = ys[marked_step]
        body.append(f'<rect class="marked-band" x="{LEFT - 34}" y="{S.fmt(y - 16)}" width="{S.fmt(width - LEFT + 30)}" height="32" '
                    f'fill="none" stroke="{S.BAD}" stroke-width="1.5" stroke-dasharray="6 3" rx="6"/>')
    if cycle_from is not None and cycle_from in ys and chart.events:
        y1, y2 = ys[cycle_from] - 14, ys[chart.events[-1].step] + 14
        x = width - 22
        body.append(f'<path class="cycle" d="M{x - 8},{S.fmt(y1)} h8 V{S.fmt(y2)} h-8" fill="none" stroke="{S.WARN}" '
                    f'stroke-width="2"/>' + S.text(x + 4, (y1 + y2) / 2, "↻", 16, "start", fill=S.WARN))
    if not chart.events:
        body.append(S.text(LEFT, top, "no step: the trace ends at the initial marking", 13, "start", fill=S.MUTED))
    label = f"message sequence chart, {len(chart.events)} steps"
    return S.document(width, height, body, label, cls="drawing msc", standalone=standalone)


def _rows(chart: Chart, top: float) -> tuple[dict, list, float]:
    """The y of each step (a gap where model time advances), the time marks, and the y below the last."""
    ys = {}
    y = top + 30
    last_time = None
    time_marks = []
    for ev in chart.events:
        if chart.timed and last_time is not None and ev.time != last_time:
            y += TIME_GAP
            time_marks.append((y - TIME_GAP / 2 - 4, ev.time))
        elif chart.timed and last_time is None:
            time_marks.append((y - 18, ev.time))
        ys[ev.step] = y
        last_time = ev.time
        y += ROW
    return ys, time_marks, y


def _lifeline(label: str, sub: str, x: float, col: float, top: float, height: float) -> str:
    """A lifeline's head (the instance's name, its module under it) and its dashed line."""
    bw = col - 24
    return (f'<g class="lifeline"><rect x="{S.fmt(x - bw / 2)}" y="{S.fmt(top - 46)}" width="{S.fmt(bw)}" '
            f'height="{36 if sub else 28}" rx="5" fill="{S.PLACE_FILL}" stroke="{S.ACCENT}"/>'
            + S.text(x, top - 28, S.clip(label, 26), 13, weight="600")
            + (S.text(x, top - 14, S.clip(sub, 28), 11, fill=S.MUTED) if sub else "")
            + f'<line x1="{S.fmt(x)}" y1="{S.fmt(top - 10)}" x2="{S.fmt(x)}" y2="{S.fmt(height - 16)}" '
            f'stroke="{S.BOX_STROKE}" stroke-dasharray="4 4"/></g>')


def _message(m, xs: list, ys: dict, widths: dict, taken: set, open_ends: dict, pending_y: float,
             prefix: str) -> str:
    """The arrow of one token from its sender to its receiver (open when still in its place, a cross when
    lost), with its label; `taken` and `open_ends` record the places already used."""
    x1, y1, x2 = xs[m.src_line], ys[m.src], xs[m.dst_line]
    first_end = False
    if m.dst is None:  # still in its place: open at the last step, below it
        first_end = not open_ends[m.dst_line]
        y2 = pending_y + 9 * open_ends[m.dst_line]
        open_ends[m.dst_line] += 1
    else:
        y2 = ys[m.dst]
    sgn = 1 if x2 > x1 else -1
    # from under the sending event to the edge of the receiving one (an open end: to its lifeline)
    x1, x2 = x1 + sgn * 8, x2 - sgn * (10 if m.dst is None else widths[m.dst] / 2 + 1)
    label = _message_label(m, xs, widths, taken, sgn, (x1, y1, x2, y2))
    line = f'x1="{S.fmt(x1)}" y1="{S.fmt(y1)}" x2="{S.fmt(x2)}" y2="{S.fmt(y2)}"'
    if m.fate == "pending":
        tip = f"{m.label}: still there at the end of the trace (produced at step {m.src})"
        drawn = (f'<line {line} stroke="{S.ACCENT}" stroke-width="1.6" stroke-dasharray="6 4" '
                 f'marker-end="url(#{prefix}-open)"/>'
                 + (S.text(x2 - sgn * 4, y2 + 4, "pending", 11, "end" if sgn > 0 else "start",
                           fill=S.MUTED, halo=True) if first_end else ""))
    elif m.fate == "lost":
        tip = f"{m.label} (produced at step {m.src}, lost at step {m.dst}: taken, and nothing put anywhere)"
        drawn = (f'<line {line} stroke="{S.ACCENT}" stroke-width="1.6"/>'
                 f'<path class="lost" d="M{S.fmt(x2 - sgn * 6 - 5)},{S.fmt(y2 - 5)} l10,10 m0,-10 l-10,10" '
                 f'stroke="{S.BAD}" stroke-width="2.2"/>')
    else:
        tip = f"{m.label} (produced at step {m.src}, consumed at step {m.dst})"
        drawn = f'<line {line} stroke="{S.ACCENT}" stroke-width="1.6" marker-end="url(#{prefix}-msg)"/>'
    return f'<g class="message {m.fate}">{S.title(tip)}{drawn}{label}</g>'


def _message_label(m, xs: list, widths: dict, taken: set, sgn: int, ends: tuple) -> str:
    """A message's label: beside the sending event, else beside the receiving one, else mid-arrow."""
    x1, y1, x2, y2 = ends
    text = S.clip(m.label, MESSAGE_CHARS)
    # A row holds one event, so a label fits in the row of its sender (beside the sending event, toward
    # the receiver) or else in the row of its receiver (beside the receiving event, toward the sender).
    if (m.src, sgn) not in taken:
        taken.add((m.src, sgn))
        return S.text(xs[m.src_line] + sgn * (widths[m.src] / 2 + 6), y1 - 4, text, 12,
                      "start" if sgn > 0 else "end", mono=True, halo=True, fill=S.ACCENT)
    if m.dst is not None and (m.dst, -sgn) not in taken:
        taken.add((m.dst, -sgn))
        return S.text(xs[m.dst_line] - sgn * (widths[m.dst] / 2 + 6), y2 - 6, text, 12,
                      "end" if sgn > 0 else "start", mono=True, halo=True, fill=S.ACCENT)
    return S.text((x1 + x2) / 2, (y1 + y2) / 2 - 5, text, 12, mono=True, halo=True, fill=S.ACCENT)


def _event(ev: Event, x: float, y: float, w: float, bad: bool) -> list[str]:
    """A step's box on its lifeline (red when it is the marked step) and its number in the left margin."""
    tip = [f"step {ev.step}: {ev.text}"] + ([f"model time {ev.time}"] if ev.time is not None else [])
    tip += [f"{p}: {a} -> {b}" for p, a, b in ev.changes[:20]]
    return [f'<g class="event{" marked" if bad else ""}">{S.title(chr(10).join(tip))}'
            f'<rect x="{S.fmt(x - w / 2)}" y="{S.fmt(y - 12)}" width="{S.fmt(w)}" height="24" rx="4" '
            f'fill="{S.BAD if bad else S.TRANS_FILL}" stroke="{S.BAD if bad else S.WARN}"/>'
            + S.text(x, y + 4, ev.label, 12, fill="#fff" if bad else S.INK, weight="600") + "</g>",
            S.text(LEFT - 12, y + 4, str(ev.step), 12, "end", fill=S.BAD if bad else S.MUTED)]
