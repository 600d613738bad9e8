"""Issue 16, item 2: lists where multisets are expected beyond the arc case, and multisets where lists are
expected (`List.map f (CS.all())`, `ms_to_list`, `List.tabulate`), as CPN Tools' multisets are lists."""

import pytest

import cpn
from cpn.lang.builtins import BUILTINS
from cpn.values.multiset import Multiset
from tests.regressions._issue_16 import figures, model_path


@pytest.mark.parametrize("name", ["lists.cpnet", "lists.cpn"])
@pytest.mark.parametrize("reference", [False, True])
def test_the_lists_model_has_its_hand_checked_figures(name, reference):
    # the 3 tokens of P move one by one: 8 states, 12 arcs, 1 dead marking
    assert figures(name, reference=reference) == (8, 12, 1)


@pytest.mark.parametrize("name", ["lists.cpnet", "lists.cpn"])
@pytest.mark.parametrize("reference", [False, True])
def test_the_initial_markings_made_of_lists(name, reference):
    e = cpn.load(model_path(name)).engine(reference=reference)
    s0 = e.initial_state()
    assert [e.format_marking(s0, p) for p in range(4)] == ["1`1++1`2++1`3", "1`5++1`6", "1`1++1`2", "empty"]
    [(_, s1), *_] = e.successors(s0)
    assert e.format_marking(s1, 3) == "2`2"


def test_ms_to_list_lists_each_element_as_often_as_it_occurs_in_colour_set_order():
    ms_to_list = BUILTINS["ms_to_list"][1]
    assert ms_to_list(Multiset([3, 1, 3, 2])) == (1, 2, 3, 3)
    # union values: a constant (its tag) and a constructor with an argument (tag, value) compare by tag
    assert ms_to_list(Multiset([(2, "b"), 1, (0, "a")])) == ((0, "a"), 1, (2, "b"))


@pytest.mark.parametrize("reference", [False, True])
def test_list_functions_take_a_multiset(reference):
    src = ("colset C = int with 1..4; var x : C;\n"
           "place P : C = 1`1;\n"
           "trans T [hd (C.all()) = 1, List.nth (ms_to_list (2`4 ++ 1`3), 1) = 4,\n"
           "         List.foldl (op +) 0 (1`2 ++ 1`3) = 5];\n"
           "arc P -> T : x;\n")
    e = cpn.loads(src, "m.cpnet").engine(reference=reference)
    assert len(e.successors(e.initial_state())) == 1


def test_a_multiset_is_not_taken_where_a_list_of_lists_is_expected():
    # a multiset given to a function that expects a list of lists stays a type error (a list given to size,
    # ms_to_col or ms_to_list is a multiset, as in CPN Tools: tests/lang/test_cpntools_library.py)
    with pytest.raises(cpn.ModelError) as info:
        cpn.loads("colset C = int; val n = List.concat (1`1 ++ 1`2);", "m.cpnet")
    assert info.value.diagnostics[0].code == "E0301"
