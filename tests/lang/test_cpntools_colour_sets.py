"""CPN Tools' colour sets `bool with (no, yes)` (the booleans, written no and yes) and
`string with "a".."z" and 3..9` (strings of those characters and lengths), in `.cpnet` and `.cpn` files
(docs/cpnml.md)."""

from __future__ import annotations

import pytest

import cpn
from cpn.errors import EvaluationError, ModelError
from cpn.io.cpntools import translate_text
from cpn.lang.parser import parse
from cpn.lang.pretty import pretty

MODEL = """colset Answer = bool with (no, yes);
colset Lower = string with "a".."z" and 1..3;
var a : Answer;
var s : Lower;
fun flip no = yes | flip yes = no;
place P : Answer = 1`no;
place Q : Lower = 1`"ab";
trans T [a = no andalso not a];
arc P -> T : a;
arc T -> P : flip a;
trans U;
arc Q -> U : s;
arc U -> Q : s ^ "c";
"""


def test_bool_with_names_is_the_booleans_written_with_those_names():
    e = cpn.loads(MODEL, "t.cpnet").engine()
    [(_be, s1), _] = sorted(e.successors(e.initial_state()), key=lambda x: str(x[0]))
    assert e.format_marking(s1, 0) == "1`yes"  # no is false: flip no = yes, and `not a` held


def test_a_string_outside_the_characters_or_lengths_is_outside_the_colour_set():
    grow = ('colset Lower = string with "a".."z" and 1..3;\nvar s : Lower;\nplace Q : Lower = 1`"ab";\n'
            'trans U;\narc Q -> U : s;\narc U -> Q : s ^ "c";\n')
    e = cpn.loads(grow, "t.cpnet").engine()
    [(_be, s1)] = list(e.successors(e.initial_state()))
    assert e.format_marking(s1, 0) == '1`"abc"'
    with pytest.raises(EvaluationError, match="outside its colour set Lower"):
        list(e.successors(s1))
    with pytest.raises(ModelError):  # a character outside a..z
        cpn.loads(grow.replace('1`"ab"', '1`"aB"'), "t.cpnet").engine()


@pytest.mark.parametrize("body", ['string with "a".."z" and 5..2', 'string with "z".."a"', 'string with "ab".."z"'])
def test_a_malformed_string_range_is_one_error(body):
    with pytest.raises(ModelError) as info:
        cpn.loads(f"colset S = {body};\n", "t.cpnet")
    assert [d.code for d in info.value.diagnostics] == ["E0304"]


def test_both_forms_print_as_written():
    text = pretty(parse(MODEL, "t.cpnet"))
    assert 'colset Answer = bool with (no, yes);' in text
    assert 'colset Lower = string with "a".."z" and 1..3;' in text


CPN = """<?xml version="1.0" encoding="iso-8859-1"?>
<workspaceElements><cpnet>
<globbox>
<color id="c1"><id>Answer</id><bool><with><id>no</id><id>yes</id></with></bool></color>
<color id="c2"><id>Small</id><string><with><ml>"a"</ml><ml>"d"</ml><and><ml>1</ml><ml>2</ml></and></with></string></color>
<var id="v1"><type><id>Small</id></type><id>s</id></var>
</globbox>
<page id="pg"><pageattr name="Top"/>
<place id="p1"><text>P</text><type><text>Small</text></type><initmark><text>1`"ab"</text></initmark></place>
<place id="p2"><text>Q</text><type><text>Answer</text></type></place>
<trans id="t1"><text>T</text></trans>
<arc id="a1" orientation="PtoT"><transend idref="t1"/><placeend idref="p1"/><annot><text>s</text></annot></arc>
<arc id="a2" orientation="TtoP"><transend idref="t1"/><placeend idref="p2"/><annot><text>yes</text></annot></arc>
</page>
<instances><instance id="i1" page="pg"/></instances>
</cpnet></workspaceElements>
"""


def test_the_cpn_elements_are_read():
    text = translate_text(CPN).text
    assert "colset Answer = bool with (no, yes);" in text
    assert 'colset Small = string with "a".."d" and 1..2;' in text
    e = cpn.loads(text, "t.cpnet").engine()
    [(_be, s1)] = list(e.successors(e.initial_state()))
    assert e.format_marking(s1, 1) == "1`yes"
