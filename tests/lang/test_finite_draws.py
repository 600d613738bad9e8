"""`discrete(a, b)` and `bernoulli(p)`, CPN Tools' random draws over finitely many integers, are explored as
a choice of every value where `CS.ran()` is one (an output arc inscription, a transition delay), with a
warning: our extension, as CPN Tools' state space tool cannot analyse random distribution functions."""

from __future__ import annotations

import pytest

import cpn
from cpn.errors import ModelError

DECLS = """colset C = int with 0..9;
colset TU = unit timed;
val HI = 3;
place P : TU = 1`();
place Q : C;
"""


def successors(text: str):
    model = cpn.loads(DECLS + text, "t.cpnet")
    e = model.engine()
    return model, list(e.successors(e.initial_state())), e


def test_every_value_of_the_draws_is_one_binding_element():
    model, succ, e = successors("trans T @+ discrete(1, 2);\narc P -> T : ();\n"
                                "arc T -> Q : discrete(0, HI) + bernoulli(0.5);")
    assert len(succ) == 2 * 4 * 2
    assert {e.format_marking(s, 1) for _, s in succ} == {f"1`{v}" for v in range(5)}
    assert [w.code for w in model.warnings] == ["W0104"] * 3


@pytest.mark.parametrize("p, values", [("0.0", {"1`0"}), ("1.0", {"1`1"}), ("0.3", {"1`0", "1`1"})])
def test_bernoulli_is_1_with_probability_p(p, values):
    _model, succ, e = successors(f"trans T;\narc P -> T : ();\narc T -> Q : bernoulli({p});")
    assert {e.format_marking(s, 1) for _, s in succ} == values


@pytest.mark.parametrize("text, line, col", [
    ("fun f () = discrete (1, 2);\ntrans T [f () = 1];\narc P -> T : ();", 6, 12),  # a function used in a guard
    ("trans T [discrete (0, 1) = 0];\narc P -> T : ();", 6, 10),
    ("var x : C;\ntrans T;\narc P -> T : ();\narc Q -> T : x;\narc T -> Q : discrete (x, 3);", 10, 14),
])
def test_a_draw_that_cannot_be_a_choice_is_simulated_and_one_error_of_explore(text, line, col):
    model = cpn.loads(DECLS + text, "t.cpnet")
    assert [(w.code, w.span.line, w.span.col) for w in model.warnings] == [("W0105", line, col)]
    with pytest.raises(ModelError) as info:
        model.engine()
    [d] = info.value.diagnostics
    assert d.code == "E0206" and "'discrete' draws a random value" in d.message
    assert (d.span.line, d.span.col) == (line, col)


def test_a_choice_without_a_value_is_an_error():
    with pytest.raises(ModelError) as info:
        cpn.loads(DECLS + "trans T;\narc P -> T : ();\narc T -> Q : discrete (3, 1);", "t.cpnet")
    errors = [d for d in info.value.diagnostics if d.severity.value == "error"]
    assert len(errors) == 1 and "has no value" in errors[0].message


def test_a_function_of_the_model_called_discrete_is_no_draw():
    _model, succ, e = successors("fun discrete (a, b) = a + b;\ntrans T;\narc P -> T : ();\n"
                                 "arc T -> Q : discrete (1, 2);")
    assert [e.format_marking(s, 1) for _, s in succ] == ["1`3"]
