"""Stubborn sets in `explore --reduction stubborn` and in a scenario's [explore] table;
the reports say which reduction ran and refuse what it does not preserve."""

import json

from cpn.cli.main import main

# two independent components: a self-loop on A and a one-shot move B -> C; and a two-way choice on D
NET = """colset U = unit; place A : U = 1`(); place B : U = 1`(); place C : U; place D : U = 1`(); place E : U;
trans loop; trans move; trans d1; trans d2;
arc A -> loop; arc loop -> A; arc B -> move; arc move -> C; arc D -> d1; arc d1 -> E; arc D -> d2; arc d2 -> E;"""

SCENARIO = """model = "n.cpnet"
[explore]
reduction = "stubborn"

[[property]]
name = "C stays empty"
kind = "invariant"
expr = "size (Top'C 1) = 0"

[[property]]
name = "E is reached"
kind = "reachable"
expr = "size (Top'E 1) = 1"

[[property]]
name = "no deadlock"
kind = "deadlock_free"

[[property]]
name = "bounded"
kind = "bound"
place = "Top'A 1"
upper = 1

[[property]]
name = "home"
kind = "home"
"""


def test_explore_reduction_stubborn_reports_only_dead_markings(tmp_path, capsys):
    model = tmp_path / "n.cpnet"
    model.write_text("colset U = unit; place A : U = 1`(); place B : U = 1`(); place C : U; place D : U;"
                     " trans a; trans b; arc A -> a; arc a -> C; arc B -> b; arc b -> D;", encoding="utf-8")
    assert main(["explore", str(model), "--reduction", "stubborn", "--json", str(tmp_path / "r.json")]) == 0
    assert main(["explore", str(model), "--reduction", "stubborn"]) == 0
    out = capsys.readouterr().out
    assert "State Space (reduced by stubborn sets)" in out and "Nodes:  3" in out  # 4 without the reduction
    assert out.count("not preserved by stubborn sets") >= 6 and "Best Integer Bounds" not in out
    assert "it preserves the dead markings" in out
    d = json.loads((tmp_path / "r.json").read_text(encoding="utf-8"))
    assert d["reduction"]["name"] == "stubborn" and d["reduction"]["preserves"] == ["dead_markings"]
    assert d["statespace"]["states"] == 3 and d["dead_markings"]["count"] == 1
    assert d["bounds"] is None and d["home_markings"] is None and d["fairness"] is None


def test_check_with_reduction_keeps_invariants_and_refuses_the_rest(tmp_path, capsys):
    (tmp_path / "n.cpnet").write_text(NET, encoding="utf-8")
    spec = tmp_path / "s.toml"
    spec.write_text(SCENARIO, encoding="utf-8")
    code = main(["check", str(spec), "--reports", str(tmp_path / "rep"), "--no-timings"])
    out = capsys.readouterr().out
    assert code == 1, out  # the invariant is violated: the cycle proviso does not let `loop` hide `move`
    doc = json.loads(next((tmp_path / "rep").glob("*.json")).read_text(encoding="utf-8"))
    verdicts = {p["name"]: (p["verdict"], p["message"]) for p in doc["properties"]}
    assert verdicts["C stays empty"][0] == "violated"
    assert verdicts["E is reached"][0] == "holds"
    assert verdicts["no deadlock"][0] == "holds"  # `loop` is always enabled
    for name in ("bounded", "home"):
        assert verdicts[name] == ("unknown", verdicts[name][1]) and "not preserved by stubborn sets" in verdicts[name][1]
    assert doc["statespace"]["reduction"] == "stubborn" and doc["bounds"] is None
    text = next((tmp_path / "rep").glob("*.txt")).read_text(encoding="utf-8")
    assert "arcs (reduced by stubborn sets)" in text


def test_a_bad_reduction_is_a_positioned_error(tmp_path, capsys):
    (tmp_path / "n.cpnet").write_text(NET, encoding="utf-8")
    spec = tmp_path / "s.toml"
    spec.write_text('model = "n.cpnet"\n[explore]\nreduction = "sweep"\n', encoding="utf-8")
    assert main(["check", str(spec), "--no-reports"]) == 65
    err = capsys.readouterr().err
    assert "s.toml:3:" in err and "error[E0702]" in err and "'reduction' must be one of 'stubborn', 'symmetry'" in err


def test_html_page_and_drawings_under_the_reduction(tmp_path, capsys):
    model = tmp_path / "n.cpnet"
    model.write_text(NET, encoding="utf-8")
    page = tmp_path / "r.html"
    assert main(["explore", str(model), "--reduction", "stubborn", "--html", str(page), "--quiet"]) == 0
    html = page.read_text(encoding="utf-8")
    assert "reduced by stubborn sets" in html and "not preserved by stubborn sets" in html
    assert 'id="bounds"' not in html
    assert main(["explore", str(model), "--reduction", "stubborn", "--dot", str(tmp_path / "g.dot")]) == 64
    assert "stubborn sets does not preserve" in capsys.readouterr().err
