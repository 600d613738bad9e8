"""Branching options (a predicate on binding elements, a maximum number of successors
per state), reported as a restricted state space."""

import json

import pytest

import cpn
from cpn.cli.main import main
from cpn.statespace.explore import Explorer
from cpn.statespace.options import ExploreOptions
from tests._models import engine_figures, model_path


def _only(engine, name):
    t = next(i for i, tr in enumerate(engine.transitions) if tr.name == name)
    return lambda be: engine.binding_element(be).transition == t


@pytest.mark.parametrize("name", ["branching.cpnet", "branching.cpn"])
@pytest.mark.parametrize("reference", [False, True])
def test_the_branching_model_has_its_hand_checked_figures(name, reference):
    def space(**options):
        engine = cpn.load(model_path(name)).engine(reference=reference)
        if options.pop("move", False):
            options["branching_predicate"] = _only(engine, "Top'Move 1")
        return engine_figures(engine, **options)

    assert space() == (8, 24, 0)
    assert space(move=True) == (8, 12, 1)
    assert space(max_successors=1) == (5, 5, 0)
    assert space(move=True, max_successors=2) == (7, 9, 1)


@pytest.mark.parametrize("reference", [False, True])
def test_a_predicate_on_the_binding(reference):
    engine = cpn.load(model_path("branching.cpnet")).engine(reference=reference)
    # token 2 never moves: Q holds a subset of {1, 3}, each state has 2 arcs
    x = Explorer(engine, ExploreOptions(branching_predicate=lambda be: engine.binding_element(be).binding["x"] != 2)
                 ).run()
    assert (x.n_states, x.n_arcs) == (4, 8) and x.restricted and x.complete


@pytest.mark.parametrize("args,status", [
    (["--branch-transitions", "Move"], "Full; a restricted state space (branching options: only the binding "
                                       "elements of Top'Move 1)"),
    (["--max-successors", "1"], "Full; a restricted state space (branching options: at most 1 successor "
                                "per state)"),
])
def test_the_report_says_the_state_space_is_restricted(tmp_path, capsys, args, status):
    out = tmp_path / "r.json"
    assert main(["explore", *args, "--json", str(out), model_path("branching.cpn")]) == 2
    captured = capsys.readouterr()
    assert f"Status: {status}" in captured.out
    assert "restricted state space" in captured.err
    data = json.loads(out.read_text())["statespace"]
    assert data["restricted"] is True and data["restriction"] in status


def test_a_transition_name_the_model_lacks_is_a_usage_error(capsys):
    assert main(["explore", "--branch-transitions", "Mvoe", model_path("branching.cpnet")]) == 64
    assert "no transition 'Mvoe'" in capsys.readouterr().err
    assert main(["explore", "--max-successors", "0", model_path("branching.cpnet")]) == 64


def test_without_branching_options_nothing_is_restricted(tmp_path):
    out = tmp_path / "r.json"
    assert main(["explore", "-q", "--json", str(out), model_path("branching.cpnet")]) == 0
    data = json.loads(out.read_text())["statespace"]
    assert data["restricted"] is False and data["restriction"] is None
