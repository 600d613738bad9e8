"""Issue 8, language items: delays into untimed places, lists as multisets, the reach of `@+`, byte-order
marks and invisible characters, `--set` values, follow-on errors, and suggestions."""

import pytest

import cpn
from cpn.errors import ModelError
from cpn.lang.parser import parse


def _diags(src: str, **kw):
    with pytest.raises(ModelError) as info:
        cpn.loads(src, "m.cpnet", **kw)
    return info.value.diagnostics


# ----------------------------------------------------------------------------- item 11


def test_a_utf8_byte_order_mark_is_accepted(tmp_path):
    path = tmp_path / "bom.cpnet"
    path.write_bytes(b"\xef\xbb\xbfcolset U = unit;\nplace P : U = 1`();\n")
    model = cpn.load(path)
    assert [p.name for p in model.net.places] == ["Top'P 1"]
    # also when the text is given directly
    assert cpn.loads("\ufeffcolset U = unit;\nplace P : U;\n").net.places[0].name == "Top'P 1"


def test_an_invisible_character_is_named_by_its_code_point():
    with pytest.raises(ModelError) as info:
        parse("colset U = unit;\nval a = 1\x00;\n", "m.cpnet")
    [d] = info.value.diagnostics
    assert (d.code, d.span.line, d.span.col) == ("E0101", 2, 10)
    assert "U+0000" in d.message and "''" not in d.message
    assert "\x00" not in info.value.render()


# ----------------------------------------------------------------------------- item 19


@pytest.mark.parametrize("src,line,col,opener", [
    ("colset S = int;\nvar x : S;\nplace P : S;\ntrans T [(x < 3];\narc P -> T : x;\n", 4, 10, "("),
    ("val z = [1, (2, 3]];\n", 1, 13, "("),
    ("val z = ([1, 2);\n", 1, 10, "["),
])
def test_an_unclosed_bracket_is_reported_where_it_opens(src, line, col, opener):
    with pytest.raises(ModelError) as info:
        parse(src, "m.cpnet")
    [d] = info.value.diagnostics
    assert (d.code, d.span.line, d.span.col) == ("E0101", line, col)
    assert f"'{opener}' is not closed" in d.message
    assert "closes nothing" not in d.message


def test_a_closing_bracket_without_partner_still_closes_nothing():
    with pytest.raises(ModelError) as info:
        parse("val y = (1]);\n", "m.cpnet")
    [d] = info.value.diagnostics
    assert (d.span.line, d.span.col) == (1, 11) and "']' closes nothing" in d.message


# ----------------------------------------------------------------------------- item 5

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


# ----------------------------------------------------------------------------- item 2

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


# ----------------------------------------------------------------------------- item 4

LISTS = """colset Worker = with w1 | w2;
colset Decision = with yes | no;
colset WorkerxDecision = product Worker * Decision;
colset WL = list WorkerxDecision;
var w : Worker;
var ws : WL;
fun decide w = [(w, yes), (w, no)];
place Idle : Worker = [w1, w2];
place Out : WorkerxDecision;
place Lists : WL = [(w1, yes)];
trans Decide;
arc Idle -> Decide : w;
arc Decide -> Out : decide w;
trans Collect;
arc Out -> Collect : [(w, yes), (w, no)];
arc Collect -> Idle : if w = w1 then [w] else [] ++ 1`w;
trans Keep;
arc Lists -> Keep : ws;
arc Keep -> Lists : ws;
"""


@pytest.mark.parametrize("reference", [False, True])
def test_a_list_of_colours_is_accepted_where_a_multiset_is_expected(reference):
    from cpn.statespace import Explorer

    e = cpn.loads(LISTS).engine(reference=reference)
    s0 = e.initial_state()
    # an initial marking given as a list; a place whose colour set is a list holds one list token
    assert (e.format_marking(s0, 0), e.format_marking(s0, 2)) == ("1`w1++1`w2", "1`[(w1,yes)]")
    succ = {e.format_binding_element(be): s for be, s in e.successors(s0)}
    assert e.format_marking(succ["Top'Decide 1: {w=w1}"], 1) == "1`(w1,yes)++1`(w1,no)"
    x = Explorer(e).run()
    assert (x.n_states, x.n_arcs, x.complete) == (4, 12, True)


def test_a_list_of_the_wrong_colour_is_still_a_type_error():
    [d] = _diags(LISTS.replace("arc Decide -> Out : decide w;", "arc Decide -> Out : [w];"))
    assert (d.code, d.span.line) == ("E0301", 13)


