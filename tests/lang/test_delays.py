"""Delays: `@+` as CPN Tools' `infix 7` (each branch of an `if` its own delay), the reach of a delay that ends
an inscription (CPN Tools' `exp @+ arc-delay`, also from `.cpn` files), delays of delayed multisets refused, and
delays into untimed places."""

import pytest

import cpn
from cpn.errors import ModelError
from cpn.lang.parser import parse


def _diags(src: str, **kw):
    with pytest.raises(ModelError) as info:
        cpn.loads(src, "m.cpnet", **kw)
    return info.value.diagnostics


# ----------------------------------------------------------------------------- the reach of `@+`

DELAY_NET = """colset U = unit; colset C = int timed; var x : C;
place S : U = 1`();
place P : C;
place Q : C;
trans Go; arc S -> Go : (); arc Go -> P : {insc};
trans Take; arc P -> Take : x; arc Take -> Q : x;
"""


def _after_go(model, reference):
    e = model.engine(reference=reference)
    [(_, s1)] = e.successors(e.initial_state())
    return e.format_marking(s1, 1)


@pytest.mark.parametrize("reference", [False, True])
@pytest.mark.parametrize("insc", ["1`0 ++ 1`1 @+ 2", "(1`0 ++ 1`1) @+ 2", "if true then 1`0 ++ 1`1 @+ 2 else empty"])
def test_a_delay_at_the_end_of_an_inscription_delays_all_of_it(insc, reference):
    # CPN Tools' `exp @+ arc-delay`: the delay that ends an inscription (or a branch of its if) delays all before it
    assert _after_go(cpn.loads(DELAY_NET.format(insc=insc)), reference) == "1`0@2+++1`1@2"


@pytest.mark.parametrize("reference", [False, True])
@pytest.mark.parametrize("insc,after", [("0 + 1 @+ 2", "1`1@2"), ("2 - 1 :: [0] @+ 2", "1`0@2+++1`1@2")])
def test_a_delay_reaches_over_looser_operators_at_the_top(insc, after, reference):
    # `i+1@++exponential(1.0/4.0)`, as models made with CPN Tools write it: (i+1) delayed
    assert _after_go(cpn.loads(DELAY_NET.format(insc=insc)), reference) == after


@pytest.mark.parametrize("reference", [False, True])
def test_a_parenthesised_delay_still_delays_one_term(reference):
    assert _after_go(cpn.loads(DELAY_NET.format(insc="1`0 ++ (1`1 @+ 2)")), reference) == "1`0@0+++1`1@2"


def test_timed_sums_of_differently_delayed_terms():
    m = cpn.loads(DELAY_NET.format(insc="1`0 @+ 1 +++ 1`1 @+ 2"))
    assert _after_go(m, False) == "1`0@1+++1`1@2"


# '@+' is CPN Tools' `infix 7`: an operator of its level, so each branch of an `if` takes its own delay (before,
# `else e @+ d` delayed the whole `if`, and a delay in a then-branch was a syntax error)
@pytest.mark.parametrize("reference", [False, True])
@pytest.mark.parametrize("insc,after", [
    ("if true then 1`0 @+ 2 else 1`1 @+ 3", "1`0@2"),
    ("if false then 1`0 @+ 2 else 1`1 @+ 3", "1`1@3"),
    ("if true then 1`0 ++ 1`1 else empty @+ 2", "1`0@0+++1`1@0"),
    ("if true then if false then 1`0 @+ 0 else 1`1 @+ 1 else 1`1 @+ 1", "1`1@1"),
    ("case 1 of 0 => 1`0 @+ 1 | _ => 1`1 @+ 2", "1`1@2"),
    ("1`0 @+ 2 ++ 1`1", "1`0@2+++1`1@0"),
])
def test_each_branch_has_its_own_delay(insc, after, reference):
    assert _after_go(cpn.loads(DELAY_NET.format(insc=insc)), reference) == after


@pytest.mark.parametrize("reference", [False, True])
def test_a_function_whose_branches_are_delayed_differently(reference):
    # the LEACH-HOP model's form: `if c then A @+ 0 else B @+ 1` in the then-branch of another `if`
    src = DELAY_NET.replace("place S", "fun f (a, b) = if a then if b then 1`0 @+ 0 else 1`1 @+ 1 else empty;\n"
                                       "place S", 1)
    assert _after_go(cpn.loads(src.format(insc="f (true, false)")), reference) == "1`1@1"


def test_a_delay_in_a_then_branch_parses():
    parse("val x = if true then 1`1 @+ 1 else empty;\nval y = case 1 of 0 => 1`1 @+ 1 | _ => empty;", "m.cpnet")


# '+++' is CPN Tools' `infix 6`, as tight as '+' (before, it was looser than every operator and than `if`: a
# '+++' in a then-branch was a syntax error, and one in an else-branch summed the whole `if`)
@pytest.mark.parametrize("src, tree", [
    ("if a then b +++ c else d", "(if a then (b +++ c) else d)"),
    ("if a then b else c +++ d", "(if a then b else (c +++ d))"),
    ("fn y => y +++ z", "(fn y => (y +++ z))"),
    ("case y of 0 => p +++ q | _ => r", "(case y of 0 => (p +++ q) | _ => r)"),
    ("a = b +++ c", "(a = (b +++ c))"),
    ("a :: b +++ c", "(a :: (b +++ c))"),
    ("a ++ b +++ c -- d", "((a ++ (b +++ c)) -- d)"),
    ("a + b +++ c - d", "(((a + b) +++ c) - d)"),
    ("a +++ b * c @+ 2", "(a +++ ((b * c) @+ 2))"),
])
def test_plus_plus_plus_is_infix_6(src, tree):
    from cpn.expr.pretty import expr

    assert expr(parse(f"val x = {src};", "m.cpnet").decls[0].expr) == tree


