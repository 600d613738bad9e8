"""Symmetry reduction declared in the model, on the command line and in a scenario;
refused, with the inscription at fault, when the net tells the values apart; the reports give the
quotient's and the full graph's counts and say what is not preserved; `check` gives `unknown` for a
property that is not symmetric."""

import json

import pytest

import cpn
from cpn.cli.main import main
from cpn.errors import ModelError

# dining philosophers over an index colour set, rotations declared (successor written with ord/col)
DP = """val N = 4;
colset PH = index ph with 0..N-1;
symmetry PH = rotations;
var p : PH;
fun r(p) = PH.col ((PH.ord p + 1) mod N);
place Think : PH = PH.all(); place HasLeft : PH; place Eat : PH; place Forks : PH = PH.all();
trans TakeLeft; trans TakeRight; trans PutDown;
arc Think -> TakeLeft : p; arc Forks -> TakeLeft : p; arc TakeLeft -> HasLeft : p;
arc HasLeft -> TakeRight : p; arc Forks -> TakeRight : r(p); arc TakeRight -> Eat : p;
arc Eat -> PutDown : p; arc PutDown -> Think : p; arc PutDown -> Forks : 1`p ++ 1`r(p);
"""

# clients that are all alike (every permutation), one of them named in a guard when BAD
CLIENTS = """colset C = with c1 | c2 | c3;
colset U = unit;
var c, d : C;
place Idle : C = C.all(); place Wait : C; place Busy : C; place Lock : U = 1`();
trans ask; trans enter{guard}; trans leave;
arc Idle -> ask : c; arc ask -> Wait : c;
arc Wait -> enter : c; arc Lock -> enter : (); arc enter -> Busy : c;
arc Busy -> leave : c; arc leave -> Lock : (); arc leave -> Idle : c;
"""


def _write(tmp_path, name, text):
    path = tmp_path / name
    path.write_text(text, encoding="utf-8")
    return str(path)


def test_declared_rotations_reduce_and_the_full_counts_are_exact(tmp_path, capsys):
    model = _write(tmp_path, "dp.cpnet", DP)
    assert main(["explore", model, "--json", str(tmp_path / "full.json"), "--quiet"]) == 0
    assert main(["explore", model, "--reduction", "symmetry", "--json", str(tmp_path / "q.json"), "--quiet"]) == 0
    full = json.loads((tmp_path / "full.json").read_text())
    q = json.loads((tmp_path / "q.json").read_text())
    assert q["statespace"]["states"] < full["statespace"]["states"]
    assert (q["statespace"]["full_states"], q["statespace"]["full_arcs"]) == (full["statespace"]["states"],
                                                                            full["statespace"]["arcs"])
    assert q["dead_markings"]["full_count"] == full["dead_markings"]["count"] == 1
    assert q["bounds"] == full["bounds"] and q["tokens"] == full["tokens"]
    assert q["live_transitions"] == full["live_transitions"] and q["fairness"] == full["fairness"]
    assert q["multiset_bounds"] is None and q["home_markings"] is None
    assert q["reduction"]["name"] == "symmetry" and q["reduction"]["symmetry"] == ["PH:rotations"]
    assert "home_markings" in q["reduction"]["not_preserved"]
    capsys.readouterr()
    assert main(["explore", model, "--reduction", "symmetry"]) == 0
    out = capsys.readouterr().out
    assert "quotient by symmetry" in out and "Full State Space (sums of the orbit sizes)" in out
    assert "not preserved by symmetry reduction" in out and "1 dead marking in the full state space" in out


def test_permutations_are_refused_where_the_net_uses_the_order(tmp_path, capsys):
    model = _write(tmp_path, "dp.cpnet", DP)
    assert main(["explore", model, "--symmetry", "PH"]) == 65
    err = capsys.readouterr().err
    assert "dp.cpnet:5:12: error[E0602]" in err and "'PH.col'" in err and "in function 'r'" in err
    assert "hint:" in err and "declare rotations instead" in err
    assert "^^^^^^" in err  # the source line and a caret


def test_a_constant_in_a_guard_is_refused_with_its_position(tmp_path, capsys):
    model = _write(tmp_path, "c.cpnet", CLIENTS.format(guard=" [c <> c1]"))
    assert main(["explore", model, "--symmetry", "C"]) == 65
    err = capsys.readouterr().err
    assert "c.cpnet:5:30: error[E0602]: the constant 'c1' tells the values of colour set 'C' apart" in err
    m = cpn.load(model)
    with pytest.raises(ModelError) as exc:
        m.symmetry("C")
    assert [d.code for d in exc.value.diagnostics] == ["E0602"]


def test_an_asymmetric_initial_marking_is_refused():
    m = cpn.loads(CLIENTS.format(guard="").replace("place Idle : C = C.all()", "place Idle : C = 1`c1 ++ 1`c2"),
                  "c.cpnet")
    with pytest.raises(ModelError) as exc:
        m.symmetry("C")
    d = exc.value.diagnostics[0]
    assert d.code == "E0602" and "initial marking of place 'Top'Idle 1'" in d.message and d.span.line == 4


