"""Families of module instances: `instance Slave[i : 1..MAXS] = Slave(me = i) { ... };` is the MAXS
declarations `instance Slave1 = Slave(me = 1) { ... };` ... written out, with the bound a constant that
--set changes; errors at the family's position; the canonical text round trip."""

import pytest

import cpn
from cpn.errors import ModelError
from cpn.lang import ast as A
from cpn.lang.parser import parse
from cpn.lang.pretty import pretty
from tests.engine._explore import graph

HEAD = """
net Ring;
val N = 4;
colset INT = int;
colset K = int with 1..N;
colset COL = with red | green | blue;
var x : INT;
place go : INT = 1`1;
place done : INT;
module Stage(me : K) {
  port io Tok : INT;
  port out Out : INT;
  place Seen : INT;
  trans pass [x = me];
  arc Tok -> pass : x;
  arc pass -> Tok : if me < N then 1`(x + 1) else empty;
  arc pass -> Out : if me = N then 1`x else empty;
  arc pass -> Seen : me * 10;
}
"""

FAMILY = HEAD + "instance Stage[i : 1..N] = Stage(me = i) { Tok = go, Out = done };\n"


def written_out(n: int) -> str:
    return HEAD + "".join(f"instance Stage{k} = Stage(me = {k}) {{ Tok = go, Out = done }};\n"
                          for k in range(1, n + 1))


def shape(model):
    """What the flattened net is made of: place and transition instances with their initial markings and
    parameter values, and the state space (every marking with its binding elements and successors)."""
    net = model.net
    places = [(p.name, sorted(p.initial.items())) for p in net.places]
    trans = [(t.name, sorted(t.params.values())) for t in net.transitions]
    return places, trans, graph(model.engine())


def instance_names(model):
    return [pi.decl.name for pi in model.net.instances if pi.decl is not None]


def errors(text, **sets):
    with pytest.raises(ModelError) as info:
        cpn.loads(text, "fam.cpnet", set=sets or None)
    return [d for d in info.value.diagnostics if d.severity.name == "ERROR"]


def test_a_family_is_its_members_written_out():
    fam = cpn.loads(FAMILY, "fam.cpnet")
    assert instance_names(fam) == ["Stage1", "Stage2", "Stage3", "Stage4"]
    assert shape(fam) == shape(cpn.loads(written_out(4), "out.cpnet"))
    assert [t.name for t in fam.net.transitions] == [f"Stage'pass {k}" for k in range(1, 5)]


def test_the_bound_follows_set():
    fam = cpn.loads(FAMILY, "fam.cpnet", set={"N": "7"})
    assert instance_names(fam)[-1] == "Stage7" and len(instance_names(fam)) == 7
    assert shape(fam) == shape(cpn.loads(written_out(7), "out.cpnet", set={"N": "7"}))


def test_a_family_over_a_colour_set_and_inside_a_module():
    text = HEAD.replace("net Ring;", "") + """
module Leaf(c : COL) { place p : COL = 1`c; }
module Mid { instance Leaf[c : COL] = Leaf(c = c); }
instance Mid = Mid;
instance Stage[k : K] = Stage(me = k) { Tok = go, Out = done };
"""
    model = cpn.loads(text, "fam.cpnet", set={"N": "2"})
    assert instance_names(model) == ["Mid", "Leafred", "Leafgreen", "Leafblue", "Stage1", "Stage2"]
    leaf = {p.name: {p.colour_set.format(v): n for v, n in p.initial.items()}
            for p in model.net.places if p.page == "Leaf"}
    assert leaf == {"Leaf'p 1": {"red": 1}, "Leaf'p 2": {"green": 1}, "Leaf'p 3": {"blue": 1}}


def test_the_variable_is_bound_in_the_arguments_only():
    fam = cpn.loads(FAMILY.replace("Stage(me = i)", "Stage(me = N + 1 - i)"), "fam.cpnet")
    seen = {t.name: list(t.params.values()) for t in fam.net.transitions}
    assert seen == {"Stage'pass 1": [4], "Stage'pass 2": [3], "Stage'pass 3": [2], "Stage'pass 4": [1]}


