"""SML's `datatype`, as CPN Tools models declare it in their ML declarations: a union colour set when every
constructor's argument is a colour set (or int, string, bool, unit), else one error at the argument
(docs/cpnml.md)."""

from __future__ import annotations

import pytest

import cpn
from cpn.errors import ModelError
from cpn.io.cpntools import translate_text

MODEL = """colset INT = int with 0..9;
datatype Msg = Ping | Data of int | Slot of INT;
var m : Msg;
fun v Ping = 0 | v (Data n) = n | v (Slot n) = n + 1;
place P : Msg = 1`Ping ++ 1`(Data 3) ++ 1`(Slot 4);
place Q : INT;
trans T;
arc P -> T : m;
arc T -> Q : v m;
"""


def test_a_datatype_is_a_union_colour_set():
    e = cpn.loads(MODEL, "t.cpnet").engine()
    got = sorted(e.format_marking(s, 1) for _be, s in e.successors(e.initial_state()))
    assert got == ["1`0", "1`3", "1`5"]


@pytest.mark.parametrize("decl, col", [("datatype T = A of int * int | B;", 19), ("datatype T = A | N of T;", 1),
                                       ("datatype T = A of INT list;", 19)])
def test_an_argument_that_is_no_colour_set_is_one_error_with_a_hint(decl, col):
    with pytest.raises(ModelError) as info:
        cpn.loads(decl + "\n", "t.cpnet")
    [d] = info.value.diagnostics
    assert (d.code, d.span.line, d.span.col) == ("E0206", 1, col)
    assert "product" in d.hint


CPN = """<?xml version="1.0" encoding="iso-8859-1"?>
<workspaceElements><cpnet>
<globbox>
<color id="c1"><id>INT</id><int/></color>
<ml id="m1">datatype Sig = Go | Stop</ml>
<color id="c2"><id>S</id><alias><id>Sig</id></alias></color>
<var id="v1"><type><id>S</id></type><id>s</id></var>
</globbox>
<page id="pg"><pageattr name="Top"/>
<place id="p1"><text>P</text><type><text>S</text></type><initmark><text>1`Go</text></initmark></place>
<trans id="t1"><text>T</text><cond><text>[s = Go]</text></cond></trans>
<arc id="a1" orientation="PtoT"><transend idref="t1"/><placeend idref="p1"/><annot><text>s</text></annot></arc>
<arc id="a2" orientation="TtoP"><transend idref="t1"/><placeend idref="p1"/><annot><text>Stop</text></annot></arc>
</page>
<instances><instance id="i1" page="pg"/></instances>
</cpnet></workspaceElements>
"""


def test_a_datatype_in_a_cpn_file_is_kept_where_the_net_uses_its_constructors():
    text = translate_text(CPN).text
    assert "datatype Sig = Go | Stop" in text
    e = cpn.loads(text, "t.cpnet").engine()
    [(_be, s1)] = list(e.successors(e.initial_state()))
    assert e.format_marking(s1, 0) == "1`Stop"
