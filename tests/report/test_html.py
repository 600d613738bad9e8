"""The HTML report, its drawings (net, state space, message sequence charts) and charts."""

import os
import pathlib
import re
import xml.etree.ElementTree as ET

import networkx as nx
import pytest

import cpn
from cpn.cli.main import main
from cpn.report import build_report
from cpn.report.graphdraw import bfs_levels, draw_state_space, level_sizes
from cpn.report.html import (
    IndexEntry,
    ReportTrace,
    Verdict,
    dead_marking_traces,
    render_html,
    render_index,
    report_fragment,
    write_pages,
)
from cpn.report.layout import back_edges, layered_layout, longest_path_layers
from cpn.report.msc import build_chart, draw_msc
from cpn.report.netdraw import draw_net, instance_tree
from cpn.report.plot import growth_chart, nice_ticks, scaling_chart
from cpn.statespace import ExploreOptions, Explorer, shortest_trace

ROOT = pathlib.Path(__file__).resolve().parents[2]
SVG = "{http://www.w3.org/2000/svg}"


def _explore(path, time_condensation=False, sets=None, **opts):
    model = cpn.load(str(ROOT / path), set=sets or {})
    x = Explorer(model.engine(time_condensation=time_condensation), ExploreOptions(**opts)).run()
    return build_report(x, model=str(path), options={"time_condensation": time_condensation})


@pytest.fixture(scope="module")
def stations():
    return _explore("models/examples/stations.cpnet")


@pytest.fixture(scope="module")
def stop_and_wait():
    return _explore("models/examples/stop_and_wait.cpnet", time_condensation=True)


def _xml(svg: str):
    """Parse an inline SVG (no xmlns in an HTML page) as XML: it must be well formed."""
    if "xmlns=" not in svg[:200]:
        svg = svg.replace("<svg ", '<svg xmlns="http://www.w3.org/2000/svg" ', 1)
    return ET.fromstring(svg)


# ------------------------------------------------------------------------------------------ layout

def test_back_edges_leave_an_acyclic_graph():
    edges = [(0, 1), (1, 2), (2, 0), (2, 3), (3, 1)]
    back = back_edges([0, 1, 2, 3], edges, roots=[0])
    G = nx.DiGraph([e for e in edges if e not in back])
    assert nx.is_directed_acyclic_graph(G) and len(back) == 2


def test_layers_follow_the_edges_and_nodes_do_not_overlap():
    G = nx.gnp_random_graph(60, 0.06, seed=3, directed=True)
    nodes, edges = list(G.nodes), list(G.edges)
    layer = longest_path_layers(nodes, edges)
    back = back_edges(nodes, edges)
    assert all(layer[v] > layer[u] for u, v in edges if (u, v) not in back and u != v)
    size = {n: (30 + n % 4 * 10, 20) for n in nodes}
    lay = layered_layout(nodes, edges, size)
    for a in nodes:
        for b in nodes:
            if a < b and lay.layer[a] == lay.layer[b]:
                assert abs(lay.pos[a][0] - lay.pos[b][0]) >= (size[a][0] + size[b][0]) / 2
    assert all(0 <= x - size[n][0] / 2 and x + size[n][0] / 2 <= lay.width for n, (x, _) in lay.pos.items())


def test_a_wide_layer_wraps_onto_rows_within_the_width():
    nodes = ["root"] + list(range(30))
    edges = [("root", i) for i in range(30)]
    size = {n: (80, 30) for n in nodes}
    lay = layered_layout(nodes, edges, size, max_width=500, margin=0)
    assert lay.width <= 500
    rows = {lay.pos[i][1] for i in range(30)}
    assert len(rows) >= 5  # 30 nodes of 80 px (+28 px gap) need at least 5 rows of 500 px
    for a in range(30):
        for b in range(a + 1, 30):
            if lay.pos[a][1] == lay.pos[b][1]:
                assert abs(lay.pos[a][0] - lay.pos[b][0]) >= 80


