"""Issue 8, language items: delays into untimed places, lists as multisets, the reach of `@+`, byte-order
marks and invisible characters, `--set` values, follow-on errors, and suggestions."""

import pytest

import cpn
from cpn.errors import ModelError
from cpn.lang.parser import parse


def _diags(src: str, **kw):
    with pytest.raises(ModelError) as info:
        cpn.loads(src, "m.cpnet", **kw)
    return info.value.diagnostics


# ----------------------------------------------------------------------------- item 11


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


# ----------------------------------------------------------------------------- item 19


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


def test_a_closing_bracket_without_partner_still_closes_nothing():
    with pytest.raises(ModelError) as info:
        parse("val y = (1]);\n", "m.cpnet")
    [d] = info.value.diagnostics
    assert (d.span.line, d.span.col) == (1, 11) and "']' closes nothing" in d.message
