"""Symmetry of module instances. A module whose parameter has a colour set declared
symmetric, instantiated once per value on the same sockets, is permuted with the values; the check
refuses, at the instance, the place or the inscription at fault, every declaration the net does not
respect; the report says which reduction ran and what it preserves; `check` decides the properties that
do not single out one instance and gives `unknown` for the others."""

import importlib.util
import json
import os

import pytest

import cpn
from cpn.cli.main import main
from cpn.errors import ModelError
from tests._shared import ROOT

CLIENTS = """colset C = index c with 1..3;
colset U = unit;
colset INT = int;
symmetry C = permutations;
var x : C;
place Lock : U = 1`();
place Req : C;
place Log : C;
module Client(me : C, w : INT) {
  port out Ask : C;
  port in Lk : U;
  place Idle : U = 1`();
  place Wait : U;
  place Crit : U;
  trans ask; arc Idle -> ask : (); arc ask -> Wait : (); arc ask -> Ask : me;
  trans enter [x = me]; arc Ask -> enter : x; arc Wait -> enter : (); arc Lk -> enter : (); arc enter -> Crit : ();
  trans leave; arc Crit -> leave : (); arc leave -> Lk : (); arc leave -> Idle : ();
}
instance Client1 = Client(me = c(1), w = 5) { Ask = Req, Lk = Lock };
instance Client2 = Client(me = c(2), w = 5) { Ask = Req, Lk = Lock };
instance Client3 = Client(me = c(3), w = 5) { Ask = Req, Lk = Lock };
"""


def _refused(text):
    m = cpn.loads(text, "c.cpnet")
    with pytest.raises(ModelError) as exc:
        m.symmetry()
    d = exc.value.diagnostics[0]
    assert d.code == "E0602" and d.hint
    return d


def test_the_instances_are_accepted_and_reduced():
    from cpn.statespace import ExploreOptions, Explorer

    m = cpn.loads(CLIENTS, "c.cpnet")
    engine = m.engine()
    q = Explorer(engine, ExploreOptions(reduction="symmetry", symmetry=m.symmetry())).run()
    full = Explorer(engine, ExploreOptions()).run()
    assert (q.n_states, full.n_states) == (7, 20)
    assert q.reduction_stats["full_states"] == 20
    assert q.reduction_stats["instances"] == ["module 'Client' (3 instances)"]


@pytest.mark.parametrize("edit,line,what", [
    # an instance missing: the renaming maps Client3's values to no instance
    (("instance Client3 = Client(me = c(3), w = 5) { Ask = Req, Lk = Lock };\n", ""), 19,
     "module 'Client' has no instance with me = c(3)"),
    # two instances for one value
    (("Client(me = c(3)", "Client(me = c(2)"), 21, "two instances of module 'Client' have me = c(2)"),
    # bound to another socket
    (("c(3), w = 5) { Ask = Req", "c(3), w = 5) { Ask = Log"), 21,
     "place 'Ask' of instance 'Client3' is Top'Log 1, that of instance 'Client1' is Top'Req 1"),
    # another parameter that differs
    (("c(2), w = 5)", "c(2), w = 6)"), 20, "parameter 'w' of instance 'Client2' is 6, not the image of 5"),
    # a constant naming one client in a guard inside the module
    (("trans enter [x = me]", "trans enter [x = me, me <> c(1)]"), 16, "the constant 'c' tells the values"),
    # ... or outside it
    (("place Log : C;", "place Log : C;\ntrans audit [x = c(2)]; arc Req -> audit : x; arc audit -> Req : x;"), 9,
     "the constant 'c' tells the values"),
    # an initial marking that singles out one instance
    (("place Idle : U = 1`();", "place Idle : U = if me = c(1) then 2`() else 1`();"), 12,
     "the initial marking of place 'Client'Idle 2' is not that of 'Client'Idle 1' renamed"),
    # an initial marking outside the instances that names one client
    (("place Log : C;", "place Log : C = 1`c(2);"), 8, "the initial marking of place 'Top'Log 1' tells"),
    # the parameter used as a number (its order)
    (("trans leave;", "trans leave [C.ord me > 0];"), 17, "'C.ord' (the order of the values)"),
])
def test_a_declaration_the_net_does_not_respect_is_refused_where_it_breaks(edit, line, what):
    d = _refused(CLIENTS.replace(*edit))
    assert what in d.message, d.message
    assert d.span is not None and d.span.line == line