def test_an_edge_spanning_layers_runs_between_the_nodes_of_those_layers():
    # a chain 0 -> 1 -> 2 -> 3 -> 4 with wide nodes beside it, and a back edge 4 -> 0 across all layers
    nodes = list(range(5)) + ["a", "b", "c"]
    edges = [(0, 1), (1, 2), (2, 3), (3, 4), (4, 0), (0, "a"), ("a", 2), (1, "b"), ("b", 3), (2, "c")]
    size = {n: (60, 20) for n in nodes}
    lay = layered_layout(nodes, edges, size, roots=[0])
    route = lay.routes[(4, 0)]
    assert len(route) == lay.layer[4] - lay.layer[0] - 1
    for x, y in route:  # each bend point lies in a layer and clear of that layer's nodes
        same = [n for n in nodes if abs(lay.pos[n][1] - y) < 1e-6]
        assert same and all(abs(lay.pos[n][0] - x) >= size[n][0] / 2 for n in same)
    assert not layered_layout(nodes, edges, size, roots=[0], max_bends=0).routes


# ----------------------------------------------------------------------------------------- the net

def test_module_instances_nest_as_in_the_model(stations):
    net = stations.engine.net
    units, top = instance_tree(net)
    assert units[top].label == "Office"
    assert [units[k].label for k in units[top].children] == ["Station1", "Station2", "Station3"]
    # every place and transition instance belongs to exactly one box
    assert sorted(p for u in units.values() for p in u.places) == list(range(len(net.places)))
    assert sorted(t for u in units.values() for t in u.transitions) == list(range(len(net.transitions)))
    for k in units[top].children:
        assert [net.transitions[t].transition for t in units[k].transitions] == ["Take", "Done"]


def test_net_drawing_shows_every_node_arc_inscription_and_bound(stations):
    net = stations.engine.net
    bounds = {b.place: (b.upper, b.lower, b.upper_text) for b in stations.bounds.places}
    svg = draw_net(net, bounds, ["Station'Take 2"])
    root = _xml(svg)
    groups = [g.get("class") for g in root.iter(f"{SVG}g")]
    assert groups.count("place") == len(net.places)
    assert groups.count("transition") + groups.count("transition dead") == len(net.transitions)
    assert groups.count("transition dead") == 1 and groups.count("module") == 4
    assert groups.count("arc") == sum(len(t.arcs) for t in net.transitions)
    assert groups.count("bound") == len(net.places)
    assert "1`1 ++ 1`2 ++ 1`3" in svg  # the inscription as written in the model
    assert "[i = me]" in svg  # the guard
    assert "Station2 : Station" in svg


def test_a_dead_transition_instance_is_marked_in_the_page(tmp_path):
    src = tmp_path / "dead.cpnet"
    src.write_text("net D;\ncolset U = unit;\nplace P : U = 1`();\nplace Q : U;\n"
                   "trans Go;\narc P -> Go;\narc Go -> Q;\ntrans Never;\narc Q -> Never : ();\narc P -> Never;\n")
    r = _explore(src)
    assert r.dead_transitions == ["D'Never 1"]
    page = render_html(r)
    assert page.count('class="transition dead"') == 1
    assert 'data-name="D&#x27;Never 1"' in page.split('class="transition dead"')[1][:80]


def test_a_multi_line_inscription_is_shown_without_what_follows_it(tmp_path):
    src = tmp_path / "ml.cpnet"
    src.write_text("net X;\ncolset U = int with 0..3;\nvar k : U;\nplace P : U = 1`0;\ntrans T;\n"
                   "arc P -> T : k;\narc T -> P : if k < 3\n    then k + 1\n    else 0;  (* wrap; k *)\n")
    net = _explore(src).engine.net
    from cpn.report.netdraw import inscription

    assert [inscription(net, a.expr) for a in net.transitions[0].arcs] == ["k", "if k < 3 then k + 1 else 0"]


def test_an_input_arcs_delay_is_drawn_with_its_inscription(tmp_path):
    src = tmp_path / "early.cpnet"
    src.write_text("net E;\ncolset U = int with 0..3 timed;\nval EARLY = 5;\nvar k : U;\nplace P : U = 1`0 @+ 8;\n"
                   "trans T;\narc P -> T : k @+ EARLY;\narc T -> P : (k + 1) mod 4;\n")
    net = _explore(src).engine.net
    from cpn.report.netdraw import arc_inscription

    assert [arc_inscription(net, a) for a in net.transitions[0].arcs] == ["k @+ 5", "(k + 1) mod 4"]
    assert "k @+ 5" in draw_net(net)


