"""Lists in the generated C (`ctables.ListDom`, `ccodegen`): tokens, variables, patterns (`x :: xs`, `[]`,
`[a, b]`), constants, literals, the library's list functions (with `fn` arguments as loops), model
functions returning records (expanded in place) and multisets (their terms inlined). The native search's
graph must be the Python search's own, with every transition in C (the engine expands no state)."""

import os

import pytest

import cpn
from cpn.statespace.store import packed_unavailable
from tests.statespace._native import both_searches, same_error, wholly_in_c

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(__file__)))
NATIVE = packed_unavailable()
pytestmark = pytest.mark.skipif(NATIVE is not None, reason=f"native code unavailable: {NATIVE}")
LISTS = os.path.join(ROOT, "tests", "statespace", "models", "lists_timed.cpnet")




def _same_error(model) -> str:
    """The error of the search of an untimed `model` wholly in C, the same as the Python search's."""
    wholly_in_c(model)
    return same_error(model)


@pytest.mark.parametrize("condensation", [False, True], ids=["timed", "condensed"])
def test_a_timed_net_of_lists_runs_wholly_in_c(condensation, fills):
    model = cpn.load(LISTS)
    wholly_in_c(model)
    c = both_searches(model.engine(time_condensation=condensation), model.engine(time_condensation=condensation))
    assert c.complete and c.n_states == 2244 and c.notes == [] and fills[0] == 0


def test_the_untimed_net_of_lists_runs_wholly_in_c():
    text = open(LISTS).read().replace(" timed;", ";")
    for delay in (" @+ k", " @+ total rest", " @+ (second (rev LIM) + hd LIM)"):
        text = text.replace(delay, "")
    model = cpn.loads(text, "lists.cpnet")
    assert not model.net.is_timed
    code, why = model.engine().native_code()
    assert code.left == {}
    c = both_searches(model.engine(), model.engine())
    assert c.n_states == 3000  # (its Got place grows without a bound)


def test_lists_of_equal_structure_share_one_domain():
    """`[]` of `int list` is one id whatever colour set holds it: the domain is the elements' structure."""
    text = ("colset INT = int; colset A = list INT; colset B = list INT; var a : A; var b : B;"
            " place P : A = 1`[]; place Q : B = 1`[1]; trans t [length a < 3 andalso a <> b];"
            " arc P -> t : a; arc Q -> t : b; arc t -> P : 1 :: a; arc t -> Q : b;")
    model = cpn.loads(text, "share.cpnet")
    code, why = model.engine().native_code()
    assert code.left == {} and code.layouts[0] is code.layouts[1]
    c = both_searches(model.engine(), model.engine())
    assert c.complete and c.n_states == 2  # ([], [1]), then ([1], [1]): 1 :: [] equals [1]


def test_an_empty_list_where_c_has_no_element_is_the_engines_error():
    """`hd []` in C hands the binding to the engine, which raises SML's exception as the Python search does."""
    text = ("colset INT = int; colset L = list INT; var l : L; place P : L = 1`[2, 1];"
            " trans t; arc P -> t : l; arc t -> P : tl l @ [hd (tl (tl l))];")
    assert "hd" in _same_error(cpn.loads(text, "hd.cpnet"))


def test_a_list_of_integers_beyond_64_bits_is_the_engines():
    """The engine makes a list C cannot hold (an element past 2^63): interned in C as a value of its own,
    whose reading hands the key back to the engine; the graphs agree."""
    text = ("colset INT = int; colset L = list INT; var l : L; var x : INT; place P : L = 1`[1];"
            " trans t [length l < 30]; arc P -> t : x :: l; arc t -> P : (x * 1000) :: x :: l;")
    model = cpn.loads(text, "big.cpnet")
    wholly_in_c(model)
    c = both_searches(model.engine(), model.engine())
    assert c.complete and c.n_states == 31
    assert any(abs(v) >= 1 << 63 for d in c.engine.marking(c.graph.states[-1]) for lst in d for v in lst)


RANGED = """
colset N = int with 0..3;
colset L = list N with 0..3;
colset P2 = product L * N;
colset LL = list L;
var x : N;
var l : L;
var ls : LL;
place P : P2 = 1`([], 0);
place Q : LL = 1`[[1], []];
trans push [length l < 3];
arc P -> push : (l, x);
arc push -> P : (x :: l, (x + 1) mod 4);
trans pop;
arc P -> pop : (x :: l, 3);
arc pop -> P : (l, x);
trans mix [length ls < 3];
arc Q -> mix : ls;
arc mix -> Q : [2] :: ls;
"""


def test_lists_with_ranges_are_checked_in_c(fills):
    """A list colour set with a length range and a ranged element type (alone, in a product, in a list of
    lists): every transition in C, its tokens checked against the ranges; the Python search's graph."""
    model = cpn.loads(RANGED, "ranged.cpnet")
    wholly_in_c(model)
    c = both_searches(model.engine(), model.engine())
    assert c.complete and c.n_states == 8  # 4 markings of P (its list grows to 3), 2 of Q


@pytest.mark.parametrize("bad", ["(x + 1) :: l", "x :: x :: l"], ids=["element", "length"])
def test_a_list_outside_its_ranges_is_the_engines_error(bad):
    """A produced list with an element outside `N`, or longer than `L` allows: C hands the binding element
    to the engine, which reports the token outside its colour set as the Python search does."""
    text = RANGED.replace("(x :: l, (x + 1) mod 4)", f"({bad}, (x + 1) mod 4)")
    assert "colour set" in _same_error(cpn.loads(text, "outside.cpnet"))