def test_the_cli_error_has_position_caret_and_hint(tmp_path, capsys):
    path = tmp_path / "c.cpnet"
    path.write_text(CLIENTS.replace("c(3), w = 5) { Ask = Req", "c(3), w = 5) { Ask = Log"), encoding="utf-8")
    assert main(["explore", str(path), "--reduction", "symmetry"]) == 65
    err = capsys.readouterr().err
    assert f"{path}:21:1: error[E0602]" in err and "^^^^" in err and "hint: Bind the ports" in err


def test_the_report_says_what_the_reduction_preserves(tmp_path, capsys):
    path = tmp_path / "c.cpnet"
    path.write_text(CLIENTS, encoding="utf-8")
    assert main(["explore", str(path), "--json", str(tmp_path / "full.json"), "--quiet"]) == 0
    assert main(["explore", str(path), "--reduction", "symmetry", "--json", str(tmp_path / "q.json"),
                 "--quiet"]) == 0
    full = json.loads((tmp_path / "full.json").read_text())
    q = json.loads((tmp_path / "q.json").read_text())
    assert (q["statespace"]["states"], q["statespace"]["full_states"]) == (7, full["statespace"]["states"])
    assert q["bounds"] == full["bounds"] and q["dead_transitions"] == full["dead_transitions"]
    assert q["live_transitions"] is None and q["fairness"] is None
    assert {"live_transitions", "fairness", "home_markings"} <= set(q["reduction"]["not_preserved"])
    assert "dead_transitions" in q["reduction"]["preserves"]
    capsys.readouterr()
    assert main(["explore", str(path), "--reduction", "symmetry"]) == 0
    out = capsys.readouterr().out
    assert "moving the instances of module 'Client' (3 instances)" in out
    assert out.count("not preserved by symmetry reduction") >= 4


SCENARIO = """model = "c.cpnet"
[explore]
symmetry = true

[[property]]
name = "mutual exclusion"
kind = "invariant"
expr = "size (sum Client'Crit) <= 1"

[[property]]
name = "one client, by its number"
kind = "invariant"
expr = "size (Client'Crit 1) <= 1"

[[property]]
name = "every client idle or busy"
kind = "invariant"
expr = "forall Client'Idle (fn m => size m <= 1)"

[[property]]
name = "dead"
kind = "dead_transitions"
expected = []

[[property]]
name = "client 2's entry is live"
kind = "live_transitions"
transitions = ["Client'enter 2"]

[[property]]
name = "bound of one instance's place"
kind = "bound"
place = "Client'Wait 2"
upper = 1

[[property]]
name = "ASK-CTL's name of one instance's place"
kind = "invariant"
expr = "size (Mark.Client'Crit 1) <= 1"

[[property]]
name = "one instance's transition in CTL"
kind = "ctl"
formula = "AG (EF (enabled \\"Client'enter 1\\"))"
"""


