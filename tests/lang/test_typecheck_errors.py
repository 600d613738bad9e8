"""Name and type errors: each malformed model gets its code and position, never a traceback; an unknown colour
set is reported once, and a failed declaration causes no follow-on errors."""

import pytest

import cpn
from cpn.errors import ConfigurationError, ModelError

HEAD = "colset INT5 = int with 0..5;\ncolset U = unit;\nvar x : INT5;\n"

CASES = [
    # (body after HEAD, code, line, col)
    ("var y : Int5;", "E0201", 4, 9),
    ("place A : INT5 = 1`x2;", "E0201", 4, 20),
    ("place A : INT5;\nplace A : INT5;", "E0202", 5, 7),
    ("place A : INT5;\nplace B : INT5;\ntrans t;\narc A -> B : x;", "E0203", 7, 1),
    ('place A : INT5 = 1`"a";', "E0301", 4, 18),
    ("place A : INT5;\ntrans t;\narc A -> t : x;\narc t -> A : x + 1;\ntrans u [y > 1];", "E0201", 8, 10),
    ("colset I = int;\nvar y : I;\nplace A : INT5;\nplace B : I;\ntrans t;\narc A -> t : x;\narc t -> B : y;",
     "E0302", 10, 14),
    ("place A : INT5 = 1`12;", "E0303", 4, 18),
    ("place A : INT5;\ntrans t [x];\narc A -> t : x;", "E0301", 5, 10),
    ("module M() { place P : INT5; }\ninstance I = N();", "E0201", 5, 14),
    ("module M(k : INT5) { place P : INT5; }\ninstance I = M();", "E0204", 5, 1),
    ("place A : INT5;\ntrans t;\nreset t -> A;", "E0203", 6, 1),
    ("fun f 0 = 1 | g n = 2;", "E0101", 4, 1),
    ("val v = hd [];\nval w = 1 div 0;", "E0401", 4, 9),
]


@pytest.mark.parametrize("body,code,line,col", CASES)
def test_error_code_and_position(body, code, line, col):
    with pytest.raises(ModelError) as info:
        cpn.loads(HEAD + body, "m.cpnet")
    d = info.value.errors[0]
    assert (d.code, d.span.line, d.span.col) == (code, line, col), info.value.render()


def test_all_errors_reported_in_one_run():
    src = HEAD + "var y : Nope;\nplace A : Nope2;\nval z = 1 + \"a\";\n"
    with pytest.raises(ModelError) as info:
        cpn.loads(src, "m.cpnet")
    assert [d.code for d in info.value.errors] == ["E0201", "E0201", "E0301"]


def test_did_you_mean_colour_set():
    with pytest.raises(ModelError) as info:
        cpn.loads("colset PH = int with 1..5;\nvar p : Ph;", "m.cpnet")
    assert "Did you mean 'PH'" in info.value.errors[0].hint


def test_unknown_override_is_reported():
    # a bad value given from outside the model is a usage error (exit 64), not a model error
    with pytest.raises(ConfigurationError) as info:
        cpn.loads("val N = 3;", "m.cpnet", set={"M": "4"})
    assert info.value.code == "E0305" and len(info.value.problems) == 1


def test_override_of_wrong_type():
    with pytest.raises(ConfigurationError) as info:
        cpn.loads("val N = 3;\ncolset C = int with 1..N;", "m.cpnet", set={"N": '"x"'})
    assert info.value.code == "E0305" and "expected an int for 'N'" in str(info.value)


def test_override_changes_colour_set():
    m = cpn.loads("val N = 3;\ncolset C = int with 1..N;\nplace P : C = C.all();", "m.cpnet", set={"N": 7})
    assert sum(m.net.places[0].initial.values()) == 7


def test_a_place_and_a_transition_may_share_a_name():
    m = cpn.loads(HEAD + "place Idle : U = 1`(); place Work : U; trans Work;\narc Idle -> Work;\n"
                  "arc Work -> Work;".replace("arc Work -> Work", "arc Work -> Idle"), "m.cpnet")
    assert [p.name for p in m.net.places] == ["Top'Idle 1", "Top'Work 1"]
    assert [t.name for t in m.net.transitions] == ["Top'Work 1"]
    assert [a.kind for a in m.net.transitions[0].arcs] == ["in", "out"]


def test_an_arc_between_two_ambiguous_names_is_an_error():
    with pytest.raises(ModelError) as info:
        cpn.loads(HEAD + "place A : U; trans A; place B : U; trans B;\narc A -> B;", "m.cpnet")
    assert info.value.errors[0].code == "E0203"


def test_delay_on_an_untimed_initial_marking_is_an_error():
    with pytest.raises(ModelError) as info:
        cpn.loads(HEAD + "place P : INT5 = 1`1 @+ 3;", "m.cpnet")
    assert info.value.errors[0].code == "E0301"


def test_fusion_members_with_different_initial_markings():
    with pytest.raises(ModelError) as info:
        cpn.loads(HEAD + "place A : INT5 = 1`1 fusion F;\nplace B : INT5 = 1`0 fusion F;", "m.cpnet")
    assert info.value.errors[0].code == "E0205"
    m = cpn.loads(HEAD + "place A : INT5 = 1`1 fusion F;\nplace B : INT5 = 1`1 fusion F;", "m.cpnet")
    assert m.net.places[0].aliases == ["Top'B 1"]


def _diags(src: str, **kw):
    with pytest.raises(ModelError) as info:
        cpn.loads(src, "m.cpnet", **kw)
    return info.value.diagnostics


def test_one_unknown_colour_set_is_reported_once():
    src = """colset S = int with 0..3;
colset P2 = product Foo * S;
var x : Foo;
var y : S;
place P : Foo = 1`1;
place Q : P2;
trans T [x < 3];
arc P -> T : x;
arc T -> Q : (x, y);
"""
    [d] = _diags(src)
    assert (d.code, d.span.line, d.params["name"]) == ("E0201", 2, "Foo")
    assert d.notes == ["also used at 3:9, 5:11"]


def test_a_failed_declaration_causes_no_follow_on_errors():
    [d] = _diags("val N = abc;\ncolset S = int with 0..N;\nvar x : S;\nplace P : S = S.all();\ntrans T [x < N];\n"
                 "arc P -> T : x;\n")
    assert (d.code, d.span.line, d.params["name"]) == ("E0201", 1, "abc")
