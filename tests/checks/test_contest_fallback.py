"""A contest formula whose on-the-fly search passes its budget (`ContestModel.fly_states`) is answered
over the whole state space instead (reachability by one pass over it, LTL by the product searched in
native code), and gives the published verdict either way."""

import json
import os

import pytest

from cpn.cli.mcc import ContestModel, answer_file
from cpn.statespace import graphnative
from tests._shared import needs_shared
from tests.checks.test_contest import VALIDATION

EXAMS = ("ReachabilityCardinality", "ReachabilityFireability", "LTLCardinality", "LTLFireability")


@needs_shared
@pytest.mark.parametrize("name", ["Philosophers-PT-000005", "Philosophers-COL-000005", "ERK-PT-000001"])
def test_past_the_budget_the_whole_state_space_answers(name, monkeypatch):
    folder = os.path.join(VALIDATION, name)
    if not os.path.isdir(folder):
        pytest.skip(f"{name} is not in the validation corpus")
    if graphnative.library() is None:
        pytest.skip("no native code here")
    monkeypatch.setattr(graphnative, "MIN_ITEMS", 0)
    products = []
    real = graphnative.ltl_accepting_cycle

    def counted(*a):
        got = real(*a)
        products.append(got)
        return got
    monkeypatch.setattr(graphnative, "ltl_accepting_cycle", counted)
    with open(os.path.join(folder, "formulas", "oracle.json"), encoding="utf-8") as fh:
        oracle = json.load(fh)["verdicts"]
    model = ContestModel.load(os.path.join(folder, "model.pnml"), max_states=10**6)
    model.fly_states = 2  # every search that needs more than 2 markings goes to the state space
    wrong = []
    for exam in EXAMS:
        for a in answer_file(model, os.path.join(folder, "formulas", f"{exam}.xml")):
            found = "TRUE" if a.value else "FALSE" if a.value is not None else None
            if found != oracle[exam][a.id]:
                wrong.append((a.id, oracle[exam][a.id], found))
    assert not wrong
    assert model._graph is not None  # the state space was built
    assert products and all(p is not None for p in products)  # LTL over it in native code


@needs_shared
def test_ctl_past_the_time_limit_cannot_compute_with_the_reason():
    import time

    folder = os.path.join(VALIDATION, "Philosophers-PT-000005")
    if not os.path.isdir(folder):
        pytest.skip("Philosophers-PT-000005 is not in the validation corpus")
    model = ContestModel.load(os.path.join(folder, "model.pnml"), max_states=10**6)
    model.graph()  # the state space is built within the limit
    model.deadline = time.monotonic() - 1  # then the time is up
    answers = answer_file(model, os.path.join(folder, "formulas", "CTLCardinality.xml"))
    labelled = [a for a in answers if a.reason and "labelling" in a.reason]
    assert labelled and all(a.value is None for a in labelled)
    assert all(a.value is None for a in answers)