WORKERS = """net Pool;
colset ID = int with 1..6;
var i : ID;
module Worker(me : ID) {
  port in Jobs : ID;
  place Done : ID;
  trans Work [i = me];
  arc Jobs -> Work : i;
  arc Work -> Done : i;
}
place Jobs : ID = 1`1 ++ 1`2;
""" + "".join(f"instance W{k} = Worker(me = {k}) {{ Jobs = Jobs }};\n" for k in range(1, 7))


def test_many_instances_of_a_module_are_summarised_beyond_the_first_ones(tmp_path):
    src = tmp_path / "pool.cpnet"
    src.write_text(WORKERS)
    r = _explore(src)
    assert sorted(r.dead_transitions) == [f"Worker'Work {k}" for k in range(3, 7)]
    svg = draw_net(r.engine.net, {}, r.dead_transitions)
    # W1 (the first) and W2 (its Work occurs) in full; W3..W6 (only dead transitions) summarised
    assert svg.count('class="module collapsed"') == 4
    assert svg.count('class="transition"') == 2 and 'class="transition dead"' not in svg
    assert svg.count("drawn like W1: 1 place, 1 transition") == 4
    assert svg.count("1 of 1 transition dead") == 4 and "ports: Jobs = Jobs" in svg
    assert "dead: Worker&#x27;Work 5" in svg  # the summary's tooltip names them


def test_arc_kinds_are_drawn_apart(tmp_path):
    src = tmp_path / "kinds.cpnet"
    src.write_text("net K;\ncolset U = unit;\nplace P : U = 1`();\nplace Q : U;\nplace R : U;\n"
                   "trans T;\narc P <-> T;\ninhibitor Q -> T;\nreset R -> T;\narc T -> Q;\n")
    r = _explore(src)
    svg = draw_net(r.engine.net)
    arcs = re.findall(r'<g class="arc"><title>([^<]*)</title><path ([^>]*)/>', svg)
    kinds = {t.split(" ")[0]: attrs for t, attrs in arcs}
    assert set(kinds) == {"both", "inhibitor", "reset", "out"}
    assert "marker-start" in kinds["both"] and "marker-end" in kinds["both"]
    assert "marker-end" not in kinds["inhibitor"] and 'stroke-dasharray="2 3"' in kinds["inhibitor"]
    assert 'stroke-dasharray="7 3"' in kinds["reset"]
    assert "marker-start" not in kinds["out"]


# ----------------------------------------------------------------------------------- state space

def test_bfs_levels_are_shortest_distances(stop_and_wait):
    g = stop_and_wait.exploration.graph
    G = nx.DiGraph()
    G.add_nodes_from(range(g.n_states))
    for i in range(g.expanded):
        G.add_edges_from((i, j) for _be, j in g.out_arcs(i))
    dist = nx.single_source_shortest_path_length(G, 0)
    assert bfs_levels(g) == [dist[i] for i in range(g.n_states)]
    sizes = level_sizes(g)
    assert sum(sizes) == g.n_states and sizes[0] == 1


def test_small_state_space_drawn_whole_with_dead_and_initial_highlighted(stations):
    kind, svg = draw_state_space(stations)
    assert kind == "full"
    root = _xml(svg)
    nodes = [g for g in root.iter(f"{SVG}g") if (g.get("class") or "").startswith("node")]
    assert len(nodes) == stations.exploration.n_states
    dead = [g.get("id") for g in nodes if g.get("class") == "node dead"]
    assert dead == [f"ss-s{d + 1}" for d in stations.dead.states]
    assert nodes[0].get("class") == "node initial"
    tip = nodes[0].find(f"{SVG}title").text
    assert "Office'Requests 1: 1`1++1`2++1`3" in tip


def test_large_state_space_drawn_as_scc_graph():
    r = _explore("bench/nets/ms.cpnet", sets={"N": "3"})
    assert r.exploration.n_states > 300
    kind, svg = draw_state_space(r)
    assert kind == "scc"
    assert svg.count('class="node') == r.scc.nodes


def test_too_large_scc_graph_is_not_drawn(monkeypatch, stations):
    import cpn.report.graphdraw as gd

    monkeypatch.setattr(gd, "MAX_FULL_NODES", 5)
    monkeypatch.setattr(gd, "MAX_SCC_NODES", 5)
    kind, text = gd.draw_state_space(stations)
    assert kind == "none" and "28 states" in text
    assert "too many" in render_html(stations)


