"""The state graph and the SCC graph as networkx graphs, written as DOT or GraphML (small nets only).

Imports `cpn.engine.protocol`, `cpn.report.model` and networkx.
"""

from __future__ import annotations

from cpn.engine.protocol import capability
from cpn.report.model import Report

MAX_EXPORT_STATES: int = 10_000  # the default limit (explore --max-export-states)


class TooLargeToExport(ValueError):
    """The state space has more states than the export limit."""


def _check_size(r: Report, max_states: int | None) -> None:
    """Refuse a state space above `max_states` (None: MAX_EXPORT_STATES; 0: no limit)."""
    limit = MAX_EXPORT_STATES if max_states is None else max_states
    if limit and r.exploration.n_states > limit:
        raise TooLargeToExport(r.exploration.n_states)


def state_graph(r: Report, max_states: int | None = None):
    """The state space; a timed model's states carry their clock (a `time` attribute and the label's second
    line, `@ time`), except under time condensation."""
    import networkx as nx

    _check_size(r, max_states)
    x = r.exploration
    engine = x.engine
    g = x.graph
    # a condensed state's clock is shifted to 0: no clock to show
    timed = bool(getattr(engine, "is_timed", False)) and not capability(engine, "time_condensation", False)
    G = nx.MultiDiGraph(name="state space")
    dead = set(r.dead.states)
    for i, s in enumerate(g.states):
        label = "\\n".join(f"{p.name}: {engine.format_marking(s, k)}" for k, p in enumerate(engine.places))
        attrs = {"time": engine.clock(s)} if timed else {}
        head = f"{i + 1}\\n@ {engine.clock(s)}" if timed else f"{i + 1}"
        G.add_node(f"s{i + 1}", label=f"{head}\\n{label}", scc=r.scc.decomposition.comp[i] + 1,
                   dead=i in dead, expanded=g.is_expanded(i), **attrs)
    for i in range(g.expanded):
        for be, j in g.out_arcs(i):
            G.add_edge(f"s{i + 1}", f"s{j + 1}", label=engine.format_binding_element(be))
    return G


def scc_graph(r: Report, max_states: int | None = None):
    import networkx as nx

    _check_size(r, max_states)
    x = r.exploration
    dec = r.scc.decomposition
    g = x.graph
    G = nx.DiGraph(name="SCC graph")
    for c in range(dec.count):
        nodes = dec.nodes(c)
        G.add_node(f"scc{c + 1}", label=f"SCC {c + 1} ({len(nodes)} nodes)", size=len(nodes),
                   terminal=bool(dec.terminal[c]))
    for i in range(g.expanded):
        for _be, j in g.out_arcs(i):
            a, b = dec.comp[i], dec.comp[j]
            if a != b:
                G.add_edge(f"scc{a + 1}", f"scc{b + 1}")
    return G


def _combined(r: Report, max_states: int | None):
    import networkx as nx

    return nx.union(state_graph(r, max_states), nx.MultiDiGraph(scc_graph(r, max_states)))


def render_dot(r: Report, max_states: int | None = None) -> str:
    """DOT text with two digraphs: the state space, then the SCC graph (TooLargeToExport above `max_states`
    states; None: MAX_EXPORT_STATES, 0: no limit)."""
    parts = []
    for name, G in (("statespace", state_graph(r, max_states)), ("sccgraph", scc_graph(r, max_states))):
        lines = [f"digraph {name} {{"]
        for n, d in G.nodes(data=True):
            lines.append(f'  "{n}" [label="{_esc(d.get("label", n))}"];')
        for u, v, d in G.edges(data=True):
            lab = d.get("label")
            lines.append(f'  "{u}" -> "{v}"' + (f' [label="{_esc(lab)}"]' if lab else "") + ";")
        lines.append("}")
        parts.append("\n".join(lines))
    return "\n".join(parts) + "\n"


def render_graphml(r: Report, max_states: int | None = None) -> str:
    """GraphML text holding the state space and the SCC graph (nodes 'scc<k>') side by side (TooLargeToExport
    above `max_states` states; None: MAX_EXPORT_STATES, 0: no limit)."""
    import networkx as nx

    G = nx.MultiDiGraph(_combined(r, max_states))
    return "\n".join(nx.generate_graphml(G)) + "\n"


def write_dot(r: Report, path: str) -> None:
    """`render_dot` written to the file `path`."""
    with open(path, "w", encoding="utf-8") as f:
        f.write(render_dot(r))


def write_graphml(r: Report, path: str) -> None:
    """`render_graphml` written to the file `path`."""
    with open(path, "w", encoding="utf-8") as f:
        f.write(render_graphml(r))


def _esc(s: str) -> str:
    return str(s).replace("\\n", "\0").replace("\\", "\\\\").replace('"', '\\"').replace("\0", "\\n")
