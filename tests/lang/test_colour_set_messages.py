"""A value outside a product colour set: the message shows the product and the component that is out."""

import pytest

import cpn
from cpn.errors import EvaluationError, ModelError
from cpn.statespace import Explorer

PRODUCT = """net P;
colset ID = int with 1..2;
colset NO = int with 0..3;
colset PEND = product ID * NO;
var i : ID;
var n : NO;
place A : PEND = {init};
place B : PEND;
trans T;
arc A -> T : (i, n);
arc T -> B : (i, n + {add});
"""


def test_a_token_outside_a_product_names_the_product_and_the_component():
    m = cpn.loads(PRODUCT.format(init="1`(1,0)", add=5), "p.cpnet")
    with pytest.raises(EvaluationError) as info:
        Explorer(m.engine()).run()
    err = info.value
    assert err.code == "E0402"
    assert "PEND = product ID * NO" in err.message
    assert "component 2, 5, is outside NO = int with 0..3" in err.message
    assert "PEND = PEND" not in err.render()


def test_an_initial_marking_outside_a_product_names_the_component():
    with pytest.raises(ModelError) as info:
        cpn.loads(PRODUCT.format(init="1`(3,0)", add=0), "p.cpnet")
    d = info.value.diagnostics[0]
    assert d.code == "E0303"
    assert "PEND = product ID * NO: its component 1, 3, is outside ID = int with 1..2" in d.message


def test_records_lists_and_unions_say_which_part_is_out():
    from cpn.values.colours import IntCS, ListCS, RecordCS, UnionCS, outside

    no = IntCS("NO", 0, 3)
    rec = RecordCS("R", [("seq", no), ("ack", no)])
    assert outside(rec, (1, 9)) == "R = record ack:NO * seq:NO: its field seq, 9, is outside NO = int with 0..3"
    assert outside(ListCS("L", no, 0, 2), (1, 2, 3)).endswith("its length 3 is outside 0..2")
    assert outside(ListCS("L", no), (1, 7)).endswith("its element 2, 7, is outside NO = int with 0..3")
    msg = UnionCS("M", [("Req", no), ("Idle", None)])
    assert outside(msg, (0, 4)) == "M = union Req:NO + Idle: the argument of Req, 4, is outside NO = int with 0..3"