def test_an_empty_range_is_an_error_at_the_family():
    assert instance_names(cpn.loads(FAMILY, "fam.cpnet", set={"N": "1"})) == ["Stage1"]
    found = [d for d in errors(FAMILY.replace("1..N]", "N..1 - 1]")) if d.code == "E0204"]
    assert len(found) == 1
    assert "has no instance: 4..0 is empty" in found[0].message
    assert (found[0].span.line, found[0].span.col) == (FAMILY.count("\n"), 20)
    assert found[0].hint


def test_a_bound_that_is_not_a_constant():
    text = HEAD + """
module Leaf(me : INT) { place p : INT = 1`me; }
module Mid(n : INT) { instance Leaf[i : 1..n] = Leaf(me = i); }
instance Mid = Mid(n = N);
"""
    (e,) = errors(text)
    assert e.code == "E0204" and "is not a constant: 'n' is a parameter of module 'Mid'" in e.message
    assert (e.span.line, e.span.col) == (text.count("\n") - 1, 44)
    assert "val" in e.hint


def test_a_bound_that_is_not_an_integer():
    (e,) = errors(FAMILY.replace("1..N]", "1..true]"))
    assert e.code == "E0301" and "upper bound of the family 'Stage[i : 1..true]'" in e.message


def test_a_member_clashing_with_another_instance():
    text = FAMILY.replace("instance Stage[", "instance Stage3 = Stage(me = 3) { Tok = go };\ninstance Stage[")
    (e,) = errors(text)
    assert e.code == "E0202" and "instance 'Stage3' is declared twice" in e.message
    assert "i = 3 of the family 'Stage'" in e.message
    assert e.notes == [f"first declared as the instance at {text.count(chr(10)) - 1}:10"]


def test_two_families_clash():
    text = FAMILY + "instance Stage[j : 4..5] = Stage(me = j - 3);\n"
    (e,) = errors(text)
    assert e.code == "E0202" and "'Stage4'" in e.message and "j = 4" in e.message
    assert "the instance i = 4 of the family 'Stage'" in e.notes[0]


def test_a_value_that_makes_no_name():
    (e,) = [d for d in errors(FAMILY.replace("1..N]", "~1..N]")) if d.code == "E0204"]
    assert "the value ~1" in e.message and "'Stage~1'" in e.message


def test_unknown_module_and_parameter_are_reported_once():
    found = errors(FAMILY.replace("Stage(me = i)", "Stage(mee = i)"))
    assert [d.code for d in found] == ["E0204", "E0204"]  # no parameter 'mee'; 'me' not given: once each


def test_parse_and_canonical_text_round_trip():
    decls = parse(FAMILY + "instance T[k : K] = Stage(me = k);\n", "fam.cpnet").decls
    fam = [d for d in decls if isinstance(d, A.InstanceFamilyDecl)]
    assert [(d.name, d.var, d.colset) for d in fam] == [("Stage", "i", None), ("T", "k", "K")]
    text = pretty(A.Model("fam.cpnet", FAMILY, decls))
    assert "instance Stage[i : 1..N] = Stage(me = i) { Tok = go, Out = done };" in text
    assert "instance T[k : K] = Stage(me = k);" in text
    assert pretty(parse(text, "again.cpnet")) == text
    again = pretty(A.Model("fam.cpnet", FAMILY, parse(FAMILY, "fam.cpnet").decls))
    assert shape(cpn.loads(again, "again.cpnet")) == shape(cpn.loads(written_out(4), "out.cpnet"))


@pytest.mark.parametrize("text", ["instance S[i] = Stage(me = i);", "instance S[i : 1..] = Stage(me = i);"])
def test_a_malformed_family_says_how_it_is_written(text):
    with pytest.raises(ModelError) as info:
        parse(text, "fam.cpnet")
    (d,) = info.value.diagnostics
    assert d.code == "E0101" and "instance NAME[i : LOW..HIGH]" in d.message
    assert (d.span.line, d.span.col) == (1, text.index("]") + 1) and "1..MAXS" in d.hint
