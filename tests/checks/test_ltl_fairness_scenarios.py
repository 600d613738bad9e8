"""`kind = "ltl"` in scenario files: strong fairness (`strong_fairness`) on a net where weak fairness is not
enough, and its names checked against the net."""

from __future__ import annotations

import pytest

from cpn.checks.verdict import Status
from cpn.errors import ModelError
from cpn.gate.run import run_scenario
from cpn.gate.scenario import loads_scenario
from tests.checks.test_traces import _replays

# the token toggles between A and A2 forever; `go` (A -> B) is enabled in every other marking only
TOGGLE = ("colset U = unit; place A : U = 1`(); place A2 : U; place B : U;"
          " trans t1; trans t2; trans go; arc A -> t1; arc t1 -> A2; arc A2 -> t2; arc t2 -> A;"
          " arc A -> go; arc go -> B;")
F_B = "F (size (Top'B 1) = 1)"


def _verdicts(tmp_path, props: str, net: str = TOGGLE):
    (tmp_path / "m.cpnet").write_text(net, encoding="utf-8")
    s = loads_scenario('model = "m.cpnet"\n' + props, str(tmp_path / "s.toml"))
    r = run_scenario(s, s.runs[0], {})
    return r, {p.spec.name: p.verdict for p in r.results}


def _prop(name: str, formula: str, extra: str = "") -> str:
    return f'[[property]]\nname = "{name}"\nkind = "ltl"\nformula = "{formula}"\n{extra}'


def test_strong_fairness_where_weak_fairness_is_not_enough(tmp_path):
    r, by = _verdicts(tmp_path, _prop("plain", F_B) + _prop("weak", F_B, 'weak_fairness = ["Top\'go"]\n')
                      + _prop("strong", F_B, 'strong_fairness = ["Top\'go 1"]\n'))
    assert by["plain"].status is Status.VIOLATED
    weak = by["weak"]  # t1 t2 t1 t2 ...: go is enabled infinitely often, never continuously
    assert weak.status is Status.VIOLATED and weak.evidence.cycle
    assert _replays(r.engine, r.exploration.graph, weak.evidence)
    assert by["strong"].status is Status.HOLDS


def test_a_strongly_fair_violation_is_a_lasso_that_replays(tmp_path):
    # "G F A2" fails only by leaving the toggle: under strong fairness to go, by the path to B (dead)
    r, by = _verdicts(tmp_path, _prop("x", "G (F (size (Top'A2 1) = 1))", 'strong_fairness = ["Top\'go"]\n'))
    v = by["x"]
    assert v.status is Status.VIOLATED and "dead" in v.message
    assert _replays(r.engine, r.exploration.graph, v.evidence)


def test_a_strong_fairness_name_not_in_the_net_is_an_error_with_a_suggestion(tmp_path):
    with pytest.raises(ModelError) as err:
        _verdicts(tmp_path, _prop("x", F_B, 'strong_fairness = ["Top\'goo"]\n'))
    d = err.value.diagnostics[0]
    assert d.code == "E0703" and "Top'go" in (d.hint or "") and d.span.line == 6


def test_strong_fairness_must_be_a_list_of_names(tmp_path):
    with pytest.raises(ModelError) as err:
        _verdicts(tmp_path, _prop("x", F_B, 'strong_fairness = "Top\'go"\n'))
    assert "strong_fairness" in str(err.value.diagnostics[0].message)
