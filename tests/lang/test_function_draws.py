"""Finite draws (`discrete(a, b)` and `bernoulli(p)` with constant arguments, `CS.ran()`) inside a function of
the model: a call of the function with all its arguments in an output arc inscription or a transition delay is
written out there, so that each draw it makes is a choice of every value (one binding element per combination
of values, the product of its draws), as a draw written in the inscription is. A function that is recursive,
partially applied, called elsewhere (a guard, a `val`), or whose draw depends on its arguments keeps random
draws: simulated, refused by explore at the draw (docs/semantics.md)."""

from __future__ import annotations

import pytest

import cpn
from cpn.errors import ModelError

HEAD = """colset N = int with 0..9;
colset D = int with 1..3;
colset B = bool;
colset TU = unit timed;
var x : N;
place P : N = 1`0;
place Q : INT;
"""  # 7 lines: a declaration below starts on line 8


def load(text):
    return cpn.loads(HEAD + text, "f.cpnet")


def first_successors(model):
    e = model.engine()
    return e, e.successors(e.initial_state())


def test_a_function_that_draws_is_the_product_of_its_choices():
    model = load("fun pick () = discrete (1, 3);\nfun two y = y + pick () + 10 * D.ran ();\n"
                 "trans T;\narc P -> T : x;\narc T -> Q : two x;\n")
    e, succ = first_successors(model)
    assert len(succ) == 3 * 3  # discrete (1, 3) times D.ran ()
    assert sorted(e.format_marking(s, 1) for _, s in succ) == sorted(
        f"1`{d + 10 * r}" for d in (1, 2, 3) for r in (1, 2, 3))
    [w] = model.warnings  # the draw in the function, explored as a choice
    assert (w.code, w.span.line, w.span.col) == ("W0104", 8, 15)


def test_curried_and_several_clauses_and_a_let_in_a_delay():
    model = load("fun add a b = a + b + bernoulli 0.5;\n"
                 "fun wait 0 = 1 | wait n = let val p = discrete (0, 2) in n + p end;\n"
                 "place R : TU = 1`();\ntrans T @+ wait 2;\narc P -> T : x;\narc R -> T : ();\n"
                 "arc T -> Q : add x 5;\narc T -> R : ();\n")
    e, succ = first_successors(model)
    assert len(succ) == 2 * 3  # bernoulli, the draw of wait's second clause (the first one draws nothing)
    assert {e.format_marking(s, 1) for _, s in succ} == {"1`5", "1`6"}
    assert {str(e.format_marking(s, 2)) for _, s in succ} == {"1`()@2", "1`()@3", "1`()@4"}


def test_a_function_calling_a_function_that_draws():
    model = load("fun coin () = if bernoulli 0.5 = 1 then true else B.ran ();\n"
                 "fun code () = if coin () then 1 else 0;\ntrans T;\narc P -> T : x;\narc T -> Q : code ();\n")
    e, succ = first_successors(model)
    assert len(succ) == 2 * 2 and {e.format_marking(s, 1) for _, s in succ} == {"1`0", "1`1"}
    assert not [w for w in model.warnings if w.code == "W0105"]
    assert model.engine() is not None


@pytest.mark.parametrize("decls, use", [
    # recursive: any number of draws
    ("fun many n = if n = 0 then 0 else discrete (0, 1) + many (n - 1);", "arc T -> Q : many 2;"),
    # the bounds depend on the function's argument
    ("fun upto n = discrete (0, n);", "arc T -> Q : upto x;"),
    # called in a guard
    ("fun pick () = discrete (1, 3);", "trans U [pick () = 2];\narc P -> U : x;"),
    # drawn in a function given to map: a draw per element
    ("fun each l = map (fn y => y + discrete (0, 1)) l;", "arc T -> Q : hd (each [x]);"),
    # drawn once when the model is loaded
    ("fun pick () = discrete (1, 3);\nval v = pick ();", "arc T -> Q : v;"),
    # a continuous draw beside a finite one: the function is not written out
    ("fun both () = discrete (1, 3) + round (uniform (0.0, 1.0));", "arc T -> Q : both ();"),
])
def test_draws_that_are_no_choice_stay_random_draws(decls, use):
    line, col = 8, decls.index("discrete") + 1
    model = load(f"{decls}\ntrans T;\narc P -> T : x;\n{use}\n")
    assert [(w.code, w.span.line, w.span.col) for w in model.warnings if "'discrete'" in w.message] == [
        ("W0105", line, col)]
    with pytest.raises(ModelError) as info:
        model.engine()
    [d] = [d for d in info.value.diagnostics if "discrete" in d.message]
    assert d.code == "E0206" and "'discrete' draws a random value" in d.message
    assert (d.span.line, d.span.col) == (line, col)
    assert model.engine(simulation=True, reference=True) is not None


def test_a_function_that_draws_and_is_never_used_is_no_refusal():
    model = load("fun unused () = discrete (1, 3);\ntrans T;\narc P -> T : x;\n")
    assert model.warnings == [] and model.engine() is not None


def test_names_in_the_function_are_the_functions_not_the_transitions():
    # `y` in the body is the function's parameter, `k` the global value, whatever the transition calls so
    model = load("val k = 100;\nfun f y = y + k + discrete (0, 1);\nvar k2 : N;\n"
                 "trans T;\narc P -> T : x;\narc T -> Q : f 1;\n")
    e, succ = first_successors(model)
    assert {e.format_marking(s, 1) for _, s in succ} == {"1`101", "1`102"}


def test_the_report_notes_the_draws_explored_as_a_choice(tmp_path):
    import json

    from cpn.cli.main import main

    path = tmp_path / "f.cpnet"
    path.write_text(HEAD + "fun pick () = discrete (1, 3);\ntrans T;\narc P -> T : x;\narc T -> Q : pick ();\n")
    out = tmp_path / "r.json"
    assert main(["explore", str(path), "--json", str(out)]) == 0
    [note] = [n for n in json.loads(out.read_text())["notes"] if "choice" in n]
    assert "discrete(1, 3) at" in note and "f.cpnet:8:15" in note and "CPN Tools" in note
    plain = tmp_path / "p.cpnet"
    plain.write_text(HEAD + "trans T;\narc P -> T : x;\n")
    assert main(["explore", str(plain), "--json", str(out)]) == 0
    assert not [n for n in json.loads(out.read_text())["notes"] if "choice" in n]


def test_a_function_drawing_from_a_colour_set_too_large_to_try_stays_a_random_draw():
    model = load("colset S = string;\nfun name () = S.ran ();\nplace R : S;\ntrans T;\narc P -> T : x;\n"
                 "arc T -> R : name ();\n")
    assert [(w.code, w.span.line) for w in model.warnings] == [("W0105", 9)]
    assert model.engine(simulation=True, reference=True) is not None
