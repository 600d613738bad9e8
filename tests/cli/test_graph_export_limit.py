"""--dot and --graphml above the drawing limit: a warning that names the option raising it, the option
itself (--max-export-states N, 0 for none), and a timed model's states carry their clock in the GraphML."""

import networkx as nx

from cpn.cli.main import main

COUNTER = """net C;
colset N = int with 0..20;
var n : N;
place P : N = 1`0;
trans Inc [n < 20];
arc P -> Inc : n;
arc Inc -> P : n + 1;
"""  # 21 states

TIMED = """net T;
colset U = unit timed;
colset N = int with 0..3;
var n : N;
place P : N = 1`0;
place Tick : U = 1`();
trans Step [n < 3];
arc P -> Step : n;
arc Tick -> Step;
arc Step -> P : n + 1;
arc Step -> Tick : () @+ 5;
"""  # 4 states; the first step occurs at time 0, each later one 5 later: clocks 0, 0, 5, 10


def _model(tmp_path, text: str, name: str = "m.cpnet") -> str:
    path = tmp_path / name
    path.write_text(text, encoding="utf-8")
    return str(path)


def _is_state(node: str) -> bool:  # 's12'; the SCC graph's nodes are 'scc3'
    return node[0] == "s" and node[1:].isdigit()


def test_a_skipped_export_warns_and_names_the_option(tmp_path, capsys):
    model, gml = _model(tmp_path, COUNTER), tmp_path / "g.graphml"
    assert main(["explore", model, "--graphml", str(gml), "--max-export-states", "20", "--quiet"]) == 0
    err = capsys.readouterr().err
    assert "warning: --graphml: GraphML export skipped" in err and "21 states" in err
    assert "--max-export-states 21" in err
    assert not gml.exists()


def test_the_default_limit_is_named_in_the_warning(tmp_path, capsys, monkeypatch):
    import cpn.report.graphs as graphs

    monkeypatch.setattr(graphs, "MAX_EXPORT_STATES", 10)
    dot = tmp_path / "g.dot"
    assert main(["explore", _model(tmp_path, COUNTER), "--dot", str(dot), "--quiet"]) == 0
    err = capsys.readouterr().err
    assert "warning: --dot: DOT export skipped" in err and "limit of 10 " in err and "--max-export-states" in err
    assert not dot.exists()


def test_the_option_raises_the_limit(tmp_path, capsys, monkeypatch):
    import cpn.report.graphs as graphs

    monkeypatch.setattr(graphs, "MAX_EXPORT_STATES", 10)
    dot, gml = tmp_path / "g.dot", tmp_path / "g.graphml"
    model = _model(tmp_path, COUNTER)
    assert main(["explore", model, "--dot", str(dot), "--graphml", str(gml), "--max-export-states", "21"]) == 0
    assert "skipped" not in capsys.readouterr().err
    assert dot.read_text(encoding="utf-8").count('"s21"') >= 1
    G = nx.read_graphml(gml)
    assert sum(1 for n in G if _is_state(n)) == 21
    assert main(["explore", model, "--graphml", str(gml), "--max-export-states", "0"]) == 0  # 0: no limit
    assert sum(1 for n in nx.read_graphml(gml) if _is_state(n)) == 21


def test_a_negative_limit_is_a_usage_error(tmp_path, capsys):
    assert main(["explore", _model(tmp_path, COUNTER), "--dot", "-", "--max-export-states", "-1"]) == 64
    assert "--max-export-states must not be negative" in capsys.readouterr().err


def test_timed_graphml_states_carry_their_clock(tmp_path):
    gml = tmp_path / "g.graphml"
    assert main(["explore", _model(tmp_path, TIMED), "--graphml", str(gml), "--quiet"]) == 0
    G = nx.read_graphml(gml)
    states = {n: d for n, d in G.nodes(data=True) if _is_state(n)}
    assert sorted(d["time"] for d in states.values()) == [0, 0, 5, 10]
    for d in states.values():
        assert f"\\n@ {d['time']}\\n" in d["label"]


def test_an_untimed_graphml_has_no_clock(tmp_path):
    gml = tmp_path / "g.graphml"
    assert main(["explore", _model(tmp_path, COUNTER), "--graphml", str(gml), "--quiet"]) == 0
    assert all("time" not in d for _n, d in nx.read_graphml(gml).nodes(data=True))
