"""`cpn-verify explore` on toy engines (loading is replaced) and exit statuses."""

import json
import os
import sys

import pytest

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "statespace"))

from _toy import dining_philosophers  # noqa: E402
from nets import counter  # noqa: E402

import cpn.cli.explore as explore  # noqa: E402


def main(argv):
    """cpn.cli.main.main once the package's public door exists; an equivalent parser until then."""
    try:
        from cpn import __version__  # noqa: F401
        from cpn.cli.main import main as real_main
    except ImportError:
        import argparse

        parser = argparse.ArgumentParser(prog="cpn-verify")
        explore.add_parser(parser.add_subparsers(dest="command"))
        try:
            args = parser.parse_args(argv)
        except SystemExit:
            return 64
        if args.command is None:
            return 64
        return explore.run(args)
    return real_main(argv)


@pytest.fixture
def toy(monkeypatch, tmp_path):
    model = tmp_path / "toy.cpnet"
    model.write_text("(* replaced by a toy engine *)\n")
    engines = {}

    def load(path, sets, time_condensation):
        engines["sets"] = sets
        return engines["engine"]

    monkeypatch.setattr(explore, "load_engine", load)
    return model, engines


def test_complete_exit_0_and_report(toy, capsys):
    model, engines = toy
    engines["engine"] = dining_philosophers(4)
    assert main(["explore", str(model), "--set", "N=4"]) == 0
    out = capsys.readouterr().out
    assert "CPN Tools state space report for:" in out and "Status: Full" in out
    assert engines["sets"] == {"N": "4"}
    assert "Top'TakeLeft 1: {p=0}" in out
    assert "Top'Think 1: " not in out.split("Shortest trace")[1].split("Dead Transition")[0]


def test_trace_to_dead_shows_marking_changes(toy, capsys):
    model, engines = toy
    engines["engine"] = dining_philosophers(4)
    assert main(["explore", str(model), "--trace-to-dead"]) == 0
    out = capsys.readouterr().out
    assert "          Top'Think 1: " in out


def test_partial_exit_2_and_json(toy, capsys, tmp_path):
    model, engines = toy
    engines["engine"] = counter()
    out_json = tmp_path / "r.json"
    assert main(["explore", str(model), "--max-states", "10", "--json", str(out_json), "--quiet"]) == 2
    d = json.loads(out_json.read_text())
    assert d["statespace"]["complete"] is False and d["statespace"]["stop_reason"] == "max_states"
    assert d["statespace"]["unexpanded"] == 1 and d["dead_markings"]["count"] == 0
    err = capsys.readouterr().err
    assert "partial state space: stopped because max_states=10 was reached" in err


def test_json_to_stdout_only(toy, capsys):
    model, engines = toy
    engines["engine"] = dining_philosophers(3)
    assert main(["explore", str(model), "--json", "-"]) == 0
    d = json.loads(capsys.readouterr().out)
    assert d["statespace"]["states"] == 17 or d["statespace"]["states"] > 0


def test_exports(toy, tmp_path):
    model, engines = toy
    engines["engine"] = dining_philosophers(3)
    dot, gml = tmp_path / "g.dot", tmp_path / "g.graphml"
    assert main(["explore", str(model), "--dot", str(dot), "--graphml", str(gml)]) == 0
    text = dot.read_text()
    assert text.startswith("digraph statespace {") and "digraph sccgraph {" in text
    import networkx as nx

    G = nx.read_graphml(gml)
    assert G.number_of_nodes() > 0


def test_export_refused_above_limit(toy, tmp_path, capsys, monkeypatch):
    import cpn.report.graphs as graphs

    monkeypatch.setattr(graphs, "MAX_EXPORT_STATES", 5)
    model, engines = toy
    engines["engine"] = dining_philosophers(3)
    assert main(["explore", str(model), "--dot", str(tmp_path / "g.dot")]) == 0
    assert "DOT export skipped" in capsys.readouterr().err
    assert not (tmp_path / "g.dot").exists()


def test_bad_usage_64(toy, capsys):
    model, engines = toy
    engines["engine"] = counter()
    assert main(["explore", str(model), "--set", "N"]) == 64
    assert main(["explore", str(model), "--max-states", "0"]) == 64
    assert main(["explore", "/nonexistent/model.cpnet"]) == 64
    assert main(["explore"]) == 64


def test_bad_model_65(monkeypatch, tmp_path, capsys):
    from cpn.diagnostics import Diagnostic
    from cpn.errors import ModelError

    def load(path, sets, time_condensation):
        raise ModelError([Diagnostic("E0201", "unknown colour set 'Phil'", None)])

    monkeypatch.setattr(explore, "load_engine", load)
    model = tmp_path / "bad.cpnet"
    model.write_text("x")
    assert main(["explore", str(model)]) == 65
    assert "unknown colour set 'Phil'" in capsys.readouterr().err


# a timed net a transition of which is left to the Python engine (reals): `auto` keeps the Python search
HALFWAY = """colset N = int with 0..3 timed; colset L = real; var x : N; var l : L;
place P : N = 1`0; place Q : L = 1`0.0; trans t [x < 3] @+ 1; arc P -> t : x; arc t -> P : (x + 1) @+ 1;
trans u [l < 2.0]; arc Q -> u : l; arc u -> Q : l + 1.0;
"""


def _halfway(tmp_path) -> str:
    path = tmp_path / "halfway.cpnet"
    path.write_text(HALFWAY)
    return str(path)


def test_notes_on_the_search_of_a_timed_net_are_said_with_verbose_only(capsys, tmp_path):
    """Which search ran, where that asks nothing of the user, is neither on stderr nor in the report
    unless --verbose asks; then once."""
    path = _halfway(tmp_path)
    assert main(["explore", path, "--time-condensation"]) == 0
    out, err = capsys.readouterr()
    assert "Python back end" not in err and "Python back end" not in out
    assert main(["explore", path, "--time-condensation", "--verbose"]) == 0
    out, err = capsys.readouterr()
    assert err.count("note: the Python back end searched this net") == 1
    assert "Python back end" not in out



def test_the_json_keeps_the_notes_on_the_search_apart(capsys, tmp_path):
    path = _halfway(tmp_path)
    assert main(["explore", path, "--time-condensation", "--json", "-"]) == 0
    doc = json.loads(capsys.readouterr().out)
    assert any("Python back end searched" in n for n in doc["backend_notes"]), doc["backend_notes"]
    assert not any("Python back end" in n for n in doc["notes"])
