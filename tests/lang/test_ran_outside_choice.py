"""`CS.ran()` is a choice of every value where it is called in an output arc inscription or a transition
delay; anywhere else (a function body, a guard, an input arc, an initial marking) it would be one random
draw, and `lint` says so (it passed `lint` and stopped `explore` with E0401 before)."""

from __future__ import annotations

import pytest

import cpn
from cpn.errors import ModelError

NET = """colset C = int with 0..3;
colset U = unit;
var x : C;
{decl}
place P : U = 1`();
place Q : C;
trans T{guard};
arc P -> T : ();
arc T -> Q : {out};
"""


@pytest.mark.parametrize("decl, guard, out, line", [
    ("fun pick () = C.ran ();", "", "pick ()", 4),
    ("", " [C.ran () = 1]", "1", 7),
    ("val v = C.ran ();", "", "v", 4),
])
def test_ran_where_it_would_be_one_draw_is_refused_by_the_front_end(decl, guard, out, line):
    with pytest.raises(ModelError) as info:
        cpn.loads(NET.format(decl=decl, guard=guard, out=out), "t.cpnet")
    [d] = info.value.diagnostics
    assert d.code == "E0206" and "'C.ran()' draws a random value here" in d.message and d.span.line == line


def test_ran_in_an_output_arc_is_a_choice_of_every_value():
    e = cpn.loads(NET.format(decl="", guard="", out="C.ran ()"), "t.cpnet").engine()
    assert len(list(e.successors(e.initial_state()))) == 4