def test_a_list_of_colours_on_an_arc_of_a_cpn_file(tmp_path):
    from tests.io.test_cpntools import arc, cpn_xml, page, place, trans

    decls = ('<color id="C1"><id>Worker</id><enum><id>w1</id><id>w2</id></enum></color>'
             '<color id="C2"><id>Decision</id><enum><id>yes</id><id>no</id></enum></color>'
             '<color id="C3"><id>WorkerxDecision</id><product><id>Worker</id><id>Decision</id></product></color>'
             '<var id="V1"><type><id>Worker</id></type><id>w</id></var>'
             '<ml id="M1">fun decide w = [(w, yes), (w, no)]</ml>')
    body = (place("P1", "Idle", "Worker", "[w1]") + place("P2", "Out", "WorkerxDecision") + trans("T1", "Decide")
            + arc("A1", "PtoT", "T1", "P1", "w") + arc("A2", "TtoP", "T1", "P2", "decide w"))
    path = tmp_path / "lists.cpn"
    path.write_text(cpn_xml(decls, page("PG1", "Top", body)), encoding="iso-8859-1")
    e = cpn.load(path).engine()
    [(_, s1)] = e.successors(e.initial_state())
    assert e.format_marking(s1, 1) == "1`(w1,yes)++1`(w1,no)"


# ----------------------------------------------------------------------------- item 13

SETS = """val N = 3;
colset S = int with 0..N;
colset P2 = product S * S;
var x : S;
place P : S = S.all();
place Q : P2;
trans T [x < N];
arc P -> T : x;
arc T -> Q : (x, x);
"""


@pytest.mark.parametrize("value,expected", [
    ("abc", "expected an int for 'N' declared at m.cpnet:1:5, found 'abc'"),
    ("1.5", "expected an int for 'N' declared at m.cpnet:1:5, found a real"),
    ('"x"', "expected an int for 'N' declared at m.cpnet:1:5, found a string"),
    ("1 +", "not a CPN ML expression"),
    ("3; val M = 4", "not a CPN ML expression"),
    ("1 div 0", "evaluating the value failed"),
])
def test_a_bad_set_value_is_one_usage_error_naming_the_value(value, expected):
    from cpn.errors import ConfigurationError

    with pytest.raises(ConfigurationError) as info:
        cpn.loads(SETS, "m.cpnet", set={"N": value})
    exc = info.value
    assert (exc.code, exc.exit_status) == ("E0305", 64)
    assert str(exc).startswith(f"--set N={value}: ") and expected in str(exc)
    assert str(exc).count("\n") == 0


def test_an_unknown_constant_is_a_usage_error_with_a_suggestion():
    from cpn.errors import ConfigurationError

    with pytest.raises(ConfigurationError) as info:
        cpn.loads(SETS.replace("val N", "val Limit").replace("..N", "..Limit").replace("< N", "< Limit"),
                  "m.cpnet", set={"Limt": "3"})
    assert [p.message for p in info.value.problems] == ["the model has no constant 'val Limt'"]
    assert "'Limit'" in info.value.hint


@pytest.mark.parametrize("value", ["-1", " - 1", "~1"])
def test_a_negative_number_may_be_written_with_a_minus(value):
    m = cpn.loads("val D = 3;\ncolset C = int with ~5..5;\nplace P : C = 1`D;", "m.cpnet", set={"D": value})
    assert m.net.places[0].initial == {-1: 1}


def test_set_values_are_parsed_before_checking_and_leave_the_model_unchanged():
    from cpn.lang.overrides import parse_overrides
    from cpn.lang.typecheck import check

    model = parse(SETS, "m.cpnet")
    original = model.decls[0].expr
    overrides = parse_overrides({"N": "-2"})
    assert overrides["N"].text == "-2"
    with pytest.raises(ModelError) as info:  # 0..~2 is an empty range: a model error, reported once
        check(model, overrides)
    [d] = info.value.diagnostics
    assert (d.code, d.span.line, d.notes) == ("E0304", 2, ["'N' is given with --set N=-2"])
    assert model.decls[0].expr is original  # the declaration still holds the model's own value


@pytest.mark.parametrize("argv", [["lint"], ["explore", "--quiet"], ["simulate"]])
@pytest.mark.parametrize("value", ["N=abc", "N=1.5", "NOPE=3"])
def test_the_command_line_exits_64_with_one_error(tmp_path, capsys, argv, value):
    from cpn.cli.main import main

    path = tmp_path / "m.cpnet"
    path.write_text(SETS)
    assert main(argv + ["--set", value, str(path)]) == 64
    err = capsys.readouterr().err
    assert err.count("error") == 1 and f"--set {value}" in err


