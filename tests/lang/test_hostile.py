"""Malformed or hostile models give ModelError (or, at run time, EvaluationError), never a traceback."""

from hypothesis import given, settings
from hypothesis import strategies as st

import cpn
from cpn.errors import EvaluationError, ModelError

TOKENS = ["colset", "C", "=", "int", "with", "0", "..", "3", ";", "var", "x", ":", "place", "P", "trans", "t",
          "arc", "->", "<->", "(", ")", "[", "]", "{", "}", "`", "++", "@+", "1", "fun", "f", "|", "if", "then",
          "else", "let", "in", "end", "case", "of", "=>", "module", "instance", "port", "\"s\"", "#", ",", "~",
          "fusion", "reset", "inhibitor", "andalso", "::", "empty", "C.all()", "(*", "*)", "val", "N"]


@settings(max_examples=300, deadline=None)
@given(st.lists(st.sampled_from(TOKENS), max_size=40))
def test_token_soup_never_crashes(tokens):
    text = " ".join(tokens)
    try:
        model = cpn.loads(text, "soup.cpnet")
    except ModelError as err:
        assert err.diagnostics
        err.render()
        return
    engine = model.engine()
    try:
        engine.successors(engine.initial_state())
    except EvaluationError:
        pass


@settings(max_examples=100, deadline=None)
@given(st.text(max_size=200))
def test_arbitrary_text_never_crashes(text):
    try:
        cpn.loads(text, "text.cpnet")
    except ModelError as err:
        assert err.diagnostics


def test_deep_nesting_is_an_error_not_a_crash():
    text = "val x = " + "(" * 5000 + "1" + ")" * 5000 + ";"
    try:
        cpn.loads(text, "deep.cpnet")
    except ModelError as err:
        assert err.diagnostics[0].code in ("E0206", "E0101")


def test_infinite_recursion_is_an_evaluation_error():
    src = ("colset C = int with 0..3; var x : C; fun f n = f (n + 1); place P : C = 1`0; trans t [f x > 0];"
           "arc P -> t : x;")
    e = cpn.loads(src, "rec.cpnet").engine()
    try:
        e.successors(e.initial_state())
    except EvaluationError as err:
        assert "recursion" in err.message
    else:
        raise AssertionError("expected an evaluation error")


def test_python_looking_text_is_never_executed(tmp_path):
    marker = tmp_path / "pwned"
    src = (f'colset S = string; place P : S = 1`"__import__(\'os\').system(\'touch {marker}\')";\n'
           "var s : S; trans t; arc P -> t : s; arc t -> P : s ^ \"x\";")
    e = cpn.loads(src, "evil.cpnet").engine()
    for _be, s in e.successors(e.initial_state()):
        e.successors(s)
    assert not marker.exists()
