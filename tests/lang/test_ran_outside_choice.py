"""`CS.ran()` is a choice of every value where it is called in an output arc inscription or a transition
delay; anywhere else (a function body, a guard, an input arc, an initial marking) it is one random draw:
`lint` warns (W0105), `simulate` draws it, `explore` and `check` refuse the model at the call (E0206)."""

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
    ("fun pick () = C.ran ();", " [pick () = 1]", "1", 4),  # in a guard (in an output arc: a choice)
    ("", " [C.ran () = 1]", "1", 7),
    ("val v = C.ran ();", "", "v", 4),
])
def test_ran_where_it_is_one_draw_is_simulated_and_refused_by_explore(decl, guard, out, line):
    model = cpn.loads(NET.format(decl=decl, guard=guard, out=out), "t.cpnet")
    [w] = model.warnings
    assert w.code == "W0105" and "'C.ran' draws a random value" in w.message and w.span.line == line
    with pytest.raises(ModelError) as info:
        model.engine()
    [d] = info.value.diagnostics
    assert d.code == "E0206" and "'C.ran' draws a random value" in d.message and d.span.line == line
    assert model.engine(simulation=True, reference=True) is not None


def test_ran_in_an_output_arc_is_a_choice_of_every_value():
    e = cpn.loads(NET.format(decl="", guard="", out="C.ran ()"), "t.cpnet").engine()
    assert len(list(e.successors(e.initial_state()))) == 4
