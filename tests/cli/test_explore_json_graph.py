"""`explore --json` holds the state space itself under "graph" (every state with its marking, every arc
with its binding element) within the export limit of --dot and --graphml, and says so when it leaves
it out."""

import json
import os

from cpn.cli.main import main

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
STATIONS = os.path.join(ROOT, "models", "examples", "stations.cpnet")
TIMED = os.path.join(ROOT, "models", "examples", "timer_cancel.cpnet")


def _explore(tmp_path, model, *extra):
    out = tmp_path / "x.json"
    status = main(["explore", model, "--json", str(out), "-q", *extra])
    return status, json.loads(out.read_text(encoding="utf-8"))


def test_the_graph_has_every_state_and_arc(tmp_path, capsys):
    status, d = _explore(tmp_path, STATIONS)
    assert status == 0
    g = d["graph"]
    assert g["skipped"] is False
    assert len(g["states"]) == d["statespace"]["states"] == 28
    assert len(g["arcs"]) == d["statespace"]["arcs"] == 55
    first = g["states"][0]
    assert first["node"] == 1 and first["marking"]["Office'Requests 1"] == "1`1++1`2++1`3"
    assert "Station'Busy 1" not in first["marking"]  # empty places are left out
    assert [s["node"] for s in g["states"] if s["dead"]] == d["dead_markings"]["examples"]
    nodes = {s["node"] for s in g["states"]}
    assert all(a["from"] in nodes and a["to"] in nodes for a in g["arcs"])
    # the trace to the dead marking is a path of the graph's arcs, binding element by binding element
    arcs = {(a["from"], a["binding_element"], a["to"]) for a in g["arcs"]}
    for step in d["dead_markings"]["trace"]:
        assert (step["from"], step["binding_element"], step["to"]) in arcs
    assert "warning" not in capsys.readouterr().err


def test_a_timed_state_carries_its_clock(tmp_path):
    status, d = _explore(tmp_path, TIMED)
    states = d["graph"]["states"]
    assert all(isinstance(s["time"], int) for s in states)
    assert max(s["time"] for s in states) > 0


def test_above_the_limit_the_graph_is_left_out_with_a_note(tmp_path, capsys):
    status, d = _explore(tmp_path, STATIONS, "--max-export-states", "10")
    assert status == 0
    g = d["graph"]
    assert g == {"skipped": True, "states": 28, "limit": 10, "note": g["note"]}
    assert "--max-export-states 28" in g["note"]
    assert "--json: the graph is left out" in capsys.readouterr().err
    _status, d = _explore(tmp_path, STATIONS, "--max-export-states", "0")  # 0: no limit
    assert len(d["graph"]["states"]) == 28
