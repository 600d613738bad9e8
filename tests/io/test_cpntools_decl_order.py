"""Globbox declarations that name a value declared further down (the XPDL converter appends
`val startDate = ...` below the functions that use it): CPN Tools checks declarations by dependency, so the
declaration is read after the one it needs. A name declared above too keeps the order as written."""

from __future__ import annotations

import pytest

import cpn
from cpn.errors import ModelError
from cpn.io.cpntools import translate_text
from tests.io.test_cpntools import DECLS, cpn_xml, page, place


def _model(decls: str) -> str:
    return cpn_xml(DECLS + decls, page("PG1", "Top", place("P1", "A", "INT", "1`(shifted 4)")))


def test_a_function_using_a_value_declared_below_loads(tmp_path):
    decls = ('<block id="B1"><id>Functions</id><ml id="M2">fun shifted n = n + start</ml></block>'
             '<ml id="M3">val start = 10;</ml>')
    model = tmp_path / "m.cpn"
    model.write_text(_model(decls))
    assert cpn.load(str(model)).net.places[0].initial == {14: 1}
    text = translate_text(_model(decls)).text
    assert text.index("val start = 10;") < text.index("fun shifted n")


def test_a_name_declared_above_and_below_keeps_the_order(tmp_path):
    decls = ('<ml id="M2">val start = 1;</ml><ml id="M3">fun shifted n = n + start</ml>'
             '<ml id="M4">val start = 10;</ml>')
    text = translate_text(_model(decls)).text
    assert text.index("fun shifted n") < text.index("val start = 10;")
    model = tmp_path / "m.cpn"
    model.write_text(_model(decls))
    assert cpn.load(str(model)).net.places[0].initial == {5: 1}


def test_a_name_bound_inside_the_declaration_is_not_a_forward_reference():
    decls = ('<ml id="M2">fun shifted n = let val start = 2 in n + start end</ml>'
             '<ml id="M3">val start = 10;</ml>')
    text = translate_text(_model(decls)).text
    assert text.index("fun shifted n") < text.index("val start = 10;")


def test_a_name_declared_nowhere_is_still_an_error(tmp_path):
    model = tmp_path / "m.cpn"
    model.write_text(_model('<ml id="M2">fun shifted n = n + start</ml>'))
    with pytest.raises(ModelError) as exc:
        cpn.load(str(model))
    assert "start" in str(exc.value)


def test_a_library_name_redeclared_below_is_the_library_one_above(tmp_path):
    decls = ('<ml id="M2">fun shifted n = n + length (filter (fn x => x > 1) [1, 2, 3])</ml>'
             '<ml id="M3">fun filter p (l : INT list) = if p 0 then l else l;</ml>')
    text = translate_text(_model(decls)).text
    assert text.index("fun shifted n") < text.index("fun filter")
    model = tmp_path / "m.cpn"
    model.write_text(_model(decls))
    assert cpn.load(str(model)).net.places[0].initial == {6: 1}
