"""Library names CPN Tools models use: record colour sets' `CS.set_<field>`, `nil`, `substring`,
`String.tokens`, `String.isPrefix`/`isSuffix`/`isSubstring`, `explode`/`implode`, `List.partition`,
`sort`, `ListMergeSort.sort`, `CS.lt`; `ms_to_list`, `size` and `ms_to_col` of a list (docs/cpnml.md)."""

from __future__ import annotations

import pytest

import cpn
from cpn.errors import ModelError

DECLS = """colset INT = int;
colset STRING = string;
colset R = record a : INT * b : STRING;
colset SL = list STRING;
colset IL = list INT;
var x : INT;
var y : STRING;
"""


def marking_after_one_step(text: str) -> str:
    e = cpn.loads(DECLS + text, "t.cpnet").engine()
    [(_be, s1)] = list(e.successors(e.initial_state()))
    return e.format_marking(s1, 1)


@pytest.mark.parametrize("value, expected", [
    ('R.set_b {a = 1, b = "x"} "y"', '1`{a=1,b="y"}'),
    ('R.set_a (R.set_b {a = 1, b = "x"} "z") 7', '1`{a=7,b="z"}'),
])
def test_record_field_setters(value, expected):
    text = f'place P : INT = 1`0; place Q : R; trans T; arc P -> T : x; arc T -> Q : {value};'
    assert marking_after_one_step(text) == expected


@pytest.mark.parametrize("value, cs, expected", [
    ('String.tokens (fn c => c = #",") "a,b,,c"', "SL", '1`["a","b","c"]'),
    ('explode "ab"', "SL", '1`["a","b"]'),
    ('[implode ["a", "b"], substring ("hello", 1, 3)]', "SL", '1`["ab","ell"]'),
    ('#1 (List.partition (fn x => x > 1) [1, 2, 3])', "IL", "1`[2,3]"),
    ('#2 (List.partition (fn x => x > 1) [1, 2, 3])', "IL", "1`[1]"),
    ('if String.isPrefix "ab" "abc" andalso String.isSuffix "bc" "abc" andalso String.isSubstring "b" "abc" '
     'andalso not (String.isPrefix "c" "abc") then [1] else []', "IL", "1`[1]"),
    ("sort (fn (a, b) => a < b) [3, 1, 2]", "IL", "1`[1,2,3]"),
    ("ListMergeSort.sort (fn (a, b) => a > b) [3, 1, 2]", "IL", "1`[1,2,3]"),
    ("sort INT.lt [2, ~1, 0]", "IL", "1`[~1,0,2]"),
    ('sort STRING.lt ["b", "a"]', "SL", '1`["a","b"]'),
    ("ms_to_list [2, 0, 2]", "IL", "1`[2,0,2]"),
    ("ms_to_list (1`2 ++ 1`0 ++ 1`2)", "IL", "1`[0,2,2]"),
    ("[size [1, 1, 2], ms_to_col [3]]", "IL", "1`[3,3]"),
    ("case nil : IL of nil => [1] | _ => [2]", "IL", "1`[1]"),
    ("case [3] of nil => [1] | _ => [2]", "IL", "1`[2]"),
])
def test_basis_functions(value, cs, expected):
    text = f"place P : INT = 1`0; place Q : {cs}; trans T; arc P -> T : x; arc T -> Q : {value};"
    assert marking_after_one_step(text) == expected


def test_a_setter_of_a_field_the_record_has_not_is_unknown_with_a_hint():
    with pytest.raises(ModelError) as info:
        cpn.loads(DECLS + "val r = R.set_c {a = 1, b = \"x\"} 2;", "t.cpnet")
    [d] = info.value.diagnostics
    assert d.code == "E0201" and "R.set_c" in d.message and "R.set_" in (d.hint or "")


def test_a_setter_of_a_colour_set_that_is_no_record_is_unknown():
    with pytest.raises(ModelError) as info:
        cpn.loads(DECLS + "val r = INT.set_a 1 2;", "t.cpnet")
    assert [d.code for d in info.value.diagnostics] == ["E0201"]


def test_a_name_of_a_structure_nobody_declares_says_so():
    with pytest.raises(ModelError) as info:
        cpn.loads(DECLS + "val v = LA.typeEquals (1, 2);", "t.cpnet")
    [d] = info.value.diagnostics
    assert d.code == "E0201" and "'LA' is neither a structure of the CPN ML library nor declared" in d.hint
    with pytest.raises(ModelError) as info:
        cpn.loads(DECLS + "val v = List.zipp [1];", "t.cpnet")
    assert "not supported" in info.value.diagnostics[0].hint or "Did you mean" in info.value.diagnostics[0].hint
