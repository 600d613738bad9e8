"""Each property kind on small nets with hand-checked verdicts, holding and violated."""

import pytest

from cpn.checks.verdict import Status
from cpn.gate.run import run_scenario
from cpn.gate.scenario import load_scenario
from tests.checks._nets import COUNTER, LOOP, SLAVES, scenario


def verdicts(tmp_path, model, body, **overrides):
    s = load_scenario(scenario(tmp_path, model, body))
    r = run_scenario(s, s.runs[0], overrides)
    return r, {p.spec.name: p.verdict for p in r.results}


def prop(name, kind, **fields):
    lines = ["[[property]]", f'name = "{name}"', f'kind = "{kind}"']
    for k, v in fields.items():
        if isinstance(v, bool):
            v = "true" if v else "false"
        elif isinstance(v, str):
            v = '"' + v.replace('"', '\\"') + '"'
        elif isinstance(v, list):
            v = "[" + ", ".join('"' + x + '"' for x in v) + "]"
        lines.append(f"{k} = {v}")
    return "\n".join(lines) + "\n"


def path_len(v):
    return len(v.evidence.path) - 1


def test_counter_verdicts(tmp_path):
    body = "".join([
        prop("one token", "invariant", expr="size (C'P 1) = 1"),
        prop("never two", "invariant", expr="C'P 1 <> (1`2)"),
        prop("three", "reachable", expr="C'P 1 = (1`3)"),
        prop("four", "reachable", expr="cf (0, C'P 1) = 2"),
        prop("no deadlock", "deadlock_free"),
        prop("one dead", "dead_markings", count=1, expr="C'P 1 = (1`3)"),
        prop("two dead", "dead_markings", count=2),
        prop("dead at zero", "dead_markings", expr="C'P 1 = (1`0)"),
        prop("place bound", "bound", place="C'P 1", upper=1, lower=1),
        prop("value bound", "bound", expr="ms_to_col (C'P 1)", upper=3, lower=0),
        prop("value bound wrong", "bound", expr="ms_to_col (C'P 1)", upper=2),
        prop("ms bound", "bound", place="C'P 1", upper_multiset="N.all()"),
        prop("none dead", "dead_transitions", expected=[]),
        prop("Inc dead", "dead_transitions", expected=["C'Inc 1"]),
        prop("live", "live_transitions"),
        prop("home exists", "home"),
        prop("initial home", "home", initial=True),
        prop("home three", "home", expr="C'P 1 = (1`3)"),
        prop("terminates", "no_livelock"),
    ])
    r, v = verdicts(tmp_path, COUNTER, body)
    assert r.exploration.n_states == 4
    H, V = Status.HOLDS, Status.VIOLATED
    want = {"one token": H, "never two": V, "three": H, "four": V, "no deadlock": V, "one dead": H,
            "two dead": V, "dead at zero": V, "place bound": H, "value bound": H, "value bound wrong": V,
            "ms bound": H, "none dead": H, "Inc dead": V, "live": V, "home exists": H, "initial home": V,
            "home three": H, "terminates": H}
    assert {k: x.status for k, x in v.items()} == want
    assert path_len(v["never two"]) == 2
    assert path_len(v["three"]) == 3
    assert path_len(v["no deadlock"]) == 3
    assert path_len(v["value bound wrong"]) == 3  # the first marking with the value 3
    assert path_len(v["Inc dead"]) == 1  # the trace ends with an occurrence of Inc
    assert path_len(v["live"]) == 3  # after the dead marking Inc never occurs again
    assert path_len(v["initial home"]) == 1  # from P=1 the initial marking is never reached again
    assert "3 dead" not in v["two dead"].message and "1 dead markings, expected 2" in v["two dead"].message


