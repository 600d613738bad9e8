"""`engine.untimed(state)`: the state less its clock and its timestamps. Two states are equal there exactly
when their markings are equal once the timestamps are dropped (the time-growth watch and the dead-marking
count without timestamps rely on it), for the compiled engine and the reference interpreter alike."""

import pytest

import cpn
from cpn.statespace import ExploreOptions, Explorer

NET = """
colset N = int with 0..2 timed;
colset U = unit timed;
var x : N;
place P : N = 1`0 ++ (1`1@+2);
place Q : U = 1`();
trans step [x < 2] @+ 1;
arc P -> step : x;
arc step -> P : (x + 1) mod 3 @+ 3;
trans back;
arc Q -> back : ();
arc back -> Q : () @+ 2;
"""


def _plain(engine, s):
    """The state's markings without timestamps, compared as values."""
    out = []
    for p, d in enumerate(engine.marking(s)):
        counts: dict = {}
        for k, n in d.items():
            v = k[0] if engine.places[p].timed else k
            counts[v] = counts.get(v, 0) + n
        out.append(frozenset(counts.items()))
    return tuple(out)


@pytest.mark.parametrize("reference", [False, True], ids=["compiled", "reference"])
def test_equal_untimed_forms_are_equal_markings_without_timestamps(reference):
    engine = cpn.loads(NET, "t.cpnet").engine(reference=reference)
    states = list(Explorer(engine, ExploreOptions(max_states=400, backend="python")).run().graph.states)
    assert len(states) > 10
    forms = [engine.untimed(s) for s in states]
    plains = [_plain(engine, s) for s in states]
    pairs = [(i, j) for i in range(len(states)) for j in range(i + 1, len(states))]
    assert all((forms[i] == forms[j]) == (plains[i] == plains[j]) for i, j in pairs)
    # the timestamps do tell states apart that are the same without them
    assert len(set(forms)) < len(states)
    assert [engine.untimed(s) for s in states] == forms  # asked again: the same