def test_partial_state_space_marks_unexpanded_states():
    r = _explore("models/examples/stations.cpnet", max_states=10)
    assert not r.exploration.complete
    kind, svg = draw_state_space(r)
    assert kind == "full" and 'class="node unexpanded"' in svg
    assert "partial" in render_html(r)


# -------------------------------------------------------------------------------------- charts

def test_msc_one_lifeline_per_module_instance_and_a_message_per_token_between_them(stations):
    x = stations.exploration
    trace = shortest_trace(x.graph, stations.dead.states[0], x.engine)
    chart = build_chart(trace, x)
    assert [a for a, _ in chart.lifelines] == ["Office", "Station1", "Station2", "Station3"]
    assert chart.by == "module instance" and len(chart.events) == len(trace) == 7
    # each station's Done puts its reply on Replies; Archive (on the top page) takes all three
    archive = next(e.step for e in chart.events if e.label == "Archive")
    assert sorted(m.label for m in chart.messages) == ["Replies: 1", "Replies: 2", "Replies: 3"]
    assert all(m.dst == archive and m.dst_line == 0 and m.src_line > 0 for m in chart.messages)
    for m in chart.messages:  # the sender is the Done of the station the value names
        ev = chart.events[m.src - 1]
        assert ev.label == "Done" and chart.lifelines[ev.line][0] == f"Station{m.label[-1]}"


def test_msc_of_a_master_a_bus_and_two_slaves():
    r = _explore("tests/report/nets/minibus.cpnet")
    x = r.exploration
    charts = [build_chart(shortest_trace(x.graph, d, x.engine), x) for d in r.dead.states]
    both = next(c for c in charts if len(c.lifelines) == 4)  # the run that asks each slave once
    assert [a for a, _ in both.lifelines] == ["Master1", "Bus1", "Slave1", "Slave2"]
    assert [b for _, b in both.lifelines] == ["Master", "Bus", "Slave", "Slave"]
    names = [a for a, _ in both.lifelines]
    hops = [(names[m.src_line], names[m.dst_line], m.label) for m in both.messages]
    first = hops[0][2][-1]
    other = "2" if first == "1" else "1"
    assert hops == [("Master1", "Bus1", f"M2B: {first}"), ("Bus1", f"Slave{first}", f"B2S: {first}"),
                    (f"Slave{first}", "Bus1", f"S2B: {first}"), ("Bus1", "Master1", f"B2M: {first}"),
                    ("Master1", "Bus1", f"M2B: {other}"), ("Bus1", f"Slave{other}", f"B2S: {other}"),
                    (f"Slave{other}", "Bus1", f"S2B: {other}"), ("Bus1", "Master1", f"B2M: {other}")]
    for m in both.messages:  # an arrow goes down: consumed after it was produced
        assert m.dst > m.src


def test_msc_of_a_flat_net_has_a_lifeline_per_transition():
    r = _explore("bench/nets/ms.cpnet", sets={"N": "2"})
    x = r.exploration
    trace = shortest_trace(x.graph, x.n_states - 1, x.engine)
    chart = build_chart(trace, x)
    assert chart.by == "transition instance"
    names = [a for a, _ in chart.lifelines]
    # a lifeline per transition that occurs, and one per transition that could take a token still on its way
    waiting = {names[m.dst_line] for m in chart.messages if m.fate == "pending"}
    assert set(names) == {e.label for e in chart.events} | waiting
    assert any(m.label.startswith("Bus: ") for m in chart.messages) or len(trace) < 2


def test_msc_timed_axis_is_model_time_even_with_time_condensation(stop_and_wait):
    x = stop_and_wait.exploration
    trace = shortest_trace(x.graph, stop_and_wait.dead.states[0], x.engine)
    chart = build_chart(trace, x)
    assert chart.timed
    times = [e.time for e in chart.events]
    assert times == sorted(times)
    # Send at 0 puts packet 1 on A with delay 2; the channel passes it on at 2, with delay 2 again
    assert [(e.label, e.time) for e in chart.events[:3]] == [("Send", 0), ("TransmitPacket", 2), ("Receive", 4)]
    # the same times as the uncondensed state space's clocks along the same binding elements
    plain = _explore("models/examples/stop_and_wait.cpnet", time_condensation=False, max_states=3000)
    pe, pg = plain.exploration.engine, plain.exploration.graph
    s = pe.initial_state()
    for e, step in zip(chart.events, trace.steps):
        want = x.engine.binding_element(step.be)
        s = next(t for be, t in pe.successors(s) if pe.binding_element(be) == want)
        assert pe.clock(s) == e.time
    assert pg.n_states > 0


