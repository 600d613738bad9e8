"""The compiled engine against the reference interpreter on `++` of two lists where a list is expected (list
append, as in CPN Tools, docs/cpnml.md) beside `++` of two lists read as a multiset of lists."""

import cpn
from tests.engine.test_differential import _compare

MODEL = """
colset C = int with 0..2;
colset L = list C;
var l : L;
var x : C;
fun keep (m : L) = m;
fun grow (m : L, y : C) = let val m = m ++ [y] in keep m end;
fun pair (m : L) = m ++ [0];
place P : L = 1`[] ++ 1`[1];
place Q : C = 1`0 ++ 1`2;
place R : L;
trans T [length l < 3];
arc P -> T : l;
arc Q -> T : x;
arc T -> P : grow (l, x);
arc T -> Q : x;
arc T -> R : pair l;
"""


def test_engines_agree_on_plus_of_lists():
    model = cpn.loads(MODEL, "plus_on_lists.cpnet")
    _compare(model, condensation=False, limit=200)


def test_plus_of_lists_appends_in_both_engines():
    for reference in (False, True):
        e = cpn.loads(MODEL, "plus_on_lists.cpnet").engine(reference=reference)
        s0 = e.initial_state()
        succ = [s for _, s in e.successors(s0)]
        seen = {e.format_marking(s, 0) for s in succ}
        # [1] grows to [1, 0] or [1, 2] (appended at the end); `pair l`, asked for as no list, is the multiset
        # of the two lists l and [0] on R
        assert "1`[]++1`[1,0]" in seen and "1`[]++1`[1,2]" in seen, seen
        assert {e.format_marking(s, 2) for s in succ} == {"1`[0]++1`[1]", "1`[]++1`[0]"}
