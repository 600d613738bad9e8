"""`++` on two lists where a list is expected: CPN Tools' multisets are lists (`type 'a ms = 'a list`) and its
`++` appends them, left operand first (`data ++ [x]` passed as a `string list`, as the XPDL converter's models
write it). Where the context does not ask for a list, `l1 ++ l2` keeps its reading as the multiset of the two
lists, so nothing that was accepted before changes meaning."""

import pytest

import cpn
from cpn.errors import ModelError

_BASE = """
colset S = string;
colset L = list S;
colset C = int with 0..1;
var c : C;
fun count (xs : string list) = length xs;
fun log (n : int, data : string list) = data;
fun twice (l : string list) = l ++ l;
"""
_DECLS = _BASE + """
fun addtwo (data : string list) = let val data = data ++ ["x", "y"] in log (0, data) end;
fun addmore (data : string list) = log (1, data ++ ["p"] ++ ["q", "r"]);
"""


def _enabled(guard: str, reference: bool, decls: str = _DECLS) -> bool:
    src = decls + f"place P : C = 1`0;\ntrans T [{guard}];\narc P -> T : c;\n"
    e = cpn.loads(src, "m.cpnet").engine(reference=reference)
    return len(e.successors(e.initial_state())) == 1


@pytest.mark.parametrize("reference", [False, True])
def test_plus_of_two_lists_passed_as_a_list_appends_left_operand_first(reference):
    assert _enabled('addtwo ["a", "b"] = ["a", "b", "x", "y"]', reference)
    assert not _enabled('addtwo ["a", "b"] = ["x", "y", "a", "b"]', reference)
    assert _enabled('addmore ["a"] = ["a", "p", "q", "r"]', reference)
    assert _enabled('count (["a"] ++ ["b", "c"]) = 3', reference)


def test_plus_of_two_lists_elsewhere_is_still_the_multiset_of_the_two_lists():
    # `twice l` is never asked for as a list: the multiset 2`l, two tokens of L
    src = _BASE + ('place P : L = 1`["a"];\nplace Q : L;\nvar l : L;\ntrans T;\narc P -> T : l;\n'
                    'arc T -> Q : twice l;\n')
    e = cpn.loads(src, "m.cpnet").engine()
    [(_, s1)] = e.successors(e.initial_state())
    assert e.format_marking(s1, 1) == '2`["a"]'


@pytest.mark.parametrize("reference", [False, True])
def test_a_list_of_lists_built_with_plus_keeps_its_meaning(reference):
    # `:: ` and `if` read `l1 ++ l2` as a multiset (then a list of its two lists), as before
    assert _enabled('length (["z"] :: (["a"] ++ ["b"])) = 3', reference, _BASE)
    assert _enabled('size (if c = 0 then ["a"] ++ ["b"] else 1`["c"]) = 2', reference, _BASE)
    assert _enabled('length (["a"] ++ ["b", "c"]) = 2 andalso size (["a"] ++ ["b"]) = 2', reference, _BASE)


def test_plus_of_lists_of_different_types_is_refused_with_its_position():
    with pytest.raises(ModelError) as info:
        cpn.loads(_BASE + 'val bad = count (["a"] ++ [1]);', "m.cpnet")
    d = info.value.diagnostics[0]
    assert d.code == "E0301" and "'++'" in d.message


@pytest.mark.parametrize("reference", [False, True])
def test_a_local_function_does_not_decide_the_enclosing_plus(reference):
    decls = _BASE + ('fun wrap (data : string list) = let val d = data ++ ["x"]; fun id y = y in log (2, id d) end;\n')
    assert _enabled('wrap ["a"] = ["a", "x"]', reference, decls)