@pytest.mark.parametrize("reference", [False, True])
@pytest.mark.parametrize("insc,after", [
    ("if true then 1`0 @+ 1 +++ 1`1 @+ 2 else empty", "1`0@1+++1`1@2"),
    ("if false then empty else 1`0 @+ 1 +++ 1`1 @+ 2", "1`0@1+++1`1@2"),
    ("1`0 +++ 1`1 @+ 2", "1`0@0+++1`1@2"),
    ("1`0 ++ 1`1 @+ 2 +++ 1`2 @+ 3", "1`0@0+++1`1@2+++1`2@3"),
    ("(1`0 ++ 1`1) @+ 2 +++ 1`2 @+ 3", "1`0@2+++1`1@2+++1`2@3"),
    ("0 + 1 @+ 2 +++ 1`2 @+ 3", "1`1@2+++1`2@3"),
])
def test_timed_sums_in_branches_and_beside_looser_operators(insc, after, reference):
    assert _after_go(cpn.loads(DELAY_NET.format(insc=insc)), reference) == after


def test_a_delay_of_a_delayed_multiset_is_a_type_error():
    # CPN Tools: '@+' takes an untimed multiset ('a ms * int -> 'a tms)
    [d] = _diags(DELAY_NET.format(insc="1`0 @+ 1 @+ 2"))
    assert (d.code, d.span.line, d.span.col) == ("E0301", 5, 43)
    assert "'e @+ (d1 + d2)'" in d.hint


def test_a_delay_followed_by_an_addition_is_a_type_error_with_a_hint():
    # `x @+ d + 1` is `(x @+ d) + 1`: '@+' is as tight as '*'
    [d] = _diags("colset C = int timed; val d = 1; val m = 1`0 @+ d + 1;")
    assert d.code == "E0301" and "'e @+ (d + 1)'" in d.hint


def test_cpn_import_reads_the_delay_as_cpn_tools_does(tmp_path):
    from tests.io.test_cpntools import arc, cpn_xml, page, place, trans

    decls = ('<color id="C1"><id>U</id><unit/></color><color id="C2"><id>C</id><timed/><int/></color>'
             '<var id="V1"><type><id>C</id></type><id>x</id></var>')
    body = (place("P1", "S", "U", "1`()") + place("P2", "P", "C") + trans("T1", "Go")
            + arc("A1", "PtoT", "T1", "P1", "()") + arc("A2", "TtoP", "T1", "P2", "1`0 ++ 1`1 @+ 2"))
    path = tmp_path / "delay.cpn"
    path.write_text(cpn_xml(decls, page("PG1", "Top", body)), encoding="iso-8859-1")
    assert _after_go(cpn.load(path), False) == "1`0@2+++1`1@2"


# ----------------------------------------------------------------------------- delays into untimed places

UNTIMED = """colset U = unit; colset UT = unit timed;
place P : U = 1`();
place Q : U;
place Z : UT;
"""


def test_an_arc_delay_into_an_untimed_place_is_a_type_error():
    [d] = _diags(UNTIMED + "trans T;\narc P -> T;\narc T -> Q : () @+ 5;\n")
    assert (d.code, d.span.line, d.span.col, d.params["place"]) == ("E0301", 7, 14, "Q")
    assert "timed" in d.hint


def test_a_delay_inside_an_if_into_an_untimed_place_is_a_type_error():
    [d] = _diags(UNTIMED + "trans T;\narc P -> T;\narc T -> Q : if true then 1`() else empty @+ 5;\n")
    assert (d.code, d.span.line) == ("E0301", 7)


def test_a_transition_delay_without_a_timed_output_is_accepted_with_a_warning():
    # CPN Tools accepts it (the delay type-checked, without effect): W0102, no longer E0301
    diags = cpn.loads(UNTIMED + "trans T @+ 5;\narc P -> T;\narc T -> Q;\ntrans S @+ 1;\narc Q -> S;\n",
                      "m.cpnet").warnings
    assert [(d.code, d.span.line, d.span.col, d.params["transition"]) for d in diags] == [
        ("W0102", 5, 12, "T"), ("W0102", 8, 12, "S")]
    assert all("timed" in d.hint for d in diags)


@pytest.mark.parametrize("reference", [False, True])
def test_a_transition_delay_applies_to_the_timed_outputs_only(reference):
    m = cpn.loads(UNTIMED + "trans T @+ 5;\narc P -> T;\narc T -> Q;\narc T -> Z;\n")
    e = m.engine(reference=reference)
    [(_, s1)] = e.successors(e.initial_state())
    assert (e.format_marking(s1, 1), e.format_marking(s1, 2)) == ("1`()", "1`()@5")


def test_a_delay_into_an_untimed_place_of_a_cpn_file_is_reported_at_the_arc(tmp_path):
    from tests.io.test_cpntools import arc, cpn_xml, page, place, trans

    decls = '<color id="C1"><id>U</id><unit/></color>'
    body = (place("P1", "S", "U", "1`()") + place("P2", "P", "U") + trans("T1", "Go")
            + arc("A1", "PtoT", "T1", "P1", "()") + arc("A2", "TtoP", "T1", "P2", "()@+5"))
    path = tmp_path / "untimed.cpn"
    path.write_text(cpn_xml(decls, page("PG1", "Top", body)), encoding="iso-8859-1")
    with pytest.raises(ModelError) as info:
        cpn.load(path)
    [d] = info.value.diagnostics
    assert d.code == "E0301" and d.span.file == str(path) and "not timed" in d.message
