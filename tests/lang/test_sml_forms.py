"""Standard ML forms that CPN Tools models use: typed expressions `e : ty` without parentheses, `let in e
end` without declarations (docs/cpnml.md)."""

from __future__ import annotations

import pytest

import cpn
from cpn.errors import ModelError
from cpn.expr import pretty
from cpn.lang import pretty as lang_pretty
from cpn.lang.parser import parse

DECLS = """colset C = int with 0..3;
colset L = list C;
colset R = record a : C * b : L;
var x : C;
"""


@pytest.mark.parametrize("text, expected", [
    ("[] : L", "([] : L)"),
    ("{a = 1, b = [] : L} : R", "({a = 1, b = ([] : L)} : R)"),
    ("x :: [] : L", "((x :: []) : L)"),
    ("x + 1 : int", "((x + 1) : int)"),
    ("a andalso b : bool", "(a andalso (b : bool))"),
    ("(x : C)", "(x : C)"),
])
def test_a_typed_expression_binds_looser_than_infix_operators(text, expected):
    [decl] = parse(f"val v = {text};", "t.cpnet").decls
    assert pretty.expr(decl.expr) == expected


def test_typed_expressions_and_an_empty_let_load_and_run():
    text = DECLS + """val e = [] : L;
val r = {a = 1, b = [] : L} : R;
fun f (y : C) = let in (y + 1) mod 4 : int end;
place P : C = 1`0;
place Q : L = 1`e;
trans T [x < 3 andalso (x :: [] : L) <> []];
arc P -> T : x;
arc T -> P : f x : C;
arc Q <-> T : #b r;
"""
    e = cpn.loads(text, "t.cpnet").engine()
    s = e.initial_state()
    for _ in range(3):
        [(_be, s)] = list(e.successors(s))
    assert e.format_marking(s, 0) == "1`3" and list(e.successors(s)) == []


def test_a_missing_semicolon_before_a_statement_is_still_a_syntax_error_at_the_statement():
    # `val x = 1 place A : INT` would otherwise read as the typed application `(1 place A) : INT`
    with pytest.raises(ModelError) as info:
        cpn.loads("colset INT = int;\nval x = 1\nplace A : INT;\n", "t.cpnet")
    [d] = info.value.diagnostics
    assert (d.code, d.span.line, d.span.col) == ("E0101", 3, 1)


def test_val_wildcard_is_checked_and_evaluated_and_names_nothing():
    model = cpn.loads(DECLS + "val _ = 1 + 2;\nval _ : int = 4;\nval n = 2;\nplace P : C = 1`n;\n", "t.cpnet")
    assert model.net.places[0].initial == {2: 1}
    assert "val _ = (1 + 2);" in lang_pretty.pretty(parse("val _ = 1 + 2;", "t.cpnet"))
    with pytest.raises(ModelError) as info:
        cpn.loads(DECLS + "val _ = 1 div 0;\nval _ = true + 1;\n", "t.cpnet")
    assert [(d.code, d.span.line) for d in info.value.diagnostics] == [("E0401", 5), ("E0301", 6)]


def test_a_coefficient_written_with_a_quote_hints_at_the_backquote():
    with pytest.raises(ModelError) as info:
        cpn.loads(DECLS + "place P : C = 1'2;\n", "t.cpnet")
    [d] = info.value.diagnostics
    assert d.code == "E0101" and "n`e" in d.hint and (d.span.line, d.span.col) == (5, 16)
