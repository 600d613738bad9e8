"""The state graph and the SCC graph as networkx graphs, written as DOT or GraphML (small nets only).

Imports `cpn.report.model` and networkx.
"""

from __future__ import annotations

from cpn.report.model import Report

MAX_EXPORT_STATES: int = 10_000


class TooLargeToExport(ValueError):
    """The state space has more states than MAX_EXPORT_STATES."""


def state_graph(r: Report):
    import networkx as nx

    x = r.exploration
    if x.n_states > MAX_EXPORT_STATES:
        raise TooLargeToExport(x.n_states)
    engine = x.engine
    g = x.graph
    G = nx.MultiDiGraph(name="state space")
    dead = set(r.dead.states)
    for i, s in enumerate(g.states):
        label = "\\n".join(f"{p.name}: {engine.format_marking(s, k)}" for k, p in enumerate(engine.places))
        G.add_node(f"s{i + 1}", label=f"{i + 1}\\n{label}", scc=r.scc.decomposition.comp[i] + 1,
                   dead=i in dead, expanded=g.is_expanded(i))
    for i in range(g.expanded):
        for be, j in g.out_arcs(i):
            G.add_edge(f"s{i + 1}", f"s{j + 1}", label=engine.format_binding_element(be))
    return G


def scc_graph(r: Report):
    import networkx as nx

    x = r.exploration
    if x.n_states > MAX_EXPORT_STATES:
        raise TooLargeToExport(x.n_states)
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


def _combined(r: Report):
    import networkx as nx

    return nx.union(state_graph(r), nx.MultiDiGraph(scc_graph(r)))


def render_dot(r: Report) -> str:
    """DOT text with two digraphs: the state space, then the SCC graph."""
    parts = []
    for name, G in (("statespace", state_graph(r)), ("sccgraph", scc_graph(r))):
        lines = [f"digraph {name} {{"]
        for n, d in G.nodes(data=True):
            lines.append(f'  "{n}" [label="{_esc(d.get("label", n))}"];')
        for u, v, d in G.edges(data=True):
            lab = d.get("label")
            lines.append(f'  "{u}" -> "{v}"' + (f' [label="{_esc(lab)}"]' if lab else "") + ";")
        lines.append("}")
        parts.append("\n".join(lines))
    return "\n".join(parts) + "\n"


def render_graphml(r: Report) -> str:
    """GraphML text holding the state space and the SCC graph (nodes 'scc<k>') side by side."""
    import networkx as nx

    G = nx.MultiDiGraph(_combined(r))
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