def test_msc_marks_the_violating_step_and_a_cycle(stations):
    x = stations.exploration
    trace = shortest_trace(x.graph, stations.dead.states[0], x.engine)
    svg = draw_msc(trace, x, marked_step=7, cycle_from=5, standalone=True)
    root = ET.fromstring(svg)
    events = [g for g in root.iter(f"{SVG}g") if (g.get("class") or "").startswith("event")]
    assert [g.get("class") for g in events].count("event marked") == 1
    assert events[6].get("class") == "event marked"
    assert 'class="cycle"' in svg and 'class="marked-band"' in svg


def test_a_trace_without_steps_says_so(tmp_path):
    src = tmp_path / "d0.cpnet"
    src.write_text("net D;\ncolset U = unit;\nplace P : U;\ntrans T;\narc P -> T;\n")
    r = _explore(src)
    t = dead_marking_traces(r)[0]
    assert len(t) == 0 and "no step: the trace ends at the initial marking" in t.svg(standalone=True)
    assert "The initial marking itself: no step is needed." in render_html(r)


def test_growth_and_scaling_charts():
    svg = growth_chart([1, 3, 6, 7, 6, 3, 1, 1])
    root = _xml(svg)
    assert len([r for r in root.iter(f"{SVG}rect") if r.get("class") == "bar"]) == 8
    assert "28 states over 8 BFS levels" in svg
    rows = [{"N": n, "states": s, "seconds": t} for n, s, t in ((2, 189, 0.01), (3, 837, 0.05), (4, 3700, 0.3))]
    svg = scaling_chart(rows, standalone=True)
    root = ET.fromstring(svg)
    assert len(list(root.iter(f"{SVG}circle"))) == 6
    assert "states at N = 3" not in svg and "states: 837 at N = 3" in svg


def test_a_scaling_table_of_a_markdown_file_as_a_chart(tmp_path):
    from cpn.report.plot import markdown_table

    text = ("intro\n\n## Scaling\n\n| NS | states | arcs | s | with a broadcast: states | arcs | s |\n"
            "|---|---|---|---|---|---|---|\n| 4 | 53 | 54 | 0.02 | 73 | 91 | 0.02 |\n"
            "| 10 | 149 | 156 | 0.06 | 1 177 | 5 281 | 0.71 |\n\nafter\n")
    rows = markdown_table(text, "## Scaling")
    assert rows == [{"NS": 4, "states": 53, "arcs": 54, "s": 0.02, "with a broadcast: states": 73,
                     "with a broadcast: arcs": 91, "with a broadcast: s": 0.02},
                    {"NS": 10, "states": 149, "arcs": 156, "s": 0.06, "with a broadcast: states": 1177,
                     "with a broadcast: arcs": 5281, "with a broadcast: s": 0.71}]
    svg = scaling_chart(rows, "NS", standalone=True, states=("states", "with a broadcast: states"),
                        seconds=("s", "with a broadcast: s"))
    assert len(list(ET.fromstring(svg).iter(f"{SVG}circle"))) == 8
    assert "with a broadcast: states: 1,177 at NS = 10" in svg
    md = tmp_path / "t.md"
    md.write_text(text)
    out = tmp_path / "t.svg"
    import subprocess
    import sys

    cmd = [sys.executable, str(ROOT / "bench/scaling_plot.py"), str(md), "--after", "## Scaling", "--param", "NS",
           "--seconds", "s", "-o", str(out)]
    assert subprocess.run(cmd, capture_output=True).returncode == 0 and out.read_text().startswith("<svg")
    bad = subprocess.run(cmd[:-2] + ["--states", "nodes", "-o", str(out)], capture_output=True, text=True)
    assert bad.returncode == 64 and "no column 'nodes'" in bad.stderr


@pytest.mark.parametrize("lo,hi", [(0, 1), (0, 837), (3, 7), (0.001, 0.02), (0, 1e6)])
def test_nice_ticks_cover_the_range(lo, hi):
    t = nice_ticks(lo, hi)
    assert t[0] <= lo and t[-1] >= hi and 3 <= len(t) <= 12
    assert t == sorted(t)


# ---------------------------------------------------------------------------------------- pages

