"""Names outside ASCII: a place or transition name is hinted to be quoted (which works), any other name to be
renamed."""

import pytest

import cpn
from cpn.errors import ModelError
from cpn.lang.parser import parse


def _error(text: str, name: str = "m.cpnet") -> ModelError:
    with pytest.raises(ModelError) as info:
        parse(text, name)
    return info.value


def test_a_place_name_outside_ascii_is_hinted_to_be_quoted_and_quoted_it_loads():
    model = "net U;\ncolset C = int with 0..2;\nplace {n} : C = 1`0;\ntrans T;\narc {n} -> T : 0;\n"
    err = _error(model.format(n="Überlauf"))
    assert [d.span.line for d in err.diagnostics] == [3, 5]
    for d in err.diagnostics:
        assert "'Ü'" in d.message
        assert '"Überlauf"' in d.hint and "Remove it" not in d.hint
    m = cpn.loads(model.format(n='"Überlauf"'), "u.cpnet")
    assert [p.name for p in m.net.places] == ["U'Überlauf 1"]


def test_a_colour_set_name_outside_ascii_is_hinted_to_be_renamed_not_quoted():
    d = _error("net V;\ncolset Zähler = int with 0..2;\n").diagnostics[0]
    assert "rename 'Zähler'" in d.hint and "'Zahler'" in d.hint
    assert '"Zähler"' not in d.hint


def test_a_string_in_an_expression_is_not_taken_for_a_quoted_name():
    """`x = größe` parses once quoted, as a string: quoting is no fix for a variable's name."""
    d = _error("net V;\ncolset C = int with 0..2;\nvar x : C;\nplace A : C;\ntrans T [x = größe];\n").diagnostics[0]
    assert "rename 'größe'" in d.hint
