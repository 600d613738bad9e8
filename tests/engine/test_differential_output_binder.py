"""A guard conjunct `y = e` that binds variables read only by the output arcs and the delay (a CPN Tools
code segment's outputs, as `.cpn` files are translated): the finite draws of e are choices, made once and
read by every inscription; the compiled engine and the reference interpreter agree."""

from __future__ import annotations

import re

import pytest

import cpn
from cpn.errors import ModelError
from tests.engine.test_differential import _compare

HEAD = """colset S = int with 0..3;
colset T = int timed;
var x, y, z : S;
place A : S = 1`0 ++ 1`1;
place B : S;
place C : T;
"""


def _first_steps(model):
    e = model.engine()
    return [(e.format_binding_element(be), [e.format_marking(s, p.index) for p in e.places[1:]])
            for be, s in e.successors(e.initial_state())]


@pytest.mark.parametrize("body, count, c_of", [
    ("trans t [y = discrete (0, 3)] @+ y;\narc A -> t : x;\narc t -> B : y;\narc t -> C : y;", 8,
     lambda v: f"1`{v['y']}@{v['y']}"),
    ("trans t [x < 1, (y, z) = (discrete (0, 1), S.ran ())];\narc A -> t : x;\narc t -> B : y;"
     "\narc t -> C : z + y;", 8, lambda v: f"1`{v['z'] + v['y']}@0"),
    ("trans t [y = (x + discrete (0, 2)) mod 4];\narc A -> t : x;\narc t -> B : y;\narc t -> C : y @+ y;", 6,
     lambda v: f"1`{v['y']}@{v['y']}"),
])
def test_the_draws_of_an_output_binding_are_choices_made_once(body, count, c_of):
    model = cpn.loads(HEAD + body, "m.cpnet")
    steps = _first_steps(model)
    assert len(steps) == count and len({be for be, _ in steps}) == count
    for be, (b, c) in steps:
        v = {k: int(x) for k, x in re.findall(r"\b([xyz])=(\d+)", be)}
        assert (b, c) == (f"1`{v['y']}", c_of(v))
    _compare(model)


def test_a_draw_in_a_guard_that_binds_an_input_variable_stays_a_draw():
    text = HEAD + "trans t [y = discrete (0, 3)];\narc A -> t : x + y;\narc t -> B : y;"
    with pytest.raises(ModelError) as info:
        cpn.loads(text, "m.cpnet").engine()
    assert [d.code for d in info.value.diagnostics] == ["E0206"]


def test_a_draw_in_a_guard_read_by_another_conjunct_stays_a_draw():
    text = HEAD + "trans t [y = discrete (0, 3), y > 1];\narc A -> t : x;\narc t -> B : y;"
    with pytest.raises(ModelError) as info:
        cpn.loads(text, "m.cpnet").engine()
    assert [d.code for d in info.value.diagnostics] == ["E0206"]


def test_the_reference_still_tests_a_binding_conjunct_whose_pattern_a_token_bound():
    model = cpn.loads(HEAD + "trans t [(x, y) = (1, 2)];\narc A -> t : x;\narc t -> B : y;", "m.cpnet")
    assert [be for be, _ in _first_steps(model)] == ["Top't 1: {x=1, y=2}"]
    _compare(model)