def test_page_is_self_contained(stations):
    page = render_html(stations)
    assert page.startswith("<!DOCTYPE html>")
    refs = re.findall(r'(?:src|href)="([^"]*)"', page)
    assert refs and all(r.startswith("#") for r in refs)
    assert "@import" not in page and "url(http" not in page
    assert "<script src" not in page
    for section in ("statistics", "dead", "net", "statespace", "bounds", "transitions"):
        assert f'<section id="{section}">' in page


def test_jupyter_shows_the_page_content(stations):
    frag = stations._repr_html_()
    assert frag == report_fragment(stations)
    assert frag in render_html(stations)
    t = dead_marking_traces(stations)[0]
    assert isinstance(t, ReportTrace) and len(t) == 7
    html = t._repr_html_()
    assert html.startswith('<div class="cpnv">') and "<svg" in html and "Archive" in html
    assert t.svg() in html  # the chart Jupyter shows is the one `--msc` writes


def test_first_violated_property_and_its_trace_come_first(stations):
    x = stations.exploration
    trace = shortest_trace(x.graph, stations.dead.states[0], x.engine)
    page = render_html(stations, [Verdict("bounded", "holds"),
                                  Verdict("no deadlock", "violated", "a dead marking", trace),
                                  Verdict("liveness", "unknown", "a limit stopped the search")])
    v = page.index('<section id="verdicts">')
    assert v < page.index('<section id="statistics">')
    first = page.index("First violated property: <strong>no deadlock</strong> — a dead marking")
    assert first < page.index("Counterexample of no deadlock (7 steps)")
    assert v < first < page.index('<table', v)
    assert page.count('class="pill bad">violated') == 1


def test_a_first_violation_without_trace_is_still_the_headline(stations):
    x = stations.exploration
    trace = shortest_trace(x.graph, stations.dead.states[0], x.engine)
    page = render_html(stations, [Verdict("no dead transition", "violated", "Station'Take 2 never occurs"),
                                  Verdict("no deadlock", "violated", "", trace)])
    head = page.index("First violated property: <strong>no dead transition</strong>")
    assert head < page.index("<table", head) < page.index("no deadlock: counterexample (7 steps)")


def test_evidence_as_a_path_and_a_cycle_becomes_a_lasso_chart():
    r = _explore("bench/nets/ms.cpnet", sets={"N": "2"})
    x = r.exploration
    g = x.graph
    # a lasso by hand: the BFS path to some state, then back to the initial state and on to it again
    target = g.n_states - 1
    path_trace = shortest_trace(g, target, x.engine)
    back = nx.shortest_path(_digraph(g), target, 0)
    loop = back[1:] + [s.target for s in path_trace.steps]
    arc = {(i, j): be for i in range(g.expanded) for be, j in g.out_arcs(i)}

    class Evidence:
        path = (0,) + tuple(s.target for s in path_trace.steps)
        arcs = tuple(s.be for s in path_trace.steps)
        cycle = tuple(loop)
        cycle_arcs = tuple(arc[(a, b)] for a, b in zip([target] + loop, loop))

    v = Verdict("no livelock", "violated", "a cycle", Evidence()).resolved(x.engine)
    assert v.cycle_from == len(path_trace) + 1
    assert len(v.trace) == len(path_trace) + len(loop)
    assert [s.source for s in v.trace.steps[1:]] == [s.target for s in v.trace.steps[:-1]]
    assert v.trace.steps[-1].target == target
    page = render_html(r, [Verdict("no livelock", "violated", "a cycle", Evidence())])
    assert 'class="cycle"' in page and "First violated property: <strong>no livelock</strong>" in page
    assert 'class="marked-band"' not in page  # a lasso marks its cycle, not one step
    assert "(the cycle starts here)" in page


def _digraph(g):
    G = nx.DiGraph()
    for i in range(g.expanded):
        G.add_edges_from((i, j) for _be, j in g.out_arcs(i))
    return G


def test_text_from_the_model_and_the_properties_is_escaped(stations):
    page = render_html(stations, [Verdict("<script>alert(1)</script>", "violated", 'a "quoted" & <b>')])
    assert "<script>alert(1)</script>" not in page and "&lt;script&gt;alert(1)&lt;/script&gt;" in page
    assert "&quot;quoted&quot; &amp; &lt;b&gt;" in page
    assert page.count("<script>") == 1  # the page's own script only


