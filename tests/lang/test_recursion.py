"""A function of the model may recurse 10,000 levels deep, in both engines and while the
model is checked; deeper than can be evaluated, a positioned run-time error names the function."""

import pytest

import cpn
from cpn.errors import EvaluationError, ModelError
from tests._models import figures


@pytest.mark.parametrize("name", ["recursion.cpnet", "recursion.cpn"])
@pytest.mark.parametrize("reference", [False, True])
def test_the_recursion_model_has_its_hand_checked_figures(name, reference):
    assert figures(name, reference=reference) == (2, 1, 1)


def _fire_once(src: str, reference: bool) -> str:
    e = cpn.loads(src, "m.cpnet").engine(reference=reference)
    [(_, s1)] = e.successors(e.initial_state())
    return e.format_marking(s1, 1)


@pytest.mark.parametrize("reference", [False, True])
@pytest.mark.parametrize("n", [600, 10000])
def test_a_recursive_function_in_a_guard_and_an_arc(reference, n):
    # one call per level: f n = n, sum n = n (n + 1) / 2
    src = ("colset C = int; var x : C;\n"
           "fun f 0 = 0 | f n = 1 + f (n - 1);\n"
           "fun sum k = if k = 0 then 0 else k + sum (k - 1);\n"
           f"place P : C = 1`{n}; place Q : C;\n"
           f"trans T [f x = {n}]; arc P -> T : x; arc T -> Q : sum x;\n")
    assert _fire_once(src, reference) == f"1`{n * (n + 1) // 2}"


@pytest.mark.parametrize("reference", [False, True])
def test_a_recursive_len_over_a_600_element_list(reference):
    src = ("colset C = int; colset L = list C; var l : L;\n"
           "fun len [] = 0 | len (_ :: t) = 1 + len t;\n"
           "place P : L = 1`(List.tabulate(600, fn i => i)); place Q : C;\n"
           "trans T [len l = 600]; arc P -> T : l; arc T -> Q : len l;\n")
    assert _fire_once(src, reference) == "1`600"


@pytest.mark.parametrize("reference", [False, True])
def test_curried_and_local_recursive_functions_left_to_the_evaluator(reference):
    # a curried function and a function of a 'let' are evaluated by the tree-walking evaluator
    src = ("colset C = int; var x : C;\n"
           "fun add a b = if a = 0 then b else add (a - 1) (b + 1);\n"
           "place P : C = 1`10000; place Q : C;\n"
           "trans T; arc P -> T : x;\n"
           "arc T -> Q : add x 0 + (let fun g 0 = 0 | g k = 2 + g (k - 1) in g x end);\n")
    assert _fire_once(src, reference) == "1`30000"


def test_deep_recursion_while_the_model_is_checked():
    src = ("colset C = int;\nfun f 0 = 0 | f n = 1 + f (n - 1);\nval d = f 10000;\n"
           "place P : C = 1`d ++ 1`(f 9999);\n")
    e = cpn.loads(src, "m.cpnet").engine()
    assert e.format_marking(e.initial_state(), 0) == "1`9999++1`10000"


@pytest.mark.parametrize("reference", [False, True])
def test_endless_recursion_is_a_positioned_error_naming_the_function_and_the_binding(reference):
    src = ("colset C = int; var x : C;\n"
           "fun loop n = 1 + loop (n + 1);\n"
           "place P : C = 1`7; place Q : C;\n"
           "trans T [x > 0];\narc P -> T : x;\narc T -> Q : loop x;\n")
    e = cpn.loads(src, "m.cpnet").engine(reference=reference)
    with pytest.raises(EvaluationError) as info:
        e.successors(e.initial_state())
    text = str(info.value)
    assert "recursion too deep in function 'loop'" in text and "x=7" in text and "Top'T 1" in text
    assert info.value.span.line == 6
    assert "Traceback" not in info.value.render()


def test_endless_recursion_while_the_model_is_checked_names_the_function():
    src = "colset C = int;\nfun loop n = 1 + loop (n + 1);\nval v = loop 0;\n"
    with pytest.raises(ModelError) as info:
        cpn.loads(src, "m.cpnet")
    d = info.value.diagnostics[0]
    assert d.code == "E0401" and d.span.line == 3 and "recursion too deep in function 'loop'" in d.message
