"""A place and a transition may share a name (as in CPN Tools); an arc between the two says which end is
the place: `arc place X -> trans X`, `arc trans X -> place X` (docs/language.md)."""

from __future__ import annotations

import pytest

import cpn
from cpn.errors import ModelError
from cpn.lang import pretty
from cpn.lang.parser import parse

NET = """colset C = int with 0..3;
var x : C;
place job : C = 1`0;
place done : C;
trans job [x < 3];
{arcs}
"""


def test_arcs_between_a_place_and_a_transition_of_one_name():
    model = cpn.loads(NET.format(arcs="arc place job -> trans job : x;\narc trans job -> place job : x + 1;\n"
                                      "arc job -> done : x;"), "t.cpnet")
    e = model.engine()
    s = e.initial_state()
    seen = [e.format_marking(s, 0)]
    for _ in range(3):
        [(_be, s)] = list(e.successors(s))
        seen.append(e.format_marking(s, 0))
    assert seen == ["1`0", "1`1", "1`2", "1`3"]
    assert list(e.successors(s)) == []  # the guard x < 3


def test_without_the_kinds_the_arc_is_ambiguous_and_the_hint_says_how_to_write_it():
    with pytest.raises(ModelError) as info:
        cpn.loads(NET.format(arcs="arc job -> job : x;"), "t.cpnet")
    [d] = info.value.diagnostics
    assert d.code == "E0203" and "arc place job -> trans job" in d.hint


def test_a_kind_that_names_no_such_element_is_an_error():
    with pytest.raises(ModelError) as info:
        cpn.loads(NET.format(arcs="arc place done -> trans done : x;"), "t.cpnet")
    [d] = info.value.diagnostics
    assert d.code == "E0201" and "unknown transition 'done'" in d.message and "is a place" in d.message


def test_places_and_transitions_named_place_and_trans_still_read_bare():
    text = "colset U = unit;\nplace place : U = 1`();\ntrans trans;\narc place -> trans;\narc trans -> place;\n"
    model = cpn.loads(text, "t.cpnet")
    assert len(model.net.places) == 1 and len(model.net.transitions) == 1


def test_the_printer_keeps_the_kinds():
    model = parse(NET.format(arcs="arc trans job -> place job : x;"), "t.cpnet")
    assert "arc trans job -> place job : x;" in pretty.pretty(model)