def test_check_decides_what_names_no_instance_and_refuses_the_rest(tmp_path):
    (tmp_path / "c.cpnet").write_text(CLIENTS, encoding="utf-8")
    spec = tmp_path / "s.toml"
    spec.write_text(SCENARIO, encoding="utf-8")
    assert main(["check", str(spec), "--reports", str(tmp_path / "rep"), "--no-timings"]) == 2
    run = json.loads(next((tmp_path / "rep").glob("*.json")).read_text(encoding="utf-8"))
    v = {p["name"]: (p["verdict"], p["message"]) for p in run["properties"]}
    assert v["mutual exclusion"][0] == "holds"
    assert v["every client idle or busy"][0] == "holds"
    assert v["dead"][0] == "holds"  # every transition of every client occurs (closed over the instances)
    for name in ("client 2's entry is live", "bound of one instance's place", "one instance's transition in CTL"):
        assert v[name][0] == "unknown" and "not preserved by symmetry" in v[name][1], (name, v[name])
    # an invariant naming one instance is decided through the orbits
    for name in ("one client, by its number", "ASK-CTL's name of one instance's place"):
        assert v[name][0] == "holds" and "every image" in v[name][1], (name, v[name])
    # the quotient's representatives put the critical client last; every client's bound is that of all
    assert [run["bounds"][f"Client'Crit {k}"] for k in (1, 2, 3)] == [{"upper": 1, "lower": 0}] * 3


def test_dead_transitions_of_the_full_graph_from_the_quotient(tmp_path):
    """A transition no instance can fire is dead in every instance; the quotient fires only the
    representatives' transitions, the closure over the instances gives the full graph's list."""
    text = CLIENTS.replace("trans leave;", "trans leave; trans never [x <> x]; arc Ask -> never : x;")
    (tmp_path / "c.cpnet").write_text(text, encoding="utf-8")
    spec = tmp_path / "s.toml"
    spec.write_text('model = "c.cpnet"\n[explore]\nsymmetry = true\n[[property]]\nname = "dead"\n'
                    'kind = "dead_transitions"\nexpected = ["Client\'never 1", "Client\'never 2", '
                    '"Client\'never 3"]\n', encoding="utf-8")
    assert main(["check", str(spec), "--reports", str(tmp_path / "rep"), "--no-timings"]) == 0


def test_a_multiset_listed_in_order_is_refused():
    """`ms_to_list (C.all())` lists the values in their declared order, so `hd` of it names the first one:
    accepted before, the quotient then claimed 8 states for a net of 2."""
    m = cpn.loads("colset C = with a | b | c; var x : C; place I : C = C.all(); place O : C;\n"
                  "trans t [x = hd (ms_to_list (C.all()))]; arc I -> t : x; arc t -> O : x;", "h.cpnet")
    with pytest.raises(ModelError) as exc:
        m.symmetry("C")
    d = exc.value.diagnostics[0]
    assert d.code == "E0602" and "'ms_to_list'" in d.message and (d.span.line, d.span.col) == (2, 18)


def test_listing_and_gathering_again_is_accepted():
    """`list_to_ms (List.map F (ms_to_list M))` does not depend on the order the values are listed in."""
    ok = ("colset C = with a | b | c; colset CC = product C * C; var x : C; place I : C = C.all(); place O : CC;\n"
          "trans t; arc I -> t : x; arc t -> O : list_to_ms (List.map (fn y => (y, x)) (ms_to_list (C.all())));")
    assert [str(s) for s in cpn.loads(ok, "h.cpnet").symmetry("C")] == ["C"]
    bad = ok.replace("list_to_ms (List.map", "list_to_ms (List.tl (List.map").replace("(C.all())));", "(C.all()))));")
    with pytest.raises(ModelError):
        cpn.loads(bad, "h.cpnet").symmetry("C")


# ---------------------------------------------------------------- MODBUS broadcasts, as module instances
MODBUS = os.path.join(ROOT, "models", "modbus", "modbus.cpnet")
def modbus_variant(ns: int) -> str:
    """bench/nets/modbus_bcast_sym.cpnet with NS slaves: the benchmark's own generator (bench/modbus.py)."""
    spec = importlib.util.spec_from_file_location("bench_modbus", os.path.join(ROOT, "bench", "modbus.py"))
    bench = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(bench)
    return bench.symmetric_model(ns)


