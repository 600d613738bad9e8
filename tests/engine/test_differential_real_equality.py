"""The compiled engine against the reference interpreter on '=' and '<>' over reals (CPN Tools defines them
on every colour set): a real, a product holding one, and the list of such products that the fuel-station
models test with `q = []`."""

import pytest

import cpn
from tests.engine.test_differential import _compare

CASES = {
    "real_and_real_lists": """
colset C = int with 0..3;
colset R = real;
colset P = product C * R;
colset Q = list P;
var x : C;
var q : Q;
fun len (q : Q) = if q = [] then 0 else 1 + len (tl q);
place A : C = 1`0 ++ 1`2;
place B : Q = 1`[];
trans T [x < 3 andalso (if q = [] then 0.0 else #2 (hd q)) <> 1.5];
arc A -> T : x;
arc B -> T : q;
arc T -> A : (x + 1) mod 4;
arc T -> B : if len q < 2 then q ^^ [(x, real x * 0.5)] else q;
""",
}


@pytest.mark.parametrize("name", sorted(CASES))
def test_engines_agree(name):
    model = cpn.loads(CASES[name], f"{name}.cpnet")
    _compare(model, condensation=False, limit=80)
