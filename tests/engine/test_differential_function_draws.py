"""The compiled engine against the reference interpreter on draws explored as a choice of every value where
they are made inside functions of the model (tests/lang/test_function_draws.py), and on time intervals."""

import pytest

import cpn
from tests.engine.test_differential import _compare

CASES = {
    # discrete, bernoulli and CS.ran() in functions, through another function, in a delay and on output arcs
    "function_draws": """
colset C = int with 0..4 timed;
colset D = int with 1..2;
colset B = bool;
var x : C;
fun step () = discrete (1, 2);
fun coin () = if bernoulli 0.5 = 1 then true else B.ran ();
fun next y = if coin () then (y + step ()) mod 5 else (y + D.ran ()) mod 5;
place P : C = 1`0;
place Flags : B;
trans T [x < 4] @+ step ();
arc P -> T : x;
arc T -> P : next x;
arc T -> Flags : coin ();
trans Drain;
arc Flags -> Drain : true;
""",
    # curried, several clauses, a let that draws, and a time interval on the same transition
    "clauses_let_interval": """
colset C = int with 0..3 timed;
var x : C;
fun bump 0 k = k | bump n k = let val p = discrete (0, 1) in (n + k + p) mod 4 end;
place P : C = 1`0 ++ 1`1;
trans T [x < 3] @+[0, 1];
arc P -> T : x;
arc T -> P : bump x 1 @+[1, 2];
""",
}


@pytest.mark.parametrize("name", sorted(CASES))
def test_engines_agree(name):
    model = cpn.loads(CASES[name], f"{name}.cpnet")
    assert not [w for w in model.warnings if w.code == "W0105"]  # every draw is a choice
    _compare(model, condensation=False, limit=80)
    _compare(model, condensation=True, limit=80)
