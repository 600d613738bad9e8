"""Lists where multisets are expected, on arcs and beyond, and multisets where lists are
expected (`List.map f (CS.all())`, `ms_to_list`, `List.tabulate`), as CPN Tools' multisets are lists."""

import pytest

import cpn
from cpn.errors import ModelError
from cpn.lang.builtins import BUILTINS
from cpn.values.multiset import Multiset
from tests._models import figures, model_path


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


def _diags(src: str, **kw):
    with pytest.raises(ModelError) as info:
        cpn.loads(src, "m.cpnet", **kw)
    return info.value.diagnostics


LISTS = """colset Worker = with w1 | w2;
colset Decision = with yes | no;
colset WorkerxDecision = product Worker * Decision;
colset WL = list WorkerxDecision;
var w : Worker;
var ws : WL;
fun decide w = [(w, yes), (w, no)];
place Idle : Worker = [w1, w2];
place Out : WorkerxDecision;
place Lists : WL = [(w1, yes)];
trans Decide;
arc Idle -> Decide : w;
arc Decide -> Out : decide w;
trans Collect;
arc Out -> Collect : [(w, yes), (w, no)];
arc Collect -> Idle : if w = w1 then [w] else [] ++ 1`w;
trans Keep;
arc Lists -> Keep : ws;
arc Keep -> Lists : ws;
"""


@pytest.mark.parametrize("reference", [False, True])
def test_a_list_of_colours_is_accepted_where_a_multiset_is_expected(reference):
    from cpn.statespace import Explorer

    e = cpn.loads(LISTS).engine(reference=reference)
    s0 = e.initial_state()
    # an initial marking given as a list; a place whose colour set is a list holds one list token
    assert (e.format_marking(s0, 0), e.format_marking(s0, 2)) == ("1`w1++1`w2", "1`[(w1,yes)]")
    succ = {e.format_binding_element(be): s for be, s in e.successors(s0)}
    assert e.format_marking(succ["Top'Decide 1: {w=w1}"], 1) == "1`(w1,yes)++1`(w1,no)"
    x = Explorer(e).run()
    assert (x.n_states, x.n_arcs, x.complete) == (4, 12, True)


def test_a_list_of_the_wrong_colour_is_still_a_type_error():
    [d] = _diags(LISTS.replace("arc Decide -> Out : decide w;", "arc Decide -> Out : [w];"))
    assert (d.code, d.span.line) == ("E0301", 13)


def test_a_list_of_colours_on_an_arc_of_a_cpn_file(tmp_path):
    from tests.io.test_cpntools import arc, cpn_xml, page, place, trans

    decls = ('<color id="C1"><id>Worker</id><enum><id>w1</id><id>w2</id></enum></color>'
             '<color id="C2"><id>Decision</id><enum><id>yes</id><id>no</id></enum></color>'
             '<color id="C3"><id>WorkerxDecision</id><product><id>Worker</id><id>Decision</id></product></color>'
             '<var id="V1"><type><id>Worker</id></type><id>w</id></var>'
             '<ml id="M1">fun decide w = [(w, yes), (w, no)]</ml>')
    body = (place("P1", "Idle", "Worker", "[w1]") + place("P2", "Out", "WorkerxDecision") + trans("T1", "Decide")
            + arc("A1", "PtoT", "T1", "P1", "w") + arc("A2", "TtoP", "T1", "P2", "decide w"))
    path = tmp_path / "lists.cpn"
    path.write_text(cpn_xml(decls, page("PG1", "Top", body)), encoding="iso-8859-1")
    e = cpn.load(path).engine()
    [(_, s1)] = e.successors(e.initial_state())
    assert e.format_marking(s1, 1) == "1`(w1,yes)++1`(w1,no)"


@pytest.mark.parametrize("reference", [False, True])
def test_a_list_of_colours_on_an_input_arc(reference):
    src = """colset W = with w1 | w2; colset D = with yes | no; colset WD = product W * D;
var w : W;
fun decide w = [(w, yes), (w, no)];
place Idle : W = [w1, w2];
place Out : WD = [(w1, yes), (w1, no), (w2, yes)];
place Done : W;
trans T;
arc Idle -> T : w;
arc Out -> T : decide w;
arc T -> Done : [w, w];
"""
    e = cpn.loads(src).engine(reference=reference)
    [(be, s1)] = e.successors(e.initial_state())
    assert e.format_binding_element(be) == "Top'T 1: {w=w1}"
    assert (e.format_marking(s1, 1), e.format_marking(s1, 2)) == ("1`(w2,yes)", "2`w1")
