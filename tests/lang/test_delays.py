"""Delays: the reach of `@+` over an output inscription (CPN Tools' reading, also from `.cpn` files), ambiguous
delays refused with a hint to parenthesise, and delays into untimed places."""

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
@pytest.mark.parametrize("insc", ["1`0 ++ 1`1 @+ 2", "if true then 1`0 ++ 1`1 else empty @+ 2",
                                  "(1`0 ++ 1`1) @+ 2"])
def test_a_delay_applies_to_the_whole_output_inscription(insc, reference):
    assert _after_go(cpn.loads(DELAY_NET.format(insc=insc)), reference) == "1`0@2+++1`1@2"


@pytest.mark.parametrize("reference", [False, True])
def test_a_parenthesised_delay_still_delays_one_term(reference):
    assert _after_go(cpn.loads(DELAY_NET.format(insc="1`0 ++ (1`1 @+ 2)")), reference) == "1`0@0+++1`1@2"


def test_timed_sums_of_differently_delayed_terms():
    m = cpn.loads(DELAY_NET.format(insc="1`0 @+ 1 +++ 1`1 @+ 2"))
    assert _after_go(m, False) == "1`0@1+++1`1@2"


@pytest.mark.parametrize("src,message", [
    ("val x = if true then 1`1 @+ 1 else empty;", "'@+' in the then-branch"),
    ("val x = 1`1 @+ 1 @+ 2;", "a second '@+'"),
    ("val x = if true then 1`1 +++ 1`2 else empty;", "'+++' in the then-branch"),
    ("val x = case 1 of 0 => 1`1 @+ 1 | _ => empty;", "'@+' in a rule of 'case'"),
    ("fun f x = case x of 0 => 1`1 @+ 1 | _ => empty;", "'@+' in a rule of 'case'"),
])
def test_an_ambiguous_delay_is_refused_with_a_hint_to_parenthesise(src, message):
    with pytest.raises(ModelError) as info:
        parse(src, "m.cpnet")
    [d] = info.value.diagnostics
    assert d.code == "E0101" and message in d.message and "(" in d.hint


def test_a_delay_that_swallows_a_sum_is_a_type_error_with_a_hint():
    [d] = _diags(DELAY_NET.format(insc="1`0 @+ 2 ++ 1`1"))
    assert (d.code, d.span.line, d.span.col) == ("E0301", 5, 50)
    assert "'(e1 @+ d) ++ e2'" in d.hint


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
