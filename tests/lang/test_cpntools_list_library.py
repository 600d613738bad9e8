"""CPN Tools' list library as it defines it (cpntools.org, "List color sets": `union l1 l2 = l1 ^^ l2`,
`intersect` and `listsub` match each element once, `remdupl` keeps the last occurrence), its `filter`, and
`empty` beside a list, which is `[]` (CPN Tools' multisets are lists). docs/cpnml.md, "Library"."""

from __future__ import annotations

import pytest

import cpn
from cpn.errors import EvaluationError

DECLS = """colset INT = int;
colset IL = list INT;
var x : INT;
"""


def marking_after_one_step(text: str) -> str:
    e = cpn.loads(DECLS + text, "t.cpnet").engine()
    [(_be, s1)] = list(e.successors(e.initial_state()))
    return e.format_marking(s1, 1)


@pytest.mark.parametrize("value, expected", [
    ("union [1, 2] [2, 3]", "1`[1,2,2,3]"),
    ("intersect [1, 1, 2] [1, 3]", "1`[1]"),
    ("remdupl [1, 2, 3, 2, 4, 2, 5, 3]", "1`[1,4,2,5,3]"),
    ("rmall 3 [1, 2, 3, 4, 3, 5]", "1`[1,2,4,5]"),
    ("listsub [1, 2, 3, 2] [2, 3]", "1`[1,2]"),
    ("if contains_all [1, 2, 3] [3, 2] andalso not (contains_all [1, 2, 3] [3, 2, 3]) "
     "andalso contains [1, 2, 3] [3, 2, 3] then [1] else [0]", "1`[1]"),
    ("filter (fn y => y > 1) [3, 1, 2]", "1`[3,2]"),
    ("filter (fn y => y > 1) (1`3 ++ 1`1)", "1`[3]"),
    ("(app (fn y => ignore y) [1, 2]; [5])", "1`[5]"),
])
def test_list_functions_as_cpn_tools_defines_them(value, expected):
    text = f"place P : INT = 1`0; place Q : IL; trans T; arc P -> T : x; arc T -> Q : {value};"
    assert marking_after_one_step(text) == expected


def test_listsub_of_an_element_the_list_has_not_is_a_run_time_error():
    text = "place P : INT = 1`0; place Q : IL; trans T; arc P -> T : x; arc T -> Q : listsub [1] [2];"
    e = cpn.loads(DECLS + text, "t.cpnet").engine()
    with pytest.raises(EvaluationError) as info:
        list(e.successors(e.initial_state()))
    assert "Subtract" in str(info.value)


@pytest.mark.parametrize("body", [
    "if l = [] then empty else hd l :: drop1 (tl l)",
    "if l <> [] then hd l :: drop1 (tl l) else empty",
    "case l of [] => [] | h :: t => if h = 1 then drop1 t else h :: drop1 t",
    "case l of h :: t => if h = 1 then drop1 t else h :: drop1 t | _ => empty",
    "case l of [] => empty | h :: t => if h = 1 then drop1 t else h :: drop1 t",
])
def test_empty_beside_a_list_is_the_empty_list(body):
    text = (f"fun drop1 (l : IL) = {body};\n"
            "place P : INT = 1`0; place Q : IL; trans T; arc P -> T : x; arc T -> Q : drop1 [2, 3];")
    assert marking_after_one_step(text) == "1`[2,3]"
