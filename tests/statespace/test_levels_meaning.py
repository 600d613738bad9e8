"""`statespace.levels` of `explore --json` is the depth of the breadth-first search (docs/statespace.md):
on a complete state space the longest shortest path from the initial marking, one less than the number
of BFS levels."""

import json
import pathlib
import re

import cpn
from cpn.cli.main import main

ROOT = pathlib.Path(__file__).resolve().parents[2]
CHAIN = "net C;\ncolset N = int with 0..3;\nvar n : N;\nplace P : N = 1`0;\ntrans Inc [n < 3];\n" \
        "arc P -> Inc : n;\narc Inc -> P : n + 1;\n"  # 0 -> 1 -> 2 -> 3: 4 states, 4 BFS levels


def _depths(graph) -> list[int]:
    depth = [0] * graph.n_states
    for v in range(1, graph.n_states):
        depth[v] = depth[graph.parent[v]] + 1  # a parent is stored before its child
    return depth


def _levels(tmp_path, text: str, *args: str) -> tuple[int, int]:
    model = tmp_path / "m.cpnet"
    model.write_text(text, encoding="utf-8")
    out = tmp_path / "r.json"
    assert main(["explore", str(model), "--json", str(out), "--quiet", *args]) == 0
    x = cpn.load(str(model)).engine()
    from cpn.statespace import ExploreOptions, Explorer

    g = Explorer(x, ExploreOptions()).run().graph
    return json.loads(out.read_text())["statespace"]["levels"], max(_depths(g))


def test_levels_is_the_depth_of_the_search(tmp_path):
    assert _levels(tmp_path, CHAIN) == (3, 3)
    dp = (ROOT / "bench" / "nets" / "dp.cpnet").read_text(encoding="utf-8")
    got, depth = _levels(tmp_path, dp, "--set", "N=5")
    assert got == depth == 5


def test_one_state_has_depth_0(tmp_path):
    assert _levels(tmp_path, "net A;\ncolset U = unit;\nplace P : U = 1`();\n") == (0, 0)


def test_the_key_is_documented_with_its_meaning():
    doc = (ROOT / "docs" / "statespace.md").read_text(encoding="utf-8")
    row = re.search(r"^\| `statespace\.levels` \| (.*) \|$", doc, re.M)
    assert row and "depth" in row.group(1) and "`levels + 1` BFS levels" in row.group(1)
    example = re.search(r'"levels": (\d+)', doc)
    assert example and int(example.group(1)) == 5  # the example is DP(5): 82 states, 265 arcs
    assert '"states": 82, "arcs": 265' in doc
