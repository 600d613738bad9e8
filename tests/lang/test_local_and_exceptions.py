"""`local ... in ... end` declarations, `exception`, `raise` and `handle`."""

import pytest

import cpn
from cpn.errors import EvaluationError, ModelError
from cpn.io.cpntools import translate
from cpn.lang.parser import parse
from cpn.lang.pretty import decl as pretty_decl
from tests._models import figures, model_path

# ----------------------------------------------------------------------------- local declarations


@pytest.mark.parametrize("name", ["local.cpnet", "local.cpn"])
@pytest.mark.parametrize("reference", [False, True])
def test_the_local_model_has_its_hand_checked_figures(name, reference):
    # F cycles 0 -> 2 -> 4 -> 1 -> 3 -> 0; the guard (global step) always holds: 5 states, 5 arcs
    assert figures(name, reference=reference) == (5, 5, 0)


def test_the_converter_keeps_a_local_block_that_the_net_uses():
    text = translate(model_path("local.cpn"))
    assert "not used by the net" not in text
    assert "local\n  fun step x = (x + 2) mod 5\nin\n  fun F x = step x\nend;" in text


def test_a_local_block_that_the_net_does_not_use_is_still_left_out_with_a_note():
    with open(model_path("local.cpn"), encoding="iso-8859-1") as fh:
        xml = fh.read().replace("F x</text>", "x</text>")
    from cpn.io.cpntools import translate_text
    text = translate_text(xml, "l.cpn").text
    assert "(* declaration ID4 (F) at line" in text and "not used by the net, left out *)" in text


def test_the_private_part_of_local_is_not_visible_after_it():
    src = "local fun h x = x + 1 in fun f x = h x end;\nval y = h 1;\n"
    with pytest.raises(ModelError) as info:
        cpn.loads(src, "m.cpnet")
    [d] = info.value.diagnostics
    assert (d.code, d.span.line, d.span.col) == ("E0201", 2, 9) and "'h'" in d.message


def test_a_local_block_prints_back_as_it_parses():
    src = "local exception E of int; fun h x = raise E x; in fun f x = h x handle E n => n; end;"
    [d] = parse(src, "m.cpnet").decls
    again = pretty_decl(d)
    assert again.startswith("local exception E of int;")
    [d2] = parse(again, "m.cpnet").decls
    assert pretty_decl(d2) == again


# ----------------------------------------------------------------------------- exceptions


@pytest.mark.parametrize("name", ["exceptions.cpnet", "exceptions.cpn"])
@pytest.mark.parametrize("reference", [False, True])
def test_the_exceptions_model_has_its_hand_checked_figures(name, reference):
    # next cycles 0 -> 1 -> 2 -> 3 -> 0, the last step through a handled TooBig: 4 states, 4 arcs
    assert figures(name, reference=reference) == (4, 4, 0)


@pytest.mark.parametrize("reference", [False, True])
def test_exception_constructors_in_the_clauses_of_a_compiled_function(reference):
    # size_of is compiled to Python by the compiled engine: its clause pattern (TooBig n) tests the tag
    src = ("colset C = int with 0..9; var x : C; exception TooBig of int; exception Stop;\n"
           "fun size_of (TooBig n) = n | size_of Stop = 1 | size_of _ = 0;\n"
           "fun pick x = if x > 3 then TooBig x else Stop;\n"
           "place P : C = 1`5 ++ 1`2; place Q : C; trans T; arc P -> T : x; arc T -> Q : size_of (pick x);\n")
    e = cpn.loads(src, "m.cpnet").engine(reference=reference)
    got = sorted(e.format_marking(s, 1) for _, s in e.successors(e.initial_state()))
    assert got == ["1`1", "1`5"]


@pytest.mark.parametrize("name", ["uncaught.cpnet", "uncaught.cpn"])
@pytest.mark.parametrize("reference", [False, True])
def test_an_uncaught_exception_is_a_positioned_run_time_error_with_the_binding(name, reference):
    with pytest.raises(EvaluationError) as info:
        figures(name, reference=reference)
    text = info.value.render() if hasattr(info.value, "render") else str(info.value)
    assert "uncaught exception Stop" in text and "x=1" in text
    assert ":20:" in text if name.endswith(".cpn") else ":16:" in text  # the arc T -> P


def test_an_uncaught_exception_exits_with_status_65(capsys):
    from cpn.cli.main import main
    assert main(["explore", "-q", model_path("uncaught.cpnet")]) == 65
    err = capsys.readouterr().err
    assert "error[E0401]" in err and "uncaught exception Stop, raised by the 'raise' at" in err


@pytest.mark.parametrize("reference", [False, True])
def test_handle_does_not_catch_run_time_errors(reference):
    src = ("colset C = int with 0..3; var x : C; exception E;\n"
           "place P : C = 1`0; trans T; arc P -> T : x; arc T -> P : (1 div x) handle E => 0;\n")
    e = cpn.loads(src, "m.cpnet").engine(reference=reference)
    with pytest.raises(EvaluationError) as info:
        e.successors(e.initial_state())
    assert "division by zero" in str(info.value).lower() or "div" in str(info.value)


@pytest.mark.parametrize("src,code,line", [
    ("exception E; val x = raise 3;", "E0301", 1),
    ("exception E; fun f (x : int) = x handle E => \"a\";", "E0301", 1),
    ("fun f x = let exception E in x end;", "E0206", 1),
    ("val z = (raise Nope) handle Nope => 1;", "E0201", 1),
])
def test_misused_exceptions_are_refused_with_positions(src, code, line):
    with pytest.raises(ModelError) as info:
        cpn.loads(src, "m.cpnet")
    d = info.value.diagnostics[0]
    assert (d.code, d.span.line) == (code, line)


def test_an_exception_value_is_evaluated_when_a_val_is_declared():
    with pytest.raises(ModelError) as info:
        cpn.loads("exception E of int; val z = raise E 3;", "m.cpnet")
    d = info.value.diagnostics[0]
    assert d.code == "E0401" and "uncaught exception E 3" in d.message


@pytest.mark.parametrize("reference", [False, True])
def test_fail_is_predeclared_and_may_be_handled(reference):
    src = ("colset C = int with 0..9; var x : C;\n"
           "fun pick x = if x > 0 then raise Fail \"too far\" else x;\n"
           "fun safe x = pick x handle Fail m => String.size m;\n"
           "place P : C = 1`2; trans T; arc P -> T : x; arc T -> P : safe x;\n")
    e = cpn.loads(src, "m.cpnet").engine(reference=reference)
    [(_, s1)] = e.successors(e.initial_state())
    assert e.format_marking(s1, 0) == "1`7"  # size "too far"
    bad = src.replace("arc T -> P : safe x;", "arc T -> P : pick x;")
    e = cpn.loads(bad, "m.cpnet").engine(reference=reference)
    with pytest.raises(EvaluationError) as info:
        e.successors(e.initial_state())
    assert 'uncaught exception Fail "too far"' in str(info.value)


def test_a_model_may_declare_its_own_fail():
    cpn.loads("exception Fail; val x = (raise Fail) handle Fail => 1;", "m.cpnet")