def test_loop_livelock_and_fairness(tmp_path):
    stop = "size (L'A 1) + size (L'B 1) = 0"
    body = "".join([
        prop("terminates", "no_livelock"),
        prop("spin is a livelock", "no_livelock", progress=["L'Go 1"]),
        prop("progress", "no_livelock", progress=["L'Go", "L'Spin 1"]),
        prop("eventually stops", "ctl", formula=f"AF ({stop})"),
        prop("stops if Stop is fair", "ctl", formula=f"AF ({stop})", fairness=["L'Stop 1"]),
        prop("fair Go is not enough", "ctl", formula=f"AF ({stop})", fairness=["L'Go 1"]),
        prop("can stop", "ctl", formula=f"AG (EF ({stop}))"),
        prop("Go enabled again", "ctl", formula="AG (enabled \"L'Go 1\" orelse EF (enabled \"L'Go\"))"),
        prop("Stop can end it", "ctl", formula=f"EXB (\"L'Stop 1\", {stop})"),
        prop("Go never ends it", "ctl", formula=f"AG (AXB (\"L'Go\", not ({stop})))"),
        prop("after Go only Back", "ctl", formula="AG (AXB (\"L'Go 1\", enabled \"L'Back 1\"))"),
        prop("Spin always stays", "ctl", formula="AXB (\"L'Spin 1\", size (L'B 1) = 1)"),
        prop("live", "live_transitions", transitions=["L'Go 1"]),
        prop("deadlock", "deadlock_free"),
    ])
    r, v = verdicts(tmp_path, LOOP, body)
    assert r.exploration.n_states == 3
    H, V = Status.HOLDS, Status.VIOLATED
    assert {k: x.status for k, x in v.items()} == {
        "terminates": V, "spin is a livelock": V, "progress": H, "eventually stops": V,
        "stops if Stop is fair": H, "fair Go is not enough": V, "can stop": H, "Go enabled again": V,
        "live": V, "deadlock": V, "Stop can end it": V, "Go never ends it": H, "after Go only Back": H,
        "Spin always stays": V}
    spin = v["Spin always stays"].evidence  # the counterexample is the Spin step, not the Go step
    assert spin.path == (0, 0) and r.engine.format_binding_element(spin.arcs[0]) == "L'Spin 1: {}"
    spin = v["spin is a livelock"].evidence
    assert spin.path == (0,) and spin.cycle == (0,)  # the Spin self-loop at the initial marking
    fair_go = v["fair Go is not enough"].evidence
    assert fair_go.cycle and fair_go.cycle[-1] == fair_go.path[-1]


def test_module_places_sum_and_quantifiers(tmp_path):
    body = "".join([
        prop("all idle at first", "reachable", expr="forall Slave'Idle (fn m => size m = 1)"),
        prop("both busy", "reachable", expr="size (sum Slave'Busy) = 2"),
        prop("someone idle", "invariant", expr="exists Slave'Idle (fn m => size m = 1)"),
        prop("ASK-CTL spelling", "invariant", expr="size (Mark.Slave'Idle 1) + size (Mark.Slave'Busy 1) = 1"),
        prop("each busy at most once", "bound", place="Slave'Busy", upper=1, lower=0),
        prop("home", "home", initial=True),
    ])
    r, v = verdicts(tmp_path, SLAVES, body)
    assert r.exploration.n_states == 4
    st = {k: x.status for k, x in v.items()}
    assert st == {"all idle at first": Status.HOLDS, "both busy": Status.HOLDS, "someone idle": Status.VIOLATED,
                  "ASK-CTL spelling": Status.HOLDS, "each busy at most once": Status.HOLDS, "home": Status.HOLDS}
    assert path_len(v["all idle at first"]) == 0
    assert path_len(v["someone idle"]) == 2