def test_one_unknown_colour_set_is_reported_once():
    src = """colset S = int with 0..3;
colset P2 = product Foo * S;
var x : Foo;
var y : S;
place P : Foo = 1`1;
place Q : P2;
trans T [x < 3];
arc P -> T : x;
arc T -> Q : (x, y);
"""
    [d] = _diags(src)
    assert (d.code, d.span.line, d.params["name"]) == ("E0201", 2, "Foo")
    assert d.notes == ["also used at 3:9, 5:11"]


def test_a_failed_declaration_causes_no_follow_on_errors():
    [d] = _diags("val N = abc;\ncolset S = int with 0..N;\nvar x : S;\nplace P : S = S.all();\ntrans T [x < N];\n"
                 "arc P -> T : x;\n")
    assert (d.code, d.span.line, d.params["name"]) == ("E0201", 1, "abc")


# ----------------------------------------------------------------------------- item 19

MISSPELT = """colset Worker = int with 0..3;
val Limit = 3;
var worker : Worker;
fun next w = (w + 1) mod Limit;
place Idle : Worker = Worker.all();
place Busy : Worker;
trans Start [worker < Limit];
trans Stop;
arc Idle -> Start : worker;
arc Start -> Busy : worker;
arc Busy -> Stop : worker;
arc Stop -> Idle : next worker;
"""


@pytest.mark.parametrize("old,new,line,hint", [
    ("place Busy : Worker;", "place Busy : Workr;", 6, "Did you mean 'Worker' (declared at 1:1)?"),
    ("arc Idle -> Start : worker;", "arc Idle -> Start : workr;", 9,
     "Did you mean the variable 'worker' (declared at 3:5)?"),
    ("[worker < Limit]", "[worker < Limt]", 7, "Did you mean the constant 'Limit' (declared at 2:5)?"),
    ("next worker;", "nxt worker;", 12, "Did you mean the function 'next' (declared at 4:1)?"),
    ("arc Busy -> Stop", "arc Bussy -> Stop", 11, "Did you mean the place 'Busy' (declared at 6:7)?"),
    ("arc Idle -> Start", "arc Idle -> Strat", 9, "Did you mean the transition 'Start' (declared at 7:7)?"),
    ("Worker.all()", "Worker.al()", 5, "Did you mean 'Worker.all'?"),
    ("(w + 1) mod Limit", "(w + 1) mod Limit + lenght []", 4, "Did you mean the library function 'length'?"),
])
def test_unknown_names_get_a_suggestion_naming_what_the_candidate_is(old, new, line, hint):
    [d] = _diags(MISSPELT.replace(old, new))
    assert (d.code, d.span.line) == ("E0201", line)
    assert d.hint.startswith(hint)


@pytest.mark.parametrize("old,new", [("[worker < Limit]", "[worker < q]"),
                                     ("place Busy : Worker;", "place Busy : Colour;")])
def test_no_suggestion_without_a_strong_candidate(old, new):
    [d] = _diags(MISSPELT.replace(old, new))
    assert "Did you mean" not in d.hint


@pytest.mark.parametrize("reference", [False, True])
def test_a_list_of_colours_on_an_input_arc(reference):
    src = """colset W = with w1 | w2; colset D = with yes | no; colset WD = product W * D;
var w : W;
fun decide w = [(w, yes), (w, no)];
place Idle : W = [w1, w2];
place Out : WD = [(w1, yes), (w1, no), (w2, yes)];
place Done : W;
trans T;
arc Idle -> T : w;
arc Out -> T : decide w;
arc T -> Done : [w, w];
"""
    e = cpn.loads(src).engine(reference=reference)
    [(be, s1)] = e.successors(e.initial_state())
    assert e.format_binding_element(be) == "Top'T 1: {w=w1}"
    assert (e.format_marking(s1, 1), e.format_marking(s1, 2)) == ("1`(w2,yes)", "2`w1")


def test_a_bad_set_value_for_a_cpn_file_names_the_declaration_in_the_cpn_file(tmp_path):
    from cpn.errors import ConfigurationError
    from tests.io.test_cpntools import DECLS, arc, cpn_xml, page, place, trans

    body = place("P1", "A", "S", "1`0") + trans("T1", "T", cond="[x &lt; N]") + arc("A1", "PtoT", "T1", "P1", "x")
    path = tmp_path / "n.cpn"
    path.write_text(cpn_xml(DECLS, page("PG1", "Top", body)), encoding="iso-8859-1")
    assert cpn.load(path, set={"N": "-1"}).net.places[0].name == "Top'A 1"
    with pytest.raises(ConfigurationError) as info:
        cpn.load(path, set={"N": "1.5"})
    text = str(info.value)
    assert text.startswith(f"--set N=1.5: expected an int for 'N' declared at {path}:")
    assert "as .cpnet" not in text
