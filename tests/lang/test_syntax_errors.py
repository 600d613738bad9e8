"""The syntax error table tests itself, and malformed models get their code and position."""

import pytest

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
