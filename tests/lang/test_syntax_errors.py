"""The syntax error table tests itself, and malformed models get their code and position: an unclosed bracket
where it opens, an invisible character by its code point; a UTF-8 byte-order mark is accepted."""

import pytest

import cpn
from cpn.errors import ModelError
from cpn.lang.parser import parse
from cpn.lang.syntax_errors import SYNTAX_ERRORS

EXAMPLES = [(code, msg, ex) for code, msg, _hint, exs in SYNTAX_ERRORS for ex in exs]


@pytest.mark.parametrize("code,message,example", EXAMPLES)
def test_each_example_gives_its_message(code, message, example):
    with pytest.raises(ModelError) as info:
        parse(example, "ex.cpnet")
    d = info.value.diagnostics[0]
    assert d.code == code
    assert message in d.message


MALFORMED = [
    # (source, code, line, col)
    ("val x = 1\nplace A : INT;", "E0101", 2, 1),
    ("place A : INT = 1`1;\nplace B : INT\nplace C : INT;", "E0101", 3, 1),
    ('val s = "abc;\n', "E0102", 1, 9),
    ("val x = 3 $ 4;", "E0101", 1, 11),
    ("trans T [x = 1;", "E0101", 1, 9),
    ("arc A => T : x;", "E0101", 1, 7),
    ("colset C = product;", "E0101", 1, 19),
]


@pytest.mark.parametrize("src,code,line,col", MALFORMED)
def test_malformed_models(src, code, line, col):
    with pytest.raises(ModelError) as info:
        parse(src, "bad.cpnet")
    d = info.value.diagnostics[0]
    assert (d.code, d.span.line, d.span.col) == (code, line, col)


def test_every_syntax_error_of_a_file_in_one_run():
    src = "val a = ;\nval b = 2;\nval c = (1;\nplace P : INT\nplace Q : INT;\n"
    with pytest.raises(ModelError) as info:
        parse(src, "bad.cpnet")
    lines = [d.span.line for d in info.value.diagnostics]
    assert lines == sorted(lines)
    assert {1, 3, 5} <= set(lines)


def test_rendering_has_caret_and_hint():
    with pytest.raises(ModelError) as info:
        parse("val x = 1\nplace A : INT;", "m.cpnet")
    text = info.value.render()
    assert "m.cpnet:2:1: error[E0101]" in text
    assert "^^^^^" in text
    assert "hint:" in text


def test_a_utf8_byte_order_mark_is_accepted(tmp_path):
    path = tmp_path / "bom.cpnet"
    path.write_bytes(b"\xef\xbb\xbfcolset U = unit;\nplace P : U = 1`();\n")
    model = cpn.load(path)
    assert [p.name for p in model.net.places] == ["Top'P 1"]
    # also when the text is given directly
    assert cpn.loads("\ufeffcolset U = unit;\nplace P : U;\n").net.places[0].name == "Top'P 1"


def test_an_invisible_character_is_named_by_its_code_point():
    with pytest.raises(ModelError) as info:
        parse("colset U = unit;\nval a = 1\x00;\n", "m.cpnet")
    [d] = info.value.diagnostics
    assert (d.code, d.span.line, d.span.col) == ("E0101", 2, 10)
    assert "U+0000" in d.message and "''" not in d.message
    assert "\x00" not in info.value.render()


@pytest.mark.parametrize("src,line,col,opener", [
    ("colset S = int;\nvar x : S;\nplace P : S;\ntrans T [(x < 3];\narc P -> T : x;\n", 4, 10, "("),
    ("val z = [1, (2, 3]];\n", 1, 13, "("),
    ("val z = ([1, 2);\n", 1, 10, "["),
])
def test_an_unclosed_bracket_is_reported_where_it_opens(src, line, col, opener):
    with pytest.raises(ModelError) as info:
        parse(src, "m.cpnet")
    [d] = info.value.diagnostics
    assert (d.code, d.span.line, d.span.col) == ("E0101", line, col)
    assert f"'{opener}' is not closed" in d.message
    assert "closes nothing" not in d.message


def test_a_let_inside_brackets_over_lines_that_begin_with_val_is_one_statement():
    # the syntax error on line 1 is the only one: the action's `val` lines are inside its parentheses
    src = ("val x = if true 1 else 2;\ncolset U = unit; place P : U;\n"
           "trans T action (let\n  val a = 1;\n  val b = 2\nin\n  a + b\nend);\narc P -> T;\n")
    with pytest.raises(ModelError) as info:
        parse(src, "m.cpnet")
    assert [(d.code, d.span.line) for d in info.value.diagnostics] == [("E0101", 1)]
    # an unclosed bracket before a line that begins with `val` is still found where it opens
    with pytest.raises(ModelError) as info:
        parse("val z = (1, 2;\nval y = 3;\n", "m.cpnet")
    [d] = info.value.diagnostics
    assert (d.span.line, d.span.col) == (1, 9) and "'(' is never closed" in d.message


def test_a_closing_bracket_without_partner_still_closes_nothing():
    with pytest.raises(ModelError) as info:
        parse("val y = (1]);\n", "m.cpnet")
    [d] = info.value.diagnostics
    assert (d.span.line, d.span.col) == (1, 11) and "']' closes nothing" in d.message
