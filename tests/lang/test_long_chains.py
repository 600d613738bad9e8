"""A long chain of one associative operator is not nesting; only real nesting is E0206."""

import pytest

import cpn
from cpn.errors import ModelError
from tests._models import figures


def _explore(src):
    return cpn.loads(src, "m.cpnet").explore()


@pytest.mark.parametrize("op,n", [("++", 600), ("++", 5000)])
def test_a_long_multiset_sum_in_an_initial_marking_is_read(op, n):
    src = ("colset C = int; colset U = unit; var x : C;\n"
           "place P : C = " + f" {op} ".join(f"1`{i}" for i in range(n)) + ";\n"
           "place Q : C;\ntrans T; arc P -> T : x; arc T -> Q : x;\n")
    model = cpn.loads(src, "m.cpnet")
    e = model.engine()
    s0 = e.initial_state()
    # every term is one token of its own value
    assert e.format_marking(s0, 0) == "++".join(f"1`{i}" for i in range(n)) and e.token_counts(s0) == (n, 0)
    if n <= 600:
        # one binding element per token, each enabled once (with 5,000 tokens the successors alone took
        # 29 s of the suite, each a new marking of 4,999 tokens; the chain is read before them)
        assert len(list(e.successors(s0))) == n


@pytest.mark.parametrize("reference", [False, True])
def test_long_list_and_string_chains_keep_their_order(reference):
    n = 600
    lst = " ^^ ".join(f"[{i}]" for i in range(n))
    app = " @ ".join(f"[{i}]" for i in range(n))
    strs = " ^ ".join(f'"{i % 10}"' for i in range(n))
    src = ("colset L = list INT; colset S = string;\n"
           f"val l1 = {lst};\nval l2 = {app};\nval s = {strs};\n"
           "place P : L = 1`l1 ++ 1`l2; place Q : S = 1`s;\n")
    model = cpn.loads(src, "m.cpnet")
    e = model.engine(reference=reference)
    s0 = e.initial_state()
    text = e.format_marking(s0, 0) + e.format_marking(s0, 1)
    expected = "[" + ",".join(str(i) for i in range(n)) + "]"
    assert text.count(expected) == 1 and "2`" + expected in text
    assert '"' + "".join(str(i % 10) for i in range(n)) + '"' in text


def test_a_type_error_in_a_long_chain_points_at_its_operand():
    src = "colset C = int;\nplace P : C = " + " ++ ".join(["1`1"] * 300 + ['1`"x"'] + ["1`2"] * 299) + ";\n"
    with pytest.raises(ModelError) as info:
        cpn.loads(src, "m.cpnet")
    d = info.value.diagnostics[0]
    assert d.span.line == 2
    col = src.splitlines()[1].index('1`"x"') + 1
    assert d.span.col <= col <= d.span.end_col


def test_real_nesting_is_still_refused_with_e0206():
    text = "val x = " + "(1 + " * 3000 + "1" + ")" * 3000 + ";"
    with pytest.raises(ModelError) as info:
        cpn.loads(text, "deep.cpnet")
    assert info.value.diagnostics[0].code == "E0206"


@pytest.mark.parametrize("name", ["chain.cpnet", "chain.cpn"])
@pytest.mark.parametrize("reference", [False, True])
def test_the_chain_model_has_its_hand_checked_figures(name, reference):
    # 600 tokens 0..599; only 598 and 599 pass the guard and each moves once: 4 states, 4 arcs, 1 dead
    assert figures(name, reference=reference) == (4, 4, 1)


@pytest.mark.parametrize("reference", [False, True])
@pytest.mark.parametrize("tail,extra", [("[]", []), ("[7, 8]", [7, 8]), ("l0", [9])])
def test_a_long_cons_chain_keeps_its_value(reference, tail, extra):
    n = 600
    src = ("colset L = list INT;\nval l0 = [9];\n"
           "val l = " + " :: ".join(str(i) for i in range(n)) + f" :: {tail};\n"
           "place P : L = 1`l;\n")
    e = cpn.loads(src, "m.cpnet").engine(reference=reference)
    expected = "[" + ",".join(str(i) for i in [*range(n), *extra]) + "]"
    assert e.format_marking(e.initial_state(), 0) == "1`" + expected


def test_a_short_cons_chain_keeps_its_own_messages():
    with pytest.raises(ModelError) as info:
        cpn.loads('val l = 1 :: "a" :: [];', "m.cpnet")
    assert "'::'" in info.value.diagnostics[0].message


@pytest.mark.parametrize("reference", [False, True])
def test_a_long_arithmetic_chain_and_deep_ifs_run_in_both_engines(reference):
    # the compiled engine used to fail with Python's "too many nested parentheses" (an internal error)
    n = 400
    src = ("colset C = int; var x : C;\n"
           "fun f y = " + " + ".join(["y"] * n) + ";\n"
           "fun g y = " + "".join(f"if y = {i} then {i} else " for i in range(60)) + "0;\n"
           "place P : C = 1`1; place Q : C; trans T; arc P -> T : x;\n"
           "arc T -> Q : " + " + ".join(["x"] * n) + " + f x + g x;\n")
    e = cpn.loads(src, "m.cpnet").engine(reference=reference)
    [(_, s1)] = e.successors(e.initial_state())
    assert e.format_marking(s1, 1) == f"1`{2 * n + 1}"
