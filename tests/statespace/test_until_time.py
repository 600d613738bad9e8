"""`--until-time B`, a model-time bound: no state whose clock exceeds B is expanded."""

import json

import pytest

import cpn
from cpn.cli.main import main
from cpn.statespace.explore import Explorer
from cpn.statespace.options import ExploreOptions, StopReason
from tests._models import figures, model_path

BRANCHING = """colset U = unit timed;
place P : U = 1`();
place Q : U = 1`();
trans A @+ 3; arc P -> A : (); arc A -> P : ();
trans B @+ 7; arc Q -> B : (); arc B -> Q : ();
"""


@pytest.mark.parametrize("name", ["until.cpnet", "until.cpn"])
@pytest.mark.parametrize("reference", [False, True])
def test_the_until_model_has_its_hand_checked_figures(name, reference):
    # clocks 0, 0, 5, 10 expanded; the state at clock 15 is stored, not expanded: 5 states, 4 arcs
    assert figures(name, reference=reference, until_time=12) == (5, 4, 0)
    engine = cpn.load(model_path(name)).engine(reference=reference)
    x = Explorer(engine, ExploreOptions(until_time=12)).run()
    assert x.stop_reason is StopReason.UNTIL_TIME and not x.complete and x.unexpanded == 1
    assert engine.clock(x.graph.states[-1]) == 15


def _bounded_bfs(engine, bound):
    """States and arcs of the state space up to `bound`, by a plain BFS (the oracle)."""
    s0 = engine.initial_state()
    seen = {s0}
    todo = [s0]
    arcs = 0
    for s in todo:
        if engine.clock(s) > bound:
            continue
        for _be, t in engine.successors(s):
            arcs += 1
            if t not in seen:
                seen.add(t)
                todo.append(t)
    return seen, arcs


@pytest.mark.parametrize("reference", [False, True])
@pytest.mark.parametrize("bound", [0, 6, 10, 21])
def test_states_beyond_the_bound_are_stored_after_the_expanded_ones(reference, bound):
    engine = cpn.loads(BRANCHING, "b.cpnet").engine(reference=reference)
    x = Explorer(engine, ExploreOptions(until_time=bound, detect_time_growth=False)).run()
    g = x.graph
    seen, arcs = _bounded_bfs(cpn.loads(BRANCHING, "b.cpnet").engine(reference=reference), bound)
    assert (x.n_states, x.n_arcs) == (len(seen), arcs)
    assert all(engine.clock(g.states[i]) <= bound for i in range(g.expanded))
    assert x.unexpanded > 0
    assert all(engine.clock(g.states[i]) > bound for i in range(g.expanded, g.n_states))
    # every arc and every parent pointer names the right state after the renumbering
    for i in range(g.expanded):
        succ = {t for _be, t in engine.successors(g.states[i])}
        assert {g.states[d] for _be, d in g.out_arcs(i)} == succ
    for i in range(1, g.n_states):
        p = g.parent[i]
        assert 0 <= p < g.expanded and i in {d for _be, d in g.out_arcs(p)}
    assert all(g.state_id(s) == i for i, s in enumerate(g.states))


def test_a_bound_beyond_every_clock_leaves_the_state_space_complete():
    # P@0 -> (clock 0) Q@4 -> (clock 4) R@4: clocks 0, 0 and 4, all within 4
    src = ("colset U = unit timed; place P : U = 1`(); place Q : U; place R : U;\n"
           "trans T @+ 4; arc P -> T : (); arc T -> Q : (); trans S; arc Q -> S : (); arc S -> R : ();\n")
    x = Explorer(cpn.loads(src, "m.cpnet").engine(), ExploreOptions(until_time=4)).run()
    assert x.complete and (x.n_states, x.n_arcs) == (3, 2)


def test_the_command_line_labels_the_partial_result(tmp_path, capsys):
    out = tmp_path / "r.json"
    assert main(["explore", "-q", "--until-time", "12", "--json", str(out), model_path("until.cpnet")]) == 2
    text = capsys.readouterr().out
    assert "Status: Partial (stopped because the model-time bound until_time=12 was reached" in text
    data = json.loads(out.read_text())
    assert data["statespace"]["stop_reason"] == "until_time" and data["statespace"]["unexpanded"] == 1
    assert data["options"]["until_time"] == 12


def test_a_negative_bound_is_a_usage_error(capsys):
    assert main(["explore", "--until-time", "-1", model_path("until.cpnet")]) == 64


def test_an_untimed_model_is_noted(capsys):
    assert main(["explore", "--until-time", "3", model_path("records.cpnet")]) == 0
    assert "untimed" in capsys.readouterr().err


def _scenario(tmp_path, explore):
    path = tmp_path / "s.toml"
    path.write_text(f'model = "{model_path("until.cpnet")}"\n[explore]\n{explore}\n'
                    '[[property]]\nname = "one token"\nkind = "invariant"\nexpr = "size (Top\'P 1) = 1"\n',
                    encoding="utf-8")
    return str(path)


def test_a_scenario_file_bounds_model_time_in_its_explore_table(tmp_path, capsys):
    code = main(["check", "--reports", str(tmp_path / "r"), _scenario(tmp_path, "until_time = 12")])
    out = capsys.readouterr().out
    # the invariant holds on the 5 states up to time 12, but beyond lies more: unknown
    assert code == 2 and "unknown" in out
    data = json.loads(next((tmp_path / "r").rglob("*.json")).read_text())
    assert '"until_time"' in json.dumps(data)


def test_a_negative_bound_in_a_scenario_file_is_a_positioned_error(tmp_path, capsys):
    assert main(["check", "--reports", str(tmp_path / "r"), _scenario(tmp_path, "until_time = -1")]) == 65
    assert "s.toml:3:14: error[E0702]: 'until_time' must be a model time" in capsys.readouterr().err