def test_a_long_dead_marking_is_folded_in_the_table(tmp_path):
    src = tmp_path / "pool.cpnet"
    src.write_text(WORKERS.replace("place Jobs : ID = 1`1 ++ 1`2;", "place Jobs : ID = ID.all();"))
    page = render_html(_explore(src))
    table = page[page.index('<section id="dead">'):page.index("</table>", page.index('<section id="dead">'))]
    assert "<summary>1 more places</summary>" not in table  # 7 lines: shown whole
    assert table.count("Worker&#x27;Done") == 6
    from cpn.report.html import _marking_cell

    cell = _marking_cell("\n".join(f"P{k}: 1`{k}" for k in range(20)))
    assert cell.count("<details>") == 1 and "<summary>14 more places</summary>" in cell
    assert cell.index("P5: 1`5") < cell.index("<details>") < cell.index("P6: 1`6")


def test_index_lists_worst_runs_first():
    page = render_index([IndexEntry("a", "a.html", "holds", 10, 0.1), IndexEntry("b", "b.html", "violated"),
                         IndexEntry("c", "c.html", "unknown", 5)])
    assert page.index("b.html") < page.index("c.html") < page.index("a.html")
    assert "1 violated, 1 unknown, 1 holds" in page


def test_pages_of_a_check_run_and_their_index(tmp_path, stations):
    x = stations.exploration
    trace = shortest_trace(x.graph, stations.dead.states[0], x.engine)
    ms = _explore("bench/nets/ms.cpnet", sets={"N": "2"})
    index = write_pages(str(tmp_path), [("stations N=3", stations, [Verdict("no deadlock", "violated", "", trace)]),
                                        ("ms N=2", ms, [Verdict("no deadlock", "holds")]),
                                        ("ms N=2", ms, [])])
    names = sorted(p.name for p in tmp_path.iterdir())
    assert names == ["index.html", "ms-N-2-2.html", "ms-N-2.html", "stations-N-3.html"]
    page = pathlib.Path(index).read_text(encoding="utf-8")
    assert page.index("stations-N-3.html") < page.index("ms-N-2.html")
    assert "violated: no deadlock" in page and "189" in page
    assert "First violated property: <strong>no deadlock</strong>" in (tmp_path / "stations-N-3.html").read_text(
        encoding="utf-8")


# ------------------------------------------------------------------------------------------ CLI

def test_explore_html_and_msc_options(tmp_path, capsys):
    html, svg = tmp_path / "r.html", tmp_path / "t.svg"
    cwd = os.getcwd()
    os.chdir(ROOT)
    try:
        code = main(["explore", "models/examples/stations.cpnet", "--quiet", "--html", str(html),
                     "--msc", str(svg)])
    finally:
        os.chdir(cwd)
    assert code == 0
    assert "class=\"drawing net\"" in html.read_text(encoding="utf-8")
    root = ET.fromstring(svg.read_text(encoding="utf-8"))
    assert root.tag == f"{SVG}svg" and "Archive" in svg.read_text(encoding="utf-8")
    assert "Dead Markings" in capsys.readouterr().out  # the text report is unchanged on stdout


def test_msc_without_dead_marking_is_a_note_not_a_failure(tmp_path, capsys):
    svg = tmp_path / "t.svg"
    code = main(["explore", str(ROOT / "bench/nets/ms.cpnet"), "--set", "N=2", "--msc", str(svg)])
    assert code == 0 and not svg.exists()
    assert "no dead marking" in capsys.readouterr().err
    code = main(["explore", str(ROOT / "bench/nets/ms.cpnet"), "--set", "N=2", "--quiet", "--msc", str(svg)])
    assert code == 0 and "no dead marking" not in capsys.readouterr().err  # a note: not with --quiet


def test_html_of_a_partial_search_keeps_the_partial_exit_status(tmp_path):
    html = tmp_path / "r.html"
    code = main(["explore", str(ROOT / "models/examples/stations.cpnet"), "--quiet", "--max-states", "5",
                 "--html", str(html)])
    assert code == 2 and "partial" in html.read_text(encoding="utf-8")


def test_unwritable_html_or_msc_path_stops_before_the_search(tmp_path, capsys):
    for option in ("--html", "--msc"):
        code = main(["explore", str(ROOT / "models/examples/stations.cpnet"), "--quiet", option,
                     str(tmp_path / "no" / "such" / "dir" / "r.out")])
        err = capsys.readouterr()
        assert code == 73 and f"cannot write {option}" in err.err
        assert err.out == ""  # checked before the search: no report


