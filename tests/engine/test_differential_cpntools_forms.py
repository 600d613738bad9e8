"""The compiled engine against the reference interpreter on the forms of CPN ML and of nets that CPN Tools
models use and that the front end accepts as CPN Tools does (docs/cpntools.md, docs/cpnml.md)."""

import pytest

import cpn
from tests.engine.test_differential import _compare

CASES = {
    # a transition delay whose only output place is untimed: accepted, without effect (W0102); in a timed net
    "delay_untimed_outputs": """
colset C = int with 0..3;
colset TC = int with 0..3 timed;
var x : C;
place P : C = 1`0;
place Q : TC = 1`1;
trans T [x < 3] @+ 7;
arc P -> T : x;
arc T -> P : (x + 1) mod 4;
trans U @+ 2;
arc Q -> U : x;
arc U -> Q : (x + 1) mod 4;
""",
    # `n`e` at CPN Tools' precedence (infix 8) and a multiset consed onto: ``x :: 1`((x+1) mod 4)`` is two tokens
    "backquote_infix8": """
colset C = int with 0..3;
var x, y : C;
place P : C = 1`0;
place Q : C;
trans T [x < 2];
arc P -> T : x;
arc T -> P : 1`(x+1);
arc T -> Q : x :: 1`((x+1) mod 4) @ 2`y;
trans U;
arc Q -> U : 2`y;
""",
    # a place and a transition that share a name, the arcs saying which end is which
    "shared_names": """
colset C = int with 0..3;
var x : C;
place job : C = 1`0 ++ 1`2;
place done : C;
trans job [x < 3];
arc place job -> trans job : x;
arc trans job -> place job : x + 1;
arc trans job -> place done : x;
inhibitor place done -> trans job : 2`2;
""",
    # typed expressions without parentheses, an empty let
    "typed_and_empty_let": """
colset C = int with 0..3;
colset L = list C;
var x : C;
val none = [] : L;
fun next (y : C) = let in (y + 1) mod 4 : C end;
place P : C = 1`0 ++ 1`1;
place Q : L = 1`none;
trans T [x < 3 andalso (x :: [] : L) <> none];
arc P -> T : x;
arc T -> P : next x : C;
arc Q -> T : none;
arc T -> Q : x :: none : L;
""",
    # record field setters, nil, List.partition, String.tokens, substring, sort and CS.lt
    "library": """
colset C = int with 0..3;
colset S = string;
colset R = record n : C * s : S;
colset CL = list C;
var r : R;
var x : C;
fun bump (q : R) = R.set_n q ((#n q + 1) mod 4);
fun parts nil = 0 | parts (l : CL) = length (#1 (List.partition (fn v => v > 1) (ListMergeSort.sort (fn (a, b) => a > b) l)));
place P : R = 1`{n = 0, s = "a,b"};
place Q : CL = 1`[];
trans T [#n r < 3];
arc P -> T : r;
arc T -> P : R.set_s (bump r) (substring (#s r ^ "xy", 0, 3 - size [x] + 1));
arc Q -> T : nil;
arc T -> Q : sort C.lt [#n r, length (String.tokens (fn c => c = #",") (#s r)), parts [#n r, 2]];
trans U;
arc Q -> U : ms_to_list [x, 1, 2];
arc U -> Q : nil;
""",
    # CPN Tools 4's time intervals on a transition and on an output arc: one binding element per delay
    "time_intervals": """
colset C = int with 0..3 timed;
colset U = unit timed;
var x : C;
val HI = 2;
place P : C = 1`0;
place Q : U = 1`();
place R : C;
trans T [x < 3] @+[1, HI];
arc P -> T : x;
arc T -> P : x + 1;
arc T -> R : x @+[0, 1];
trans V [x < 2];
arc Q -> V : ();
arc R -> V : x;
arc V -> Q : () @+[1, 3];
""",
    # discrete and bernoulli explored as a choice of every value (W0104), in a delay and on an output arc
    "finite_draws": """
colset C = int with 0..5 timed;
var x : C;
place P : C = 1`0;
trans T [x < 3] @+ discrete(0, 1);
arc P -> T : x;
arc T -> P : x + bernoulli(0.5) + 1;
""",
    # '@+' at CPN Tools' level (infix 7): each branch of an `if` its own delay, on an arc and in a function (an
    # `if` with delays in the then-branch of another), and `e1 + e2 @+ d` at the top of an inscription
    "delays_per_branch": """
colset B = bool;
colset C = int with 0..3 timed;
colset U = unit;
var b : B;
var x : C;
fun pick (b, x) = if b then if x < 2 then 1`x @+ 0 else 1`(x - 1) @+ 1 else 1`((x + 1) mod 4) @+ 2;
place P : C = 1`0;
place Q : C;
place Go : U = 3`();
trans T;
arc Go -> T : ();
arc P -> T : x;
arc T -> Q : if b then 1`x @+ 2 else 1`((x + 1) mod 4) @+ 3;
arc T -> P : pick (b, x);
trans R;
arc Q -> R : x;
arc R -> P : if x < 3 then x + 1 @+ 1 else 0 @+ 4;
""",
}


@pytest.mark.parametrize("name", sorted(CASES))
def test_engines_agree(name):
    model = cpn.loads(CASES[name], f"{name}.cpnet")
    _compare(model, condensation=False, limit=80)
    if model.net.is_timed and not model.engine().reads_clock:
        _compare(model, condensation=True, limit=80)


def test_delays_per_branch_explore_alike_in_c_and_python():
    """The per-branch delays of "delays_per_branch" in the native search and the Python one: the same graph."""
    from cpn.statespace import ExploreOptions, Explorer
    from cpn.statespace.store import packed_unavailable
    from tests.engine._explore import same_exploration

    if packed_unavailable() is not None:
        pytest.skip(f"native code unavailable: {packed_unavailable()}")
    model = cpn.loads(CASES["delays_per_branch"], "delays_per_branch.cpnet")
    c = Explorer(model.engine(), ExploreOptions(backend="c", max_states=5000)).run()
    py = Explorer(model.engine(), ExploreOptions(backend="python", max_states=5000, packed_states=False)).run()
    same_exploration(c, py)
    stamps = {py.engine.format_marking(s, 1) for s in py.graph.states}
    # the first occurrence of T with b = true puts 1`0 on Q at 2, with b = false 1`1 at 3
    assert {"1`0@2", "1`1@3"} <= stamps
