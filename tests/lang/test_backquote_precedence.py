"""`n`e` at CPN Tools' precedence: `infix 8`, tighter than `* div mod`, `+ -`, `::` and `=`, looser than
application (docs/language.md). A multiset on either side of `::`, `@` or `^^` is the list of its elements,
as in CPN Tools, whose multisets are lists."""

from __future__ import annotations

import pytest

import cpn
from cpn.errors import ModelError
from cpn.expr import pretty
from cpn.lang.parser import parse


def grouped(expr: str) -> str:
    """The expression fully parenthesised as the parser groups it."""
    [decl] = parse(f"val v = {expr};", "t.cpnet").decls
    return pretty.expr(decl.expr)


@pytest.mark.parametrize("text, expected", [
    ("x :: 1`((x+1) mod 4)", "(x :: (1 ` ((x + 1) mod 4)))"),
    ("1`(x+1) mod 4", "((1 ` (x + 1)) mod 4)"),
    ("2`x + 1", "((2 ` x) + 1)"),
    ("2`x * 3", "((2 ` x) * 3)"),
    ("1`x = 1`y", "((1 ` x) = (1 ` y))"),
    ("1`f x", "(1 ` (f x))"),
    ("1`x ++ 2`y", "((1 ` x) ++ (2 ` y))"),
    ("n*2`x", "(n * (2 ` x))"),
])
def test_backquote_groups_as_in_cpn_tools(text, expected):
    assert grouped(text) == expected


NET = """colset C = int with 0..3;
var x : C;
place P : C = 1`0;
place Q : C;
trans T [x < 3];
arc P -> T : x;
arc T -> P : {out};
"""


def test_a_multiset_consed_onto_is_a_list_of_tokens():
    model = cpn.loads(NET.format(out="x :: 1`((x+1) mod 4)"), "t.cpnet")
    e = model.engine()
    s0 = e.initial_state()
    [(_be, s1)] = list(e.successors(s0))
    assert e.format_marking(s1, 0) == "1`0++1`1"


@pytest.mark.parametrize("out", ["1`(x+1) mod 4", "2`x + 1"])
def test_what_cpn_tools_refuses_is_a_type_error(out):
    with pytest.raises(ModelError) as info:
        cpn.loads(NET.format(out=out), "t.cpnet")
    assert [d.code for d in info.value.diagnostics] == ["E0301"]
