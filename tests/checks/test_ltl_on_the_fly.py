"""`kind = "ltl"` in a scenario is decided on the fly: the product with the automaton is built as the
markings are generated and the search stops at the first accepting cycle, before the state space is
explored; the lasso's prefix is the shortest path in the product to the cycle found."""

from __future__ import annotations

import re

from cpn.checks.ltl import check_ltl
from cpn.checks.verdict import Status
from cpn.gate.run import run_scenario
from cpn.gate.scenario import loads_scenario
from tests.checks.test_ltl import Kripke
from tests.checks.test_traces import _replays

# a toggle (go, back) beside a counter that counts to 3,000: 6,002 markings
MODEL = """
colset U = unit;
colset N = int with 0..3000;
var n : N;
place A : U = 1`();
place B : U;
place C : N = 1`0;
trans go; arc A -> go; arc go -> B;
trans back; arc B -> back; arc back -> A;
trans inc [n < 3000]; arc C -> inc : n; arc inc -> C : n + 1;
"""
MOVES = '[[property]]\nname = "the counter moves"\nkind = "ltl"\nformula = "F (not (Top\'C 1 = 1`0))"\n'


def _run(tmp_path, body: str, **explore):
    (tmp_path / "m.cpnet").write_text(MODEL, encoding="utf-8")
    head = 'model = "m.cpnet"\n' + ("[explore]\n" + "".join(f"{k} = {v}\n" for k, v in explore.items())
                                    if explore else "")
    s = loads_scenario(head + body, str(tmp_path / "s.toml"))
    return run_scenario(s, s.runs[0])


def _generated(message: str) -> int:
    return int(re.search(r"on the fly: ([\d,]+) markings generated", message).group(1).replace(",", ""))


def test_the_violation_is_found_before_the_state_space_is_built(tmp_path):
    r = _run(tmp_path, MOVES, stop_at_first_violation="true")
    v = r.results[0].verdict
    assert v.status is Status.VIOLATED and "on the fly" in v.message
    assert _generated(v.message) <= 4  # toggling with the counter at 0: a cycle of two markings
    # the exploration stopped as soon as the lasso's markings were stored, far short of 6,002
    assert not r.exploration.complete and r.exploration.n_states < 100
    ev = v.evidence
    assert ev is not None and ev.path[0] == 0 and ev.cycle and ev.cycle[-1] == ev.path[-1]
    assert _replays(r.engine, r.exploration.graph, ev)


def test_on_the_whole_state_space_the_same_lasso_is_replayable(tmp_path):
    r = _run(tmp_path, MOVES)
    assert r.exploration.complete and r.exploration.n_states == 6002
    v = r.results[0].verdict
    assert v.status is Status.VIOLATED and _generated(v.message) <= 4
    assert _replays(r.engine, r.exploration.graph, v.evidence)


def test_a_formula_that_holds_is_decided_on_the_fly_too(tmp_path):
    body = '[[property]]\nname = "toggles"\nkind = "ltl"\nformula = "G (F (size (Top\'A 1) = 1))"\n' \
           'weak_fairness = ["Top\'go", "Top\'back"]\n'
    r = _run(tmp_path, body, max_states=10)  # the graph stops at 10 markings; the search needs them all
    v = r.results[0].verdict
    assert v.status is Status.UNKNOWN  # within 10 markings on the fly neither can decide
    r = _run(tmp_path, body)
    v = r.results[0].verdict
    assert v.status is Status.HOLDS and "on the fly" in v.message


def test_the_prefix_is_the_shortest_path_to_the_cycle_found():
    # depth first, the search walks 0 1 2 3 4 5 and finds the loop at 5; 5 is one step from 0
    k = Kripke({0: [1, 5], 1: [2], 2: [3], 3: [4], 4: [5], 5: [5]}, {s: set() for s in range(6)})
    res = check_ltl(k, ("F", ("ap", 0)), k.props(1))
    assert res.holds is False
    assert [s for _label, s in res.prefix] == [0, 5]
    assert [s for _label, s in res.cycle] == [5]


def test_the_cycle_is_entered_at_its_nearest_state():
    # the search reaches the cycle 3 -> 4 -> 5 -> 3 at 3 (through 1 and 2); 5 is one step from 0
    k = Kripke({0: [1, 5], 1: [2], 2: [3], 3: [4], 4: [5], 5: [3]}, {s: set() for s in range(6)})
    res = check_ltl(k, ("F", ("ap", 0)), k.props(1))
    prefix = [s for _label, s in res.prefix]
    cycle = [s for _label, s in res.cycle]
    assert prefix == [0, 5] and cycle == [3, 4, 5]
    assert [label for label, _s in res.cycle] == ["5->3", "3->4", "4->5"]