def test_partial_state_space_is_never_holds(tmp_path):
    body = "".join([
        prop("one token", "invariant", expr="size (C'P 1) = 1"),
        prop("three", "reachable", expr="C'P 1 = (1`3)"),
        prop("no deadlock", "deadlock_free"),
        prop("one dead", "dead_markings", count=1),
        prop("bound", "bound", place="C'P 1", upper=1),
        prop("bound exceeded", "bound", expr="ms_to_col (C'P 1)", upper=0),
        prop("none dead", "dead_transitions", expected=[]),
        prop("live", "live_transitions"),
        prop("home", "home"),
        prop("terminates", "no_livelock"),
        prop("ctl", "ctl", formula="AG (size (C'P 1) = 1)"),
    ])
    r, v = verdicts(tmp_path, COUNTER, body, max_states=2)
    assert not r.exploration.complete
    assert all(x.status is not Status.HOLDS for k, x in v.items()), {k: x.status for k, x in v.items()}
    assert v["bound exceeded"].status is Status.VIOLATED  # a violation found in a partial graph is real
    assert v["one token"].status is Status.UNKNOWN and "max_states" in v["one token"].message


@pytest.mark.parametrize("stop", [False, True])
def test_on_the_fly_finds_the_same_violation_as_the_full_graph(tmp_path, stop):
    body = f"[explore]\nstop_at_first_violation = {'true' if stop else 'false'}\n" + "".join([
        prop("never two", "invariant", expr="C'P 1 <> (1`2)"),
        # the same predicate read through 'enabled' is decided on the finished graph
        prop("never two (graph)", "invariant", expr="C'P 1 <> (1`2) orelse enabled \"C'Inc 9\" = false andalso false"),
    ])
    # 'C'Inc 9' does not exist: use a real name so that the text is valid
    body = body.replace("C'Inc 9", "C'Inc 1")
    r, v = verdicts(tmp_path, COUNTER, body)
    assert v["never two"].status is Status.VIOLATED
    assert v["never two"].evidence.path == (0, 1, 2)
    if stop:
        assert not r.exploration.complete
    else:
        assert v["never two (graph)"].evidence.path == v["never two"].evidence.path


def test_the_clock_in_a_property(tmp_path):
    timed = """net T;
colset U = unit timed;
place A : U = 1`();
place B : U;
trans Go;
arc A -> Go;
arc Go -> B : () @+ 5;
trans Back;
arc B -> Back;
"""
    body = prop("late", "reachable", expr="intTime () >= 5") + prop("early", "invariant", expr="intTime () < 5")
    r, v = verdicts(tmp_path, timed, body)
    assert v["late"].status is Status.HOLDS and v["early"].status is Status.VIOLATED
    assert len(v["early"].evidence.path) - 1 == 2  # Go at 0, Back at 5


def test_a_place_named_by_a_string(tmp_path):
    net = 'net Q;\ncolset U = unit;\nplace "to send" : U = 2`();\nplace sent : U;\ntrans go;\narc "to send" -> go;\n' \
          'arc go -> sent;\n'
    body = prop("conserved", "invariant", expr="size (Mark \"Q'to send\" 1) + size (Q'sent 1) = 2")
    r, v = verdicts(tmp_path, net, body)
    assert v["conserved"].status is Status.HOLDS


def test_a_place_read_inside_a_let_declaration_is_read_in_every_marking(tmp_path):
    # the memo key of a predicate is the places it reads: a read inside `let val` must count too
    body = "".join([
        prop("let read", "invariant", expr="let val x = ms_to_col (C'P 1) in x <= 0 end"),
        prop("fun read", "invariant", expr="let fun f () = ms_to_col (C'P 1) in f () <= 2 end"),
        prop("let read holds", "invariant", expr="let val x = ms_to_col (C'P 1) in x <= 3 end"),
    ])
    _, v = verdicts(tmp_path, COUNTER, body)
    assert v["let read"].status is Status.VIOLATED and path_len(v["let read"]) == 1
    assert v["fun read"].status is Status.VIOLATED and path_len(v["fun read"]) == 3
    assert v["let read holds"].status is Status.HOLDS