def test_symmetry_auto_and_bad_specifications(tmp_path, capsys):
    model = _write(tmp_path, "c.cpnet", CLIENTS.format(guard=""))
    assert [str(s) for s in cpn.load(model).symmetry("auto")] == ["C"]
    assert main(["explore", model, "--symmetry", "C:mirror"]) == 64
    assert "'mirror' is not a kind of symmetry" in capsys.readouterr().err
    assert main(["explore", model, "--reduction", "symmetry"]) == 64  # nothing declared
    assert "declares no symmetry" in capsys.readouterr().err
    assert main(["explore", model, "--symmetry", "U"]) == 65
    assert "only enumerations and index colour sets" in capsys.readouterr().err


def test_the_declaration_is_checked_by_the_language():
    with pytest.raises(ModelError) as exc:
        cpn.loads("colset U = unit; symmetry U = permutations; symmetry Q = rotations; colset E = with a | b;"
                  " symmetry E = mirror; place P : U;", "s.cpnet")
    assert [(d.code, d.span.col) for d in exc.value.diagnostics] == [("E0304", 27), ("E0201", 54), ("E0304", 105)]
    m = cpn.loads("colset E = with a | b; symmetry E = permutations; place P : E = E.all();", "s.cpnet")
    assert [str(s) for s in m.symmetry()] == ["E"]


SCENARIO = """model = "c.cpnet"
[explore]
symmetry = ["C"]

[[property]]
name = "mutual exclusion"
kind = "invariant"
expr = "size (Top'Busy 1) <= 1"

[[property]]
name = "no deadlock"
kind = "deadlock_free"

[[property]]
name = "c1 never waits"
kind = "invariant"
expr = "size (Top'Wait 1) = 0 orelse not (cf (c1, Top'Wait 1) > 0)"

[[property]]
name = "home"
kind = "home"

[[property]]
name = "someone can enter"
kind = "ctl"
formula = "AG (EF (size (Top'Busy 1) = 1))"
"""


def test_check_decides_symmetric_properties_and_refuses_the_others(tmp_path, capsys):
    _write(tmp_path, "c.cpnet", CLIENTS.format(guard=""))
    spec = _write(tmp_path, "s.toml", SCENARIO)
    assert main(["check", spec, "--reports", str(tmp_path / "rep"), "--no-timings"]) == 1
    run = json.loads(next((tmp_path / "rep").glob("*.json")).read_text(encoding="utf-8"))
    verdicts = {p["name"]: (p["verdict"], p["message"]) for p in run["properties"]}
    assert verdicts["mutual exclusion"][0] == "holds" and "one state per orbit" in verdicts["mutual exclusion"][1]
    assert verdicts["no deadlock"][0] == "holds"
    assert verdicts["someone can enter"][0] == "holds"
    # a text naming a value: an invariant is decided through the orbits (c1 does wait in some image)
    assert verdicts["c1 never waits"][0] == "violated" and "orbit" in verdicts["c1 never waits"][1]
    assert verdicts["home"][0] == "unknown" and "home markings" in verdicts["home"][1]
    st = run["statespace"]
    assert st["reduction"] == "symmetry" and st["full_states"] > st["states"]


def test_a_violation_found_on_the_quotient_has_a_trace_of_the_full_graph(tmp_path, capsys):
    _write(tmp_path, "c.cpnet", CLIENTS.format(guard=""))
    spec = _write(tmp_path, "s.toml", SCENARIO.replace("size (Top'Busy 1) <= 1", "size (Top'Wait 1) <= 1"))
    assert main(["check", spec, "--reports", str(tmp_path / "rep"), "--no-timings"]) == 1
    run = json.loads(next((tmp_path / "rep").glob("*.json")).read_text(encoding="utf-8"))
    p = next(p for p in run["properties"] if p["name"] == "mutual exclusion")
    steps = p["trace"]["steps"]
    assert p["verdict"] == "violated" and len(steps) == 2
    # two different clients ask: the lifted trace names two different values (the quotient's would not)
    assert steps[0]["binding_element"] != steps[1]["binding_element"]


def test_the_order_of_a_product_holding_the_colour_set_is_refused():
    m = cpn.loads("colset C = with a | b; colset P = product C * C; var x : P; place I : P = P.all();"
                  " place O : P; trans t [P.ord x = 0]; arc I -> t : x; arc t -> O : x;", "p.cpnet")
    with pytest.raises(ModelError) as exc:
        m.symmetry("C")
    assert "'P.ord' (the order of the values of 'P'" in exc.value.diagnostics[0].message
    assert [str(s) for s in cpn.loads("colset C = with a | b; colset P = product C * C; var x : P;"
                                      " place I : P = P.all(); trans t; arc I -> t : x;").symmetry("C")] == ["C"]


def test_the_declaration_prints_back():
    from cpn.lang.parser import parse
    from cpn.lang.pretty import decl

    m = parse("colset E = with a | b; symmetry E = rotations;", "s.cpnet")
    assert decl(m.decls[1]) == "symmetry E = rotations;"


def test_a_bad_symmetry_in_a_scenario_is_a_positioned_error(tmp_path, capsys):
    _write(tmp_path, "c.cpnet", CLIENTS.format(guard=""))
    spec = _write(tmp_path, "s.toml", 'model = "c.cpnet"\n[explore]\nsymmetry = ["C:mirror"]\n'
                  '[[property]]\nname = "d"\nkind = "deadlock_free"\n')
    assert main(["check", spec, "--no-reports"]) == 65
    err = capsys.readouterr().err
    assert "s.toml:3:1: error[E0702]" in err and "'mirror' is not a kind of symmetry" in err