@pytest.mark.parametrize("ns,adrs", [(2, "[0]"), (3, "[0]"), (4, "[0,0]"), (5, "[0]"), (3, "[0,7,0]")])
def test_modbus_broadcasts_quotient_against_the_full_modbus_model(ns, adrs):
    """On broadcast frames (and a frame to an absent address), the variant whose slaves are module
    instances permuted by symmetry: the full counts computed from the quotient's orbits equal its full
    graph's, with the same dead markings modulo time and the same bounds of the master's and the bus's
    places. (It was built as a copy of modbus.cpnet's broadcasts; modbus.cpnet now explores the slaves'
    receptions in slave order, which a permutation of the slaves does not preserve, so the two state
    spaces are no longer compared.)"""
    from cpn.statespace import ExploreOptions, Explorer

    values = {"ADRS": adrs, "FCS": "[1]", "PO": "1"}
    var = cpn.loads(modbus_variant(ns), "modbus_bcast_sym.cpnet", set=values)
    ev = var.engine(time_condensation=True)
    xv = Explorer(ev, ExploreOptions()).run()
    xq = Explorer(ev, ExploreOptions(reduction="symmetry", symmetry=var.symmetry())).run()
    st = xq.reduction_stats
    assert (st["full_states"], st["full_arcs"]) == (xv.n_states, xv.n_arcs)
    assert xq.n_states < xv.n_states
    dead_v = {ev.untimed(xv.graph.states[i]) for i in xv.graph.dead_states()}
    assert len(dead_v) == 1 == len({ev.untimed(xq.graph.states[i]) for i in xq.graph.dead_states()})
    from cpn.report import build_report

    rq = build_report(xq, trace_to_dead=False)
    assert rq.full_dead_count == len(xv.graph.dead_states())
    names = {t.name for t in ev.transitions}
    master_bus = [p.name for p in ev.places if p.page in ("Master", "Bus", "Modbus")]
    rv = build_report(xv, trace_to_dead=False)
    bounds_v = {b.place: (b.upper, b.lower) for b in rv.bounds.places}
    bounds_q = {b.place: (b.upper, b.lower) for b in rq.bounds.places}
    assert all(bounds_v[p] == bounds_q[p] for p in master_bus)
    # the master's and the bus's transitions that never occur are the same in both
    dead_mb = {t for t in rv.dead_transitions if t.split("'")[0] in ("Master", "Bus")}
    assert dead_mb == {t for t in rq.dead_transitions if t.split("'")[0] in ("Master", "Bus")} and dead_mb < names


def test_the_modbus_broadcast_scenario_gives_the_same_verdicts_on_the_quotient(tmp_path):
    """bench/nets/modbus_bcast_sym.toml (the MODBUS properties that name no single slave) holds on the
    quotient, and on the full graph of the same model."""
    import shutil

    for name in ("modbus_bcast_sym.cpnet", "modbus_bcast_sym.toml"):
        shutil.copy(os.path.join(ROOT, "bench", "nets", name), tmp_path / name)
    spec = tmp_path / "modbus_bcast_sym.toml"
    text = spec.read_text(encoding="utf-8")
    verdicts, bounds = [], []
    for variant in (text, text.replace("symmetry = true\n", "")):
        spec.write_text(variant, encoding="utf-8")
        reports = tmp_path / f"rep{len(verdicts)}"
        assert main(["check", str(spec), "--reports", str(reports), "--no-timings", "-q"]) == 0
        run = json.loads(next(reports.glob("*.json")).read_text(encoding="utf-8"))
        verdicts.append([(p["name"], p["verdict"]) for p in run["properties"]])
        bounds.append(run["bounds"])
    assert bounds[0] == bounds[1]  # the slaves' places: closed over the instances
    assert verdicts[0] == verdicts[1] and {v for _, v in verdicts[0]} == {"holds"} and len(verdicts[0]) == 9