def test_check_html_writes_a_page_per_run_and_an_index(tmp_path, capsys):
    out = tmp_path / "pages"
    code = main(["check", str(ROOT / "docs/ci/broken/stop_and_wait.toml"), str(ROOT / "specs/examples/ms.toml"),
                 "--no-reports", "--quiet", "--html", str(out)])
    assert code == 1  # the broken variant violates its properties
    names = sorted(p.name for p in out.iterdir())
    assert names == ["index.html", "ms-N=1.html", "ms-N=2.html", "ms-N=3.html", "stop-and-wait-broken.html"]
    index = (out / "index.html").read_text(encoding="utf-8")
    assert index.index("stop-and-wait-broken.html") < index.index("ms-N=1.html")  # the failing run first
    assert "violated: it only stops when every packet is acknowledged" in index
    page = (out / "stop-and-wait-broken.html").read_text(encoding="utf-8")
    assert "<h1>stop-and-wait-broken " in page
    head = page.index('class="headline"')
    assert head < page.index('class="drawing msc"') < page.index('<section id="statistics">')
    assert page.count('class="drawing msc"') >= 4  # every counterexample with a trace is a chart
    assert "(expected" not in page
    ok = (out / "ms-N=2.html").read_text(encoding="utf-8")
    assert 'class="pill ok">holds' in ok and 'class="headline"' not in ok


def test_check_html_of_a_mutant_whose_violation_is_expected(tmp_path, capsys):
    out = tmp_path / "pages"
    spec = ROOT / "specs/modbus/mutants/slave-ignores-crc.toml"
    assert main(["check", str(spec), "--no-reports", "--quiet", "--html", str(out)]) == 0
    (page,) = [p for p in out.iterdir() if p.name != "index.html"]
    text = page.read_text(encoding="utf-8")
    assert "(expected: violated)" in text and 'class="headline"' in text and 'class="drawing msc"' in text
    assert 'class="pill ok">holds' in (out / "index.html").read_text(encoding="utf-8")  # the gate's result


def test_check_html_folder_that_cannot_be_made_stops_before_the_runs(tmp_path, capsys):
    blocker = tmp_path / "file"
    blocker.write_text("")
    code = main(["check", str(ROOT / "specs/examples/stations.toml"), "--no-reports", "--html", str(blocker / "x")])
    err = capsys.readouterr()
    assert code == 73 and "cannot write --html" in err.err and "stations" not in err.out


def test_html_to_standard_output_replaces_the_text_report(capsys):
    code = main(["explore", str(ROOT / "models/examples/stations.cpnet"), "--quiet", "--html", "-"])
    out = capsys.readouterr().out
    assert code == 0 and out.startswith("<!DOCTYPE html>") and "Dead Markings" not in out


def test_check_no_timings_writes_the_same_pages_on_every_run(tmp_path, capsys, monkeypatch):
    # seconds, peak memory and the date are what differs from run to run; --no-timings leaves them out
    import time

    spec = str(pathlib.Path(__file__).resolve().parents[2] / "specs/examples/stations.toml")
    pages = []
    for k in range(2):
        assert main(["check", spec, "--no-reports", "--html", str(tmp_path / str(k)), "--no-timings"]) == 0
        pages.append({p.name: p.read_text(encoding="utf-8") for p in (tmp_path / str(k)).iterdir()})
        monkeypatch.setattr(time, "strftime", lambda *a: "Mon Jan 01 00:00:00 2029")  # another date
    assert pages[0] == pages[1] and "by cpn-verify" in pages[0]["stations.html"]
    assert "generated by cpn-verify" in pages[0]["stations.html"] and "Peak memory" not in pages[0]["stations.html"]
    assert "<th>Seconds</th>" not in pages[0]["index.html"]
    assert main(["check", spec, "--no-reports", "--html", str(tmp_path / "t")]) == 0
    timed = (tmp_path / "t" / "stations.html").read_text(encoding="utf-8")
    assert "generated Mon Jan 01 00:00:00 2029 by cpn-verify" in timed and "Peak memory" in timed
    assert "<th>Seconds</th>" in (tmp_path / "t" / "index.html").read_text(encoding="utf-8")
    capsys.readouterr()
